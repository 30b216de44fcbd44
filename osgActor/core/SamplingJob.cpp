// Clip sampling on the per-frame path. Compiled with -O3, without trapping math (so the branch-free selects
// vectorize) and without fused multiply-adds: the vectorized path for ranges of channels (the x86-64-v3 clone) and
// the per-channel path (the baseline) must give the same bits, whichever a player takes.
#include <osgActor/core/SamplingJob>

#include <glm/ext/scalar_constants.hpp>

#include "detail/HotPath.h"

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

/** The value at t in [0, 1] along a Catmull-Rom spline through p0..p3 (p1 at t = 0, p2 at t = 1). */
double catmullRom(double p0, double p1, double p2, double p3, double t)
{
    const double t2 = t * t;
    const double t3 = t2 * t;
    return 0.5 * (2.0 * p1 + (p2 - p0) * t + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2 +
                  (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3);
}

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

/** Which channels a run samples: the listed ones, or (channels null) first .. first + count - 1. */
struct ChannelSet
{
    const std::uint32_t* channels;
    unsigned first;
    unsigned count;
};

/** Calls sampleOne(channel) -> value for each channel of the set. */
template <class SampleOne>
void sampleEach(ChannelSet set, double* values, SampleOne sampleOne)
{
    if (set.channels)
        for (unsigned i = 0; i < set.count; ++i) values[i] = sampleOne(set.channels[i]);
    else
        for (unsigned i = 0; i < set.count; ++i) values[i] = sampleOne(set.first + i);
}

/** A clip's storage as the sampling loops read it (see Clip's members). */
struct ClipArrays
{
    const Clip::Kernel* kernels;
    const double* angularMask;
    const unsigned* nonLinearBefore;
    const double* values;
    const double* times;
    const std::uint32_t* keyBegin;
    unsigned numChannels;
    unsigned numFrames;
    double frameRate;

    const double* frame(unsigned i) const { return values + std::size_t(i) * numChannels; }
    /** Whether every channel in first .. first + count - 1 interpolates linearly (angular or not). */
    bool isLinearRange(unsigned first, unsigned count) const
    {
        return nonLinearBefore[first + count] == nonLinearBefore[first];
    }
};

void sampleUniform(const ClipArrays& clip, double time, ChannelSet set, double* values)
{
    const unsigned last = clip.numFrames - 1;
    double position = time * clip.frameRate; // in frames
    double whole = std::floor(position);
    double t = position - whole;
    // Frame times computed as frame / rate come back a hair below the frame: snap them onto it.
    if (t > 1.0 - 1e-9)
    {
        whole += 1.0;
        t = 0.0;
    }
    const unsigned i = std::min(static_cast<unsigned>(whole), last);
    const double* a = clip.frame(i);
    if (i == last || t == 0.0)
    {
        if (set.channels)
            sampleEach(set, values, [a](unsigned c) { return a[c]; });
        else
            std::copy(a + set.first, a + set.first + set.count, values);
        return;
    }
    const double* b = clip.frame(i + 1);
    if (!set.channels && clip.isLinearRange(set.first, set.count) &&
        lerpRange(a + set.first, b + set.first, clip.angularMask + set.first, t, set.count, values))
        return;
    const double* before = clip.frame(i > 0 ? i - 1 : 0);
    const double* after = clip.frame(std::min(i + 2, last));
    const Clip::Kernel* kernels = clip.kernels;
    sampleEach(set, values, [=](unsigned c) {
        // Motion capture is all angular-linear (and linear for the root's travel): those inline, the rest call.
        const Clip::Kernel kernel = kernels[c];
        if (kernel == Clip::Kernel::LinearAngular) return a[c] + t * shortestDelta(b[c] - a[c]);
        if (kernel == Clip::Kernel::Linear) return a[c] + t * (b[c] - a[c]);
        return interpolate(kernel, before[c], a[c], b[c], after[c], t);
    });
}

double sampleKeyed(const ClipArrays& clip, unsigned channel, double time, std::uint32_t& cursorKey)
{
    const double* times = clip.times + clip.keyBegin[channel];
    const double* keyValues = clip.values + clip.keyBegin[channel];
    const std::uint32_t numKeys = clip.keyBegin[channel + 1] - clip.keyBegin[channel];
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
    return interpolate(clip.kernels[channel], before, keyValues[k], keyValues[k + 1], after, t);
}

} // namespace

bool SamplingJob::validate() const
{
    if (!clip || !cursor) return false;
    const unsigned numChannels = clip->getNumChannels();
    // A uniform clip's sampling reads no cursor (so any will do, and a player's is not touched for it).
    if (!clip->isUniform() && cursor->keys.size() != numChannels) return false;
    if (channels.empty()) return firstChannel <= numChannels && values.size() <= numChannels - firstChannel;
    if (channels.size() != values.size()) return false;
    return std::all_of(channels.begin(), channels.end(), [numChannels](std::uint32_t c) { return c < numChannels; });
}

bool SamplingJob::run() const
{
    if (!validate()) return false;
    const ClipArrays arrays{clip->_kernels.data(), clip->_angularMask.data(), clip->_nonLinearBefore.data(),
                            clip->_values.data(),  clip->_times.data(),       clip->_keyBegin.data(),
                            clip->getNumChannels(), clip->_numFrames,          clip->_frameRate};
    const ChannelSet set{channels.empty() ? nullptr : channels.data(), firstChannel,
                         static_cast<unsigned>(values.size())};
    const double t = std::isfinite(time) ? std::min(std::max(time, 0.0), clip->getDuration()) : 0.0;
    if (clip->isUniform())
        sampleUniform(arrays, t, set, values.data());
    else
        sampleEach(set, values.data(), [&](unsigned c) { return sampleKeyed(arrays, c, t, cursor->keys[c]); });
    return true;
}

bool sampleEveryChannel(const Clip& clip, double time, ClipCursor& cursor, Span<double> values)
{
    if (values.size() != clip.getNumChannels()) return false;
    SamplingJob job;
    job.clip = &clip;
    job.time = time;
    job.cursor = &cursor;
    job.values = values;
    return job.run();
}

} // namespace osgActor
