/* osgactorrender: renders an OSG scene into images through OSMesa, with no display. */
#ifndef OSGACTORRENDER_OFFSCREENRENDERER_H
#define OSGACTORRENDER_OFFSCREENRENDERER_H 1

#include "CameraView.h"
#include "OsMesaContext.h"

#include <osg/Image>
#include <osg/Node>
#include <osg/Vec4>
#include <osgViewer/Viewer>

#include <memory>
#include <string>

namespace osgActorRender {

using osgActorApps::CameraView;
using osgActorApps::frameBoundingSphere;

/** An osgViewer::Viewer embedded in an OSMesa context (docs/architecture.md): single-threaded, one frame per
  * call, each frame read back as an RGB osg::Image (rows bottom-first). The frame stamp's simulation time is the
  * one given, so actor controllers animate exactly as they would in a viewer at that time.
  *
  *     std::string error;
  *     auto renderer = OffscreenRenderer::create(640, 480, error);
  *     if (!renderer) { OSG_WARN << error << std::endl; return 1; }
  *     renderer->setScene(scene);
  *     renderer->stepTo(2.0, 30.0);                            // pose the scene at t = 2 s, stepping at 30 Hz
  *     renderer->setCameraView(renderer->frameScene());         // auto-frame what is there now
  *     osg::ref_ptr<osg::Image> image = renderer->draw();
  */
class OffscreenRenderer
{
public:
    /** A renderer of width x height pixels; null, with the reason in error, if no OSMesa context can be made. */
    static std::unique_ptr<OffscreenRenderer> create(int width, int height, std::string& error);
    ~OffscreenRenderer();
    OffscreenRenderer(const OffscreenRenderer&) = delete;
    OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

    void setScene(osg::Node* scene);
    osg::Node* getScene() { return _viewer->getSceneData(); }

    /** The clear colour (RGBA, 0..1); the alpha channel is not kept in the images. */
    void setBackground(const osg::Vec4& colour);
    /** Vertical field of view in degrees (default 30, as osgViewer's). */
    void setFieldOfView(double fovyDegrees);
    double getFieldOfView() const { return _fovyDegrees; }

    void setCameraView(const CameraView& view);
    const CameraView& getCameraView() const { return _view; }
    /** A view that frames the scene's current bound (call after update() so that actors are posed). */
    CameraView frameScene() const;

    /** Advances the frame stamp to simulationTime (seconds) and runs the event and update traversals. */
    void update(double simulationTime);
    /** Brings the scene to simulationTime as a viewer running at fps frames per second from time 0 would: runs
      * update() at every frame time k / fps (k = 0, 1, 2, ...) before simulationTime that no earlier stepTo() ran,
      * then at simulationTime itself. Callbacks that advance by the frame's delta time (clip and trajectory
      * players, IK solved from the previous frame's pose, osg::AnimationPathCallback) then show at time t what
      * frame t * fps of a run from frame 0 shows, whichever frames were drawn before. Players do not go back: a
      * time before the last one stepped to is updated directly. fps > 0. */
    void stepTo(double simulationTime, double fps);
    /** Culls and draws the current state, waits for the GL to finish and returns the pixels (RGB). */
    osg::ref_ptr<osg::Image> draw();
    /** update() then draw(). */
    osg::ref_ptr<osg::Image> renderFrame(double simulationTime);

    /** A world-space point in window coordinates of the images: x, y in pixels from the bottom left (pixel
      * centres at +0.5), z the depth in [0, 1]. */
    osg::Vec3d projectToWindow(const osg::Vec3d& world) const;

    int getWidth() const { return _context->getWidth(); }
    int getHeight() const { return _context->getHeight(); }
    osgViewer::Viewer* getViewer() { return _viewer.get(); }

private:
    explicit OffscreenRenderer(std::unique_ptr<OsMesaContext> context);

    // Declared first so that it is destroyed last: the viewer releases its GL objects in this context.
    std::unique_ptr<OsMesaContext> _context;
    osg::ref_ptr<osgViewer::Viewer> _viewer;
    CameraView _view;
    double _fovyDegrees;
    unsigned long long _nextStep; // the next frame k (at time k / fps) that stepTo() has not run yet
};

} // namespace osgActorRender

#endif
