#include <osgActor/core/Clip>

#include <glm/ext/scalar_constants.hpp>

#include <algorithm>
#include <cmath>

namespace osgActor {

namespace {

constexpr double kTwoPi = 2.0 * glm::pi<double>();

/** An angle difference folded into [-pi, pi] (radians); the library call only when it is outside, which keeps
  * the common case (neighbouring frames) to two compares. */
inline double shortestDelta(double delta)
{
    return delta > glm::pi<double>() || delta < -glm::pi<double>() ? std::remainder(delta, kTwoPi) : delta;
}

/** value moved by a whole number of turns to lie within half a turn of reference (radians). */
inline double nearAngle(double reference, double value) { return reference + shortestDelta(value - reference); }

/** Interpolates between a (t = 0) and b (t = 1) with neighbours before (of a) and after (of b). */
inline double interpolate(const ClipChannel& channel, double before, double a, double b, double after, double t)
{
    switch (channel.interpolation)
    {
    case Interpolation::Step: return a;
    case Interpolation::Linear:
        return channel.angular ? a + t * shortestDelta(b - a) : a + t * (b - a);
    case Interpolation::Cubic:
        if (channel.angular)
        {
            // Unwrap the neighbours around a so that a 179 -> -179 degree step is 2 degrees, not 358.
            b = nearAngle(a, b);
            before = nearAngle(a, before);
            after = nearAngle(b, after);
        }
        return catmullRom(before, a, b, after, t);
    }
    return a;
}

} // namespace

double catmullRom(double p0, double p1, double p2, double p3, double t)
{
    const double t2 = t * t;
    const double t3 = t2 * t;
    return 0.5 * (2.0 * p1 + (p2 - p0) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                  (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3);
}

int Clip::findChannel(const std::string& target) const
{
    for (unsigned c = 0; c < _channels.size(); ++c)
        if (_channels[c].target == target) return static_cast<int>(c);
    return -1;
}

void Clip::initCursor(ClipCursor& cursor) const { cursor.keys.assign(_uniform ? 0 : _channels.size(), 0u); }

void Clip::sample(double time, ClipCursor& cursor, double* values) const
{
    time = std::isfinite(time) ? std::min(std::max(time, 0.0), _duration) : 0.0;
    if (_uniform)
    {
        sampleUniform(time, values);
        return;
    }
    for (unsigned c = 0; c < _channels.size(); ++c) values[c] = sampleKeyed(c, time, cursor.keys[c]);
}

void Clip::sampleUniform(double time, double* values) const
{
    const unsigned numChannels = getNumChannels();
    const unsigned last = _numFrames - 1;
    double position = time * _frameRate; // in frames
    double whole = std::floor(position);
    double t = position - whole;
    // Frame times computed as frame / rate come back a hair below the frame: snap them onto it.
    if (t > 1.0 - 1e-9)
    {
        whole += 1.0;
        t = 0.0;
    }
    const unsigned i = std::min(static_cast<unsigned>(whole), last);
    if (i == last || t == 0.0)
    {
        std::copy(getFrame(i), getFrame(i) + numChannels, values);
        return;
    }
    const double* before = getFrame(i > 0 ? i - 1 : 0);
    const double* a = getFrame(i);
    const double* b = getFrame(i + 1);
    const double* after = getFrame(std::min(i + 2, last));
    for (unsigned c = 0; c < numChannels; ++c) values[c] = interpolate(_channels[c], before[c], a[c], b[c], after[c], t);
}

double Clip::sampleKeyed(unsigned channel, double time, std::uint32_t& cursorKey) const
{
    const double* times = _times.data() + _keyBegin[channel];
    const double* keyValues = _values.data() + _keyBegin[channel];
    const std::uint32_t numKeys = _keyBegin[channel + 1] - _keyBegin[channel];
    // The cursor is the last key at or before the time: usually unchanged or one step on from the last frame.
    std::uint32_t k = std::min(cursorKey, numKeys - 1);
    if (times[k] > time)
        k = static_cast<std::uint32_t>(std::upper_bound(times, times + k, time) - times) - (times[0] <= time ? 1 : 0);
    while (k + 1 < numKeys && times[k + 1] <= time) ++k;
    cursorKey = k;
    if (k + 1 >= numKeys || time <= times[k]) return keyValues[k];
    const double t = (time - times[k]) / (times[k + 1] - times[k]);
    const double before = keyValues[k > 0 ? k - 1 : 0];
    const double after = keyValues[std::min(k + 2, numKeys - 1)];
    return interpolate(_channels[channel], before, keyValues[k], keyValues[k + 1], after, t);
}

} // namespace osgActor
