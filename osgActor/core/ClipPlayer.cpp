#include <osgActor/core/ClipPlayer>
#include <osgActor/core/LocalMatricesJob>
#include <osgActor/core/SamplingJob>

#include "detail/EnumNames.h"

#include <glm/ext/matrix_double3x3.hpp>
#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace osgActor {

namespace {

const glm::dvec3 kUp(0.0, 0.0, 1.0);

/** Room for this frame's samples of a player's driven channels: one buffer per thread, reused by every player it
  * runs, so an instance carries no per-frame buffer of its own. */
double* drivenValuesScratch(unsigned count)
{
    thread_local std::vector<double> values;
    if (values.size() < count) values.resize(count);
    return values.data();
}

glm::dquat headingRotation(double heading) { return glm::angleAxis(heading, kUp); }


} // namespace

namespace {

const char* const kRootMotionNames[] = {"in_skeleton", "to_transforms", "in_place"}; // in RootMotion's order

} // namespace

const char* rootMotionName(RootMotion mode) { return kRootMotionNames[static_cast<unsigned>(mode)]; }

bool parseRootMotion(const std::string& text, RootMotion& mode) { return parseEnumName(kRootMotionNames, text, mode); }

ClipPlayer::ClipPlayer(ClipPtr clip) : _clip(std::move(clip)) {}

void ClipPlayer::setClip(ClipPtr clip)
{
    _clip = std::move(clip);
    _boundTo.reset(); // bind again on the next update
}

void ClipPlayer::seek(double playTime)
{
    if (!_playHead.seek(playTime)) return;
    // A jump is not travel: root motion carries on from here without adding the cycles skipped.
    const double duration = clipDuration();
    if (duration > 0.0) _cycle = std::floor(playTime / duration);
}

void ClipPlayer::setFadeWeight(double weight)
{
    if (!std::isfinite(weight)) return;
    _fade = _fadeTarget = std::min(1.0, std::max(0.0, weight));
    _fadeRate = 0.0;
}

void ClipPlayer::fadeTo(double weight, double seconds, double delay)
{
    if (!std::isfinite(weight) || std::isnan(seconds) || !std::isfinite(delay)) return;
    const double target = std::min(1.0, std::max(0.0, weight));
    _fadeDelay = std::max(0.0, delay);
    if (!(seconds > 0.0) && _fadeDelay == 0.0)
    {
        setFadeWeight(target);
        return;
    }
    _fadeTarget = target;
    _fadeRate = seconds > 0.0 ? (_fadeTarget - _fade) / seconds
                              : std::copysign(std::numeric_limits<double>::infinity(), _fadeTarget - _fade);
}

void ClipPlayer::setRootMotion(RootMotion mode, const std::string& rootJoint)
{
    _rootMotion = mode;
    _rootJointName = rootJoint;
    _boundTo.reset();
    _haveBase = false;
}

void ClipPlayer::setSwayWindow(double seconds)
{
    if (std::isfinite(seconds)) _swayWindow = std::max(0.0, seconds);
}

bool ClipPlayer::bind(const ActorDefinition& definition)
{
    const unsigned numChannels = _clip->getNumChannels();
    std::vector<int> channelDof(numChannels, -1);
    for (unsigned c = 0; c < numChannels; ++c) channelDof[c] = definition.findDof(_clip->getChannel(c).target);
    _clip->initCursor(_cursor);
    _clip->initCursor(_swayCursor);
    bindSelection(definition, std::move(channelDof));
    bindRootMotion(definition);
    return true;
}

void ClipPlayer::bindSelection(const ActorDefinition& definition, std::vector<int> channelDof)
{
    auto binding = std::make_shared<ClipBinding>();
    binding->channelDof = std::move(channelDof);
    const DofSelection& selection = getSelection();
    for (unsigned c = 0; c < binding->channelDof.size(); ++c)
    {
        if (binding->channelDof[c] < 0) continue;
        const unsigned dof = static_cast<unsigned>(binding->channelDof[c]);
        const double weight = selection.weight(dof);
        if (!(weight > 0.0) || dof >= definition.getNumDofs()) continue;
        binding->drivenChannels.push_back(c);
        binding->drivenDofs.push_back(dof);
        binding->drivenAtFullWeight = binding->drivenAtFullWeight && weight >= 1.0;
    }
    findRuns(*binding);
    _binding = std::move(binding);
    _boundSelectionVersion = getSelectionVersion();
}

