#include <osgActor/detail/InstanceBufferLimit.h>

#include <osg/GL>
#include <osg/GLDefines>

#include <algorithm>

namespace osgActor {
namespace detail {

unsigned InstanceBufferLimit::texels() const
{
    const unsigned queried = _queried.load(std::memory_order_acquire);
    unsigned limit = queried ? queried : kGLMinimum;
    const unsigned cap = getCap();
    if (cap) limit = std::min(limit, cap);
    return std::max(limit, kLeast);
}

void InstanceBufferLimit::noteContext(osg::State& state)
{
    const unsigned id = state.getContextID();
    if (id < 64)
    {
        const std::uint64_t bit = std::uint64_t(1) << id;
        if (_queriedContexts.load(std::memory_order_acquire) & bit) return;
        // Two draws of one context run on its one draw thread: no other thread queries this bit's context.
        _queriedContexts.fetch_or(bit, std::memory_order_acq_rel);
    }
    else
    {
        std::lock_guard<std::mutex> lock(_mutex);
        if (std::find(_queriedHighContexts.begin(), _queriedHighContexts.end(), id) != _queriedHighContexts.end())
            return;
        _queriedHighContexts.push_back(id);
    }
    GLint value = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &value);
    // A context that does not answer (an error leaves value alone) is taken at OpenGL's minimum.
    const unsigned limit = value > 0 ? static_cast<unsigned>(value) : kGLMinimum;
    unsigned known = _queried.load(std::memory_order_relaxed);
    while ((known == 0 || limit < known) &&
           !_queried.compare_exchange_weak(known, limit, std::memory_order_acq_rel, std::memory_order_relaxed))
    {
    }
}

} // namespace detail
} // namespace osgActor
