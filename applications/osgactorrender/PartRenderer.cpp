#include "PartRenderer.h"

#include "ImageFile.h"
#include "OutputPattern.h"
#include "RetargetPreview.h"

#include <cstdlib>
#include <vector>

namespace osgActorRender {

namespace {

std::vector<double> frameTimes(const RenderOptions& options, unsigned first, unsigned last)
{
    std::vector<double> times;
    for (unsigned frame = first; frame <= last; ++frame) times.push_back(options.frameTime(frame));
    return times;
}

/** The scene of the options' files, with the retargeting preview when one is asked for (--retarget-preview). */
osg::ref_ptr<osg::Node> readRenderScene(const RenderOptions& options, std::string& error)
{
    osg::ref_ptr<osg::Node> scene = osgActor::readScene(options.files, error);
    if (scene && !options.retargetPreview.empty())
        scene = osgActorApps::makeRetargetPreview(*scene, options.retargetPreview, error);
    return scene;
}

} // namespace

bool renderPart(const RenderOptions& options, unsigned first, unsigned last, const std::string& scratchPattern,
                bool scratchEveryFrame, FrameSink& sink, std::string& error)
{
    const OutputPattern output = OutputPattern::fromChecked(options.outputPattern);
    const OutputPattern references = OutputPattern::fromChecked(options.referencePattern);
    const OutputPattern diffs = OutputPattern::fromChecked(options.diffPattern);
    const OutputPattern scratch = OutputPattern::fromChecked(scratchPattern);

    std::srand(options.settings.seed);
    const osg::ref_ptr<osg::Node> scene = readRenderScene(options, error);
    if (!scene) return false;

    bool failed = false;
    const bool rendered = osgActor::renderFrames(
        scene.get(), frameTimes(options, first, last), options.settings,
        [&](unsigned index, osg::Image& image) {
            FrameOutcome outcome;
            outcome.frame = options.frameNumber(first + index);
            failed = (options.writeFrames && !writeImage(image, output.format(outcome.frame), error)) ||
                     (options.comparing() &&
                      !checkAgainstReference(image, references.format(outcome.frame),
                                             options.diffPattern.empty() ? "" : diffs.format(outcome.frame),
                                             options.rules, outcome, error)) ||
                     (!scratchPattern.empty() && (scratchEveryFrame || outcome.differs()) &&
                      !writeImage(image, scratch.format(outcome.frame), error));
            if (!failed) sink.frameDone(outcome, &image);
            return !failed;
        },
        error);
    return rendered && !failed;
}

bool checkPartDeterminism(const RenderOptions& options, unsigned first, unsigned last,
                          const std::function<void()>& onFrame, int& firstDifferingFrame, std::string& error)
{
    const osgActor::DeterminismCheck check = osgActor::checkDeterminism(
        [&options](std::string& loadError) { return readRenderScene(options, loadError); },
        frameTimes(options, first, last), options.settings, onFrame);
    if (!check.completed)
    {
        error = check.error;
        return false;
    }
    firstDifferingFrame =
        check.firstDifferingFrame < 0 ? -1 : int(options.frameNumber(first + unsigned(check.firstDifferingFrame)));
    return true;
}

} // namespace osgActorRender
