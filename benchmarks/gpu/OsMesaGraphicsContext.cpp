#include "OsMesaGraphicsContext"

#include <GL/osmesa.h>

#include <osg/State>

namespace bench {

osg::ref_ptr<OsMesaGraphicsContext> OsMesaGraphicsContext::create(int width, int height, int, std::string& error)
{
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_STENCIL_BITS, 8,
                              OSMESA_PROFILE, OSMESA_COMPAT_PROFILE, 0};
    OSMesaContext context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (!context)
    {
        error = "OSMesaCreateContextAttribs failed (compatibility profile, RGBA, depth 24, stencil 8)";
        return nullptr;
    }
    osg::ref_ptr<osg::GraphicsContext::Traits> traits = new osg::GraphicsContext::Traits;
    traits->width = width;
    traits->height = height;
    traits->pbuffer = true;
    traits->doubleBuffer = false;
    traits->red = traits->green = traits->blue = traits->alpha = 8;
    traits->depth = 24;
    traits->stencil = 8;
    osg::ref_ptr<OsMesaGraphicsContext> made = new OsMesaGraphicsContext(traits.get(), context);
    if (!made->makeCurrentImplementation())
    {
        error = "OSMesaMakeCurrent failed on a " + std::to_string(width) + " x " + std::to_string(height) + " buffer";
        return nullptr;
    }
    return made;
}

OsMesaGraphicsContext::OsMesaGraphicsContext(osg::GraphicsContext::Traits* traits, void* context)
    : _context(context), _pixels(static_cast<std::size_t>(traits->width) * traits->height * 4u)
{
    _traits = traits;
    setState(new osg::State);
    getState()->setGraphicsContext(this);
    getState()->setContextID(osg::GraphicsContext::createNewContextID());
}

OsMesaGraphicsContext::~OsMesaGraphicsContext() { close(false); }

bool OsMesaGraphicsContext::realizeImplementation()
{
    _realized = valid();
    return _realized;
}

void OsMesaGraphicsContext::closeImplementation()
{
    if (_context) OSMesaDestroyContext(static_cast<OSMesaContext>(_context));
    _context = nullptr;
    _realized = false;
}

bool OsMesaGraphicsContext::makeCurrentImplementation()
{
    return _context && OSMesaMakeCurrent(static_cast<OSMesaContext>(_context), _pixels.data(), GL_UNSIGNED_BYTE,
                                         _traits->width, _traits->height);
}

} // namespace bench
