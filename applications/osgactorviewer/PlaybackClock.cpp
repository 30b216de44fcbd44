#include "PlaybackClock.h"

#include <algorithm>

namespace osgActorViewer {

void PlaybackClock::advance(double elapsedSeconds)
{
    if (_playing && elapsedSeconds > 0.0) _time += std::min(elapsedSeconds, kMaxStepSeconds) * _speed;
}

void PlaybackClock::setSpeed(double speed) { _speed = std::clamp(speed, 1.0 / 64.0, 64.0); }

void PlaybackClock::scrub(int steps)
{
    _playing = false;
    setTime(_time + steps * kStepSeconds);
}

} // namespace osgActorViewer
