#include <osgActor/core/skin/SkinningJob>

#include "../detail/HotPath.h"
#include "Float4.h"
#include "IndexScan.h"

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

/** columns = sum over the vertex's K influences of weight x matrix (the first numColumns columns). Summed as two
  * halves (even and odd influences) added at the end: half the chain of dependent additions, so that more vertices
  * are in flight at once. */
template <unsigned K>
OSGACTOR_SKIN_INLINE void blendColumns(const glm::mat4* matrices, const std::uint16_t* joints, const float* weights,
                                       unsigned numColumns, Float4* columns)
{
    Float4 odd[4];
    for (unsigned c = 0; c < numColumns; ++c) columns[c] = loadFloat4(&matrices[joints[0]][c][0]) * weights[0];
    for (unsigned c = 0; c < numColumns; ++c) odd[c] = loadFloat4(&matrices[joints[1]][c][0]) * weights[1];
    for (unsigned k = 2; k < K; ++k)
    {
        Float4* sum = k % 2 == 0 ? columns : odd;
        for (unsigned c = 0; c < numColumns; ++c) sum[c] += loadFloat4(&matrices[joints[k]][c][0]) * weights[k];
    }
    for (unsigned c = 0; c < numColumns; ++c) columns[c] += odd[c];
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
            const float weight = std::copysign(weights[k], skin::dot4(qReal, firstReal));
            real += qReal * weight;
            dual += load(q.dual) * weight;
        }
        // The blend is normalised by dividing by the real part's length; every entry of the rotation matrix and the
        // translation is a product of two parts, so one division by the squared length does it all (no square root).
        const float s = 2.0f / skin::dot4(real, real);
        // The rotation matrix of the blend q = (x, y, z, w) normalised, column by column, with s = 2 / |q|^2; each
        // entry's products come from lanes picked from q and -q (the fourth lanes are unused):
        //   column 0: 1 - s (y y + z z),  s (x y + w z),      s (x z - w y)
        //   column 1: s (x y - w z),      1 - s (x x + z z),  s (y z + w x)
        //   column 2: s (x z + w y),      s (y z - w x),      1 - s (x x + y y)
        using skin::shuffle;
        const Float4& q = real;
        const Float4 n = -real;
        t.normal[0] = skin::makeFloat4(1.0f, 0.0f, 0.0f, 0.0f) +
                      s * (shuffle<5, 0, 0, 3>(q, n) * shuffle<1, 1, 2, 3>(q, n) +
                           shuffle<6, 3, 7, 3>(q, n) * shuffle<2, 2, 1, 3>(q, n));
        t.normal[1] = skin::makeFloat4(0.0f, 1.0f, 0.0f, 0.0f) +
                      s * (shuffle<1, 4, 1, 3>(q, n) * shuffle<0, 0, 2, 3>(q, n) +
                           shuffle<7, 6, 3, 3>(q, n) * shuffle<2, 2, 0, 3>(q, n));
        t.normal[2] = skin::makeFloat4(0.0f, 0.0f, 1.0f, 0.0f) +
                      s * (shuffle<2, 2, 4, 3>(q, n) * shuffle<0, 1, 0, 3>(q, n) +
                           shuffle<3, 7, 5, 3>(q, n) * shuffle<1, 0, 1, 3>(q, n));
        // translation = 2 (dual real*) / |q|^2, vector part: s (w d - dw r + r x d), with r and d the vector parts
        // of real and dual, and r x d = r.yzx d.zxy - r.zxy d.yzx.
        const Float4 cross = shuffle<1, 2, 0, 3>(q, q) * shuffle<2, 0, 1, 3>(dual, dual) -
                             shuffle<2, 0, 1, 3>(q, q) * shuffle<1, 2, 0, 3>(dual, dual);
        t.point[3] = s * (dual * q[3] - q * dual[3] + cross);
        t.point[3][3] = 1.0f;
        for (unsigned c = 0; c < 3; ++c)
        {
            t.tangent[c] = t.normal[c];
            t.point[c] = t.normal[c] * bindScale;
        }
    }
};

// Both sum in pairs, for a shorter chain of dependent operations than left to right.
OSGACTOR_SKIN_INLINE Float4 transformPoint(const Float4* columns, const glm::vec3& p)
{
    return (columns[0] * p.x + columns[3]) + (columns[1] * p.y + columns[2] * p.z);
}

OSGACTOR_SKIN_INLINE Float4 transformVector(const Float4* columns, float x, float y, float z)
{
    return columns[0] * x + (columns[1] * y + columns[2] * z);
}

/** Writes vertex v's outputs, moved by t. */
template <bool Normals, bool Tangents>
OSGACTOR_SKIN_INLINE void writeVertex(const Group& group, const Outputs& out, std::size_t v, const VertexTransform& t)
{
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

template <unsigned K, bool Normals, bool Tangents, class Blend>
OSGACTOR_SKIN_INLINE void skinGroup(const Group& group, const Outputs& out, const Blend& blend)
{
    const std::uint16_t* __restrict joints = group.joints;
    const float* __restrict weights = group.weights;
    for (std::size_t v = 0; v < group.count; ++v, joints += K, weights += K)
    {
        VertexTransform t;
        blend.template operator()<K>(joints, weights, t);
        writeVertex<Normals, Tangents>(group, out, v, t);
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

OSGACTOR_HOT_PATH long long largestOf(Span<const std::uint16_t> indices)
{
    return skin::largestIndexOf(indices.data(), indices.size());
}

OSGACTOR_HOT_PATH long long largestOf(Span<const std::uint32_t> indices)
{
    return skin::largestIndexOf(indices.data(), indices.size());
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
