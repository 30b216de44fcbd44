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

/** One node's motion in the two models: osgAnimation's (exact, blended) and the animation's (as it plays). */
class Chains
{
public:
    Chains(const std::map<int, AnimatedNode>& animated, const RiggedModel& model, const RiggedAnimation& animation)
        : _animated(animated), _model(model)
    {
        for (const AnimationChannel& channel : animation.channels)
        {
            if (channel.path == AnimationPath::Rotation) _rotations.emplace(channel.node, &channel);
            if (channel.path == AnimationPath::Scale) _scales.emplace(channel.node, &channel);
        }
    }

    /** osgAnimation's matrix of a node at t (local to its parent, scene units): its stacked transform, or its rest. */
    glm::dmat4 blendedLocal(int node, double t) const
    {
        const auto moved = _animated.find(node);
        return moved != _animated.end() ? moved->second.at(t) : restMatrix(_model.nodes[node]);
    }

    /** osgAnimation's world matrix of a node at t (the scene root's space, scene units). */
    glm::dmat4 blendedWorld(int node, double t) const
    {
        glm::dmat4 world(1.0);
        for (int n = node; n >= 0; n = _model.nodes[n].parent) world = blendedLocal(n, t) * world;
        return world;
    }

    /** The linear part (rotation and scale, no translation) of a node's world matrix as the animation plays it: its
      * rotation and scale channels, else its rest values, composed up to the root. */
    glm::dmat3 playedLinear(int node, double t) const
    {
        glm::dmat3 linear(1.0);
        for (int n = node; n >= 0; n = _model.nodes[n].parent)
        {
            const RiggedNode& rest = _model.nodes[n];
            const auto rotation = _rotations.find(n);
            const auto scale = _scales.find(n);
            const glm::dquat q = rotation != _rotations.end() ? sampleRotationChannel(*rotation->second, t) : rest.rotation;
            const glm::dvec3 s = scale != _scales.end() ? sampleVectorChannel(*scale->second, t) : rest.scale;
            glm::dmat3 local = glm::mat3_cast(q);
            for (int axis = 0; axis < 3; ++axis) local[axis] *= s[axis];
            linear = local * linear;
        }
        return linear;
    }

    /** The translation (local to its parent) that puts the node at osgAnimation's world position at t, seen through
      * the rotations and scales the animation plays above it; also that linear part, for measuring errors. */
    glm::dvec3 translation(int node, double t, glm::dmat3& parentLinear) const
    {
        const int parent = _model.nodes[node].parent;
        const glm::dmat4 parentWorld = parent >= 0 ? blendedWorld(parent, t) : glm::dmat4(1.0);
        const glm::dvec3 position(parentWorld * blendedLocal(node, t)[3]);
        parentLinear = parent >= 0 ? playedLinear(parent, t) : glm::dmat3(1.0);
        return glm::inverse(parentLinear) * (position - glm::dvec3(parentWorld[3]));
    }

    /** The breakpoints of the animated nodes from the root down to node, merged and sorted. */
    std::vector<double> breakpoints(int node) const
    {
        std::set<double> times;
        for (int n = node; n >= 0; n = _model.nodes[n].parent)
        {
            const auto moved = _animated.find(n);
            if (moved != _animated.end()) times.insert(moved->second.breakpoints.begin(), moved->second.breakpoints.end());
        }
        return std::vector<double>(times.begin(), times.end());
    }

private:
    const std::map<int, AnimatedNode>& _animated;
    const RiggedModel& _model;
    /** The animation's rotation and scale channels, by node (one of each at most). */
    std::map<int, const AnimationChannel*> _rotations, _scales;
};

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

/** The node's translation channel, sampled at its breakpoints and, between them, at evenly spaced times, as few as
  * keep the played position (the linear interpolation seen through the parent's played linear part) within
  * tolerance of osgAnimation's; capped is set where the cap on samples was reached first. */
AnimationChannel sampleTranslation(const Chains& chains, int node, double tolerance, bool& capped)
{
    AnimationChannel channel;
    channel.node = node;
    channel.path = AnimationPath::Translation;
    channel.interpolation = KeyInterpolation::Linear;
    const std::vector<double> keys = chains.breakpoints(node);
    glm::dmat3 linear;
    auto at = [&](double t) { return chains.translation(node, t, linear); };
    for (std::size_t k = 0; k < keys.size(); ++k)
    {
        const glm::dvec3 first = at(keys[k]);
        channel.times.push_back(keys[k]);
        channel.values.push_back(glm::dvec4(first, 0.0));
        if (k + 1 == keys.size()) continue;
        const double t0 = keys[k], t1 = keys[k + 1];
        if (std::nextafter(t0, t1) == t1) continue; // one unit in the last place: nothing between
        std::vector<glm::dvec3> values;
        auto strays = [&](const glm::dvec3& a, const glm::dvec3& b, double u, double t) {
            const glm::dvec3 exact = at(t); // sets linear: the parent's, at t
            return glm::length(linear * (glm::mix(a, b, u) - exact));
        };
        capped = subdivideInterval(t0, t1, first, at(t1), at, strays, tolerance, channel.times, values) || capped;
        for (const glm::dvec3& value : values) channel.values.push_back(glm::dvec4(value, 0.0));
    }
    return channel;
}

} // namespace

std::vector<int> addBlendedPositionChannels(const std::map<int, AnimatedNode>& animated, const RiggedModel& model,
                                            double tolerance, RiggedAnimation& animation)
{
    std::vector<int> capped;
    std::vector<AnimationChannel> added;
    {
        const Chains chains(animated, model, animation);
        for (std::size_t n = 0; n < model.nodes.size(); ++n)
        {
            if (!belowBlendedMatrices(animated, model, int(n))) continue;
            bool cap = false;
            AnimationChannel channel = sampleTranslation(chains, int(n), tolerance, cap);
            if (cap) capped.push_back(int(n));
            // A translation that never leaves its rest value by more than a tenth of the tolerance (seen in the
            // scene: what the float products of osgAnimation's matrices leave where nothing stretches) is no channel
            // (no needless DOFs), unless it replaces the node's own.
            const int parent = model.nodes[n].parent;
            const glm::dvec3 rest = model.nodes[n].translation;
            bool moves = false;
            for (std::size_t k = 0; k < channel.times.size() && !moves; ++k)
            {
                const glm::dmat3 linear = parent >= 0 ? chains.playedLinear(parent, channel.times[k]) : glm::dmat3(1.0);
                moves = glm::length(linear * (glm::dvec3(channel.values[k]) - rest)) > 0.1 * tolerance;
            }
            if (moves || findChannel(animation, int(n), AnimationPath::Translation))
                added.push_back(std::move(channel));
        }
    }
    for (AnimationChannel& channel : added)
    {
        auto& channels = animation.channels;
        channels.erase(std::remove_if(channels.begin(), channels.end(),
                                      [&](const AnimationChannel& c) {
                                          return c.node == channel.node && c.path == AnimationPath::Translation;
                                      }),
                       channels.end());
        channels.push_back(std::move(channel));
    }
    return capped;
}

} // namespace osganimation
} // namespace osgActor
