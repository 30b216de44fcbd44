#include <osgActor/core/PlayHead>

#include "detail/EnumNames.h"

#include <algorithm>
#include <cmath>

namespace osgActor {

namespace {

const char* const kPlayModeNames[] = {"once", "loop", "pingpong"}; // in PlayMode's order

} // namespace

const char* playModeName(PlayMode mode) { return kPlayModeNames[static_cast<unsigned>(mode)]; }

bool parsePlayMode(const std::string& text, PlayMode& mode) { return parseEnumName(kPlayModeNames, text, mode); }

bool PlayHead::setSpeed(double speed)
{
    if (!std::isfinite(speed)) return false;
    _speed = speed;
    return true;
}

bool PlayHead::seek(double time)
{
    if (!std::isfinite(time)) return false;
    _time = time;
    return true;
}

double PlayHead::fold(double time, double start, double length) const
{
    if (!(length > 0.0)) return start;
    const double u = time - start;
    switch (_mode)
    {
    case PlayMode::Once: return start + std::min(std::max(u, 0.0), length);
    case PlayMode::Loop: return start + (u - length * std::floor(u / length));
    case PlayMode::PingPong:
    {
        const double v = u - 2.0 * length * std::floor(u / (2.0 * length));
        return start + (v <= length ? v : 2.0 * length - v);
    }
    }
    return start;
}

bool PlayHead::isFinished(double start, double length) const
{
    if (_mode != PlayMode::Once) return false;
    return _speed >= 0.0 ? _time >= start + length : _time <= start;
}

} // namespace osgActor