void ClipPlayer::findRuns(ClipBinding& binding)
{
    const std::vector<std::uint32_t>& channels = binding.drivenChannels;
    const std::vector<std::uint32_t>& dofs = binding.drivenDofs;
    for (std::uint32_t i = 0; i < channels.size(); ++i)
    {
        ClipBinding::Run* last = binding.runs.empty() ? nullptr : &binding.runs.back();
        if (last && channels[i] == last->firstChannel + last->count && dofs[i] == last->firstDof + last->count)
            ++last->count;
        else
            binding.runs.push_back(ClipBinding::Run{channels[i], dofs[i], 1});
    }
    // A run costs a call and a frame lookup: below a few channels per run the per-channel path is faster.
    constexpr std::size_t kMinChannelsPerRun = 4;
    if (binding.runs.size() * kMinChannelsPerRun > channels.size()) binding.runs.clear();
}

bool ClipPlayer::writesAtFullWeight() const { return _binding->drivenAtFullWeight && getWeight() * _fade >= 1.0; }

void ClipPlayer::writeDrivenDofs(ActorPose& pose, const double* values) const
{
    const ClipBinding& binding = *_binding;
    const unsigned count = static_cast<unsigned>(binding.drivenDofs.size());
    if (writesAtFullWeight())
    {
        pose.setDofs(binding.drivenDofs.data(), values, count);
        return;
    }
    for (unsigned i = 0; i < count; ++i) writeDof(pose, binding.drivenDofs[i], values[i], _fade);
}

void ClipPlayer::bindRootMotion(const ActorDefinition& definition)
{
    _rootJoint = -1;
    _rootJointChannels.clear();
    if (_rootMotion == RootMotion::InSkeleton) return;
    if (!_rootJointName.empty()) _rootJoint = definition.findJoint(_rootJointName);
    else
        for (unsigned j = 0; j < definition.getNumJoints() && _rootJoint < 0; ++j)
            if (definition.getDofMask(j) & kTranslationDofs) _rootJoint = static_cast<int>(j);
    if (_rootJoint < 0) return;
    const unsigned root = static_cast<unsigned>(_rootJoint);
    const std::vector<int>& channelDof = _binding->channelDof;
    for (unsigned c = 0; c < channelDof.size(); ++c)
        if (channelDof[c] >= 0 && definition.getDofJoint(static_cast<unsigned>(channelDof[c])) == root)
            _rootJointChannels.push_back(c);
    _sample.assign(channelDof.size(), 0.0);
    _swaySample.assign(channelDof.size(), 0.0);
    _scratchDofs = definition.getDefaultDofs();
    for (unsigned axis = 0; axis < 3; ++axis)
    {
        const int dof = definition.getDofIndex(root, static_cast<Dof>(3 + axis));
        _rootChannel[axis] = dof >= 0 ? _clip->findChannel(definition.getDofName(static_cast<unsigned>(dof))) : -1;
    }

    // The heading is measured on the root-local axis that lies flattest at clip time 0 (so its ground projection
    // is well defined), relative to its direction then.
    sampleEveryChannel(*_clip, 0.0, _cursor, _sample);
    for (std::uint32_t c : _rootJointChannels)
        _scratchDofs[static_cast<unsigned>(_binding->channelDof[c])] = _sample[c];
    const glm::dmat3 rotation0(computeJointMatrix(definition.getKinematics(root), _scratchDofs.data()));
    double flattest = 2.0;
    for (unsigned axis = 0; axis < 3; ++axis)
        if (std::abs(rotation0[axis].z) < flattest)
        {
            flattest = std::abs(rotation0[axis].z);
            _forwardAxis = glm::dvec3(0.0);
            _forwardAxis[axis] = 1.0;
        }
    const glm::dvec3 forward0 = rotation0 * _forwardAxis;
    _heading0 = std::atan2(forward0.y, forward0.x);
    glm::dvec3 start, end;
    double heading;
    rootTravelFromSample(definition, start, heading); // heading is 0 here by construction

    // One loop cycle moves the reference point from the start's ground point to the end's, turning it by the
    // heading gained: delta = (g_end, Rz(h_end)) * (-g_0, identity).
    sampleEveryChannel(*_clip, _clip->getDuration(), _cursor, _sample);
    rootTravelFromSample(definition, end, heading);
    _cycleRotation = headingRotation(heading);
    _cycleTranslation = glm::dvec3(end.x, end.y, 0.0) - _cycleRotation * glm::dvec3(start.x, start.y, 0.0);
    _haveBase = false;
}

