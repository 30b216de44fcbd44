#include <osgActor/core/retarget/ClipFrames>
#include <osgActor/core/SamplingJob>

#include <algorithm>
#include <cmath>

namespace osgActor {

std::string sampleClipFrames(const ActorDefinition& definition, const Clip& clip, double keyedFrameRate,
                             ClipFrames& out)
{
    std::vector<int> dofOfChannel(clip.getNumChannels(), -1);
    bool any = false;
    for (unsigned c = 0; c < clip.getNumChannels(); ++c)
    {
        dofOfChannel[c] = definition.findDof(clip.getChannel(c).target);
        any = any || dofOfChannel[c] >= 0;
    }
    if (!any)
        return "clip '" + clip.getName() + "' drives no DOF of the skeleton '" + definition.getName() + "'";
    out.numDofs = definition.getNumDofs();
    if (clip.isUniform())
    {
        out.frameRate = clip.getFrameRate();
        out.numFrames = clip.getNumFrames();
    }
    else
    {
        if (!(keyedFrameRate > 0.0) || !std::isfinite(keyedFrameRate))
            return "sampling clip '" + clip.getName() + "': the frame rate must be positive";
        out.frameRate = keyedFrameRate;
        out.numFrames = static_cast<unsigned>(std::floor(clip.getDuration() * keyedFrameRate + 1e-9)) + 1;
    }
    if (out.numFrames == 0) return "clip '" + clip.getName() + "' has no frame";
    out.values.resize(std::size_t(out.numFrames) * out.numDofs);
    ClipCursor cursor;
    clip.initCursor(cursor);
    std::vector<double> sampled(clip.getNumChannels());
    for (unsigned f = 0; f < out.numFrames; ++f)
    {
        const double* channels = clip.isUniform() ? clip.getFrame(f) : sampled.data();
        if (!clip.isUniform()) sampleEveryChannel(clip, f / out.frameRate, cursor, sampled);
        double* dofs = out.values.data() + std::size_t(f) * out.numDofs;
        std::copy(definition.getDefaultDofs().begin(), definition.getDefaultDofs().end(), dofs);
        for (unsigned c = 0; c < clip.getNumChannels(); ++c)
            if (dofOfChannel[c] >= 0) dofs[dofOfChannel[c]] = channels[c];
    }
    return std::string();
}

} // namespace osgActor
