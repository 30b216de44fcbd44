#include "OsMesaGraphicsContext"

#include <GL/osmesa.h>


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
    osg::ref_ptr<OsMesaGraphicsContext> made = new OsMesaGraphicsContext(width, height, context);
    if (!made->makeCurrentImplementation())
    {
        error = "OSMesaMakeCurrent failed on a " + std::to_string(width) + " x " + std::to_string(height) + " buffer";
        return nullptr;
    }
    return made;
}

OsMesaGraphicsContext::OsMesaGraphicsContext(int width, int height, void* context)
    : HeadlessGraphicsContext(width, height), _context(context),
      _pixels(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4u)
{
}

OsMesaGraphicsContext::~OsMesaGraphicsContext() { close(false); }

void OsMesaGraphicsContext::closeImplementation()
{
    if (_context) OSMesaDestroyContext(static_cast<OSMesaContext>(_context));
    _context = nullptr;
    markClosed();
}

bool OsMesaGraphicsContext::makeCurrentImplementation()
{
    return _context && OSMesaMakeCurrent(static_cast<OSMesaContext>(_context), _pixels.data(), GL_UNSIGNED_BYTE,
                                         _traits->width, _traits->height);
}

} // namespace bench
