#include <osgActor/core/skin/SkinningJob>

#include "../HotPath.h"
#include "Float4.h"

#include <cmath>
#include <cstdint>

namespace osgActor {

namespace {

using skin::Float4;
using skin::loadFloat4;
using skin::makeFloat4;

/** One group of the run: count vertices that all have K influences. */
struct Group
{
    std::size_t count;
    const glm::vec3* positions;
    const glm::vec3* normals;
    const glm::vec4* tangents;
    const std::uint32_t* outputIndices;
    const std::uint16_t* joints;
    const float* weights;
};

struct Outputs
{
    glm::vec3* positions;
    glm::vec3* normals;
    glm::vec4* tangents;
};

/** How one vertex moves, as four-float columns (column-vector notation, bind space to model space): point maps
  * positions (its fourth column the translation), tangent and normal map directions. */
struct VertexTransform
{
    Float4 point[4];
    Float4 tangent[3];
    Float4 normal[3];
};

OSGACTOR_SKIN_INLINE void loadColumns(const glm::mat4& m, unsigned numColumns, Float4* columns)
{
    for (unsigned c = 0; c < numColumns; ++c) columns[c] = loadFloat4(&m[c][0]);
}

/** columns = sum over the vertex's K influences of weight x matrix (the first numColumns columns). */
template <unsigned K>
OSGACTOR_SKIN_INLINE void blendColumns(const glm::mat4* matrices, const std::uint16_t* joints, const float* weights,
                                       unsigned numColumns, Float4* columns)
{
    for (unsigned c = 0; c < numColumns; ++c) columns[c] = loadFloat4(&matrices[joints[0]][c][0]) * weights[0];
    for (unsigned k = 1; k < K; ++k)
        for (unsigned c = 0; c < numColumns; ++c) columns[c] += loadFloat4(&matrices[joints[k]][c][0]) * weights[k];
}

/** Linear blend skinning, normals by the blended matrix's linear part. */
struct LinearBlend
{
    const glm::mat4* matrices;

    template <unsigned K>
    OSGACTOR_SKIN_INLINE void operator()(const std::uint16_t* joints, const float* weights, VertexTransform& t) const
    {
        if (K == 1)
            loadColumns(matrices[joints[0]], 4, t.point);
        else
            blendColumns<K>(matrices, joints, weights, 4, t.point);
        for (unsigned c = 0; c < 3; ++c) t.tangent[c] = t.normal[c] = t.point[c];
    }
};

/** Linear blend skinning, normals by the blend of the joints' inverse-transposed linear parts. */
struct LinearBlendInverseTranspose
{
    const glm::mat4* matrices;
    const glm::mat4* normalMatrices;

    template <unsigned K>
    OSGACTOR_SKIN_INLINE void operator()(const std::uint16_t* joints, const float* weights, VertexTransform& t) const
    {
        LinearBlend{matrices}.operator()<K>(joints, weights, t);
        blendColumns<K>(normalMatrices, joints, weights, 3, t.normal);
    }
};

/** Dual-quaternion skinning: the normalised blend of the joints' unit dual quaternions as a rigid matrix. */
struct DualQuaternionBlend
{
    const SkinDualQuaternion* dualQuaternions;
    float bindScale;

    static OSGACTOR_SKIN_INLINE Float4 load(const glm::quat& q) { return makeFloat4(q.x, q.y, q.z, q.w); }

