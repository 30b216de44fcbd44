#include <osgActor/core/ClipBuilder>
#include <osgActor/core/Dof>

#include <cmath>
#include <sstream>
#include <unordered_set>

namespace osgActor {

namespace {

/** Parses the DOF suffix of a target "joint.rx"; false when there is no joint name or no valid suffix. */
bool parseTarget(const std::string& target, Dof& dof)
{
    const std::size_t dot = target.rfind('.');
    return dot != std::string::npos && dot > 0 && parseDof(target.substr(dot + 1), dof);
}

} // namespace

unsigned ClipBuilder::addChannel(const std::string& target, Interpolation interpolation)
{
    ClipChannel channel;
    channel.target = target;
    channel.interpolation = interpolation;
    Dof dof;
    channel.angular = parseTarget(target, dof) && isRotation(dof);
    _channels.push_back(channel);
    _keys.emplace_back();
    return getNumChannels() - 1;
}

void ClipBuilder::addKey(unsigned channel, double time, double value)
{
    if (channel < _keys.size()) _keys[channel].push_back(Key{time, value});
}

void ClipBuilder::setFrames(double frameRate, std::vector<double> values)
{
    _uniform = true;
    _frameRate = frameRate;
    _frames = std::move(values);
}

ClipBuildResult ClipBuilder::build() const
{
    ClipBuildResult result;
    const std::string clipName = "clip '" + _name + "'";
    if (_channels.empty())
    {
        result.error = clipName + " has no channel";
        return result;
    }
    std::unordered_set<std::string> targets;
    for (const ClipChannel& channel : _channels)
    {
        Dof dof;
        if (!parseTarget(channel.target, dof))
            result.error = clipName + ": channel target '" + channel.target + "' is not a DOF name like 'joint.rx'";
        else if (!targets.insert(channel.target).second)
            result.error = clipName + " has two channels for '" + channel.target + "'";
        if (!result.error.empty()) return result;
    }

    std::shared_ptr<Clip> clip(new Clip);
    clip->_name = _name;
    clip->setChannels(_channels);
    const std::size_t numChannels = _channels.size();
    if (_uniform)
    {
        if (!(_frameRate > 0.0) || !std::isfinite(_frameRate))
            result.error = clipName + ": the frame rate must be positive";
        else if (_frames.empty() || _frames.size() % numChannels != 0)
            result.error = clipName + ": " + std::to_string(_frames.size()) + " values are not a whole number of " +
                           std::to_string(numChannels) + "-channel frames";
        for (std::size_t i = 0; result.error.empty() && i < _frames.size(); ++i)
            if (!std::isfinite(_frames[i]))
                result.error = clipName + ": frame " + std::to_string(i / numChannels) + " channel '" +
                               _channels[i % numChannels].target + "' is not a finite number";
        if (!result.error.empty()) return result;
        clip->_uniform = true;
        clip->_frameRate = _frameRate;
        clip->_numFrames = static_cast<unsigned>(_frames.size() / numChannels);
        clip->_duration = (clip->_numFrames - 1) / _frameRate;
        clip->_values = _frames;
        result.clip = clip;
        return result;
    }

    clip->_keyBegin.push_back(0);
    for (std::size_t c = 0; c < numChannels; ++c)
    {
        const std::vector<Key>& keys = _keys[c];
        const std::string channelName = clipName + " channel '" + _channels[c].target + "'";
        if (keys.empty())
        {
            result.error = channelName + " has no key";
            return result;
        }
        for (std::size_t k = 0; k < keys.size(); ++k)
        {
            std::ostringstream what;
            if (!std::isfinite(keys[k].time) || keys[k].time < 0.0)
                what << channelName << ": key " << k << " has time " << keys[k].time << "; times must be >= 0";
            else if (k > 0 && !(keys[k].time > keys[k - 1].time))
                what << channelName << ": key " << k << " at " << keys[k].time
                     << " s does not come after the key before it";
            else if (!std::isfinite(keys[k].value))
                what << channelName << ": key " << k << " has a non-finite value";
            if (!what.str().empty())
            {
                result.error = what.str();
                return result;
            }
            clip->_times.push_back(keys[k].time);
            clip->_values.push_back(keys[k].value);
            clip->_duration = std::max(clip->_duration, keys[k].time);
        }
        clip->_keyBegin.push_back(static_cast<std::uint32_t>(clip->_times.size()));
    }
    result.clip = clip;
    return result;
}

} // namespace osgActor
