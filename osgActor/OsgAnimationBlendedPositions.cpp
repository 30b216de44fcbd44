// Joint positions under osgAnimation's matrix channels (OsgAnimationScene): osgAnimation blends a matrix channel's
// keys element by element, which between keys is a rotation times a stretch. The import turns each node rigidly (the
// rotation, OsgAnimationClips), and the DOF model has no animated stretch, so the nodes below such a channel get
// translation channels that put them where osgAnimation's blended matrices put them.
#include "OsgAnimationScene"

#include <osgActor/import/ChannelSampling>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace osgActor {
namespace osganimation {

namespace {

/** The channel of a node and path in an animation, or null. */
const AnimationChannel* findChannel(const RiggedAnimation& animation, int node, AnimationPath path)
{
    for (const AnimationChannel& channel : animation.channels)
        if (channel.node == node && channel.path == path) return &channel;
    return nullptr;
}

/** Every node at one time, in the two models. */
struct Frame
{
    /** osgAnimation's world matrix (the scene root's space, scene units): the blended stacked transforms. */
    std::vector<glm::dmat4> blendedWorld;
    /** The linear part (rotation and scale) of the world matrix as the animation plays it: its rotation and scale
      * channels, else the rest values. */
    std::vector<glm::dmat3> playedLinear;
};

/** The frames of one interval, each computed once for all nodes (top-down) the first time it is asked for. */
class Frames
{
public:
    Frames(const std::map<int, AnimatedNode>& animated, const RiggedModel& model, const RiggedAnimation& animation)
        : _animated(animated), _model(model)
    {
        for (const AnimationChannel& channel : animation.channels)
        {
            if (channel.path == AnimationPath::Rotation) _rotations.emplace(channel.node, &channel);
            if (channel.path == AnimationPath::Scale) _scales.emplace(channel.node, &channel);
        }
        // Parents before children.
        std::vector<std::size_t> depth(model.nodes.size(), 0);
        for (std::size_t n = 0; n < model.nodes.size(); ++n)
        {
            for (int a = model.nodes[n].parent; a >= 0; a = model.nodes[a].parent) ++depth[n];
            _order.push_back(int(n));
        }
        std::stable_sort(_order.begin(), _order.end(), [&](int a, int b) { return depth[a] < depth[b]; });
    }

    const Frame& at(double t)
    {
        const auto known = _frames.find(t);
        if (known != _frames.end()) return known->second;
        Frame& frame = _frames[t];
        frame.blendedWorld.resize(_model.nodes.size());
        frame.playedLinear.resize(_model.nodes.size());
        for (int n : _order)
        {
            const RiggedNode& node = _model.nodes[n];
            const auto moved = _animated.find(n);
            const glm::dmat4 local = moved != _animated.end() ? moved->second.at(t) : restMatrix(node);
            const auto rotation = _rotations.find(n);
            const auto scale = _scales.find(n);
            const glm::dquat q =
                rotation != _rotations.end() ? sampleRotationChannel(*rotation->second, t) : node.rotation;
            const glm::dvec3 s = scale != _scales.end() ? sampleVectorChannel(*scale->second, t) : node.scale;
            glm::dmat3 linear = glm::mat3_cast(q);
            for (int axis = 0; axis < 3; ++axis) linear[axis] *= s[axis];
            frame.blendedWorld[n] = node.parent >= 0 ? frame.blendedWorld[node.parent] * local : local;
            frame.playedLinear[n] = node.parent >= 0 ? frame.playedLinear[node.parent] * linear : linear;
        }
        return frame;
    }

