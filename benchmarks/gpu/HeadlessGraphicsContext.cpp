#include "HeadlessGraphicsContext"

#include <osg/State>

namespace bench {

HeadlessGraphicsContext::HeadlessGraphicsContext(int width, int height)
{
    osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
    traits->width = width;
    traits->height = height;
    traits->pbuffer = true;
    traits->doubleBuffer = false;
    traits->red = traits->green = traits->blue = traits->alpha = 8;
    traits->depth = 24;
    traits->stencil = 8;
    _traits = traits;
    setState(new osg::State);
    getState()->setGraphicsContext(this);
    getState()->setContextID(osg::GraphicsContext::createNewContextID());
}

bool HeadlessGraphicsContext::realizeImplementation()
{
    _realized = valid();
    return _realized;
}

} // namespace bench
