/* osgactorrender: the command line. */
#ifndef OSGACTORRENDER_RENDEROPTIONS_H
#define OSGACTORRENDER_RENDEROPTIONS_H 1

#include "CameraView.h"

#include <osg/ArgumentParser>
#include <osg/Vec4>

#include <string>
#include <vector>

namespace osgActorRender {

using osgActorApps::CameraView;
using osgActorApps::frameBoundingSphere;

/** Everything osgactorrender was asked to do. */
struct RenderOptions
{
    std::vector<std::string> files;
    int width = 640;
    int height = 480;
    double fovyDegrees = 30.0;

    /** Camera: auto-framed from what the scene draws at the first frame unless eye is given. */
    bool hasEye = false;
    bool hasCenter = false;
    CameraView view;

    /** Frames firstFrame..lastFrame, each at simulation time frame / fps seconds; or one frame at time. */
    unsigned firstFrame = 0;
    unsigned lastFrame = 0;
    double fps = 30.0;
    bool hasTime = false;
    double time = 0.0;

    std::string outputPattern = "frame_%04d.png";
    bool writeFrames = true;
    osg::Vec4 background{0.2f, 0.2f, 0.4f, 1.0f}; // osgViewer's clear colour

    std::string contactSheet; // empty: none
    std::string retargetPreview; // a motion file to show retargeted onto the scene's first actor; empty: none
    unsigned sheetColumns = 0;
    int sheetTileWidth = 160;

    bool forceProgress = false;

    unsigned getNumFrames() const { return lastFrame - firstFrame + 1; }
    /** Simulation time of the i-th frame rendered (0-based), in seconds. */
    double frameTime(unsigned i) const { return hasTime ? time : (firstFrame + i) / fps; }
    /** The number that names the i-th frame rendered in the output pattern. */
    unsigned frameNumber(unsigned i) const { return hasTime ? 0 : firstFrame + i; }
};

/** Describes the options in the parser's ApplicationUsage (for --help and errors). */
void describeRenderOptions(osg::ArgumentParser& arguments);

/** Reads the options and the file names; false, with the reason in error, when they are wrong or contradictory
  * (unknown options are reported too). */
bool parseRenderOptions(osg::ArgumentParser& arguments, RenderOptions& options, std::string& error);

} // namespace osgActorRender

#endif
