// osgactorviewer: an osgViewer for actors. Loads any file osgDB can read (actors, pseudo-loaded mocap such as
// walk.bvh.actor, plain models as a stage), with OSG's usual handlers and options (--window, --screen, --clear-color,
// ...) and its own keys for playback, direct kinematics, hiding limbs and showing skeletons (press h).
//
//   osgactorviewer data/humanoid.actor
//   osgactorviewer --frames 10 data/humanoid.actor     (quits after 10 frames: for tests)
#include "ActorControls.h"
#include "ActorFinder.h"
#include "CameraView.h"
#include "InfoPanel.h"
#include "PlaybackClock.h"
#include "RetargetPreview.h"
#include "SceneLoader.h"
#include "SkeletonOverlay.h"
#include "WindowCapture.h"

#include <osg/ArgumentParser>
#include <osg/Group>
#include <osg/Timer>
#include <osgGA/KeySwitchMatrixManipulator>
#include <osgGA/OrbitManipulator>
#include <osgGA/StateSetManipulator>
#include <osgGA/TerrainManipulator>
#include <osgGA/TrackballManipulator>
#include <osgViewer/Viewer>
#include <osgViewer/ViewerEventHandlers>
#include <osgDB/FileUtils>
#include <osgDB/WriteFile>

#include <iostream>

using namespace osgActorViewer;

namespace {

int fail(const std::string& message)
{
    std::cerr << "osgactorviewer: " << message << std::endl;
    return 1;
}

void describeUsage(osg::ArgumentParser& arguments)
{
    osg::ApplicationUsage* usage = arguments.getApplicationUsage();
    usage->setApplicationName(arguments.getApplicationName());
    usage->setDescription(arguments.getApplicationName() +
                          " shows actors (and any scene osgDB can read) and lets you play, pose and inspect them.");
    usage->setCommandLineUsage(arguments.getApplicationName() + " [options] file ...");
    usage->addCommandLineOption("-h or --help", "Display this information.");
    usage->addCommandLineOption("--frames <n>", "Quit after n frames (for tests and recordings).");
    usage->addCommandLineOption("--paused", "Start with playback paused.");
    usage->addCommandLineOption("--capture <file>", "Write the last frame's image to a file (runs single-threaded).");
    usage->addCommandLineOption("--retarget-preview <motion>", "Retarget a motion file (BVH, or ASF with its AMC "
                                                              "beside it) onto the first actor and show its own "
                                                              "skeleton playing it beside (docs/retargeting.md).");
}

/** The panel's window size: the master camera's viewport once the viewer is realized. */
void panelSize(osgViewer::Viewer& viewer, int& width, int& height)
{
    width = 1280;
    height = 1024;
    if (const osg::Viewport* viewport = viewer.getCamera()->getViewport())
    {
        width = int(viewport->width());
        height = int(viewport->height());
    }
}

} // namespace

