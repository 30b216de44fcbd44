/* osgactorrender: the command line. */
#ifndef OSGACTORRENDER_RENDEROPTIONS_H
#define OSGACTORRENDER_RENDEROPTIONS_H 1

#include "ReferenceCheck.h"

#include <osgActor/Offscreen/RenderFrames>

#include <osg/ArgumentParser>

#include <string>
#include <vector>

namespace osgActorRender {

/** Everything osgactorrender was asked to do. */
struct RenderOptions
{
    std::vector<std::string> files;
    /** Size, frame rate, camera, background, seed: what the library renders with. */
    osgActor::RenderSettings settings;

    /** Frames firstFrame..lastFrame, each at simulation time frame / fps seconds; or one frame at time. */
    unsigned firstFrame = 0;
    unsigned lastFrame = 0;
    bool hasTime = false;
    double time = 0.0;
    /** This run renders part `part` (1..numParts) of the frames: a contiguous share, numParts about equal shares. */
    unsigned part = 1;
    unsigned numParts = 1;
    /** Processes to spread the parts over (--jobs). */
    unsigned jobs = 1;

    std::string outputPattern = "frame_%04d.png";
    bool writeFrames = true;

    std::string contactSheet; // empty: none
    std::string retargetPreview; // a motion file to show retargeted onto the scene's first actor; empty: none
    unsigned sheetColumns = 0;
    int sheetTileWidth = 160;

    /** --compare: the references' pattern; empty: no comparison. */
    std::string referencePattern;
    /** --tolerance, --allowed-share, --update-references. */
    ReferenceRules rules;
    std::string diffPattern;   // empty: no diff images
    std::string compareSheet;  // empty: none
    std::string reportFile;    // empty: none

    bool checkDeterminism = false;
    bool forceProgress = false;

    /** Set by a --jobs parent for its children (not for users): where to report each frame, and a pattern to
      * write frames to for the parent's sheets (every frame with jobScratchAll, else only the differing ones). */
    int jobReportFd = -1;
    std::string jobScratchPattern;
    bool jobScratchAll = false;

    bool isJobChild() const { return jobReportFd >= 0; }
    bool comparing() const { return !referencePattern.empty(); }
    unsigned getNumFrames() const { return lastFrame - firstFrame + 1; }
    /** The frames part `part` of numParts renders: [first, last]; empty (first > last) if there are fewer frames
      * than parts. */
    void getPartFrames(unsigned part, unsigned numParts, unsigned& first, unsigned& last) const;
    /** Simulation time of a frame, in seconds. */
    double frameTime(unsigned frame) const { return hasTime ? time : frame / settings.fps; }
    /** The number that names a frame in the patterns (0 for --time). */
    unsigned frameNumber(unsigned frame) const { return hasTime ? 0 : frame; }
};

/** Describes the options in the parser's ApplicationUsage (for --help and errors). */
void describeRenderOptions(osg::ArgumentParser& arguments);

/** Reads the options and the file names; false, with the reason in error, when they are wrong or contradictory
  * (unknown options are reported too). */
bool parseRenderOptions(osg::ArgumentParser& arguments, RenderOptions& options, std::string& error);

} // namespace osgActorRender

#endif
