#include <osgActor/core/skin/SkinBoundsJob>

#include "../detail/HotPath.h"
#include "Float4.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace osgActor {

namespace {

/** The margin around the bound, relative to the size of the numbers SkinningJob adds: its float rounding is a small
  * multiple of 2^-24 of them, far below this. */
constexpr float kRoundingMargin = 1e-5f;

OSGACTOR_SKIN_INLINE float largestAbs(const glm::vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/** The model-space axis-aligned box around a joint box moved by m, an affine map (or a difference of two, whose
  * bottom row is zero): the box's centre moves as a point, and its half-size along model axis r is the sum over the
  * box's axes c of |(m boxToBind)[c][r]| halfSize[c]. Only the 3x3 and translation parts are multiplied. */
OSGACTOR_SKIN_INLINE SkinBox boxAround(const glm::mat4& m, const SkinJointBox& joint)
{
    const glm::mat3 linear(m);
    const glm::vec3 boxCentre = 0.5f * (joint.box.min + joint.box.max);
    const glm::vec3 halfSize = 0.5f * (joint.box.max - joint.box.min);
    const glm::vec3 bindCentre = glm::vec3(joint.boxToBind[3]) + glm::mat3(joint.boxToBind) * boxCentre;
    const glm::vec3 centre = glm::vec3(m[3]) + linear * bindCentre;
    glm::vec3 reach(0.0f);
    for (int c = 0; c < 3; ++c) reach += glm::abs(linear * glm::vec3(joint.boxToBind[c])) * halfSize[c];
    SkinBox moved;
    moved.min = centre - reach;
    moved.max = centre + reach;
    return moved;
}

/** The largest absolute row sum of the matrix's linear part: how much it can lengthen a vector's largest
  * coordinate. */
OSGACTOR_SKIN_INLINE float rowSumNorm(const glm::mat4& m)
{
    return std::max({std::abs(m[0][0]) + std::abs(m[1][0]) + std::abs(m[2][0]),
                     std::abs(m[0][1]) + std::abs(m[1][1]) + std::abs(m[2][1]),
                     std::abs(m[0][2]) + std::abs(m[1][2]) + std::abs(m[2][2])});
}

/** The farthest a point of the box can be from the bind-space origin, coordinate-wise (at most). */
OSGACTOR_SKIN_INLINE float bindReachOf(const SkinJointBox& joint)
{
    const glm::vec3 halfSize = 0.5f * (joint.box.max - joint.box.min);
    const glm::vec3 centre = glm::vec3(joint.boxToBind[3]) + glm::mat3(joint.boxToBind) * (0.5f * (joint.box.min + joint.box.max));
    return largestAbs(centre) + halfSize.x + halfSize.y + halfSize.z;
}

/** The rotation between two skinning matrices that share a uniform scale s: the cosine of its angle, from
  * trace(La^T Lk) = s^2 (1 + 2 cos angle). */
OSGACTOR_SKIN_INLINE float cosineBetween(const glm::mat4& a, const glm::mat4& k, float scaleSquared)
{
    float trace = 0.0f;
    for (int c = 0; c < 3; ++c) trace += glm::dot(glm::vec3(a[c]), glm::vec3(k[c]));
    return glm::clamp(0.5f * (trace / scaleSquared - 1.0f), -1.0f, 1.0f);
}

/** How far from M_a v dual-quaternion skinning can take a vertex v of the set (see SkinBoundsJob):
  * 2 sin(phi / 2) s r + sum_k W_k tau_k / m. */
OSGACTOR_SKIN_INLINE float dualQuaternionReachOf(const glm::mat4& ma, const SkinBlendSet& set, Span<const std::uint32_t> setJoints,
                            Span<const float> setWeights, Span<const glm::mat4> matrices)
{
    const float scale = glm::length(glm::vec3(ma[0]));
    const glm::vec3 centre = glm::vec3(ma * glm::vec4(set.centre, 1.0f));
    float scalarLoss = 0.0f;  // sum_k W_k (1 - cos(theta_k / 2))
    float vectorPart = 0.0f;  // sum_k W_k sin(theta_k / 2)
    float displacement = 0.0f; // sum_k W_k tau_k
    for (std::uint32_t i = 1; i < set.numJoints; ++i)
    {
        const glm::mat4& mk = matrices[setJoints[set.firstJoint + i]];
        const float weight = setWeights[set.firstJoint + i];
        const float cosine = cosineBetween(ma, mk, scale * scale);
        scalarLoss += weight * (1.0f - std::sqrt(0.5f * (1.0f + cosine)));
        vectorPart += weight * std::sqrt(0.5f * (1.0f - cosine));
        displacement += weight * glm::length(glm::vec3(mk * glm::vec4(set.centre, 1.0f)) - centre);
    }
    const float m = std::max(1.0f - scalarLoss, setWeights[set.firstJoint]);
    // sin(phi / 2) from tan(phi / 2) = vectorPart / m.
    const float tangent = vectorPart / m;
    const float sinePhi = tangent / std::sqrt(1.0f + tangent * tangent);
    return 2.0f * sinePhi * scale * set.radius + displacement / m;
}

} // namespace

SkinBoundsJob makeSkinBoundsJob(const Skin& skin)
{
    SkinBoundsJob job;
    job.method = skin.getMethod();
    job.blendSets = skin.getBlendSets();
    job.blendSetJoints = skin.getBlendSetJoints();
    job.blendSetWeights = skin.getBlendSetWeights();
    return job;
}

bool SkinBoundsJob::validate() const
{
    if (bound == nullptr) return false;
    if (blendSetWeights.size() != blendSetJoints.size()) return false;
    for (const SkinBlendSet& set : blendSets)
    {
        if (set.numJoints == 0 || set.numJoints > kMaxSkinInfluences || set.firstJoint > blendSetJoints.size() ||
            set.numJoints > blendSetJoints.size() - set.firstJoint)
            return false;
        for (std::uint32_t i = 0; i < set.numJoints; ++i)
            if (blendSetJoints[set.firstJoint + i] >= matrices.size()) return false;
    }
    return true;
}

namespace {

/** A piece's box moved by M_a and widened by how far linear blending can take its vertices past M_a v along each
  * model axis, per side (see SkinBoundsJob): the largest sum_k w_k d_k over 0 <= w_k <= W_k with
  * sum_k w_k <= 1 - W_a, d_k that side of the box around (M_k - M_a) B; the largest d_k filled first. The box around
  * (M_k - M_a) B is computed from each joint's own products with B's centre and half-axes (the map is linear). */
OSGACTOR_SKIN_INLINE SkinBox linearBlendBoxOf(const SkinBlendSet& set, Span<const std::uint32_t> setJoints,
                                              Span<const float> setWeights, Span<const glm::mat4> matrices)
{
    const SkinJointBox& box = set.box;
    const glm::vec3 halfSize = 0.5f * (box.box.max - box.box.min);
    const glm::vec3 bindCentre = glm::vec3(box.boxToBind[3]) + glm::mat3(box.boxToBind) * (0.5f * (box.box.min + box.box.max));
    const glm::vec3 halfAxes[3] = {glm::vec3(box.boxToBind[0]) * halfSize.x, glm::vec3(box.boxToBind[1]) * halfSize.y,
                                   glm::vec3(box.boxToBind[2]) * halfSize.z};
    const glm::mat4& ma = matrices[setJoints[set.firstJoint]];
    const glm::mat3 la(ma);
    const glm::vec3 centreA = glm::vec3(ma[3]) + la * bindCentre;
    const glm::vec3 axesA[3] = {la * halfAxes[0], la * halfAxes[1], la * halfAxes[2]};
    const glm::vec3 reachA = glm::abs(axesA[0]) + glm::abs(axesA[1]) + glm::abs(axesA[2]);
    SkinBox moved;
    moved.min = centreA - reachA;
    moved.max = centreA + reachA;
    const std::uint32_t others = set.numJoints - 1;
    if (others == 0) return moved;

    // Per other joint, the box around (M_k - M_a) B: its low and high sides.
    glm::vec3 lows[kMaxSkinInfluences], highs[kMaxSkinInfluences];
    for (std::uint32_t i = 0; i < others; ++i)
    {
        const glm::mat4& mk = matrices[setJoints[set.firstJoint + 1 + i]];
        const glm::mat3 lk(mk);
        const glm::vec3 centre = glm::vec3(mk[3]) + lk * bindCentre - centreA;
        const glm::vec3 reach = glm::abs(lk * halfAxes[0] - axesA[0]) + glm::abs(lk * halfAxes[1] - axesA[1]) +
                                glm::abs(lk * halfAxes[2] - axesA[2]);
        lows[i] = centre - reach;
        highs[i] = centre + reach;
    }
    // Weights sum to 1 within float rounding: what the others may have, rounded up by as much.
    const float budget = std::max(0.0f, 1.0f - setWeights[set.firstJoint]) + 4.0f * std::numeric_limits<float>::epsilon();
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side)
        {
            // Each other joint's gain along this side (only positive gains are worth a weight), largest first.
            float gains[kMaxSkinInfluences];
            float caps[kMaxSkinInfluences];
            std::uint32_t count = 0;
            for (std::uint32_t i = 0; i < others; ++i)
            {
                const float gain = side == 1 ? highs[i][axis] : -lows[i][axis];
                if (!(gain > 0.0f)) continue;
                std::uint32_t at = count++;
                for (; at > 0 && gains[at - 1] < gain; --at) gains[at] = gains[at - 1], caps[at] = caps[at - 1];
                gains[at] = gain;
                caps[at] = setWeights[set.firstJoint + 1 + i];
            }
            float left = budget, sum = 0.0f;
            for (std::uint32_t i = 0; i < count && left > 0.0f; ++i)
            {
                const float weight = std::min(left, caps[i]);
                sum += weight * gains[i];
                left -= weight;
            }
            if (side == 1) moved.max[axis] += sum;
            else moved.min[axis] -= sum;
        }
    return moved;
}

/** run()'s work, built for x86-64-v3 and the baseline (OSGACTOR_HOT_PATH): per piece, a few small matrix
  * products. */
OSGACTOR_HOT_PATH SkinBox computeBound(const SkinBoundsJob& job)
{
    const Span<const SkinBlendSet> blendSets = job.blendSets;
    const Span<const std::uint32_t> blendSetJoints = job.blendSetJoints;
    const Span<const float> blendSetWeights = job.blendSetWeights;
    const Span<const glm::mat4> matrices = job.matrices;
    SkinBox result;
    float bindReach = 0.0f; // over every piece, so over every vertex
    for (const SkinBlendSet& set : blendSets)
    {
        if (set.box.box.isEmpty()) continue;
        bindReach = std::max(bindReach, bindReachOf(set.box));
        SkinBox box;
        if (job.method == SkinningMethod::DualQuaternion)
        {
            const glm::mat4& first = matrices[blendSetJoints[set.firstJoint]];
            const glm::vec3 reach(dualQuaternionReachOf(first, set, blendSetJoints, blendSetWeights, matrices));
            box = boxAround(first, set.box);
            box.min -= reach;
            box.max += reach;
        }
        else
        {
            box = linearBlendBoxOf(set, blendSetJoints, blendSetWeights, matrices);
        }
        const bool empty = result.isEmpty();
        result.min = empty ? box.min : glm::min(result.min, box.min);
        result.max = empty ? box.max : glm::max(result.max, box.max);
    }
    if (!result.isEmpty())
    {
        // How large the numbers SkinningJob adds can be: a joint's translation plus its linear part applied to the
        // farthest bind position.
        float translation = 0.0f, linear = 0.0f;
        for (const glm::mat4& m : matrices)
        {
            translation = std::max(translation, largestAbs(glm::vec3(m[3])));
            linear = std::max(linear, rowSumNorm(m));
        }
        const glm::vec3 margin(kRoundingMargin * (translation + linear * bindReach));
        result.min -= margin;
        result.max += margin;
    }
    return result;
}

} // namespace

bool SkinBoundsJob::run() const
{
    if (!validate()) return false;
    *bound = computeBound(*this);
    return true;
}

} // namespace osgActor