    template <unsigned K>
    OSGACTOR_SKIN_INLINE void operator()(const std::uint16_t* joints, const float* weights, VertexTransform& t) const
    {
        const SkinDualQuaternion& first = dualQuaternions[joints[0]];
        const Float4 firstReal = load(first.real);
        Float4 real = firstReal * weights[0];
        Float4 dual = load(first.dual) * weights[0];
        for (unsigned k = 1; k < K; ++k)
        {
            // q and -q are the same rotation; blend each joint's on the first joint's hemisphere, so that the
            // blend takes the short way between them.
            const SkinDualQuaternion& q = dualQuaternions[joints[k]];
            const Float4 qReal = load(q.real);
            const float weight = skin::dot4(qReal, firstReal) < 0.0f ? -weights[k] : weights[k];
            real += qReal * weight;
            dual += load(q.dual) * weight;
        }
        // Normalise by the real part's length (the dual part's component along the real part does not affect the
        // translation formula below).
        const float inverseLength = 1.0f / std::sqrt(skin::dot4(real, real));
        real = real * inverseLength;
        dual = dual * inverseLength;
        const float x = real[0], y = real[1], z = real[2], w = real[3];
        const float dx = dual[0], dy = dual[1], dz = dual[2], dw = dual[3];
        // The rotation matrix of the unit quaternion (x, y, z, w), column by column.
        t.normal[0] = makeFloat4(1.0f - 2.0f * (y * y + z * z), 2.0f * (x * y + w * z), 2.0f * (x * z - w * y), 0.0f);
        t.normal[1] = makeFloat4(2.0f * (x * y - w * z), 1.0f - 2.0f * (x * x + z * z), 2.0f * (y * z + w * x), 0.0f);
        t.normal[2] = makeFloat4(2.0f * (x * z + w * y), 2.0f * (y * z - w * x), 1.0f - 2.0f * (x * x + y * y), 0.0f);
        // translation = 2 (dual real*), vector part: 2 (w d - dw r + r x d) with r = (x, y, z), d = (dx, dy, dz).
        t.point[3] = makeFloat4(2.0f * (w * dx - dw * x + (y * dz - z * dy)), 2.0f * (w * dy - dw * y + (z * dx - x * dz)),
                                2.0f * (w * dz - dw * z + (x * dy - y * dx)), 1.0f);
        for (unsigned c = 0; c < 3; ++c)
        {
            t.tangent[c] = t.normal[c];
            t.point[c] = t.normal[c] * bindScale;
        }
    }
};

OSGACTOR_SKIN_INLINE Float4 transformPoint(const Float4* columns, const glm::vec3& p)
{
    return columns[0] * p.x + columns[1] * p.y + columns[2] * p.z + columns[3];
}

OSGACTOR_SKIN_INLINE Float4 transformVector(const Float4* columns, float x, float y, float z)
{
    return columns[0] * x + columns[1] * y + columns[2] * z;
}

template <unsigned K, bool Normals, bool Tangents, class Blend>
OSGACTOR_SKIN_INLINE void skinGroup(const Group& group, const Outputs& out, const Blend& blend)
{
    const std::uint16_t* __restrict joints = group.joints;
    const float* __restrict weights = group.weights;
    for (std::size_t v = 0; v < group.count; ++v, joints += K, weights += K)
    {
        VertexTransform t;
        blend.template operator()<K>(joints, weights, t);
        const std::uint32_t at = group.outputIndices[v];
        const Float4 position = transformPoint(t.point, group.positions[v]);
        out.positions[at] = glm::vec3(position[0], position[1], position[2]);
        if (Normals)
        {
            const glm::vec3& n = group.normals[v];
            const Float4 normal = transformVector(t.normal, n.x, n.y, n.z);
            out.normals[at] = glm::vec3(normal[0], normal[1], normal[2]);
        }
        if (Tangents)
        {
            const glm::vec4& bindTangent = group.tangents[v];
            const Float4 tangent = transformVector(t.tangent, bindTangent.x, bindTangent.y, bindTangent.z);
            out.tangents[at] = glm::vec4(tangent[0], tangent[1], tangent[2], bindTangent.w);
        }
    }
}

template <bool Normals, bool Tangents, class Blend>
OSGACTOR_SKIN_INLINE void skinGroupOf(unsigned influences, const Group& group, const Outputs& out, const Blend& blend)
{
    switch (influences)
    {
    case 1: skinGroup<1, Normals, Tangents>(group, out, blend); break;
    case 2: skinGroup<2, Normals, Tangents>(group, out, blend); break;
    case 3: skinGroup<3, Normals, Tangents>(group, out, blend); break;
    case 4: skinGroup<4, Normals, Tangents>(group, out, blend); break;
    case 5: skinGroup<5, Normals, Tangents>(group, out, blend); break;
    case 6: skinGroup<6, Normals, Tangents>(group, out, blend); break;
    case 7: skinGroup<7, Normals, Tangents>(group, out, blend); break;
    default: skinGroup<8, Normals, Tangents>(group, out, blend); break;
    }
}

/** What is skinned: positions only, with normals, or with normals and tangents. */
enum class Attributes { Positions, Normals, NormalsAndTangents };

template <class Blend>
OSGACTOR_SKIN_INLINE void skinAny(Attributes attributes, unsigned influences, const Group& group, const Outputs& out,
                                  const Blend& blend)
{
    switch (attributes)
    {
    case Attributes::Positions: skinGroupOf<false, false>(influences, group, out, blend); break;
    case Attributes::Normals: skinGroupOf<true, false>(influences, group, out, blend); break;
    case Attributes::NormalsAndTangents: skinGroupOf<true, true>(influences, group, out, blend); break;
    }
}

// One entry point per blend, each built for x86-64-v3 and the baseline (OSGACTOR_HOT_PATH), with every loop
// variant inlined into it.
OSGACTOR_HOT_PATH void skinLinear(Attributes attributes, unsigned influences, const Group& group, const Outputs& out,
                                  const LinearBlend& blend)
{
    skinAny(attributes, influences, group, out, blend);
}

OSGACTOR_HOT_PATH void skinLinearInverseTranspose(Attributes attributes, unsigned influences, const Group& group,
                                                  const Outputs& out, const LinearBlendInverseTranspose& blend)
{
    skinAny(attributes, influences, group, out, blend);
}

OSGACTOR_HOT_PATH void skinDualQuaternion(Attributes attributes, unsigned influences, const Group& group,
                                          const Outputs& out, const DualQuaternionBlend& blend)
{
    skinAny(attributes, influences, group, out, blend);
}

/** The largest element of a run of indices, or -1 for none (a plain loop the compiler vectorises). */
template <class Index>
long long largestOf(Span<const Index> indices)
{
    Index largest = 0;
    for (const Index index : indices) largest = index > largest ? index : largest;
    return indices.empty() ? -1 : static_cast<long long>(largest);
}

} // namespace

bool SkinningJob::validate() const
{
    const std::size_t n = vertices.size();
    std::size_t counted = 0;
    std::size_t influences = 0;
    for (unsigned k = 1; k <= kMaxSkinInfluences; ++k)
    {
        counted += vertices.counts[k - 1];
        influences += std::size_t(vertices.counts[k - 1]) * k;
    }
    if (counted != n || vertices.outputIndices.size() != n) return false;
    if (vertices.joints.size() != influences || vertices.weights.size() != influences) return false;
    if (!vertices.normals.empty() && vertices.normals.size() != n) return false;
    if (!vertices.tangents.empty() && vertices.tangents.size() != n) return false;

    if (positions.empty()) return false;
    if (!normals.empty() && vertices.normals.empty()) return false;
    if (!tangents.empty() && (vertices.tangents.empty() || normals.empty())) return false;
    std::size_t outputSize = positions.size();
    if (!normals.empty() && normals.size() < outputSize) outputSize = normals.size();
    if (!tangents.empty() && tangents.size() < outputSize) outputSize = tangents.size();
    if (largestOf(vertices.outputIndices) >= static_cast<long long>(outputSize)) return false;

    std::size_t numJoints = 0;
    if (method == SkinningMethod::LinearBlend)
    {
        if (!normalMatrices.empty() && normalMatrices.size() != matrices.size()) return false;
        numJoints = matrices.size();
    }
    else
    {
        if (!(std::isfinite(bindScale) && bindScale > 0.0f)) return false;
        numJoints = dualQuaternions.size();
    }
    return largestOf(vertices.joints) < static_cast<long long>(numJoints) && (numJoints > 0 || n == 0);
}

bool SkinningJob::run() const
{
    if (!validate()) return false;
    const Attributes attributes = tangents.empty()
                                      ? (normals.empty() ? Attributes::Positions : Attributes::Normals)
                                      : Attributes::NormalsAndTangents;
    const Outputs out{positions.data(), normals.data(), tangents.data()};
    std::size_t first = 0;
    std::size_t firstInfluence = 0;
    for (unsigned k = 1; k <= kMaxSkinInfluences; ++k)
    {
        const std::size_t count = vertices.counts[k - 1];
        if (count == 0) continue;
        const Group group{count,
                          vertices.positions.data() + first,
                          vertices.normals.empty() ? nullptr : vertices.normals.data() + first,
                          vertices.tangents.empty() ? nullptr : vertices.tangents.data() + first,
                          vertices.outputIndices.data() + first,
                          vertices.joints.data() + firstInfluence,
                          vertices.weights.data() + firstInfluence};
        if (method == SkinningMethod::DualQuaternion)
            skinDualQuaternion(attributes, k, group, out, DualQuaternionBlend{dualQuaternions.data(), bindScale});
        else if (!normalMatrices.empty() && attributes != Attributes::Positions)
            skinLinearInverseTranspose(attributes, k, group, out,
                                       LinearBlendInverseTranspose{matrices.data(), normalMatrices.data()});
        else
            skinLinear(attributes, k, group, out, LinearBlend{matrices.data()});
        first += count;
        firstInfluence += count * k;
    }
    return true;
}

} // namespace osgActor
