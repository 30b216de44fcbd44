#include <osgActor/core/Trajectory>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>

#include <algorithm>
#include <cmath>

namespace osgActor {

TrajectoryKey Trajectory::sample(double time, std::size_t& cursor) const
{
    const std::size_t last = _keys.size() - 1;
    if (!(time > _keys.front().time)) return _keys.front();
    if (time >= _keys.back().time) return _keys.back();
    std::size_t k = std::min(cursor, last);
    if (_keys[k].time > time)
        k = static_cast<std::size_t>(std::upper_bound(_keys.begin(), _keys.begin() + static_cast<long>(k), time,
                                                      [](double t, const TrajectoryKey& key) { return t < key.time; }) -
                                     _keys.begin()) - 1;
    while (k + 1 <= last && _keys[k + 1].time <= time) ++k;
    cursor = k;
    const TrajectoryKey& a = _keys[k];
    const TrajectoryKey& b = _keys[k + 1];
    const double t = (time - a.time) / (b.time - a.time);
    TrajectoryKey result;
    result.time = time;
    result.position = a.position + t * (b.position - a.position);
    result.heading = blendAngle(a.heading, b.heading, t);
    return result;
}

TrajectoryBuildResult TrajectoryBuilder::build(const std::string& name, std::vector<TrajectoryKey> keys)
{
    TrajectoryBuildResult result;
    const std::string what = "trajectory '" + name + "'";
    if (keys.empty())
    {
        result.error = what + " has no point";
        return result;
    }
    for (std::size_t k = 0; k < keys.size(); ++k)
    {
        const TrajectoryKey& key = keys[k];
        if (!std::isfinite(key.time) || !std::isfinite(key.heading) || !std::isfinite(key.position.x) ||
            !std::isfinite(key.position.y) || !std::isfinite(key.position.z))
            result.error = what + ": point " + std::to_string(k) + " is not finite";
        else if (k > 0 && !(key.time > keys[k - 1].time))
            result.error = what + ": point " + std::to_string(k) + " does not come after the point before it";
        if (!result.error.empty()) return result;
    }
    std::shared_ptr<Trajectory> trajectory(new Trajectory);
    trajectory->_name = name;
    trajectory->_keys = std::move(keys);
    result.trajectory = trajectory;
    return result;
}

TrajectoryPlayer::TrajectoryPlayer(TrajectoryPtr trajectory) : _trajectory(std::move(trajectory)) {}

void TrajectoryPlayer::setTrajectory(TrajectoryPtr trajectory)
{
    _trajectory = std::move(trajectory);
    _started = false;
    _cursor = 0;
}

void TrajectoryPlayer::seek(double time)
{
    if (_playHead.seek(time)) _started = true;
}

double TrajectoryPlayer::pathTimeAt(double playTime) const
{
    if (!_trajectory) return playTime;
    const double start = _trajectory->getStartTime();
    return _playHead.fold(playTime, start, _trajectory->getEndTime() - start);
}

void TrajectoryPlayer::update(const ControllerContext& context, ControllerTarget& target)
{
    if (!_trajectory) return;
    if (!_started)
    {
        _playHead.seek(_trajectory->getStartTime());
        _started = true;
    }
    else
        _playHead.advance(context.deltaTime);
    const TrajectoryKey key = _trajectory->sample(pathTimeAt(_playHead.getTime()), _cursor);
    // The pre-transform is the reference point: written whole (a trajectory has no per-DOF weights).
    target.transforms.preTranslation = key.position;
    target.transforms.preRotation = glm::angleAxis(key.heading, glm::dvec3(0.0, 0.0, 1.0));
    target.transformsChanged = true;
}

} // namespace osgActor
