#include "EglPbufferContext"

#include <EGL/egl.h>
#include <EGL/eglext.h>


#include <cstring>
#include <sstream>
#include <vector>

namespace bench {

namespace {

/** The devices EGL enumerates (EGL_EXT_device_enumeration), empty if it cannot. */
std::vector<EGLDeviceEXT> queryDevices()
{
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (!queryDevices) return {};
    EGLint count = 0;
    if (!queryDevices(0, nullptr, &count) || count <= 0) return {};
    std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
    if (!queryDevices(count, devices.data(), &count)) return {};
    devices.resize(static_cast<std::size_t>(count));
    return devices;
}

std::string describeDevice(EGLDeviceEXT device)
{
    auto queryString =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    if (!queryString) return "?";
    const char* extensions = queryString(device, EGL_EXTENSIONS);
    if (extensions && std::strstr(extensions, "EGL_EXT_device_drm"))
        if (const char* node = queryString(device, EGL_DRM_DEVICE_FILE_EXT)) return node;
    if (extensions && std::strstr(extensions, "EGL_MESA_device_software")) return "software";
    return extensions ? extensions : "?";
}

/** A desktop-OpenGL context and a pbuffer on one device, or an error naming the step that failed. */
bool openOnDevice(EGLDeviceEXT device, int width, int height, EGLDisplay& display, EGLContext& context,
                  EGLSurface& surface, std::string& error)
{
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!getPlatformDisplay)
    {
        error = "EGL has no eglGetPlatformDisplayEXT";
        return false;
    }
    display = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor))
    {
        error = "eglInitialize failed on device " + describeDevice(device);
        return false;
    }
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                       EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_ALPHA_SIZE, 8,
                                       EGL_DEPTH_SIZE, 24, EGL_STENCIL_SIZE, 8, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint numConfigs = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &numConfigs) || numConfigs < 1)
    {
        error = "no RGBA8/depth 24 pbuffer config for desktop OpenGL on device " + describeDevice(device);
        eglTerminate(display);
        return false;
    }
    const EGLint surfaceAttributes[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
    surface = eglCreatePbufferSurface(display, config, surfaceAttributes);
    if (!eglBindAPI(EGL_OPENGL_API) || surface == EGL_NO_SURFACE)
    {
        error = "no " + std::to_string(width) + " x " + std::to_string(height) + " pbuffer on device " +
                describeDevice(device);
        eglTerminate(display);
        return false;
    }
    // No version asked: the driver's highest compatibility-profile context, which OSG's GL2 build needs.
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
    if (context == EGL_NO_CONTEXT)
    {
        error = "eglCreateContext (desktop OpenGL) failed on device " + describeDevice(device);
        eglDestroySurface(display, surface);
        eglTerminate(display);
        return false;
    }
    return true;
}

} // namespace

osg::ref_ptr<EglPbufferContext> EglPbufferContext::create(int width, int height, int deviceIndex,
                                                          std::string& error)
{
    const std::vector<EGLDeviceEXT> devices = queryDevices();
    if (devices.empty())
    {
        error = "EGL enumerates no device (EGL_EXT_device_enumeration)";
        return nullptr;
    }
    if (deviceIndex >= static_cast<int>(devices.size()))
    {
        error = "no EGL device " + std::to_string(deviceIndex) + "; the devices:\n" + listDevices();
        return nullptr;
    }
    std::string reasons;
    for (int d = 0; d < static_cast<int>(devices.size()); ++d)
    {
        if (deviceIndex >= 0 && d != deviceIndex) continue;
        EGLDisplay display = EGL_NO_DISPLAY;
        EGLContext context = EGL_NO_CONTEXT;
        EGLSurface surface = EGL_NO_SURFACE;
        std::string reason;
        if (openOnDevice(devices[d], width, height, display, context, surface, reason))
        {
            return new EglPbufferContext(width, height, display, context, surface);
        }
        reasons += "\n  device " + std::to_string(d) + ": " + reason;
    }
    error = "no EGL device gives a desktop OpenGL pbuffer context:" + reasons;
    return nullptr;
}

std::string EglPbufferContext::listDevices()
{
    std::ostringstream out;
    const std::vector<EGLDeviceEXT> devices = queryDevices();
    for (std::size_t d = 0; d < devices.size(); ++d) out << "  " << d << ": " << describeDevice(devices[d]) << "\n";
    return out.str();
}

EglPbufferContext::EglPbufferContext(int width, int height, void* display, void* context, void* surface)
    : HeadlessGraphicsContext(width, height), _display(display), _context(context), _surface(surface)
{
}

EglPbufferContext::~EglPbufferContext() { close(false); }

void EglPbufferContext::closeImplementation()
{
    if (!_surface) return;
    eglMakeCurrent(_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(_display, _context);
    eglDestroySurface(_display, _surface);
    eglTerminate(_display);
    _surface = nullptr;
    _context = nullptr;
    markClosed();
}

bool EglPbufferContext::makeCurrentImplementation()
{
    return _surface && eglMakeCurrent(_display, _surface, _surface, _context) == EGL_TRUE;
}

bool EglPbufferContext::makeContextCurrentImplementation(osg::GraphicsContext*) { return makeCurrentImplementation(); }

bool EglPbufferContext::releaseContextImplementation()
{
    return _surface && eglMakeCurrent(_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT) == EGL_TRUE;
}

} // namespace bench