    /** Forgets the frames (at the end of an interval: its times are not asked for again). */
    void clear() { _frames.clear(); }

private:
    const std::map<int, AnimatedNode>& _animated;
    const RiggedModel& _model;
    /** The animation's rotation and scale channels, by node (one of each at most). */
    std::map<int, const AnimationChannel*> _rotations, _scales;
    std::vector<int> _order;
    std::map<double, Frame> _frames;
};

/** The translation (local to its parent) that puts a node at osgAnimation's world position in the frame, seen
  * through the rotation and scale the animation plays for its parent. */
glm::dvec3 blendedTranslation(const Frame& frame, const RiggedModel& model, int node)
{
    const int parent = model.nodes[node].parent;
    const glm::dvec3 position(frame.blendedWorld[node][3]);
    if (parent < 0) return position;
    return glm::inverse(frame.playedLinear[parent]) * (position - glm::dvec3(frame.blendedWorld[parent][3]));
}

/** How far a translation (local to node's parent) is from another, seen in the scene through the parent's played
  * linear part in the frame. */
double sceneDistance(const Frame& frame, const RiggedModel& model, int node, const glm::dvec3& a, const glm::dvec3& b)
{
    const int parent = model.nodes[node].parent;
    return glm::length(parent >= 0 ? frame.playedLinear[parent] * (a - b) : a - b);
}

/** Whether a proper ancestor of node is driven by a matrix channel. */
bool belowBlendedMatrices(const std::map<int, AnimatedNode>& animated, const RiggedModel& model, int node)
{
    for (int n = model.nodes[node].parent; n >= 0; n = model.nodes[n].parent)
    {
        const auto moved = animated.find(n);
        if (moved != animated.end() && moved->second.blendsMatrices) return true;
    }
    return false;
}

/** A node below a matrix channel, and its translation channel as it is sampled. */
struct Placed
{
    int node = -1;
    AnimationChannel channel;
    bool capped = false;
    /** Whether a sample leaves the rest translation by more than a tenth of the tolerance (in the scene). */
    bool moves = false;
};

} // namespace

std::vector<int> addBlendedPositionChannels(const std::map<int, AnimatedNode>& animated, const RiggedModel& model,
                                            double tolerance, RiggedAnimation& animation)
{
    std::vector<Placed> placed;
    std::set<double> breakpoints;
    for (std::size_t n = 0; n < model.nodes.size(); ++n)
    {
        if (!belowBlendedMatrices(animated, model, int(n))) continue;
        Placed node;
        node.node = int(n);
        node.channel.node = int(n);
        node.channel.path = AnimationPath::Translation;
        node.channel.interpolation = KeyInterpolation::Linear;
        placed.push_back(std::move(node));
        for (int a = int(n); a >= 0; a = model.nodes[a].parent)
        {
            const auto moved = animated.find(a);
            if (moved != animated.end())
                breakpoints.insert(moved->second.breakpoints.begin(), moved->second.breakpoints.end());
        }
    }
    if (placed.empty()) return {};
    // Every node below a matrix channel is keyed at the breakpoints of the animated nodes above them all and, between
    // two, at evenly spaced times, as few as keep its played position within tolerance of osgAnimation's.
    Frames frames(animated, model, animation);
    const std::vector<double> keys(breakpoints.begin(), breakpoints.end());
    for (std::size_t k = 0; k < keys.size(); ++k)
    {
        frames.clear();
        const double t0 = keys[k];
        const bool interval = k + 1 < keys.size() && std::nextafter(t0, keys[k + 1]) != keys[k + 1];
        for (Placed& node : placed)
        {
            auto exact = [&](double t) { return blendedTranslation(frames.at(t), model, node.node); };
            std::vector<double> times{t0};
            std::vector<glm::dvec3> values{exact(t0)};
            if (interval)
            {
                const double t1 = keys[k + 1];
                auto strays = [&](const glm::dvec3& a, const glm::dvec3& b, double u, double t) {
                    return sceneDistance(frames.at(t), model, node.node, glm::mix(a, b, u), exact(t));
                };
                node.capped = subdivideInterval(t0, t1, values.front(), exact(t1), exact, strays, tolerance, times,
                                                values) || node.capped;
            }
            const glm::dvec3 rest = model.nodes[node.node].translation;
            for (std::size_t i = 0; i < times.size(); ++i)
            {
                node.channel.times.push_back(times[i]);
                node.channel.values.push_back(glm::dvec4(values[i], 0.0));
                node.moves = node.moves ||
                             sceneDistance(frames.at(times[i]), model, node.node, values[i], rest) > 0.1 * tolerance;
            }
        }
    }
    std::vector<int> capped;
    for (Placed& node : placed)
    {
        if (node.capped) capped.push_back(node.node);
        // A translation that never leaves its rest value by more than a tenth of the tolerance (what the float
        // products of osgAnimation's matrices leave where nothing stretches) is no channel (no needless DOFs), unless
        // it replaces the node's own.
        if (!node.moves && !findChannel(animation, node.node, AnimationPath::Translation)) continue;
        auto& channels = animation.channels;
        channels.erase(std::remove_if(channels.begin(), channels.end(),
                                      [&](const AnimationChannel& c) {
                                          return c.node == node.node && c.path == AnimationPath::Translation;
                                      }),
                       channels.end());
        channels.push_back(std::move(node.channel));
    }
    return capped;
}

} // namespace osganimation
} // namespace osgActor
