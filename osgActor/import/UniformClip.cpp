#include <osgActor/import/UniformClip>
#include <osgActor/core/SamplingJob>

#include <algorithm>
#include <cmath>

namespace osgActor {

ClipBuildResult sampleClipUniformly(const Clip& clip, double first, double last, double frameRate)
{
    ClipBuildResult result;
    if (!(frameRate > 0.0) || !std::isfinite(frameRate) || !(last >= first) || !std::isfinite(last - first))
    {
        result.error = "clip '" + clip.getName() + "': cannot sample it at " + std::to_string(frameRate) +
                       " frames per second from " + std::to_string(first) + " s to " + std::to_string(last) + " s";
        return result;
    }
    const double frameCount = std::floor((last - first) * frameRate + 1e-6) + 1.0;
    const unsigned channels = clip.getNumChannels();
    if (frameCount * std::max(1u, channels) > 1e8)
    {
        result.error = "clip '" + clip.getName() + "': " + std::to_string(frameCount) + " frames of " +
                       std::to_string(channels) + " channels are too many";
        return result;
    }
    const std::size_t frames = static_cast<std::size_t>(frameCount);
    std::vector<double> values(frames * channels);
    ClipCursor cursor;
    clip.initCursor(cursor);
    for (std::size_t k = 0; k < frames; ++k)
        sampleEveryChannel(clip, first + double(k) / frameRate, cursor, {values.data() + k * channels, channels});
    ClipBuilder builder(clip.getName());
    for (unsigned c = 0; c < channels; ++c) builder.addChannel(clip.getChannel(c).target, clip.getChannel(c).interpolation);
    builder.setFrames(frameRate, std::move(values));
    return builder.build();
}

} // namespace osgActor
