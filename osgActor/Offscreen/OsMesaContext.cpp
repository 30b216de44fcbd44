#include "OsMesaContext.h"

#include <GL/osmesa.h>

#include <dlfcn.h>

#include <cstring>
#include <new>

namespace osgActor {

bool OsMesaContext::glResolvesToOsMesa(std::string& error)
{
    // RTLD_DEFAULT searches the process's global scope in load order, exactly as OSG's own lookups do.
    void* symbol = dlsym(RTLD_DEFAULT, "glGetString");
    Dl_info info;
    if (symbol == nullptr || dladdr(symbol, &info) == 0 || info.dli_fname == nullptr)
    {
        error = "glGetString cannot be found in this process";
        return false;
    }
    if (std::strstr(info.dli_fname, "libOSMesa") == nullptr)
    {
        // The executable's link line decides; a CMake target linked to osgActor::Offscreen gets libOSMesa first.
        error = std::string("glGetString resolves into ") + info.dli_fname +
                ", not libOSMesa: libOSMesa must come first on the executable's link line (link the program to "
                "osgActor::Offscreen with CMake, or put -Wl,--no-as-needed -lOSMesa ahead of every other library)";
        return false;
    }
    return true;
}

std::unique_ptr<OsMesaContext> OsMesaContext::create(int width, int height, std::string& error)
{
    if (!glResolvesToOsMesa(error)) return nullptr;
    if (width < 1 || height < 1)
    {
        error = "cannot make an OSMesa context of " + std::to_string(width) + "x" + std::to_string(height) + " pixels";
        return nullptr;
    }

    std::unique_ptr<OsMesaContext> context(new OsMesaContext(width, height));
    try
    {
        context->_pixels.resize(static_cast<size_t>(width) * static_cast<size_t>(height) * 4u);
    }
    catch (const std::bad_alloc&)
    {
        error = "not enough memory for a " + std::to_string(width) + "x" + std::to_string(height) + " colour buffer";
        return nullptr;
    }

    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                              OSMESA_DEPTH_BITS, 24,
                              OSMESA_STENCIL_BITS, 8,
                              OSMESA_PROFILE, OSMESA_COMPAT_PROFILE,
                              0};
    context->_context = OSMesaCreateContextAttribs(attributes, nullptr);
    if (context->_context == nullptr)
    {
        error = "OSMesaCreateContextAttribs failed (compatibility profile, RGBA, depth 24, stencil 8)";
        return nullptr;
    }
    if (!context->makeCurrent())
    {
        error = "OSMesaMakeCurrent failed on a " + std::to_string(width) + "x" + std::to_string(height) +
                " buffer (the largest OSMesa accepts is usually 16384x16384)";
        return nullptr;
    }
    return context;
}

OsMesaContext::OsMesaContext(int width, int height) : _width(width), _height(height), _context(nullptr) {}

OsMesaContext::~OsMesaContext()
{
    if (_context != nullptr) OSMesaDestroyContext(static_cast<OSMesaContext>(_context));
}

bool OsMesaContext::makeCurrent()
{
    if (OSMesaMakeCurrent(static_cast<OSMesaContext>(_context), _pixels.data(), GL_UNSIGNED_BYTE, _width, _height) ==
        GL_FALSE)
        return false;
    OSMesaPixelStore(OSMESA_Y_UP, 1); // row 0 at the bottom, as osg::Image and glReadPixels have it
    return true;
}

} // namespace osgActor
