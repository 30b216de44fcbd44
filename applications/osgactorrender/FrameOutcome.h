/* osgactorrender: what became of one frame, and how a --jobs child tells its parent. */
#ifndef OSGACTORRENDER_FRAMEOUTCOME_H
#define OSGACTORRENDER_FRAMEOUTCOME_H 1

#include <osgActor/Offscreen/ImageComparison>

#include <string>

namespace osgActorRender {

/** One frame, once rendered (and compared, or its reference updated). */
struct FrameOutcome
{
    enum Status
    {
        RENDERED,           // no reference involved
        MATCHES,            // compared: matches its reference
        DIFFERS,            // compared: differs (or a reference of another size)
        REFERENCE_KEPT,     // --update-references: it matched, the reference stays as it was
        REFERENCE_CHANGED,  // --update-references: rewritten
        REFERENCE_NEW       // --update-references: there was none
    };

    unsigned frame = 0;
    Status status = RENDERED;
    /** The comparison with the reference, where there was one. */
    osgActor::ImageComparison comparison;

    bool differs() const { return status == DIFFERS; }
    bool referenceWritten() const { return status == REFERENCE_CHANGED || status == REFERENCE_NEW; }
};

/** The line a --jobs child writes for a frame (no newline), and the frame read back from it: the status, the
  * comparison's figures (PSNR to 17 digits) and why it was not comparable, if it was not. */
std::string encodeFrameOutcome(const FrameOutcome& outcome);
bool decodeFrameOutcome(const std::string& line, FrameOutcome& outcome);

} // namespace osgActorRender

#endif
