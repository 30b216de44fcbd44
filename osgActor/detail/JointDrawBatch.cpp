#include <osgActor/detail/JointDrawBatch.h>

#include <osg/State>
#include <osgUtil/CullVisitor>

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

void JointDrawBatch::reset(const osg::Referenced* keepAlive, const JointModelViews* modelViews)
{
    _entries.clear();
    _keepAlive = keepAlive;
    _modelViews = modelViews;
}

void JointDrawBatch::drawImplementation(osg::RenderInfo& renderInfo) const
{
    osg::State& state = *renderInfo.getState();
    const bool uniforms = state.getUseModelViewAndProjectionUniforms();
    const osg::Matrixd* matrices = _modelViews->matrices.data();
    for (const Entry& entry : _entries)
    {
        state.applyModelViewMatrix(matrices[entry.frame]);
        if (uniforms) state.applyModelViewAndProjectionUniformsIfRequired();
        entry.drawable->draw(renderInfo);
    }
}

} // namespace detail
} // namespace osgActor
