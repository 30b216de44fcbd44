#include <osgActor/core/skin/SkinBoundsJob>

#include "../detail/HotPath.h"
#include "Float8.h"
#include "IndexScan.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace osgActor {

namespace {

/** The margin around the bound, relative to the size S of the numbers SkinningJob adds (a joint's translation plus
  * its linear part applied to the farthest bind position). SkinningJob's float rounding is a small multiple of 2^-24
  * S (a sum of at most 8 weighted products), and so is the bound's own: each side is a few sums of products of
  * numbers at most 2 S (the differences M_k - M_a) and weights at most 1, done in float on either path, one piece
  * at a time or eight at once, with or without fused multiply-adds. Together they stay far below this, about 170
  * times 2^-24. */
constexpr float kRoundingMargin = 1e-5f;

/** How many pieces a group holds: the lanes of SkinBoundsJob's eight-float vectors. */
constexpr unsigned kLanes = kSkinBlendSetGroupSize;

OSGACTOR_SKIN_INLINE float largestAbs(const glm::vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

/** A joint box as the per-frame arithmetic reads it: the centre of the box in bind space, and its half axes (the
  * direction of each of the box's axes in bind space times its half size), model units. */
struct BindFrame
{
    glm::vec3 centre;
    glm::vec3 halfAxes[3];
};

OSGACTOR_SKIN_INLINE BindFrame bindFrameOf(const SkinJointBox& joint)
{
    const glm::vec3 halfSize = 0.5f * (joint.box.max - joint.box.min);
    BindFrame frame;
    frame.centre = glm::vec3(joint.boxToBind[3]) + glm::mat3(joint.boxToBind) * (0.5f * (joint.box.min + joint.box.max));
    for (int c = 0; c < 3; ++c) frame.halfAxes[c] = glm::vec3(joint.boxToBind[c]) * halfSize[c];
    return frame;
}

/** How much weight the joints after a piece's first may share, given the first's smallest weight: weights sum to 1
  * within float rounding, so the rest is rounded up by as much. */
OSGACTOR_SKIN_INLINE float otherJointsBudget(float firstWeight)
{
    return std::max(0.0f, 1.0f - firstWeight) + 4.0f * std::numeric_limits<float>::epsilon();
}

/** The model-space axis-aligned box around a joint box moved by m, an affine map (or a difference of two, whose
  * bottom row is zero): the box's centre moves as a point, and its half-size along model axis r is the sum over the
  * box's axes c of |(m boxToBind)[c][r]| halfSize[c]. Only the 3x3 and translation parts are multiplied. */
OSGACTOR_SKIN_INLINE SkinBox boxAround(const glm::mat4& m, const SkinJointBox& joint)
{
    const glm::mat3 linear(m);
    const BindFrame frame = bindFrameOf(joint);
    const glm::vec3 centre = glm::vec3(m[3]) + linear * frame.centre;
    glm::vec3 reach(0.0f);
    for (int c = 0; c < 3; ++c) reach += glm::abs(linear * frame.halfAxes[c]);
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
    return largestAbs(bindFrameOf(joint).centre) + halfSize.x + halfSize.y + halfSize.z;
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
    job.blendSetGroups = skin.getBlendSetGroups();
    return job;
}

namespace {

/** validate()'s scans, built for x86-64-v3 and the baseline (OSGACTOR_HOT_PATH) as they run every frame: every
  * piece's joints within the joint list, and every joint of the list and of the groups within the matrices. */
OSGACTOR_HOT_PATH bool piecesFit(const SkinBoundsJob& job)
{
    const std::size_t listed = job.blendSetJoints.size();
    bool fit = true;
    for (const SkinBlendSet& set : job.blendSets)
        fit &= (set.numJoints - 1u < kMaxSkinInfluences) & (set.firstJoint <= listed) &
               (set.numJoints <= listed - set.firstJoint); // unsigned: wraps past the end, caught by the previous
    const long long numMatrices = static_cast<long long>(job.matrices.size());
    fit &= skin::largestIndexOf(job.blendSetJoints.data(), listed) < numMatrices;
    for (const SkinBlendSetGroup& group : job.blendSetGroups)
        fit &= skin::largestIndexOf(&group.joints[0][0], kSkinBlendSetGroupJoints * kSkinBlendSetGroupSize) < numMatrices;
    return fit;
}

} // namespace

bool SkinBoundsJob::validate() const
{
    if (bound == nullptr) return false;
    if (blendSetWeights.size() != blendSetJoints.size()) return false;
    return piecesFit(*this);
}

namespace {

/** Writes a piece (with at most kSkinBlendSetGroupJoints joints) into one lane of a group. */
void putInLane(SkinBlendSetGroup& group, unsigned lane, const SkinBlendSet& set, Span<const std::uint32_t> setJoints,
               Span<const float> setWeights)
{
    const BindFrame frame = bindFrameOf(set.box);
    for (int r = 0; r < 3; ++r)
    {
        group.centre[r][lane] = frame.centre[r];
        for (int c = 0; c < 3; ++c) group.halfAxes[c][r][lane] = frame.halfAxes[c][r];
    }
    const std::uint32_t first = setJoints[set.firstJoint];
    group.budget[lane] = otherJointsBudget(setWeights[set.firstJoint]);
    group.joints[0][lane] = first;
    for (unsigned slot = 1; slot < kSkinBlendSetGroupJoints; ++slot)
    {
        // A slot the piece does not use: its first joint again, which may take no weight.
        const bool used = slot < set.numJoints;
        group.joints[slot][lane] = used ? setJoints[set.firstJoint + slot] : first;
        group.caps[slot - 1][lane] = used ? setWeights[set.firstJoint + slot] : 0.0f;
    }
    group.bindReach = std::max(group.bindReach, bindReachOf(set.box));
}

} // namespace

std::vector<SkinBlendSetGroup> groupSkinBlendSets(Span<const SkinBlendSet> sets, Span<const std::uint32_t> setJoints,
                                                  Span<const float> setWeights)
{
    std::vector<const SkinBlendSet*> groupable;
    for (const SkinBlendSet& set : sets)
        if (set.numJoints <= kSkinBlendSetGroupJoints && !set.box.box.isEmpty()) groupable.push_back(&set);
    std::vector<SkinBlendSetGroup> groups((groupable.size() + kLanes - 1) / kLanes);
    for (SkinBlendSetGroup& group : groups) group.bindReach = 0.0f;
    for (std::size_t at = 0; at < groups.size() * kLanes; ++at)
    {
        // The last group's lanes past the last piece: copies of that group's first.
        const std::size_t piece = at < groupable.size() ? at : at / kLanes * kLanes;
        putInLane(groups[at / kLanes], unsigned(at % kLanes), *groupable[piece], setJoints, setWeights);
    }
    return groups;
}

namespace {

/** A piece's box moved by M_a and widened by how far linear blending can take its vertices past M_a v along each
  * model axis, per side (see SkinBoundsJob): the largest sum_k w_k d_k over 0 <= w_k <= W_k with
  * sum_k w_k <= 1 - W_a, d_k that side of the box around (M_k - M_a) B; the largest d_k filled first. The box around
  * (M_k - M_a) B is computed from each joint's own products with B's centre and half-axes (the map is linear). */
OSGACTOR_SKIN_INLINE SkinBox linearBlendBoxOf(const SkinBlendSet& set, Span<const std::uint32_t> setJoints,
                                              Span<const float> setWeights, Span<const glm::mat4> matrices)
{
    const BindFrame frame = bindFrameOf(set.box);
    const glm::vec3& bindCentre = frame.centre;
    const glm::vec3* halfAxes = frame.halfAxes;
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
    const float budget = otherJointsBudget(setWeights[set.firstJoint]);
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

/** A group's skinning matrices, lane by lane: [joint slot][element][lane], the elements the linear part column by
  * column (9), then the translation (3). */
using GroupMatrices = float[kSkinBlendSetGroupJoints][12][kLanes];

/** Fills out from the matrices of a group's joints, four matrix columns of eight lanes at a time: the columns of
  * lanes l and l + 4 side by side in one vector, then a transpose within each half (unpacks and shuffles). */
OSGACTOR_SKIN_INLINE void gatherMatrices(const SkinBlendSetGroup& group, const glm::mat4* matrices, GroupMatrices& out)
{
    static_assert(kLanes == 8, "two halves of four lanes");
    using skin::Float8;
    for (unsigned slot = 0; slot < kSkinBlendSetGroupJoints; ++slot)
    {
        const float* m[kLanes];
        for (unsigned lane = 0; lane < kLanes; ++lane) m[lane] = &matrices[group.joints[slot][lane]][0][0];
        for (int c = 0; c < 4; ++c)
        {
            Float8 v[4]; // rows 0-3 of column c: lane i in the low half, lane i + 4 in the high
            for (int i = 0; i < 4; ++i) v[i] = skin::joinFloat4(skin::loadFloat4(m[i] + 4 * c), skin::loadFloat4(m[i + 4] + 4 * c));
            const Float8 rows01Of01 = skin::shuffle8<0, 8, 1, 9, 4, 12, 5, 13>(v[0], v[1]);
            const Float8 rows23Of01 = skin::shuffle8<2, 10, 3, 11, 6, 14, 7, 15>(v[0], v[1]);
            const Float8 rows01Of23 = skin::shuffle8<0, 8, 1, 9, 4, 12, 5, 13>(v[2], v[3]);
            const Float8 rows23Of23 = skin::shuffle8<2, 10, 3, 11, 6, 14, 7, 15>(v[2], v[3]);
            skin::storeFloat8(out[slot][3 * c], skin::shuffle8<0, 1, 8, 9, 4, 5, 12, 13>(rows01Of01, rows01Of23));
            skin::storeFloat8(out[slot][3 * c + 1], skin::shuffle8<2, 3, 10, 11, 6, 7, 14, 15>(rows01Of01, rows01Of23));
            skin::storeFloat8(out[slot][3 * c + 2], skin::shuffle8<0, 1, 8, 9, 4, 5, 12, 13>(rows23Of01, rows23Of23));
        }
    }
}

/** linearBlendBoxOf()'s fill for three other joints, lane by lane with no branch: the largest sum_k w_k g_k over
  * 0 <= w_k <= cap_k, sum_k w_k <= budget (gains >= 0). The greedy fill, largest gain first, gives joint k what the
  * budget leaves once the joints ranked before it (a larger gain, or the same gain and listed first) have their caps,
  * between 0 and its own cap: so each weight comes from three comparisons, with no sort. */
OSGACTOR_SKIN_INLINE skin::Float8 greedyFill(const skin::Float8 (&gains)[3], const skin::Float8 (&caps)[3],
                                             const skin::Float8& budget)
{
    using skin::selectLess;
    const skin::Float8 &g0 = gains[0], &g1 = gains[1], &g2 = gains[2], &c0 = caps[0], &c1 = caps[1], &c2 = caps[2];
    const skin::Float8 zero = skin::splatFloat8(0.0f);
    const skin::Float8 before0 = selectLess(g0, g1, c1, zero) + selectLess(g0, g2, c2, zero);
    const skin::Float8 before1 = selectLess(g0, g1, zero, c0) + selectLess(g1, g2, c2, zero);
    const skin::Float8 before2 = selectLess(g0, g2, zero, c0) + selectLess(g1, g2, zero, c1);
    const skin::Float8 w0 = skin::min8(c0, skin::max8(zero, budget - before0));
    const skin::Float8 w1 = skin::min8(c1, skin::max8(zero, budget - before1));
    const skin::Float8 w2 = skin::min8(c2, skin::max8(zero, budget - before2));
    return w0 * g0 + w1 * g1 + w2 * g2;
}

/** Row r of a joint slot's linear part applied to a bind-space vector given lane by lane (v[coordinate]). */
OSGACTOR_SKIN_INLINE skin::Float8 rowTimes(const float (&m)[12][kLanes], int r, const skin::Float8 (&v)[3])
{
    return skin::loadFloat8(m[r]) * v[0] + skin::loadFloat8(m[3 + r]) * v[1] + skin::loadFloat8(m[6 + r]) * v[2];
}

/** linearBlendBoxOf() on every lane of a group at once, each lane's box joined into low and high (per model
  * axis). */
OSGACTOR_SKIN_INLINE void joinGroupBoxes(const SkinBlendSetGroup& group, const GroupMatrices& m, skin::Float8 (&low)[3],
                                         skin::Float8 (&high)[3])
{
    constexpr unsigned kOthers = kSkinBlendSetGroupJoints - 1;
    static_assert(kOthers == 3, "greedyFill() sorts three gains");
    skin::Float8 centre[3], halfAxes[3][3];
    for (int r = 0; r < 3; ++r)
    {
        centre[r] = skin::loadFloat8(group.centre[r]);
        for (int c = 0; c < 3; ++c) halfAxes[c][r] = skin::loadFloat8(group.halfAxes[c][r]);
    }
    const skin::Float8 budget = skin::loadFloat8(group.budget);
    skin::Float8 caps[kOthers];
    for (unsigned k = 0; k < kOthers; ++k) caps[k] = skin::loadFloat8(group.caps[k]);
    const skin::Float8 zero = skin::splatFloat8(0.0f);
    for (int r = 0; r < 3; ++r)
    {
        // Along model axis r: the box moved by M_a, its centre and the half axes' coordinates, and its reach.
        const skin::Float8 centreA = skin::loadFloat8(m[0][9 + r]) + rowTimes(m[0], r, centre);
        skin::Float8 axesA[3];
        for (int c = 0; c < 3; ++c) axesA[c] = rowTimes(m[0], r, halfAxes[c]);
        const skin::Float8 reachA = skin::abs8(axesA[0]) + skin::abs8(axesA[1]) + skin::abs8(axesA[2]);
        // Per other joint, the gains of the box around (M_k - M_a) B on the high and low sides.
        skin::Float8 up[kOthers], down[kOthers];
        for (unsigned k = 0; k < kOthers; ++k)
        {
            const float(&mk)[12][kLanes] = m[k + 1];
            const skin::Float8 offset = skin::loadFloat8(mk[9 + r]) + rowTimes(mk, r, centre) - centreA;
            const skin::Float8 reach = skin::abs8(rowTimes(mk, r, halfAxes[0]) - axesA[0]) +
                                       skin::abs8(rowTimes(mk, r, halfAxes[1]) - axesA[1]) +
                                       skin::abs8(rowTimes(mk, r, halfAxes[2]) - axesA[2]);
            up[k] = skin::max8(zero, offset + reach);
            down[k] = skin::max8(zero, reach - offset);
        }
        high[r] = skin::max8(high[r], centreA + reachA + greedyFill(up, caps, budget));
        low[r] = skin::min8(low[r], centreA - reachA - greedyFill(down, caps, budget));
    }
}

/** The union of the boxes of every group's pieces (empty for no group); bindReach raised to theirs. */
OSGACTOR_SKIN_INLINE SkinBox groupsBound(Span<const SkinBlendSetGroup> groups, const glm::mat4* matrices, float& bindReach)
{
    SkinBox result;
    if (groups.empty()) return result;
    skin::Float8 low[3], high[3];
    for (int r = 0; r < 3; ++r)
    {
        low[r] = skin::splatFloat8(std::numeric_limits<float>::infinity());
        high[r] = skin::splatFloat8(-std::numeric_limits<float>::infinity());
    }
    GroupMatrices gathered;
    for (const SkinBlendSetGroup& group : groups)
    {
        gatherMatrices(group, matrices, gathered);
        joinGroupBoxes(group, gathered, low, high);
        bindReach = std::max(bindReach, group.bindReach);
    }
    for (int r = 0; r < 3; ++r)
    {
        float lows[kLanes], highs[kLanes];
        skin::storeFloat8(lows, low[r]);
        skin::storeFloat8(highs, high[r]);
        result.min[r] = *std::min_element(lows, lows + kLanes);
        result.max[r] = *std::max_element(highs, highs + kLanes);
    }
    return result;
}

/** run()'s work, built for x86-64-v3 and the baseline (OSGACTOR_HOT_PATH): per piece, a few small matrix
  * products. */
OSGACTOR_HOT_PATH SkinBox computeBound(const SkinBoundsJob& job)
{
    const Span<const SkinBlendSet> blendSets = job.blendSets;
    const Span<const std::uint32_t> blendSetJoints = job.blendSetJoints;
    const Span<const float> blendSetWeights = job.blendSetWeights;
    const Span<const glm::mat4> matrices = job.matrices;
    float bindReach = 0.0f; // over every piece, so over every vertex
    const bool grouped = job.method == SkinningMethod::LinearBlend && !job.blendSetGroups.empty();
    SkinBox result = grouped ? groupsBound(job.blendSetGroups, matrices.data(), bindReach) : SkinBox();
    for (const SkinBlendSet& set : blendSets)
    {
        if ((grouped && set.numJoints <= kSkinBlendSetGroupJoints) || set.box.box.isEmpty()) continue;
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