int main(int argc, char** argv)
{
    osg::ArgumentParser arguments(&argc, argv);
    describeUsage(arguments);
    osgViewer::Viewer viewer(arguments); // reads OSG's own options (--window, --screen, --run-on-demand, ...)

    if (arguments.read("-h") || arguments.read("--help"))
    {
        arguments.getApplicationUsage()->write(std::cout, osg::ApplicationUsage::COMMAND_LINE_OPTION |
                                                              osg::ApplicationUsage::ENVIRONMENTAL_VARIABLE);
        return 0;
    }
    unsigned maxFrames = 0;
    while (arguments.read("--frames", maxFrames)) {}
    PlaybackClock clock;
    while (arguments.read("--paused")) clock.setPlaying(false);
    std::string captureFile;
    while (arguments.read("--capture", captureFile)) {}
    std::string retargetPreview;
    while (arguments.read("--retarget-preview", retargetPreview)) {}

    arguments.reportRemainingOptionsAsUnrecognized();
    if (arguments.errors())
    {
        arguments.writeErrorMessages(std::cerr);
        return 1;
    }
    std::vector<std::string> files;
    for (int pos = 1; pos < arguments.argc(); ++pos)
        if (!arguments.isOption(pos)) files.push_back(arguments[pos]);
    if (files.empty()) return fail("no file to show (--help lists the options)");
    if (!captureFile.empty() && maxFrames == 0) return fail("--capture needs --frames (which frame to capture)");

    std::string error;
    osg::ref_ptr<osg::Node> scene = osgActorApps::loadSceneFiles(files, error);
    if (scene && !retargetPreview.empty()) scene = osgActorApps::makeRetargetPreview(*scene, retargetPreview, error);
    if (!scene) return fail(error);

    // The scene, an overlay per actor, and the panel.
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(scene.get());
    const std::vector<osg::ref_ptr<osgActor::ActorNode>> actors = findActors(*scene);
    std::vector<osg::ref_ptr<SkeletonOverlay>> overlays;
    for (const osg::ref_ptr<osgActor::ActorNode>& actor : actors)
    {
        overlays.push_back(new SkeletonOverlay(actor.get()));
        root->addChild(overlays.back().get());
    }
    osg::ref_ptr<osg::Group> ikGoals = new osg::Group; // where the IK goal's dragger goes
    root->addChild(ikGoals.get());
    osg::ref_ptr<InfoPanel> panel = new InfoPanel(1280, 1024);
    panel->setKeys(ActorControls::keyList());
    root->addChild(panel.get());

    // OSG's usual handlers, as osgviewer has them, and our own keys.
    osg::ref_ptr<osgGA::KeySwitchMatrixManipulator> manipulators = new osgGA::KeySwitchMatrixManipulator;
    manipulators->addMatrixManipulator('1', "Trackball", new osgGA::TrackballManipulator);
    manipulators->addMatrixManipulator('2', "Orbit", new osgGA::OrbitManipulator);
    manipulators->addMatrixManipulator('3', "Terrain", new osgGA::TerrainManipulator);
    viewer.setCameraManipulator(manipulators.get());
    viewer.addEventHandler(new osgGA::StateSetManipulator(viewer.getCamera()->getOrCreateStateSet()));
    viewer.addEventHandler(new osgViewer::StatsHandler);
    viewer.addEventHandler(new osgViewer::WindowSizeHandler);
    viewer.addEventHandler(new osgViewer::ThreadingHandler);
    viewer.addEventHandler(new osgViewer::ScreenCaptureHandler);
    viewer.addEventHandler(new osgViewer::HelpHandler(arguments.getApplicationUsage()));
    osg::ref_ptr<ActorControls> controls = new ActorControls(actors, overlays, clock, panel.get());
    controls->setIkGoalDragger(std::make_shared<IkGoalDragger>(ikGoals.get()));
    viewer.addEventHandler(controls.get());
    viewer.setSceneData(root.get());
    osg::ref_ptr<WindowCapture> capture = new WindowCapture;
    if (!captureFile.empty())
    {
        // The image is read back right after viewer.frame() returns: the draw must have happened by then.
        viewer.setThreadingModel(osgViewer::ViewerBase::SingleThreaded);
        viewer.getCamera()->setFinalDrawCallback(capture.get());
    }

    viewer.realize();
    if (!viewer.isRealized()) return fail("cannot open a window (is there a display? try xvfb-run)");
    int width = 0;
    int height = 0;
    panelSize(viewer, width, height);
    panel->resize(width, height);

    // Home: the scene from the front, a little above (as osgactorrender frames it), not edge-on to a floor.
    const osgActorApps::CameraView home =
        osgActorApps::frameBoundingSphere(osgActorApps::shownBound(*scene), 30.0, double(width) / height);
    manipulators->setAutoComputeHomePosition(false);
    manipulators->setHomePosition(home.eye, home.center, home.up);
    viewer.home();

    // The frame loop of osgViewer::Viewer::run(), with the simulation time taken from the playback clock.
    const osg::Timer* timer = osg::Timer::instance();
    osg::Timer_t previous = timer->tick();
    unsigned numFrames = 0;
    while (!viewer.done() && (maxFrames == 0 || numFrames < maxFrames))
    {
        const osg::Timer_t now = timer->tick();
        clock.advance(timer->delta_s(previous, now));
        previous = now;
        const bool lastFrame = maxFrames > 0 && numFrames + 1 == maxFrames;
        if (lastFrame && !captureFile.empty()) capture->arm();
        viewer.frame(clock.getTime());
        ++numFrames;
    }
    if (!captureFile.empty())
    {
        osgDB::makeDirectoryForFile(captureFile);
        if (!capture->getImage() || !osgDB::writeImageFile(*capture->getImage(), captureFile))
            return fail("cannot capture the last frame into \"" + captureFile + "\"");
        std::cout << "osgactorviewer: wrote " << captureFile << std::endl;
    }
    std::cout << "osgactorviewer: " << numFrames << " frames, " << actors.size() << " actor(s)" << std::endl;
    return 0;
}
