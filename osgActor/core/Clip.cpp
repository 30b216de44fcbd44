#include <osgActor/core/Clip>

#include <glm/ext/scalar_constants.hpp>

#include "HotPath.h"

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
inline double interpolate(Clip::Kernel kernel, double before, double a, double b, double after, double t)
{
    switch (kernel)
    {
    case Clip::Kernel::Step: return a;
    case Clip::Kernel::Linear: return a + t * (b - a);
    case Clip::Kernel::LinearAngular: return a + t * shortestDelta(b - a);
    case Clip::Kernel::Cubic: return catmullRom(before, a, b, after, t);
    case Clip::Kernel::CubicAngular:
        // Unwrap the neighbours around a so that a 179 -> -179 degree step is 2 degrees, not 358.
        b = nearAngle(a, b);
        return catmullRom(nearAngle(a, before), a, b, nearAngle(b, after), t);
    }
    return a;
}

/** values[c] = a[c] + t (b[c] - a[c]) for c < count, the whole loop vectorized: the linear kernel, and the
  * linear-angular one (angular[c] = 1) whenever no angular step exceeds half a turn. Returns false, with values
  * unspecified, when one does (the caller then folds it exactly, like shortestDelta); between neighbouring frames
  * of motion capture that is a wrap through +-180 degrees, once in a while. */
OSGACTOR_HOT_PATH bool lerpRange(const double* __restrict a, const double* __restrict b,
                                 const double* __restrict angular, double t, unsigned count,
                                 double* __restrict values)
{
    std::uint64_t wraps = 0; // as wide as the values: a bool would keep the loop from vectorizing
    for (unsigned c = 0; c < count; ++c)
    {
        const double delta = b[c] - a[c];
        values[c] = a[c] + t * delta;
        wraps |= std::fabs(delta) * angular[c] > glm::pi<double>() ? 1u : 0u;
    }
    return wraps == 0;
}

Clip::Kernel kernelOf(const ClipChannel& channel)
{
    switch (channel.interpolation)
    {
    case Interpolation::Step: return Clip::Kernel::Step;
    case Interpolation::Linear: return channel.angular ? Clip::Kernel::LinearAngular : Clip::Kernel::Linear;
    case Interpolation::Cubic: return channel.angular ? Clip::Kernel::CubicAngular : Clip::Kernel::Cubic;
    }
    return Clip::Kernel::Linear;
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

void Clip::setChannels(const std::vector<ClipChannel>& channels)
{
    _channels = channels;
    _kernels.clear();
    _angularMask.clear();
    _nonLinearBefore.assign(1, 0u);
    for (const ClipChannel& channel : _channels)
    {
        const Kernel kernel = kernelOf(channel);
        _kernels.push_back(kernel);
        _angularMask.push_back(kernel == Kernel::LinearAngular ? 1.0 : 0.0);
        const bool linear = kernel == Kernel::Linear || kernel == Kernel::LinearAngular;
        _nonLinearBefore.push_back(_nonLinearBefore.back() + (linear ? 0u : 1u));
    }
}

void Clip::initCursor(ClipCursor& cursor) const { cursor.keys.assign(_uniform ? 0 : _channels.size(), 0u); }

template <class SampleOne>
void Clip::sampleEach(ChannelSet set, double* values, SampleOne sampleOne) const
{
    if (set.channels)
        for (unsigned i = 0; i < set.count; ++i) values[i] = sampleOne(set.channels[i]);
    else
        for (unsigned i = 0; i < set.count; ++i) values[i] = sampleOne(set.first + i);
}

void Clip::sample(double time, ClipCursor& cursor, double* values) const
{
    sampleAny(time, cursor, ChannelSet{nullptr, 0, getNumChannels()}, values);
}

void Clip::sample(double time, ClipCursor& cursor, const std::uint32_t* channels, unsigned count,
                  double* values) const
{
    sampleAny(time, cursor, ChannelSet{channels, 0, count}, values);
}

void Clip::sampleRange(double time, ClipCursor& cursor, unsigned firstChannel, unsigned count, double* values) const
{
    sampleAny(time, cursor, ChannelSet{nullptr, firstChannel, count}, values);
}

void Clip::sampleAny(double time, ClipCursor& cursor, ChannelSet set, double* values) const
{
    time = std::isfinite(time) ? std::min(std::max(time, 0.0), _duration) : 0.0;
    if (_uniform)
        sampleUniform(time, set, values);
    else
        sampleEach(set, values, [&](unsigned c) { return sampleKeyed(c, time, cursor.keys[c]); });
}

void Clip::sampleUniform(double time, ChannelSet set, double* values) const
{
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
    const double* a = getFrame(i);
    if (i == last || t == 0.0)
    {
        if (set.channels)
            sampleEach(set, values, [a](unsigned c) { return a[c]; });
        else
            std::copy(a + set.first, a + set.first + set.count, values);
        return;
    }
    const double* b = getFrame(i + 1);
    if (!set.channels && isLinearRange(set.first, set.count) &&
        lerpRange(a + set.first, b + set.first, _angularMask.data() + set.first, t, set.count, values))
        return;
    const double* before = getFrame(i > 0 ? i - 1 : 0);
    const double* after = getFrame(std::min(i + 2, last));
    const Kernel* kernels = _kernels.data();
    sampleEach(set, values, [=](unsigned c) {
        // Motion capture is all angular-linear (and linear for the root's travel): those inline, the rest call.
        const Kernel kernel = kernels[c];
        if (kernel == Kernel::LinearAngular) return a[c] + t * shortestDelta(b[c] - a[c]);
        if (kernel == Kernel::Linear) return a[c] + t * (b[c] - a[c]);
        return interpolate(kernel, before[c], a[c], b[c], after[c], t);
    });
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
    return interpolate(_kernels[channel], before, keyValues[k], keyValues[k + 1], after, t);
}

} // namespace osgActor
