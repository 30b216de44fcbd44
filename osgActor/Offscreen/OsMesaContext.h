/* osgActor::Offscreen (not installed): an OSMesa context rendering into a client memory buffer
 * (docs/architecture.md). */
#ifndef OSGACTOR_OFFSCREEN_OSMESACONTEXT_H
#define OSGACTOR_OFFSCREEN_OSMESACONTEXT_H 1

#include <memory>
#include <string>
#include <vector>

namespace osgActor {

/** A compatibility-profile OSMesa context (RGBA, depth 24, stencil 8) made current on a buffer this object owns.
  * The buffer holds RGBA bytes, rows bottom-first, as osg::Image expects. Everything that uses the context (an
  * osgViewer::Viewer) must be destroyed before it. */
class OsMesaContext
{
public:
    /** A context of width x height pixels, made current on this thread; null, with the reason in error, if the
      * GL functions do not resolve into libOSMesa or OSMesa refuses the context. */
    static std::unique_ptr<OsMesaContext> create(int width, int height, std::string& error);

    /** True if glGetString, as the dynamic linker resolves it for the whole process (which is how OSG finds its
      * GL functions), comes from libOSMesa. It does only when libOSMesa is ahead of glvnd's libGL in the link
      * order; otherwise OSG fails its OpenGL version test and renders black. error names the library it found. */
    static bool glResolvesToOsMesa(std::string& error);

    ~OsMesaContext();
    OsMesaContext(const OsMesaContext&) = delete;
    OsMesaContext& operator=(const OsMesaContext&) = delete;

    /** Makes this context current on the calling thread (another context may have been made current since). */
    bool makeCurrent();

    int getWidth() const { return _width; }
    int getHeight() const { return _height; }
    /** The colour buffer: width * height RGBA pixels, rows bottom-first. Complete only after glFinish(). */
    const unsigned char* getPixels() const { return _pixels.data(); }

private:
    OsMesaContext(int width, int height);

    int _width;
    int _height;
    std::vector<unsigned char> _pixels;
    void* _context; // OSMesaContext, kept opaque so that no GL header leaks into users of this class
};

} // namespace osgActor

#endif
