#include <osgActor/core/skin/SkinBoundBoxes>

#include <glm/ext/matrix_double3x3.hpp>
#include <glm/ext/vector_double3.hpp>
#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace osgActor {

namespace {

glm::dmat3 eigenvectorsOf(glm::dmat3 a)
{
    glm::dmat3 vectors(1.0);
    for (int sweep = 0; sweep < 32; ++sweep)
    {
        const double offDiagonal = a[1][0] * a[1][0] + a[2][0] * a[2][0] + a[2][1] * a[2][1];
        if (offDiagonal < 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]) || offDiagonal == 0.0)
            break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q)
            {
                if (a[q][p] == 0.0) continue;
                // The rotation in the (p, q) plane that zeroes a[q][p].
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[q][p]);
                const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0);
                const double s = t * c;
                glm::dmat3 rotation(1.0);
                rotation[p][p] = c;
                rotation[q][q] = c;
                rotation[q][p] = s;
                rotation[p][q] = -s;
                a = glm::transpose(rotation) * a * rotation;
                vectors = vectors * rotation;
            }
    }
    return vectors;
}

/** Columns made orthonormal (Gram-Schmidt), right-handed. */
glm::dmat3 orthonormalised(const glm::dmat3& m)
{
    glm::dvec3 x = glm::normalize(m[0]);
    glm::dvec3 y = m[1] - glm::dot(m[1], x) * x;
    y = glm::normalize(y);
    return glm::dmat3(x, y, glm::cross(x, y));
}

struct FrameBox
{
    glm::dmat3 axes{1.0};
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
    double volume = std::numeric_limits<double>::infinity();
};

FrameBox boxInFrame(const glm::dmat3& axes, const std::vector<glm::dvec3>& points)
{
    FrameBox box;
    box.axes = axes;
    const glm::dmat3 toFrame = glm::transpose(axes);
    box.min = box.max = toFrame * points[0];
    for (const glm::dvec3& p : points)
    {
        const glm::dvec3 q = toFrame * p;
        box.min = glm::min(box.min, q);
        box.max = glm::max(box.max, q);
    }
    const glm::dvec3 size = box.max - box.min;
    box.volume = size.x * size.y * size.z;
    return box;
}

bool isUsableFrame(const glm::dmat3& axes)
{
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (!std::isfinite(axes[c][r])) return false;
    return true;
}

/** The smallest of the candidate boxes around one joint's points. */
SkinJointBox smallestBox(const std::vector<glm::dvec3>& points, const glm::dmat4& inverseBind)
{
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& p : points) mean += p;
    mean /= static_cast<double>(points.size());
    glm::dmat3 covariance(0.0);
    for (const glm::dvec3& p : points)
    {
        const glm::dvec3 d = p - mean;
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) covariance[c][r] += d[c] * d[r];
    }
    const glm::dmat3 candidates[3] = {glm::dmat3(1.0), orthonormalised(glm::inverse(glm::dmat3(inverseBind))),
                                      orthonormalised(eigenvectorsOf(covariance))};
    FrameBox best;
    for (const glm::dmat3& axes : candidates)
    {
        if (!isUsableFrame(axes)) continue;
        const FrameBox box = boxInFrame(axes, points);
        if (box.volume < best.volume) best = box;
    }
    // The box's frame has its origin at the box's centre (float keeps the centre's digits once, not in each
    // corner); the half-size is rounded up so that the float box still holds every point.
    const glm::dvec3 centre = best.axes * (0.5 * (best.min + best.max));
    const glm::dvec3 half = 0.5 * (best.max - best.min);
    SkinJointBox result;
    result.boxToBind = glm::mat4(glm::dmat4(best.axes));
    result.boxToBind[3] = glm::vec4(glm::vec3(centre), 1.0f);
    const glm::vec3 halfFloat(half);
    const glm::vec3 halfUp(std::nextafter(halfFloat.x, std::numeric_limits<float>::infinity()),
                           std::nextafter(halfFloat.y, std::numeric_limits<float>::infinity()),
                           std::nextafter(halfFloat.z, std::numeric_limits<float>::infinity()));
    // Widen by the rounding of the frame's float columns and centre too: a few ulps of the points' distance from
    // the bind-space origin.
    const double reach = glm::length(centre) + glm::length(half);
    const float slack = static_cast<float>(4.0 * std::numeric_limits<float>::epsilon() * reach);
    result.box.min = -halfUp - glm::vec3(slack);
    result.box.max = halfUp + glm::vec3(slack);
    return result;
}

} // namespace

