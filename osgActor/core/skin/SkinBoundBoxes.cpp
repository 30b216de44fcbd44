#include <osgActor/core/skin/SkinBoundBoxes>
#include <osgActor/core/skin/SkinBoundsJob>

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

namespace {

/** Vertices of one set of joints (Set::joints: the first joint, then the others in increasing order): bind
  * positions and, per vertex, the weight of each joint of the set in that order. */
struct SetVertices
{
    std::vector<glm::dvec3> points;
    std::vector<float> weights; // points.size() rows of joints.size()
};

/** A piece is small enough when its box's longest side and every joint's weight spread (as that fraction of half
  * the bind box's diagonal) are within an eighth of that diagonal; a skin gets at most kPiecesPerJoint pieces per
  * joint (or one per joint set, if more), the largest split first. */
constexpr double kPieceFraction = 1.0 / 8.0;
constexpr double kWeightLength = 0.5;
constexpr std::size_t kPiecesPerJoint = 8;

/** A piece being split: its vertices, the set they follow, and how it would be split. */
struct Piece
{
    std::size_t set = 0;
    SetVertices vertices;
    double size = 0.0;        // the larger of the box's longest side and the largest weight spread (model units)
    glm::dvec3 direction{0.0}; // split along this bind-space direction, or
    int weightJoint = -1;     // along this joint's weight, when >= 0
};

Piece measured(std::size_t set, SetVertices vertices, std::size_t numJoints, const glm::dmat4& inverseBind, double diagonal)
{
    Piece piece;
    piece.set = set;
    const std::size_t count = vertices.points.size();
    const SkinJointBox box = smallestBox(vertices.points, inverseBind);
    const glm::vec3 size = box.box.max - box.box.min;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : (size.y >= size.z ? 1 : 2);
    piece.size = size[axis];
    piece.direction = glm::dvec3(glm::vec3(box.boxToBind[axis]));
    for (std::size_t j = 0; j < numJoints; ++j)
    {
        float low = 1.0f, high = 0.0f;
        for (std::size_t i = 0; i < count; ++i)
        {
            low = std::min(low, vertices.weights[i * numJoints + j]);
            high = std::max(high, vertices.weights[i * numJoints + j]);
        }
        const double spread = (high - low) * kWeightLength * diagonal;
        if (spread > piece.size) piece.size = spread, piece.weightJoint = static_cast<int>(j);
    }
    if (count < 2) piece.size = 0.0; // nothing to split
    piece.vertices = std::move(vertices);
    return piece;
}

/** The two halves of a piece's vertices, cut at the median along its split direction. */
void splitInHalves(const Piece& piece, std::size_t numJoints, SetVertices halves[2])
{
    const SetVertices& vertices = piece.vertices;
    const std::size_t count = vertices.points.size();
    std::vector<std::pair<double, std::size_t>> order(count);
    for (std::size_t i = 0; i < count; ++i)
        order[i] = {piece.weightJoint < 0 ? glm::dot(piece.direction, vertices.points[i])
                                          : vertices.weights[i * numJoints + std::size_t(piece.weightJoint)],
                    i};
    std::sort(order.begin(), order.end());
    for (std::size_t i = 0; i < count; ++i)
    {
        SetVertices& half = halves[i < count / 2 ? 0 : 1];
        half.points.push_back(vertices.points[order[i].second]);
        const auto row = vertices.weights.begin() + static_cast<std::ptrdiff_t>(order[i].second * numJoints);
        half.weights.insert(half.weights.end(), row, row + static_cast<std::ptrdiff_t>(numJoints));
    }
}

} // namespace

