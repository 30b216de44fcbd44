#include <osgActor/core/skin/SkinBuilder>

#include <osgActor/core/skin/SkinBoundBoxes>

#include <glm/ext/matrix_double3x3.hpp>
#include <glm/ext/vector_double3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace osgActor {

namespace {

/** How far an inverse bind matrix's linear part may be from a rotation times a uniform scale, relative to the
  * scale squared, and still count as one: files store these matrices in floats. */
constexpr double kSimilarityTolerance = 1e-4;
/** The most joints a skin can have: joint indices are 16 bits. */
constexpr std::size_t kMaxSkinJoints = 65536;

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool isFinite(const glm::vec4& v) { return isFinite(glm::vec3(v)) && std::isfinite(v.w); }

/** What the linear part of an affine matrix is. */
struct LinearPart
{
    /** The uniform scale when the part is a rotation (or a mirror) times it, else 0. */
    double similarityScale = 0.0;
    double determinant = 0.0;
};

LinearPart analyseLinearPart(const glm::dmat4& m)
{
    const glm::dvec3 c[3] = {glm::dvec3(m[0]), glm::dvec3(m[1]), glm::dvec3(m[2])};
    LinearPart part;
    part.determinant = glm::dot(c[0], glm::cross(c[1], c[2]));
    const double scale2 = (glm::dot(c[0], c[0]) + glm::dot(c[1], c[1]) + glm::dot(c[2], c[2])) / 3.0;
    bool similar = scale2 > 0.0;
    for (int i = 0; i < 3 && similar; ++i)
        for (int j = 0; j < 3 && similar; ++j)
            similar = std::abs(glm::dot(c[i], c[j]) - (i == j ? scale2 : 0.0)) <= kSimilarityTolerance * scale2;
    if (similar) part.similarityScale = std::sqrt(scale2);
    return part;
}

/** Builds error messages "skin 'name': place: what". */
class Refusal
{
public:
    explicit Refusal(const std::string& skinName) : _prefix(skinName.empty() ? "skin: " : "skin '" + skinName + "': ")
    {
    }
    SkinBuildResult general(const std::string& what) const
    {
        SkinBuildResult result;
        result.error = _prefix + what;
        return result;
    }
    SkinBuildResult joint(unsigned joint, const std::string& name, const std::string& what) const
    {
        SkinBuildResult result;
        std::ostringstream text;
        text << _prefix << "joint " << joint << " '" << name << "': " << what;
        result.error = text.str();
        result.errorJoint = static_cast<int>(joint);
        return result;
    }
    SkinBuildResult vertex(std::size_t vertex, const std::string& what) const
    {
        SkinBuildResult result;
        std::ostringstream text;
        text << _prefix << "vertex " << vertex << ": " << what;
        result.error = text.str();
        result.errorVertex = static_cast<long long>(vertex);
        return result;
    }

private:
    std::string _prefix;
};

struct Weighted
{
    unsigned joint;
    double weight;
};

} // namespace

unsigned SkinBuilder::addJoint(const std::string& name, const glm::dmat4& inverseBindMatrix)
{
    _jointNames.push_back(name);
    _inverseBindMatrices.push_back(inverseBindMatrix);
    return static_cast<unsigned>(_jointNames.size() - 1);
}

unsigned SkinBuilder::addVertex(const glm::vec3& position)
{
    _positions.push_back(position);
    return static_cast<unsigned>(_positions.size() - 1);
}

void SkinBuilder::addInfluence(unsigned vertex, unsigned joint, float weight)
{
    if (weight == 0.0f) return;
    _influences.push_back({vertex, joint, weight});
}

void SkinBuilder::addInfluences(unsigned vertex, const unsigned* joints, const float* weights, unsigned count)
{
    for (unsigned i = 0; i < count; ++i) addInfluence(vertex, joints[i], weights[i]);
}