SkinBoundBoxes computeSkinBoundBoxes(const SkinVertices& vertices, Span<const glm::dmat4> inverseBindMatrices)
{
    // Per vertex, its first (largest-weight) joint: influences come largest first (the builder's order).
    const std::size_t numJoints = inverseBindMatrices.size();
    std::vector<std::vector<glm::dvec3>> firstOf(numJoints);
    struct Pair
    {
        std::vector<glm::dvec3> points;
        float maxWeight = 0.0f;
    };
    std::vector<std::vector<std::pair<std::uint32_t, Pair>>> pairsOf(numJoints); // per first joint, by other joint
    // Per set of joints (the first joint, then the others in increasing order), its vertices and their largest sum
    // of weights other than the first joint's.
    struct BlendSetPoints
    {
        std::vector<glm::dvec3> points;
        std::vector<float> weights; // per joint of the key: the largest weight (the first joint's smallest)
    };
    std::map<std::vector<std::uint32_t>, BlendSetPoints> sets;
    std::size_t influence = 0;
    std::size_t vertex = 0;
    for (unsigned k = 1; k <= kMaxSkinInfluences; ++k)
        for (std::uint32_t i = 0; i < vertices.counts[k - 1]; ++i, ++vertex, influence += k)
        {
            const glm::dvec3 position(vertices.positions[vertex]);
            const std::uint32_t first = vertices.joints[influence];
            firstOf[first].push_back(position);
            if (k > 1)
            {
                std::vector<std::uint32_t> key(vertices.joints.begin() + influence, vertices.joints.begin() + influence + k);
                std::sort(key.begin() + 1, key.end());
                BlendSetPoints& set = sets[key];
                if (set.weights.empty())
                {
                    set.weights.assign(k, 0.0f);
                    set.weights[0] = 1.0f;
                }
                set.points.push_back(position);
                for (unsigned j = 0; j < k; ++j)
                {
                    const float weight = vertices.weights[influence + j];
                    const std::size_t at = j == 0 ? 0 : std::size_t(std::find(key.begin() + 1, key.end(),
                                                                               vertices.joints[influence + j]) - key.begin());
                    set.weights[at] = j == 0 ? std::min(set.weights[0], weight) : std::max(set.weights[at], weight);
                }
            }
            for (unsigned j = 1; j < k; ++j)
            {
                const std::uint32_t other = vertices.joints[influence + j];
                auto& pairs = pairsOf[first];
                auto found = std::find_if(pairs.begin(), pairs.end(), [&](const auto& p) { return p.first == other; });
                if (found == pairs.end())
                {
                    pairs.emplace_back(other, Pair());
                    found = pairs.end() - 1;
                }
                found->second.points.push_back(position);
                found->second.maxWeight = std::max(found->second.maxWeight, vertices.weights[influence + j]);
            }
        }

    SkinBoundBoxes boxes;
    boxes.joints.resize(numJoints);
    for (std::size_t a = 0; a < numJoints; ++a)
    {
        if (!firstOf[a].empty()) boxes.joints[a] = smallestBox(firstOf[a], inverseBindMatrices[a]);
        std::sort(pairsOf[a].begin(), pairsOf[a].end(), [](const auto& p, const auto& q) { return p.first < q.first; });
        for (const auto& pair : pairsOf[a])
        {
            SkinBlendBox blend;
            blend.joint = static_cast<std::uint32_t>(a);
            blend.other = pair.first;
            blend.maxWeight = pair.second.maxWeight;
            blend.box = smallestBox(pair.second.points, inverseBindMatrices[a]);
            boxes.blends.push_back(blend);
        }
    }
    for (const auto& entry : sets)
    {
        // Centred on the points' box (close enough to the smallest sphere), the radius rounded up.
        const std::vector<glm::dvec3>& points = entry.second.points;
        glm::dvec3 low = points[0], high = points[0];
        for (const glm::dvec3& p : points)
        {
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
        const glm::vec3 centre(0.5 * (low + high));
        double radius = 0.0;
        for (const glm::dvec3& p : points) radius = std::max(radius, glm::length(p - glm::dvec3(centre)));
        SkinBlendSet set;
        set.box = smallestBox(points, inverseBindMatrices[entry.first[0]]);
        set.centre = centre;
        set.radius = static_cast<float>(radius * (1.0 + 1e-6));
        set.firstJoint = static_cast<std::uint32_t>(boxes.setJoints.size());
        set.numJoints = static_cast<std::uint32_t>(entry.first.size());
        boxes.setJoints.insert(boxes.setJoints.end(), entry.first.begin(), entry.first.end());
        // Weights sum to 1 within float rounding: the other joints' weights rounded up by as much.
        for (std::size_t j = 0; j < entry.first.size(); ++j)
            boxes.setWeights.push_back(j == 0 ? entry.second.weights[0]
                                              : entry.second.weights[j] + 4.0f * std::numeric_limits<float>::epsilon());
        boxes.sets.push_back(set);
    }
    return boxes;
}

} // namespace osgActor
