/* osgactorviewer: reads what a camera drew into an image, on request. */
#ifndef OSGACTORVIEWER_WINDOWCAPTURE_H
#define OSGACTORVIEWER_WINDOWCAPTURE_H 1

#include <osg/Camera>
#include <osg/Image>

namespace osgActorViewer {

/** A final draw callback for a camera: once armed, the next frame it sees is read back (RGB, rows bottom-first)
  * and kept. OSG's ScreenCaptureHandler names its files itself; this lets --capture write exactly the file asked for.
  * Read the image only after the draw has finished (the viewer is single-threaded when capturing). */
class WindowCapture : public osg::Camera::DrawCallback
{
public:
    void arm() { _armed = true; }
    osg::Image* getImage() { return _image.get(); }

    void operator()(osg::RenderInfo& renderInfo) const override;

private:
    mutable bool _armed = false;
    mutable osg::ref_ptr<osg::Image> _image;
};

} // namespace osgActorViewer

#endif
