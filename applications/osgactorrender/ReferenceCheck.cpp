#include "ReferenceCheck.h"

#include "ImageFile.h"

#include <osgDB/FileUtils>

namespace osgActorRender {

bool checkAgainstReference(const osg::Image& render, const std::string& referenceFile, const std::string& diffFile,
                           const ReferenceRules& rules, FrameOutcome& outcome, std::string& error)
{
    const bool referenceExists = osgDB::fileExists(referenceFile);
    std::string readError;
    const osg::ref_ptr<osg::Image> reference =
        referenceExists ? osgActor::readRgbImage(referenceFile, readError) : nullptr;
    if (reference) outcome.comparison = osgActor::compareImages(render, *reference, rules.tolerance);

    if (rules.updateReferences)
    {
        if (reference && outcome.comparison.matches(rules.allowedShare))
        {
            outcome.status = FrameOutcome::REFERENCE_KEPT;
            return true;
        }
        // A reference that cannot be read is replaced, as one that differs is.
        outcome.status = referenceExists ? FrameOutcome::REFERENCE_CHANGED : FrameOutcome::REFERENCE_NEW;
        return writeImage(render, referenceFile, error);
    }

    if (!reference)
    {
        error = (referenceExists ? readError : "the reference \"" + referenceFile + "\" does not exist") +
                " (make or refresh the references with --update-references, and look at them before committing)";
        return false;
    }
    outcome.status = outcome.comparison.matches(rules.allowedShare) ? FrameOutcome::MATCHES : FrameOutcome::DIFFERS;
    if (outcome.status == FrameOutcome::DIFFERS && !diffFile.empty())
    {
        const osg::ref_ptr<osg::Image> diff = osgActor::makeDiffImage(render, *reference, rules.tolerance);
        if (diff && !writeImage(*diff, diffFile, error)) return false;
    }
    return true;
}

} // namespace osgActorRender
