// The osgAnimation converter's animations (OsgAnimationScene): each animated stacked transform sampled with
// osgAnimation's own samplers into translation, rotation and scale channels of its node.
#include "OsgAnimationScene"

#include <osgActor/GlmOsg>
#include <osgActor/import/ChannelSampling>

#include <osgAnimation/Animation>
#include <osgAnimation/Channel>
#include <osgAnimation/StackedMatrixElement>
#include <osgAnimation/StackedQuaternionElement>
#include <osgAnimation/StackedRotateAxisElement>
#include <osgAnimation/StackedScaleElement>
#include <osgAnimation/StackedTranslateElement>

#include <glm/ext/quaternion_common.hpp>
#include <glm/ext/quaternion_geometric.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

namespace osgActor {
namespace osganimation {

namespace {

/** A channel's value at a time, as osgAnimation's sampler gives it, and its key times. */
template <class Value>
struct Curve
{
    std::function<Value(double)> at;
    std::vector<double> times;
    bool step = false;
};

/** The curve of a channel whose sampler is of type SamplerT, or false. */
template <class SamplerT, class Value>
bool bindCurve(const osgAnimation::Channel& channel, bool step, Curve<Value>& curve)
{
    const SamplerT* sampler = dynamic_cast<const SamplerT*>(channel.getSampler());
    if (!sampler || !sampler->getKeyframeContainerTyped() || sampler->getKeyframeContainerTyped()->empty())
        return false;
    curve.at = [sampler](double t) {
        typename SamplerT::UsingType value;
        sampler->getValueAt(t, value);
        return Value(value);
    };
    curve.times.clear();
    for (const auto& key : *sampler->getKeyframeContainerTyped()) curve.times.push_back(key.getTime());
    curve.step = step;
    return true;
}

using namespace osgAnimation;

bool bindVec3(const Channel& c, Curve<osg::Vec3d>& curve)
{
    return bindCurve<Vec3LinearSampler>(c, false, curve) || bindCurve<Vec3StepSampler>(c, true, curve) ||
           bindCurve<Vec3CubicBezierSampler>(c, false, curve);
}

bool bindQuat(const Channel& c, Curve<osg::Quat>& curve)
{
    return bindCurve<QuatSphericalLinearSampler>(c, false, curve) || bindCurve<QuatStepSampler>(c, true, curve);
}

bool bindAngle(const Channel& c, Curve<double>& curve)
{
    return bindCurve<FloatLinearSampler>(c, false, curve) || bindCurve<FloatStepSampler>(c, true, curve) ||
           bindCurve<FloatCubicBezierSampler>(c, false, curve) || bindCurve<DoubleLinearSampler>(c, false, curve) ||
           bindCurve<DoubleStepSampler>(c, true, curve) || bindCurve<DoubleCubicBezierSampler>(c, false, curve);
}

bool bindMatrix(const Channel& c, Curve<osg::Matrixd>& curve)
{
    return bindCurve<MatrixLinearSampler>(c, false, curve);
}

/** One element of a stacked transform, its matrix at any time: its own value, or its channel's. */
struct AnimatedElement
{
    std::function<glm::dmat4(double)> at;
    std::vector<double> times;
    bool step = true; // no channel, or a step channel
};

/** The element as it is (not animated). */
AnimatedElement fixedElement(const StackedTransformElement& element)
{
    const glm::dmat4 matrix = toGlm(element.getAsMatrix());
    AnimatedElement animated;
    animated.at = [matrix](double) { return matrix; };
    return animated;
}

/** The element driven by a channel, as osgAnimation's element applies its target's value; false when the channel's
  * type is not the element's (osgAnimation does not link it either). */
bool animatedElement(const StackedTransformElement& element, const Channel& channel, AnimatedElement& animated)
{
    auto take = [&](auto& curve, auto toMatrix) {
        animated.at = [curve, toMatrix](double t) { return toGlm(toMatrix(curve.at(t))); };
        animated.times = curve.times;
        animated.step = curve.step;
        return true;
    };
    if (dynamic_cast<const StackedTranslateElement*>(&element))
    {
        Curve<osg::Vec3d> curve;
        return bindVec3(channel, curve) && take(curve, [](const osg::Vec3d& v) { return osg::Matrixd::translate(v); });
    }
    if (dynamic_cast<const StackedScaleElement*>(&element))
    {
        Curve<osg::Vec3d> curve;
        return bindVec3(channel, curve) && take(curve, [](const osg::Vec3d& v) { return osg::Matrixd::scale(v); });
    }
    if (dynamic_cast<const StackedQuaternionElement*>(&element))
    {
        Curve<osg::Quat> curve;
        return bindQuat(channel, curve) && take(curve, [](const osg::Quat& q) { return osg::Matrixd::rotate(q); });
    }
    if (const auto* rotate = dynamic_cast<const StackedRotateAxisElement*>(&element))
    {
        Curve<double> curve;
        const osg::Vec3d axis = rotate->getAxis();
        return bindAngle(channel, curve) &&
               take(curve, [axis](double angle) { return osg::Matrixd::rotate(osg::Quat(angle, axis)); });
    }
    if (dynamic_cast<const StackedMatrixElement*>(&element))
    {
        Curve<osg::Matrixd> curve;
        return bindMatrix(channel, curve) && take(curve, [](const osg::Matrixd& m) { return m; });
    }
    return false;
}

/** A rigid pose and scale taken from a matrix that may not be one (osgAnimation interpolates matrices element by
  * element): the translation, the rotation nearest the 3x3 part (its polar factor), the scale along that
  * rotation's axes. */
struct Pose
{
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
};

Pose poseOf(const glm::dmat4& matrix)
{
    Pose pose;
    pose.translation = glm::dvec3(matrix[3]);
    const glm::dmat3 linear(matrix);
    glm::dmat3 mirror(1.0);
    if (glm::determinant(linear) < 0.0) mirror[0][0] = -1.0; // a mirror goes on X, as decomposeNodeMatrix puts it
    glm::dmat3 rotation = linear * mirror;
    for (int i = 0; i < 30; ++i) // Newton's iteration to the polar factor; quadratic near the end
    {
        const glm::dmat3 next = 0.5 * (rotation + glm::transpose(glm::inverse(rotation)));
        const double change = glm::length(next[0] - rotation[0]) + glm::length(next[1] - rotation[1]) +
                              glm::length(next[2] - rotation[2]);
        rotation = next;
        if (change < 1e-15) break;
    }
    pose.rotation = glm::normalize(glm::quat_cast(rotation));
    const glm::dmat3 stretch = glm::transpose(rotation) * linear;
    pose.scale = glm::dvec3(stretch[0][0], stretch[1][1], stretch[2][2]);
    return pose;
}

double angleBetween(const glm::dquat& a, const glm::dquat& b)
{
    return 2.0 * std::acos(std::min(1.0, std::abs(glm::dot(a, b))));
}

/** One stacked transform under one animation: its elements, and the channels that drive them. */
class AnimatedStack
{
public:
    std::vector<AnimatedElement> elements;