SkinBuildResult SkinBuilder::build() const
{
    const Refusal refuse(_name);
    const std::size_t numJoints = _jointNames.size();
    const std::size_t numVertices = _positions.size();
    if (numJoints == 0) return refuse.general("has no joints");
    if (numJoints > kMaxSkinJoints)
    {
        std::ostringstream what;
        what << "has " << numJoints << " joints; at most " << kMaxSkinJoints << " are supported";
        return refuse.general(what.str());
    }
    if (numVertices == 0) return refuse.general("has no vertices");
    // Influences are indexed with 32 bits.
    if (numVertices > std::numeric_limits<std::uint32_t>::max() / kMaxSkinInfluences)
    {
        std::ostringstream what;
        what << "has " << numVertices << " vertices; at most " << std::numeric_limits<std::uint32_t>::max() / kMaxSkinInfluences
             << " are supported";
        return refuse.general(what.str());
    }
    if (!_normals.empty() && _normals.size() != numVertices)
    {
        std::ostringstream what;
        what << "has " << _normals.size() << " normals for " << numVertices << " vertices";
        return refuse.general(what.str());
    }
    if (!_tangents.empty() && _tangents.size() != numVertices)
    {
        std::ostringstream what;
        what << "has " << _tangents.size() << " tangents for " << numVertices << " vertices";
        return refuse.general(what.str());
    }

    // --- joints ---
    std::unordered_map<std::string, unsigned> jointByName;
    std::vector<glm::dmat4> inverseBinds(_inverseBindMatrices);
    bool allSimilar = true;
    double bindScale = 0.0;
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const std::string& name = _jointNames[j];
        if (name.empty()) return refuse.joint(j, name, "has an empty name");
        const auto inserted = jointByName.emplace(name, j);
        if (!inserted.second)
        {
            std::ostringstream what;
            what << "the name is used twice (joints " << inserted.first->second << " and " << j << ")";
            return refuse.joint(j, name, what.str());
        }
        glm::dmat4& m = inverseBinds[j];
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m[c][r])) return refuse.joint(j, name, "inverse bind matrix is not finite");
        if (std::abs(m[0][3]) > 1e-6 || std::abs(m[1][3]) > 1e-6 || std::abs(m[2][3]) > 1e-6 ||
            std::abs(m[3][3] - 1.0) > 1e-6)
            return refuse.joint(j, name, "inverse bind matrix is not affine (its bottom row is not 0 0 0 1)");
        m[0][3] = m[1][3] = m[2][3] = 0.0;
        m[3][3] = 1.0;
        const LinearPart part = analyseLinearPart(m);
        const double columnScale = std::max({glm::length(glm::dvec3(m[0])), glm::length(glm::dvec3(m[1])),
                                             glm::length(glm::dvec3(m[2]))});
        if (!(std::abs(part.determinant) > 1e-12 * columnScale * columnScale * columnScale))
            return refuse.joint(j, name, "inverse bind matrix is singular");
        allSimilar = allSimilar && part.similarityScale > 0.0;
        if (_method == SkinningMethod::DualQuaternion)
        {
            if (part.similarityScale == 0.0)
                return refuse.joint(j, name, "inverse bind matrix has shear or non-uniform scale; dual-quaternion "
                                             "skinning needs rigid joints (use linear blend skinning)");
            if (part.determinant < 0.0)
                return refuse.joint(j, name, "inverse bind matrix mirrors; dual-quaternion skinning needs rotations "
                                             "(use linear blend skinning)");
            if (j == 0)
                bindScale = part.similarityScale;
            else if (std::abs(part.similarityScale - bindScale) > kSimilarityTolerance * bindScale)
            {
                std::ostringstream what;
                what << "inverse bind matrix scales by " << part.similarityScale << " where joint 0 scales by "
                     << bindScale << "; dual-quaternion skinning needs one scale for the whole skin";
                return refuse.joint(j, name, what.str());
            }
        }
    }

    // --- vertex attributes ---
    for (std::size_t v = 0; v < numVertices; ++v)
    {
        if (!isFinite(_positions[v])) return refuse.vertex(v, "position is not finite");
        if (!_normals.empty())
        {
            if (!isFinite(_normals[v])) return refuse.vertex(v, "normal is not finite");
            if (glm::dot(_normals[v], _normals[v]) == 0.0f) return refuse.vertex(v, "normal is zero");
        }
        if (!_tangents.empty())
        {
            const glm::vec4& t = _tangents[v];
            if (!isFinite(t)) return refuse.vertex(v, "tangent is not finite");
            if (t.x == 0.0f && t.y == 0.0f && t.z == 0.0f) return refuse.vertex(v, "tangent is zero");
            if (t.w != 1.0f && t.w != -1.0f)
            {
                std::ostringstream what;
                what << "tangent handedness (w) is " << t.w << ", not +1 or -1";
                return refuse.vertex(v, what.str());
            }
        }
    }

    // --- influences, gathered per vertex (a counting sort keeps each vertex's in the order given) ---
    std::vector<std::uint32_t> firstInfluence(numVertices + 1, 0);
    for (std::size_t i = 0; i < _influences.size(); ++i)
    {
        const Influence& influence = _influences[i];
        if (influence.vertex >= numVertices)
        {
            std::ostringstream what;
            what << "influence " << i << " (joint " << influence.joint << ") names vertex " << influence.vertex
                 << ", but the skin has " << numVertices << " vertices";
            return refuse.general(what.str());
        }
        ++firstInfluence[influence.vertex + 1];
    }
    std::partial_sum(firstInfluence.begin(), firstInfluence.end(), firstInfluence.begin());
    std::vector<Weighted> byVertex(_influences.size());
    {
        std::vector<std::uint32_t> next(firstInfluence.begin(), firstInfluence.end() - 1);
        for (const Influence& influence : _influences)
            byVertex[next[influence.vertex]++] = {influence.joint, static_cast<double>(influence.weight)};
    }

    // Validate and mend each vertex's influences: refuse bad ones, keep the largest kMaxSkinInfluences, largest
    // first, and divide by their sum.
    std::vector<std::uint8_t> counts(numVertices);
    std::vector<Weighted> kept(numVertices * std::size_t(kMaxSkinInfluences));
    std::vector<Weighted> scratch;
    for (std::size_t v = 0; v < numVertices; ++v)
    {
        scratch.assign(byVertex.begin() + firstInfluence[v], byVertex.begin() + firstInfluence[v + 1]);
        for (const Weighted& w : scratch)
        {
            std::ostringstream what;
            if (w.joint >= numJoints)
                what << "joint index " << w.joint << " is out of range (the skin has " << numJoints << " joints)";
            else if (!std::isfinite(w.weight))
                what << "weight of joint " << w.joint << " is not finite";
            else if (w.weight < 0.0)
                what << "weight " << w.weight << " of joint " << w.joint << " is negative";
            if (!what.str().empty()) return refuse.vertex(v, what.str());
        }
        std::sort(scratch.begin(), scratch.end(), [](const Weighted& a, const Weighted& b) {
            return a.weight != b.weight ? a.weight > b.weight : a.joint < b.joint;
        });
        for (std::size_t a = 0; a < scratch.size(); ++a)
            for (std::size_t b = a + 1; b < scratch.size(); ++b)
                if (scratch[a].joint == scratch[b].joint)
                {
                    std::ostringstream what;
                    what << "joint " << scratch[a].joint << " is given two non-zero weights";
                    return refuse.vertex(v, what.str());
                }
        if (scratch.size() > kMaxSkinInfluences) scratch.resize(kMaxSkinInfluences);
        double sum = 0.0;
        for (const Weighted& w : scratch) sum += w.weight;
        if (scratch.empty() || !(sum > 0.0)) return refuse.vertex(v, "its weights sum to zero (it follows no joint)");
        counts[v] = static_cast<std::uint8_t>(scratch.size());
        // Weights that already sum to 1 as closely as floats can (a skin's own, written out and read back: each was
        // rounded to a float, by at most half an ulp, 2^-25 below 1) are kept as they are: dividing them again would
        // move some by an ulp, and a skin read back would not be the one written.
        const double roundingOfFloats = static_cast<double>(scratch.size()) * std::ldexp(1.0, -25);
        const double divisor = std::abs(sum - 1.0) <= roundingOfFloats ? 1.0 : sum;
        for (std::size_t k = 0; k < scratch.size(); ++k)
            kept[v * kMaxSkinInfluences + k] = {scratch[k].joint, scratch[k].weight / divisor};
    }

    // --- the skin, vertices grouped by influence count (file order within a group) ---
    std::shared_ptr<Skin> skin(new Skin);
    skin->_name = _name;
    skin->_method = _method;
    skin->_normalTransform = _normalTransform != NormalTransform::Automatic
                                 ? _normalTransform
                                 : (allSimilar ? NormalTransform::LinearPart : NormalTransform::InverseTranspose);
    skin->_bindScale = _method == SkinningMethod::DualQuaternion ? bindScale : 1.0;
    skin->_jointNames = _jointNames;
    skin->_inverseBindMatrices = inverseBinds;

    for (std::size_t v = 0; v < numVertices; ++v) ++skin->_groupCounts[counts[v] - 1];
    std::size_t groupBegin[kMaxSkinInfluences];
    std::size_t influenceBegin[kMaxSkinInfluences];
    std::size_t numInfluences = 0;
    for (unsigned k = 1, vertex = 0; k <= kMaxSkinInfluences; ++k)
    {
        groupBegin[k - 1] = vertex;
        influenceBegin[k - 1] = numInfluences;
        vertex += skin->_groupCounts[k - 1];
        numInfluences += std::size_t(skin->_groupCounts[k - 1]) * k;
    }
    skin->_positions.resize(numVertices);
    if (!_normals.empty()) skin->_normals.resize(numVertices);
    if (!_tangents.empty()) skin->_tangents.resize(numVertices);
    skin->_fileOrder.resize(numVertices);
    skin->_skinOrder.resize(numVertices);
    skin->_influenceCount.resize(numVertices);
    skin->_influenceBegin.resize(numVertices);
    skin->_joints.resize(numInfluences);
    skin->_weights.resize(numInfluences);
    for (std::size_t v = 0; v < numVertices; ++v)
    {
        const unsigned k = counts[v];
        const std::size_t at = groupBegin[k - 1]++;
        const std::size_t influences = influenceBegin[k - 1];
        influenceBegin[k - 1] += k;
        skin->_positions[at] = _positions[v];
        if (!_normals.empty()) skin->_normals[at] = _normals[v];
        if (!_tangents.empty()) skin->_tangents[at] = _tangents[v];
        skin->_fileOrder[at] = static_cast<std::uint32_t>(v);
        skin->_skinOrder[v] = static_cast<std::uint32_t>(at);
        skin->_influenceCount[at] = static_cast<std::uint8_t>(k);
        skin->_influenceBegin[at] = static_cast<std::uint32_t>(influences);
        for (unsigned i = 0; i < k; ++i)
        {
            skin->_joints[influences + i] = static_cast<std::uint16_t>(kept[v * kMaxSkinInfluences + i].joint);
            skin->_weights[influences + i] = static_cast<float>(kept[v * kMaxSkinInfluences + i].weight);
        }
        SkinBox& box = skin->_bindBox;
        box.min = v == 0 ? _positions[v] : glm::min(box.min, _positions[v]);
        box.max = v == 0 ? _positions[v] : glm::max(box.max, _positions[v]);
    }
    SkinBoundBoxes boxes = computeSkinBoundBoxes(skin->getVertices(), skin->_inverseBindMatrices);
    skin->_jointBoxes = std::move(boxes.joints);
    skin->_blendSets = std::move(boxes.sets);
    skin->_blendSetJoints = std::move(boxes.setJoints);
    skin->_blendSetWeights = std::move(boxes.setWeights);
    skin->_blendSetGroups = std::move(boxes.setGroups);

    SkinBuildResult result;
    result.skin = skin;
    return result;
}

} // namespace osgActor
