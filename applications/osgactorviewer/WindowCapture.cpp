#include "WindowCapture.h"

#include <osg/RenderInfo>

namespace osgActorViewer {

void WindowCapture::operator()(osg::RenderInfo& renderInfo) const
{
    if (!_armed) return;
    const osg::Viewport* viewport = renderInfo.getCurrentCamera()->getViewport();
    if (viewport == nullptr) return;
    _armed = false;
    _image = new osg::Image;
    _image->readPixels(int(viewport->x()), int(viewport->y()), int(viewport->width()), int(viewport->height()),
                       GL_RGB, GL_UNSIGNED_BYTE);
}

} // namespace osgActorViewer