    glm::dmat4 at(double t) const
    {
        glm::dmat4 matrix(1.0);
        for (const AnimatedElement& element : elements) matrix = matrix * element.at(t);
        return matrix;
    }

    /** Whether every animated element steps. */
    bool allStep() const
    {
        return std::all_of(elements.begin(), elements.end(), [](const AnimatedElement& e) { return e.step; });
    }

    /** The times the stacked transform is smooth between, sorted: the elements' key times and, beside the keys of
      * step channels, the times one unit in the last place away where osgAnimation's steps change (just after an
      * inner key, whose own time still shows the key before; just before the last key, whose time shows it), so
      * that the samples hold the value on either side of each change exactly. */
    std::vector<double> breakpoints() const
    {
        std::set<double> times;
        for (const AnimatedElement& element : elements)
        {
            times.insert(element.times.begin(), element.times.end());
            if (!element.step || element.times.size() < 2) continue;
            for (std::size_t k = 1; k + 1 < element.times.size(); ++k)
                times.insert(std::nextafter(element.times[k], std::numeric_limits<double>::infinity()));
            times.insert(std::nextafter(element.times.back(), -std::numeric_limits<double>::infinity()));
        }
        return std::vector<double>(times.begin(), times.end());
    }
};

/** Samples a stacked transform into channels of its node: exact at its breakpoints (key times); between them,
  * evenly spaced samples, as few as keep the linear (spherical for rotations) interpolation within tolerance. Returns
  * whether the cap on samples was reached. */
bool sampleStack(const AnimatedStack& stack, int node, const RiggedNode& rest, double tolerance, double lever,
                 const std::string& place, RiggedAnimation& animation)
{
    const bool allStep = stack.allStep();
    const std::vector<double> keys = stack.breakpoints();
    std::vector<double> times;
    std::vector<Pose> poses;
    bool capped = false;
    for (std::size_t k = 0; k < keys.size(); ++k)
    {
        times.push_back(keys[k]);
        poses.push_back(poseOf(stack.at(keys[k])));
        if (allStep || k + 1 == keys.size()) continue;
        const double t0 = keys[k], t1 = keys[k + 1];
        if (std::nextafter(t0, t1) == t1) continue; // one unit in the last place: nothing between
        const Pose first = poses.back(), last = poseOf(stack.at(t1));
        auto exact = [&](double t) { return poseOf(stack.at(t)); };
        auto strays = [&](const Pose& a, const Pose& b, double u, double t) {
            const Pose pose = exact(t);
            const glm::dquat to = glm::dot(a.rotation, b.rotation) < 0.0 ? -b.rotation : b.rotation;
            const glm::dquat rotation = glm::normalize(glm::slerp(a.rotation, to, u));
            const glm::dvec3 translation = glm::mix(a.translation, b.translation, u);
            return glm::length(translation - pose.translation) + lever * angleBetween(rotation, pose.rotation);
        };
        capped = subdivideInterval(t0, t1, first, last, exact, strays, tolerance, times, poses) || capped;
    }
    for (const Pose& pose : poses)
        if (!std::isfinite(pose.translation.x + pose.translation.y + pose.translation.z + pose.rotation.x +
                           pose.rotation.y + pose.rotation.z + pose.rotation.w + pose.scale.x + pose.scale.y +
                           pose.scale.z))
            throw Refusal(place, "the animated transform of '" + rest.name + "' is not finite");
    const glm::dvec4 restParts[3] = {glm::dvec4(rest.translation, 0.0),
                                     glm::dvec4(rest.rotation.x, rest.rotation.y, rest.rotation.z, rest.rotation.w),
                                     glm::dvec4(rest.scale, 0.0)};
    const AnimationPath paths[3] = {AnimationPath::Translation, AnimationPath::Rotation, AnimationPath::Scale};
    for (int part = 0; part < 3; ++part)
    {
        auto value = [&](std::size_t i) {
            const Pose& pose = poses[i];
            return part == 0   ? glm::dvec4(pose.translation, 0.0)
                   : part == 1 ? glm::dvec4(pose.rotation.x, pose.rotation.y, pose.rotation.z, pose.rotation.w)
                               : glm::dvec4(pose.scale, 0.0);
        };
        // Scales that differ by less than float matrices resolve are the same.
        auto differ = [&](const glm::dvec4& a, const glm::dvec4& b) {
            if (part == 1) return angleBetween(glm::dquat(a.w, a.x, a.y, a.z), glm::dquat(b.w, b.x, b.y, b.z)) > 1e-9;
            return glm::length(a - b) > (part == 2 ? 1e-6 : 1e-12) * (1.0 + glm::length(b));
        };
        // A part that never leaves its rest value is no channel (no needless DOFs). Scale counts at the breakpoints
        // only: between them, the shrink of an element-wise matrix interpolation is no scale the file holds.
        bool moves = false, jumps = false, glides = false;
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            if (part != 2 || std::binary_search(keys.begin(), keys.end(), times[i]))
                moves = moves || differ(value(i), restParts[part]);
            if (i + 1 == poses.size() || !differ(value(i), value(i + 1))) continue;
            if (std::nextafter(times[i], times[i + 1]) == times[i + 1]) jumps = true;
            else glides = true;
        }
        if (!moves) continue;
        AnimationChannel channel;
        channel.node = node;
        channel.path = paths[part];
        // What only jumps is a step; what only glides is linear; a part that does both (a step channel in a stack
        // with smooth ones) is linear without the samples beside the steps, its steps turned into ramps as short
        // as a sampled piece.
        channel.interpolation = allStep || !glides ? KeyInterpolation::Step : KeyInterpolation::Linear;
        for (std::size_t i = 0; i < poses.size(); ++i)
        {
            const bool besideStep = i > 0 && std::nextafter(times[i - 1], times[i]) == times[i];
            if (jumps && glides && besideStep) continue;
            channel.times.push_back(times[i]);
            channel.values.push_back(value(i));
        }
        animation.channels.push_back(std::move(channel));
    }
    return capped;
}

} // namespace

glm::dmat4 restStackMatrix(const StackedTransform& stack)
{
    glm::dmat4 matrix(1.0);
    for (const auto& element : stack)
        if (element) matrix = matrix * toGlm(element->getAsMatrix());
    return matrix;
}

void readAnimations(const AnimationManagerBase& manager, const std::multimap<std::string, StackTarget>& targets,
                    double tolerance, const std::vector<double>& levers, RiggedModel& model,
                    std::vector<std::string>& warnings)
{
    const AnimationList& list = manager.getAnimationList();
    for (std::size_t a = 0; a < list.size(); ++a)
    {
        if (!list[a]) continue;
        const Animation& source = *list[a];
        const std::string place = "animations[" + std::to_string(a) + "] '" + source.getName() + "'";
        RiggedAnimation animation;
        animation.name = source.getName(); // "animation<i>" when empty (makeAnimationNamesUnique)
        // The channels of each stacked transform, by the element they drive.
        std::map<const StackedTransform*, std::pair<int, std::map<std::size_t, const Channel*>>> driven;
        const ChannelList& channels = source.getChannels();
        for (std::size_t c = 0; c < channels.size(); ++c)
        {
            if (!channels[c]) continue;
            const Channel& channel = *channels[c];
            const std::string where = place + ".channels[" + std::to_string(c) + "] '" + channel.getTargetName() +
                                      "." + channel.getName() + "'";
            const auto range = targets.equal_range(channel.getTargetName());
            if (range.first == range.second)
            {
                warnings.push_back(where + ": targets no UpdateMatrixTransform or UpdateBone and is left out");
                continue;
            }
            for (auto target = range.first; target != range.second; ++target)
            {
                const StackedTransform& stack = *target->second.stack;
                std::size_t e = 0;
                while (e < stack.size() && !(stack[e] && stack[e]->getName() == channel.getName())) ++e;
                if (e == stack.size())
                {
                    warnings.push_back(where + ": its target has no element '" + channel.getName() +
                                       "'; it is left out");
                    continue;
                }
                auto& entry = driven[&stack];
                entry.first = target->second.node;
                entry.second[e] = &channel;
            }
        }
        std::map<int, AnimatedNode> animatedNodes;
        for (const auto& [stack, entry] : driven)
        {
            AnimatedStack animated;
            bool blendsMatrices = false;
            for (std::size_t e = 0; e < stack->size(); ++e)
            {
                const StackedTransformElement* element = (*stack)[e].get();
                if (!element) continue;
                const auto channel = entry.second.find(e);
                if (channel == entry.second.end())
                {
                    animated.elements.push_back(fixedElement(*element));
                    continue;
                }
                AnimatedElement driven;
                if (!animatedElement(*element, *channel->second, driven))
                {
                    warnings.push_back(place + ": the channel of '" + channel->second->getTargetName() + "." +
                                       element->getName() + "' is not of a type its " + element->className() +
                                       " takes (or has no keys); it is left out");
                    animated.elements.push_back(fixedElement(*element));
                    continue;
                }
                for (std::size_t k = 1; k < driven.times.size(); ++k)
                    if (!(driven.times[k] > driven.times[k - 1]) || !std::isfinite(driven.times[k]))
                        throw Refusal(place + ".channel '" + channel->second->getTargetName() + "." +
                                          element->getName() + "'",
                                      "key times are not strictly increasing at key " + std::to_string(k));
                animated.elements.push_back(driven);
                blendsMatrices = blendsMatrices || dynamic_cast<const StackedMatrixElement*>(element) != nullptr;
            }
            if (sampleStack(animated, entry.first, model.nodes[entry.first], tolerance, levers[entry.first], place,
                            animation))
                warnings.push_back(place + ": the motion of '" + model.nodes[entry.first].name +
                                   "' is resampled with the most samples allowed and strays more than the tolerance");
            animatedNodes[entry.first] = AnimatedNode{[animated](double t) { return animated.at(t); },
                                                      animated.breakpoints(), blendsMatrices};
        }
        for (int node : addBlendedPositionChannels(animatedNodes, model, tolerance, animation))
            warnings.push_back(place + ": the position of '" + model.nodes[node].name +
                               "' under blended matrices is resampled with the most samples allowed and strays more "
                               "than the tolerance");
        model.animations.push_back(std::move(animation));
    }
}

} // namespace osganimation
} // namespace osgActor
