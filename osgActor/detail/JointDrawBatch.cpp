#include <osgActor/detail/JointDrawBatch.h>

#include <osg/State>

namespace osgActor {
namespace detail {

JointDrawBatch::JointDrawBatch()
{
    // Drawn afresh every frame from its entries: nothing to compile or cache.
    setUseDisplayList(false);
    setUseVertexBufferObjects(false);
    setUseVertexArrayObject(false);
    setCullingActive(false);
}

JointDrawBatch* JointDrawBatch::acquire()
{
    // Batches are let go of in the order they were taken, a frame or two later: looking on from the last one taken
    // finds a free one at once in the steady state. A few looks, then a new batch, so that a growing crowd does not
    // look through all the busy ones each time.
    constexpr std::size_t kLooks = 8;
    thread_local std::vector<osg::ref_ptr<JointDrawBatch>> pool;
    thread_local std::size_t next = 0;
    for (std::size_t k = 0; k < kLooks && k < pool.size(); ++k)
    {
        const std::size_t i = (next + k) % pool.size();
        if (pool[i]->referenceCount() == 1)
        {
            next = i + 1;
            pool[i]->_entries.clear();
            return pool[i].get();
        }
    }
    pool.push_back(new JointDrawBatch);
    return pool.back().get();
}

void JointDrawBatch::drawImplementation(osg::RenderInfo& renderInfo) const
{
    osg::State& state = *renderInfo.getState();
    const bool uniforms = state.getUseModelViewAndProjectionUniforms();
    for (const Entry& entry : _entries)
    {
        state.applyModelViewMatrix(entry.modelView);
        if (uniforms) state.applyModelViewAndProjectionUniformsIfRequired();
        entry.drawable->draw(renderInfo);
    }
}

} // namespace detail
} // namespace osgActor