SkinBoundBoxes computeSkinBoundBoxes(const SkinVertices& vertices, Span<const glm::dmat4> inverseBindMatrices)
{
    // Per vertex, its first (largest-weight) joint: influences come largest first (the builder's order).
    const std::size_t numJoints = inverseBindMatrices.size();
    std::vector<std::vector<glm::dvec3>> firstOf(numJoints);
    std::map<std::vector<std::uint32_t>, SetVertices> sets;
    glm::dvec3 low(std::numeric_limits<double>::max()), high(-std::numeric_limits<double>::max());
    std::size_t influence = 0;
    std::size_t vertex = 0;
    for (unsigned k = 1; k <= kMaxSkinInfluences; ++k)
        for (std::uint32_t i = 0; i < vertices.counts[k - 1]; ++i, ++vertex, influence += k)
        {
            const glm::dvec3 position(vertices.positions[vertex]);
            low = glm::min(low, position);
            high = glm::max(high, position);
            firstOf[vertices.joints[influence]].push_back(position);
            std::vector<std::uint32_t> key(vertices.joints.begin() + influence, vertices.joints.begin() + influence + k);
            std::sort(key.begin() + 1, key.end());
            SetVertices& set = sets[key];
            set.points.push_back(position);
            const std::size_t row = set.weights.size();
            set.weights.resize(row + k);
            for (unsigned j = 0; j < k; ++j)
            {
                const std::size_t at = std::size_t(std::find(key.begin(), key.end(), vertices.joints[influence + j]) - key.begin());
                set.weights[row + at] = vertices.weights[influence + j];
            }
        }

    SkinBoundBoxes boxes;
    boxes.joints.resize(numJoints);
    for (std::size_t a = 0; a < numJoints; ++a)
        if (!firstOf[a].empty()) boxes.joints[a] = smallestBox(firstOf[a], inverseBindMatrices[a]);
    const double diagonal = vertex > 0 ? glm::length(high - low) : 0.0;
    std::vector<std::vector<std::uint32_t>> setJoints;
    std::vector<Piece> pieces;
    for (auto& entry : sets)
    {
        pieces.push_back(measured(setJoints.size(), std::move(entry.second), entry.first.size(),
                                  inverseBindMatrices[entry.first[0]], diagonal));
        setJoints.push_back(entry.first);
    }
    // Split the largest piece until every one is small enough or the budget is spent.
    const std::size_t budget = std::max(pieces.size(), kPiecesPerJoint * numJoints);
    const auto smaller = [](const Piece& p, const Piece& q) { return p.size < q.size; };
    std::make_heap(pieces.begin(), pieces.end(), smaller);
    while (!pieces.empty() && pieces.size() < budget && pieces.front().size > kPieceFraction * diagonal)
    {
        std::pop_heap(pieces.begin(), pieces.end(), smaller);
        const Piece largest = std::move(pieces.back());
        pieces.pop_back();
        const std::vector<std::uint32_t>& joints = setJoints[largest.set];
        SetVertices halves[2];
        splitInHalves(largest, joints.size(), halves);
        for (SetVertices& half : halves)
        {
            pieces.push_back(measured(largest.set, std::move(half), joints.size(), inverseBindMatrices[joints[0]], diagonal));
            std::push_heap(pieces.begin(), pieces.end(), smaller);
        }
    }
    // In the order of their sets, for a skin built the same way twice to have the same pieces in the same order.
    std::stable_sort(pieces.begin(), pieces.end(), [](const Piece& p, const Piece& q) { return p.set < q.set; });
    for (const Piece& piece : pieces)
    {
        const std::vector<std::uint32_t>& joints = setJoints[piece.set];
        const std::vector<float>& weights = piece.vertices.weights;
        // Centred on the points' box (close enough to the smallest sphere), the radius rounded up.
        const std::vector<glm::dvec3>& points = piece.vertices.points;
        glm::dvec3 pieceLow = points[0], pieceHigh = points[0];
        for (const glm::dvec3& p : points)
        {
            pieceLow = glm::min(pieceLow, p);
            pieceHigh = glm::max(pieceHigh, p);
        }
        const glm::vec3 centre(0.5 * (pieceLow + pieceHigh));
        double radius = 0.0;
        for (const glm::dvec3& p : points) radius = std::max(radius, glm::length(p - glm::dvec3(centre)));
        SkinBlendSet set;
        set.box = smallestBox(points, inverseBindMatrices[joints[0]]);
        set.centre = centre;
        set.radius = static_cast<float>(radius * (1.0 + 1e-6));
        set.firstJoint = static_cast<std::uint32_t>(boxes.setJoints.size());
        set.numJoints = static_cast<std::uint32_t>(joints.size());
        boxes.setJoints.insert(boxes.setJoints.end(), joints.begin(), joints.end());
        // The first joint's smallest weight, the others' largest; weights sum to 1 within float rounding: the
        // other joints' weights rounded up by as much.
        for (std::size_t j = 0; j < joints.size(); ++j)
        {
            float weight = j == 0 ? 1.0f : 0.0f;
            for (std::size_t i = 0; i < points.size(); ++i)
                weight = j == 0 ? std::min(weight, weights[i * joints.size()])
                                : std::max(weight, weights[i * joints.size() + j]);
            boxes.setWeights.push_back(j == 0 ? weight : weight + 4.0f * std::numeric_limits<float>::epsilon());
        }
        boxes.sets.push_back(set);
    }
    boxes.setGroups = groupSkinBlendSets(boxes.sets, boxes.setJoints, boxes.setWeights);
    return boxes;
}

} // namespace osgActor
