// Internal to the library (not installed, NOT API): how many texels one texture buffer of the instanced draws may
// hold (InstancedActorGroup, issue 28). OpenGL bounds a texture buffer's texels by GL_MAX_TEXTURE_BUFFER_SIZE, at
// least 65536, per context. Only the draw knows its context, and the cull that lays the instances out runs before it:
// the draws query each context once and the limit is the least of the contexts queried so far, OpenGL's minimum
// until one has been, below a cap the group may set (InstancedActorGroup::setMaxTexelsPerBuffer()). The cull of a
// frame reads the limit as it is then; a context with a lower limit first drawing this frame lowers the next frame's.
#ifndef OSGACTOR_DETAIL_INSTANCEBUFFERLIMIT_H
#define OSGACTOR_DETAIL_INSTANCEBUFFERLIMIT_H 1

#include <osg/Referenced>
#include <osg/State>

#include <atomic>
#include <cstdint>
#include <mutex>
#include <vector>

namespace osgActor {
namespace detail {

class InstanceBufferLimit : public osg::Referenced
{
public:
    /** OpenGL's least GL_MAX_TEXTURE_BUFFER_SIZE (OpenGL 3.1 and later). */
    static constexpr unsigned kGLMinimum = 65536;
    /** The fewest texels a limit may be: one rigid instance's matrix. */
    static constexpr unsigned kLeast = 4;

    /** The texels one buffer may hold now: the least of the queried contexts' limits (kGLMinimum before any) and the
      * cap, at least kLeast. Read by the cull on any thread. */
    unsigned texels() const;

    /** Whether texels() is more than OpenGL's minimum taken for want of a context's answer: a context answered, or
      * a cap is set. */
    bool isKnown() const { return _queried.load(std::memory_order_acquire) != 0 || getCap() != 0; }

    /** A cap below the contexts' limits (0: none). */
    void setCap(unsigned cap) { _cap.store(cap, std::memory_order_relaxed); }
    unsigned getCap() const { return _cap.load(std::memory_order_relaxed); }

    /** Queries the limit of state's context the first time a draw of that context calls it (on its draw thread,
      * the context current). */
    void noteContext(osg::State& state);

protected:
    ~InstanceBufferLimit() override = default;

private:
    /** The least limit queried, 0 before any query. */
    std::atomic<unsigned> _queried{0};
    std::atomic<unsigned> _cap{0};
    /** The contexts queried: a bit per context id below 64, the others in the list under the mutex. */
    std::atomic<std::uint64_t> _queriedContexts{0};
    std::mutex _mutex;
    std::vector<unsigned> _queriedHighContexts;
};

} // namespace detail
} // namespace osgActor

#endif