void ClipPlayer::rootTravelFromSample(const ActorDefinition& definition, glm::dvec3& displacement, double& heading)
{
    const unsigned root = static_cast<unsigned>(_rootJoint);
    glm::dvec3 p(0.0);
    for (unsigned axis = 0; axis < 3; ++axis)
        if (_rootChannel[axis] >= 0) p[axis] = _sample[static_cast<unsigned>(_rootChannel[axis])];
    // The root's translation DOFs act before its rotation, in its offset frame: L = offset * T(p) * R.
    displacement = definition.getOffsetRotation(root) * p;
    for (std::uint32_t c : _rootJointChannels)
        _scratchDofs[static_cast<unsigned>(_binding->channelDof[c])] = _sample[c];
    const glm::dvec3 forward =
        glm::dmat3(computeJointMatrix(definition.getKinematics(root), _scratchDofs.data())) * _forwardAxis;
    heading = std::atan2(forward.y, forward.x) - _heading0;
}

glm::dvec3 ClipPlayer::groundAt(const ActorDefinition& definition, double clipTime)
{
    sampleEveryChannel(*_clip, clipTime, _swayCursor, _swaySample);
    glm::dvec3 p(0.0);
    for (unsigned axis = 0; axis < 3; ++axis)
        if (_rootChannel[axis] >= 0) p[axis] = _swaySample[static_cast<unsigned>(_rootChannel[axis])];
    const glm::dvec3 displacement = definition.getOffsetRotation(static_cast<unsigned>(_rootJoint)) * p;
    return glm::dvec3(displacement.x, displacement.y, 0.0);
}

void ClipPlayer::applyRootMotion(const ActorDefinition& definition, double clipTime, ControllerTarget& target)
{
    glm::dvec3 displacement;
    double heading;
    rootTravelFromSample(definition, displacement, heading);
    const unsigned root = static_cast<unsigned>(_rootJoint);
    for (unsigned axis = 0; axis < 3; ++axis)
    {
        const int dof = definition.getDofIndex(root, static_cast<Dof>(3 + axis));
        if (dof >= 0 && _rootChannel[axis] >= 0) writeDof(target.pose, static_cast<unsigned>(dof), 0.0, _fade);
    }
    const glm::dvec3 ground(displacement.x, displacement.y, 0.0); // model space, over the ground (Z-up)
    const glm::dvec3 bob(0.0, 0.0, displacement.z);
    ActorTransforms& transforms = target.transforms;
    if (_rootMotion == RootMotion::InPlace)
    {
        transforms.postTranslation = bob;
        transforms.postRotation = glm::dquat(1.0, 0.0, 0.0, 0.0);
    }
    else
    {
        const double duration = _clip->getDuration();
        const double cycle = getPlayMode() == PlayMode::Loop && duration > 0.0
                                 ? std::floor(_playHead.getTime() / duration)
                                 : 0.0;
        if (!_haveBase)
        {
            _baseTranslation = transforms.preTranslation;
            _baseRotation = transforms.preRotation;
            _cycle = cycle;
            _haveBase = true;
        }
        for (; _cycle < cycle; _cycle += 1.0)
        {
            _baseTranslation += _baseRotation * _cycleTranslation;
            _baseRotation = _baseRotation * _cycleRotation;
        }
        for (; _cycle > cycle; _cycle -= 1.0)
        {
            _baseRotation = _baseRotation * glm::conjugate(_cycleRotation);
            _baseTranslation -= _baseRotation * _cycleTranslation;
        }
        const glm::dquat turn = headingRotation(heading);
        // The reference path: the ground point itself, or the midpoint of the ground points half a sway window
        // before and after (the sway, ground - path, then goes to the post-transform).
        glm::dvec3 path = ground;
        if (_swayWindow > 0.0)
        {
            const double duration = _clip->getDuration();
            const double half = 0.5 * _swayWindow;
            path = 0.5 * (groundAt(definition, std::max(0.0, clipTime - half)) +
                          groundAt(definition, std::min(duration, clipTime + half)));
        }
        // pre * post = base * T(path) * Rz(h) * T(Rz(-h) (ground - path) + bob) * Rz(-h) = base * T(ground + bob):
        // the world pose is the one the skeleton had with its translation DOFs.
        transforms.preTranslation = _baseTranslation + _baseRotation * path;
        transforms.preRotation = _baseRotation * turn;
        transforms.postTranslation = glm::conjugate(turn) * (ground - path) + bob;
        transforms.postRotation = glm::conjugate(turn);
    }
    target.transformsChanged = true;
}

