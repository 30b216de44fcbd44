/* osgactorrender: one rendered frame against its reference image (--compare, --update-references). */
#ifndef OSGACTORRENDER_REFERENCECHECK_H
#define OSGACTORRENDER_REFERENCECHECK_H 1

#include "FrameOutcome.h"

#include <osg/Image>

#include <string>

namespace osgActorRender {

/** How frames are held against their references. */
struct ReferenceRules
{
    int tolerance = 2;
    /** The share (0..1) of pixels over the tolerance a matching frame may have. */
    double allowedShare = 0.0;
    /** Write the render as the reference where it does not match or none exists, instead of reporting it. */
    bool updateReferences = false;
};

/** Compares the render with referenceFile and fills the outcome's status and figures; a differing frame's diff
  * image goes to diffFile (unless it is empty or the sizes differ). With updateReferences, a render that does not
  * match (or has no reference yet) is written as the reference. False, with a message naming the file, when the
  * reference cannot be read (comparing) or a file cannot be written. */
bool checkAgainstReference(const osg::Image& render, const std::string& referenceFile, const std::string& diffFile,
                           const ReferenceRules& rules, FrameOutcome& outcome, std::string& error);

} // namespace osgActorRender

#endif
