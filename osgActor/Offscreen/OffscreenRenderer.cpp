#include <osgActor/Offscreen/OffscreenRenderer>

#include "CullOnlyRenderer.h"
#include "OsMesaContext.h"

#include "CameraView.h"

#include <osg/GL>

namespace osgActor {

osg::ref_ptr<OffscreenRenderer> OffscreenRenderer::create(int width, int height, std::string& error)
{
    std::unique_ptr<OsMesaContext> context = OsMesaContext::create(width, height, error);
    if (!context) return nullptr;
    return new OffscreenRenderer(std::move(context));
}

bool OffscreenRenderer::glResolvesToOsMesa(std::string& error) { return OsMesaContext::glResolvesToOsMesa(error); }

OffscreenRenderer::OffscreenRenderer(std::unique_ptr<OsMesaContext> context)
    : _context(std::move(context)), _viewer(new osgViewer::Viewer), _fovyDegrees(30.0), _nextStep(0),
      _hasUpdated(false), _lastUpdateTime(0.0), _frameNeedsCull(false)
{
    // The context is current on this thread only: any other threading model would draw from another thread.
    _viewer->setThreadingModel(osgViewer::ViewerBase::SingleThreaded);
    _viewer->setUpViewerAsEmbeddedInWindow(0, 0, _context->getWidth(), _context->getHeight());
    _viewer->setKeyEventSetsDone(0);
    _cameraRenderer = new CullOnlyRenderer(_viewer->getCamera());
    _viewer->getCamera()->setRenderer(_cameraRenderer.get());
    _viewer->realize();
    setFieldOfView(_fovyDegrees);
    const osgActorApps::CameraView view;
    setViewMatrixAsLookAt(view.eye, view.center, view.up);
}

OffscreenRenderer::~OffscreenRenderer()
{
    // The viewer goes first, while its context is current, so that it can release its GL objects there.
    _context->makeCurrent();
    _viewer = nullptr;
    _cameraRenderer = nullptr;
}

void OffscreenRenderer::setScene(osg::Node* scene) { _viewer->setSceneData(scene); }

osg::Node* OffscreenRenderer::getScene() { return _viewer->getSceneData(); }

void OffscreenRenderer::setBackground(const osg::Vec4& colour) { _viewer->getCamera()->setClearColor(colour); }

void OffscreenRenderer::setFieldOfView(double fovyDegrees)
{
    _fovyDegrees = fovyDegrees;
    const double aspect = double(_context->getWidth()) / double(_context->getHeight());
    // Near and far are recomputed from the scene's bound every frame (OSG's default); only the field of view and
    // the aspect ratio of this matrix matter.
    _viewer->getCamera()->setProjectionMatrixAsPerspective(fovyDegrees, aspect, 1.0, 10000.0);
}

void OffscreenRenderer::setViewMatrixAsLookAt(const osg::Vec3d& eye, const osg::Vec3d& center, const osg::Vec3d& up)
{
    _viewer->getCamera()->setViewMatrixAsLookAt(eye, center, up);
}

void OffscreenRenderer::getViewMatrixAsLookAt(osg::Vec3d& eye, osg::Vec3d& center, osg::Vec3d& up) const
{
    // The distance only places center on the line of sight; the one eye to center was set with is not kept.
    _viewer->getCamera()->getViewMatrixAsLookAt(eye, center, up, 1.0);
}

void OffscreenRenderer::computeFramingView(osg::Vec3d& eye, osg::Vec3d& center, osg::Vec3d& up) const
{
    osgActorApps::CameraView view;
    const osg::Node* scene = _viewer->getSceneData();
    if (scene != nullptr)
    {
        const double aspect = double(_context->getWidth()) / double(_context->getHeight());
        view = osgActorApps::frameBoundingSphere(osgActorApps::shownBound(*const_cast<osg::Node*>(scene)),
                                                 _fovyDegrees, aspect);
    }
    eye = view.eye;
    center = view.center;
    up = view.up;
}

void OffscreenRenderer::frameScene()
{
    osg::Vec3d eye, center, up;
    computeFramingView(eye, center, up);
    setViewMatrixAsLookAt(eye, center, up);
}

void OffscreenRenderer::cullUndrawnFrame()
{
    if (!_frameNeedsCull) return;
    _context->makeCurrent();
    _cameraRenderer->setDrawEnabled(false);
    _viewer->renderingTraversals();
    _cameraRenderer->setDrawEnabled(true);
    _frameNeedsCull = false;
}

void OffscreenRenderer::update(double simulationTime)
{
    cullUndrawnFrame();
    _viewer->advance(simulationTime);
    // advance() reads the wall clock into the reference time; callbacks that animate by it (instead of the
    // simulation time) would differ from run to run.
    _viewer->getFrameStamp()->setReferenceTime(simulationTime);
    _viewer->eventTraversal();
    _viewer->updateTraversal();
    _hasUpdated = true;
    _lastUpdateTime = simulationTime;
    _frameNeedsCull = true;
}

void OffscreenRenderer::stepTo(double simulationTime, double fps)
{
    if (_hasUpdated && _lastUpdateTime == simulationTime) return;
    // Frame times are computed as k / fps, exactly as a frame range names them, so that a time given as a number
    // of frames meets its step exactly instead of running it twice.
    while (double(_nextStep) / fps < simulationTime)
    {
        update(double(_nextStep) / fps);
        ++_nextStep;
    }
    update(simulationTime);
    if (double(_nextStep) / fps == simulationTime) ++_nextStep;
}

osg::ref_ptr<osg::Image> OffscreenRenderer::draw()
{
    // Another renderer in this process may have made its own context current since the last frame.
    _context->makeCurrent();
    _viewer->renderingTraversals();
    _frameNeedsCull = false;
    glFinish(); // the buffer is complete only once the GL has executed every command

    const int width = _context->getWidth();
    const int height = _context->getHeight();
    osg::ref_ptr<osg::Image> image = new osg::Image;
    image->allocateImage(width, height, 1, GL_RGB, GL_UNSIGNED_BYTE);
    const unsigned char* rgba = _context->getPixels();
    unsigned char* rgb = image->data();
    const size_t numPixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    for (size_t i = 0; i < numPixels; ++i)
    {
        rgb[3 * i + 0] = rgba[4 * i + 0];
        rgb[3 * i + 1] = rgba[4 * i + 1];
        rgb[3 * i + 2] = rgba[4 * i + 2];
    }
    return image;
}

osg::ref_ptr<osg::Image> OffscreenRenderer::renderFrame(double simulationTime)
{
    update(simulationTime);
    return draw();
}

osg::Vec3d OffscreenRenderer::projectToWindow(const osg::Vec3d& world) const
{
    const osg::Camera* camera = _viewer->getCamera();
    const osg::Matrixd worldToWindow =
        camera->getViewMatrix() * camera->getProjectionMatrix() * camera->getViewport()->computeWindowMatrix();
    return world * worldToWindow;
}

int OffscreenRenderer::getWidth() const { return _context->getWidth(); }

int OffscreenRenderer::getHeight() const { return _context->getHeight(); }

} // namespace osgActor