void ClipPlayer::update(const ControllerContext& context, ControllerTarget& target)
{
    const ActorDefinitionPtr& definition = target.pose.getDefinition();
    if (!_clip || !definition) return;
    if (_boundTo != definition)
    {
        bind(*definition);
        _boundTo = definition;
    }
    if (_boundSelectionVersion != getSelectionVersion()) bindSelection(*definition, _binding->channelDof);
    _playHead.advance(context.deltaTime);
    double fadeTime = std::max(0.0, context.deltaTime); // fades only go forward
    if (_fadeDelay > 0.0)
    {
        const double waited = std::min(fadeTime, _fadeDelay);
        _fadeDelay -= waited;
        fadeTime -= waited;
    }
    if (_fadeRate != 0.0 && fadeTime > 0.0)
    {
        _fade += _fadeRate * fadeTime;
        if ((_fadeRate > 0.0 && _fade >= _fadeTarget) || (_fadeRate < 0.0 && _fade <= _fadeTarget))
        {
            _fade = _fadeTarget;
            _fadeRate = 0.0;
        }
    }
    if (_fade <= 0.0) return;
    const double clipTime = getClipTime();
    if (_rootJoint < 0 && !_binding->runs.empty() && writesAtFullWeight())
    {
        // The common case, one clip driving the skeleton it was made for: sample and write a run at a time, through
        // a buffer on the stack (a skeleton's run fits in one or two chunks; the thread's scratch buffer would cost a
        // call to find the thread-local storage of a shared library).
        constexpr unsigned kChunk = 128;
        double values[kChunk];
        SamplingJob job;
        job.clip = _clip.get();
        job.time = clipTime;
        job.cursor = &_cursor;
        for (const ClipBinding::Run& run : _binding->runs)
            for (unsigned done = 0; done < run.count; done += kChunk)
            {
                const unsigned count = std::min(kChunk, run.count - done);
                job.firstChannel = run.firstChannel + done;
                job.values = {values, count};
                job.run();
                target.pose.setDofRange(run.firstDof + done, values, count);
            }
        return;
    }
    const std::vector<std::uint32_t>& driven = _binding->drivenChannels;
    const unsigned numDriven = static_cast<unsigned>(driven.size());
    double* values = drivenValuesScratch(numDriven);
    if (_rootJoint >= 0)
    {
        // Root motion reads the root's channels from a whole sample; the driven ones are picked from it.
        sampleEveryChannel(*_clip, clipTime, _cursor, _sample);
        for (unsigned i = 0; i < numDriven; ++i) values[i] = _sample[driven[i]];
    }
    else
    {
        SamplingJob job;
        job.clip = _clip.get();
        job.time = clipTime;
        job.cursor = &_cursor;
        job.channels = driven;
        job.values = {values, numDriven};
        job.run();
    }
    writeDrivenDofs(target.pose, values);
    if (_rootJoint >= 0) applyRootMotion(*definition, clipTime, target);
}

void crossFade(ClipPlayer& from, ClipPlayer& to, double seconds)
{
    from.fadeTo(0.0, 0.0, std::max(0.0, seconds));
    to.setFadeWeight(0.0);
    to.fadeIn(seconds);
    to.play();
}

} // namespace osgActor
