#include <osgActor/import/RiggedModel>

#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace osgActor {

glm::dmat4 restMatrix(const RiggedNode& node)
{
    glm::dmat4 m = glm::mat4_cast(node.rotation);
    m[0] *= node.scale.x;
    m[1] *= node.scale.y;
    m[2] *= node.scale.z;
    m[3] = glm::dvec4(node.translation, 1.0);
    return m;
}

glm::dmat4 restSceneMatrix(const RiggedModel& model, int node)
{
    glm::dmat4 m(1.0);
    for (int n = node; n >= 0; n = model.nodes[n].parent) m = restMatrix(model.nodes[n]) * m;
    return m;
}

std::string decomposeNodeMatrix(const glm::dmat4& matrix, RiggedNode& node, bool& hasShear)
{
    hasShear = false;
    for (int i = 0; i < 16; ++i)
        if (!std::isfinite(matrix[i / 4][i % 4])) return "holds a number that is not finite";
    if (matrix[0][3] != 0.0 || matrix[1][3] != 0.0 || matrix[2][3] != 0.0 || matrix[3][3] != 1.0)
        return "is not affine (its last row is not 0 0 0 1)";
    const glm::dvec3 columns[3] = {glm::dvec3(matrix[0]), glm::dvec3(matrix[1]), glm::dvec3(matrix[2])};
    glm::dvec3 scale(glm::length(columns[0]), glm::length(columns[1]), glm::length(columns[2]));
    if (scale.x == 0.0 || scale.y == 0.0 || scale.z == 0.0) return "has a zero scale";
    const double determinant = glm::determinant(glm::dmat3(columns[0], columns[1], columns[2]));
    if (determinant < 0.0) scale.x = -scale.x; // a mirror: put it on X
    const glm::dmat3 rotation(columns[0] / scale.x, columns[1] / scale.y, columns[2] / scale.z);
    const double shear = std::max({std::abs(glm::dot(rotation[0], rotation[1])),
                                   std::abs(glm::dot(rotation[0], rotation[2])),
                                   std::abs(glm::dot(rotation[1], rotation[2]))});
    hasShear = shear > 1e-5;
    node.translation = glm::dvec3(matrix[3]);
    node.rotation = glm::normalize(glm::quat_cast(rotation));
    node.scale = scale;
    return std::string();
}

std::vector<int> makeNodeNamesUnique(RiggedModel& model)
{
    std::vector<int> renamed;
    std::map<std::string, int> firstWithName;
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
    {
        RiggedNode& node = model.nodes[n];
        if (node.name.empty()) node.name = "node" + std::to_string(n);
        if (firstWithName.emplace(node.name, int(n)).second) continue;
        node.name += "#" + std::to_string(n);
        firstWithName.emplace(node.name, int(n));
        renamed.push_back(int(n));
    }
    return renamed;
}

void makeAnimationNamesUnique(RiggedModel& model)
{
    std::set<std::string> names;
    for (std::size_t a = 0; a < model.animations.size(); ++a)
    {
        std::string& name = model.animations[a].name;
        if (name.empty()) name = "animation" + std::to_string(a);
        if (!names.insert(name).second)
        {
            name += "#" + std::to_string(a);
            names.insert(name);
        }
    }
}

std::size_t setInfluences(RiggedPrimitive& primitive, std::vector<std::vector<JointWeight>>& weights)
{
    constexpr std::size_t kMost = 8;
    std::size_t most = 0, cut = 0;
    for (std::vector<JointWeight>& list : weights)
    {
        std::stable_sort(list.begin(), list.end(),
                         [](const JointWeight& a, const JointWeight& b) { return a.joint < b.joint; });
        std::size_t kept = 0;
        for (std::size_t i = 0; i < list.size(); ++i)
        {
            if (kept > 0 && list[kept - 1].joint == list[i].joint) list[kept - 1].weight += list[i].weight;
            else list[kept++] = list[i];
        }
        list.resize(kept);
        std::stable_sort(list.begin(), list.end(),
                         [](const JointWeight& a, const JointWeight& b) { return a.weight > b.weight; });
        if (list.size() > kMost)
        {
            list.resize(kMost);
            ++cut;
        }
        most = std::max(most, list.size());
    }
    primitive.influencesPerVertex = most <= 4 ? 4 : unsigned(kMost);
    primitive.joints.assign(weights.size() * primitive.influencesPerVertex, 0);
    primitive.weights.assign(weights.size() * primitive.influencesPerVertex, 0.0f);
    for (std::size_t v = 0; v < weights.size(); ++v)
        for (std::size_t i = 0; i < weights[v].size(); ++i)
        {
            primitive.joints[v * primitive.influencesPerVertex + i] = weights[v][i].joint;
            primitive.weights[v * primitive.influencesPerVertex + i] = weights[v][i].weight;
        }
    return cut;
}

bool startAnimationAtZero(RiggedAnimation& animation, double& moved)
{
    double first = 0.0;
    for (const AnimationChannel& channel : animation.channels)
        if (!channel.times.empty()) first = std::min(first, channel.times.front());
    moved = -first;
    if (first == 0.0) return true;
    std::vector<std::vector<double>> times;
    for (const AnimationChannel& channel : animation.channels)
    {
        times.push_back(channel.times);
        for (std::size_t k = 0; k < channel.times.size(); ++k)
        {
            times.back()[k] -= first;
            if (k > 0 && !(times.back()[k] > times.back()[k - 1])) return false;
        }
    }
    for (std::size_t c = 0; c < animation.channels.size(); ++c) animation.channels[c].times = std::move(times[c]);
    return true;
}

bool isSelfOrAncestor(const RiggedModel& model, int ancestor, int node)
{
    for (int n = node; n >= 0; n = model.nodes[n].parent)
        if (n == ancestor) return true;
    return false;
}

} // namespace osgActor
