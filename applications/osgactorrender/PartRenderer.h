/* osgactorrender: renders a run of frames of the sequence the options name, and does with each what they ask. */
#ifndef OSGACTORRENDER_PARTRENDERER_H
#define OSGACTORRENDER_PARTRENDERER_H 1

#include "FrameOutcome.h"
#include "RenderOptions.h"

#include <osg/Image>

#include <functional>
#include <string>

namespace osgActorRender {

/** Where the outcome of each frame goes: the run's summary in this process, or a --jobs parent's pipe. */
class FrameSink
{
public:
    virtual ~FrameSink() = default;
    /** A frame is done. image is its render where there is one (a --jobs parent has only the outcome). */
    virtual void frameDone(const FrameOutcome& outcome, const osg::Image* image) = 0;
};

/** Frames first..last (inclusive) of the options' sequence: the scene is read (after std::srand(seed)), brought
  * there from time 0 and rendered; each frame is written (-o), compared with its reference or written as one
  * (--compare, --update-references, --diff), written to scratchPattern (every frame with scratchEveryFrame, else
  * only those that differ; empty: nowhere) and handed to the sink. False, with the reason, on the first error. */
bool renderPart(const RenderOptions& options, unsigned first, unsigned last, const std::string& scratchPattern,
                bool scratchEveryFrame, FrameSink& sink, std::string& error);

/** --check-determinism on frames first..last: firstDifferingFrame is the number of the first frame whose bytes
  * differ between two renders, or -1. onFrame is called after every frame of both renders. */
bool checkPartDeterminism(const RenderOptions& options, unsigned first, unsigned last,
                          const std::function<void()>& onFrame, int& firstDifferingFrame, std::string& error);

} // namespace osgActorRender

#endif
