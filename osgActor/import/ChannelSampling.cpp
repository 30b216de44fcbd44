#include <osgActor/import/ChannelSampling>

#include <glm/ext/quaternion_common.hpp>
#include <glm/ext/quaternion_geometric.hpp>

#include <algorithm>
#include <limits>

namespace osgActor {

namespace {

/** The key interval holding time: key k and k + 1 with the fraction u in [0, 1) between them; k = last key (u = 0)
  * at or after the last key, k = 0 (u = 0) at or before the first. */
struct KeySpan
{
    std::size_t key;
    double u;
    double duration; // seconds between key and key + 1 (0 at the ends)
};

KeySpan findSpan(const std::vector<double>& times, double time)
{
    if (times.size() < 2 || time <= times.front()) return KeySpan{0, 0.0, 0.0};
    if (time >= times.back()) return KeySpan{times.size() - 1, 0.0, 0.0};
    const std::size_t next = std::size_t(std::upper_bound(times.begin(), times.end(), time) - times.begin());
    const std::size_t key = next - 1;
    const double duration = times[next] - times[key];
    return KeySpan{key, (time - times[key]) / duration, duration};
}

/** The cubic Hermite curve between p0 (tangent m0) and p1 (tangent m1) at u, tangents per second over duration. */
glm::dvec4 hermite(const glm::dvec4& p0, const glm::dvec4& m0, const glm::dvec4& p1, const glm::dvec4& m1,
                   double duration, double u)
{
    const double u2 = u * u, u3 = u2 * u;
    return (2.0 * u3 - 3.0 * u2 + 1.0) * p0 + (u3 - 2.0 * u2 + u) * duration * m0 + (-2.0 * u3 + 3.0 * u2) * p1 +
           (u3 - u2) * duration * m1;
}

glm::dquat toQuaternion(const glm::dvec4& xyzw) { return glm::dquat(xyzw.w, xyzw.x, xyzw.y, xyzw.z); }

/** The channel's value at time as a 4-vector, before any rotation-specific step (CubicSpline's unnormalised
  * result; Linear left to the caller). */
glm::dvec4 sampleRaw(const AnimationChannel& channel, const KeySpan& span)
{
    const std::size_t k = span.key;
    if (span.u == 0.0 || channel.interpolation == KeyInterpolation::Step) return channel.values[k];
    if (channel.interpolation == KeyInterpolation::CubicSpline)
        return hermite(channel.values[k], channel.outTangents[k], channel.values[k + 1], channel.inTangents[k + 1],
                       span.duration, span.u);
    return channel.values[k] + span.u * (channel.values[k + 1] - channel.values[k]);
}

} // namespace

glm::dvec3 sampleVectorChannel(const AnimationChannel& channel, double time)
{
    return glm::dvec3(sampleRaw(channel, findSpan(channel.times, time)));
}

glm::dquat sampleRotationChannel(const AnimationChannel& channel, double time)
{
    const KeySpan span = findSpan(channel.times, time);
    if (channel.interpolation == KeyInterpolation::Linear && span.u != 0.0)
    {
        const glm::dquat a = toQuaternion(channel.values[span.key]);
        glm::dquat b = toQuaternion(channel.values[span.key + 1]);
        if (glm::dot(a, b) < 0.0) b = -b; // the shorter arc
        return glm::normalize(glm::slerp(a, b, span.u));
    }
    return glm::normalize(toQuaternion(sampleRaw(channel, span)));
}

void animationTimeRange(const RiggedAnimation& animation, double& first, double& last)
{
    first = std::numeric_limits<double>::infinity();
    last = -std::numeric_limits<double>::infinity();
    for (const AnimationChannel& channel : animation.channels)
    {
        if (channel.times.empty()) continue;
        first = std::min(first, channel.times.front());
        last = std::max(last, channel.times.back());
    }
    if (first > last) first = last = 0.0;
}

} // namespace osgActor
