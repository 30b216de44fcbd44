#include <osgActor/InstancedActorGroup>
#include <osgActor/detail/ActorCull.h>
#include <osgActor/detail/InstancedCull.h>
#include <osgActor/shaders/ShaderSources.h>

#include <osg/Uniform>
#include <osgUtil/CullVisitor>
#include <osgUtil/RenderBin>

#include <algorithm>
#include <string>

namespace osgActor {

namespace {

osg::ref_ptr<osg::StateSet> makeProgramState(std::uint8_t lights)
{
    osg::ref_ptr<osg::StateSet> state = new osg::StateSet;
    state->setAttributeAndModes(InstancedActorGroup::createRigidProgram(true, lights).get());
    state->addUniform(new osg::Uniform("osgActor_instances", static_cast<int>(InstancedActorGroup::kInstanceTextureUnit)));
    return state;
}

} // namespace

osg::ref_ptr<osg::Program> InstancedActorGroup::createRigidProgram(bool instanced, std::uint8_t lights)
{
    std::string prelude = "#version 150 compatibility\n#define OSGACTOR_MODEL_VIEW gl_ModelViewMatrix\n"
                          "#define OSGACTOR_INSTANCED ";
    prelude += instanced ? "1\n" : "0\n";
    prelude += "#define OSGACTOR_LIGHTS_ON bool[8](";
    for (unsigned i = 0; i < 8; ++i) prelude += std::string(i ? ", " : "") + ((lights >> i) & 1u ? "true" : "false");
    prelude += ")\n";
    osg::ref_ptr<osg::Program> program = new osg::Program;
    program->setName(instanced ? "osgActor instanced rigid parts" : "osgActor rigid parts, one at a time");
    program->addShader(new osg::Shader(
        osg::Shader::VERTEX, prelude + shaders::kLightingCompatibility + shaders::kInstanceData + shaders::kInstancedRigidVertex));
    program->addShader(
        new osg::Shader(osg::Shader::FRAGMENT, std::string("#version 150 compatibility\n") + shaders::kInstancedRigidFragment));
    return program;
}

InstancedActorGroup::InstancedActorGroup()
    : _drawMode(INSTANCED), _lights(1), _maxTexelsPerBuffer(0), _programState(makeProgramState(1)),
      _cullState(new detail::InstancedCullState)
{
}

InstancedActorGroup::InstancedActorGroup(const InstancedActorGroup& group, const osg::CopyOp& copyop)
    : ActorGroup(group, copyop), _drawMode(group._drawMode), _lights(group._lights),
      _maxTexelsPerBuffer(group._maxTexelsPerBuffer), _programState(makeProgramState(group._lights)),
      _cullState(new detail::InstancedCullState)
{
    _cullState->getBufferLimit().setCap(_maxTexelsPerBuffer);
}

InstancedActorGroup::~InstancedActorGroup() = default;

void InstancedActorGroup::setLights(std::uint8_t lights)
{
    if (lights == _lights) return;
    _lights = lights;
    // The frames of the old program's state are dropped with it; the next cull makes new ones.
    _programState = makeProgramState(lights);
    _cullState = new detail::InstancedCullState;
    _cullState->getBufferLimit().setCap(_maxTexelsPerBuffer);
}

void InstancedActorGroup::setMaxTexelsPerBuffer(unsigned texels)
{
    _maxTexelsPerBuffer = texels ? std::max(texels, detail::InstanceBufferLimit::kLeast) : 0u;
    _cullState->getBufferLimit().setCap(_maxTexelsPerBuffer);
}

InstancedActorGroup::Statistics InstancedActorGroup::getStatistics() const
{
    const detail::InstancedCullState::Statistics s = _cullState->getStatistics();
    Statistics statistics;
    statistics.actorsInstanced = s.actorsInstanced;
    statistics.actorsOrdinary = s.actorsOrdinary;
    statistics.actorsOutOfView = s.actorsOutOfView;
    statistics.actorsKept = s.actorsKept;
    statistics.draws = s.draws;
    statistics.instances = s.instances;
    statistics.skinnedDraws = s.skinnedDraws;
    statistics.skinnedInstances = s.skinnedInstances;
    statistics.buffers = s.buffers;
    statistics.texelLimit = s.texelLimit;
    return statistics;
}

void InstancedActorGroup::traverse(osg::NodeVisitor& nv)
{
    osgUtil::CullVisitor* cv = nv.getVisitorType() == osg::NodeVisitor::CULL_VISITOR ? nv.asCullVisitor() : nullptr;
    // The instances of a part are drawn together, in no order by depth: only in a bin sorted by state. Near and far
    // from primitives clip each drawable's triangles against the frustum in the drawable's own frame, which the
    // instanced cull (one culling set for the group) does not follow: each actor is then culled as one, which does.
    if (_drawMode != INSTANCED || !cv || !detail::ActorCull::canCullAsOne(*cv) ||
        detail::ActorCull::nearFarFromPrimitives(*cv) ||
        cv->getCurrentRenderBin()->getSortMode() != osgUtil::RenderBin::SORT_BY_STATE || !_cullState->tryAcquire())
    {
        ActorGroup::traverse(nv);
        return;
    }
    // From getMinActorsForParallelCull() children on, each actor's part of the cull on the group's threads, where
    // they are free.
    if (getNumChildren() >= getMinActorsForParallelCull())
    {
        CullThreads threads(*this);
        const detail::InstancedCull cull(*cv, *_cullState, *this, _programState.get(), kInstanceTextureUnit,
                                         {threads.get(), getMinActorsForParallelCull(), getChildrenVersion()});
        if (cull.culledInParallel()) _numParallelCulls.fetch_add(1, std::memory_order_relaxed);
    }
    else
        detail::InstancedCull(*cv, *_cullState, *this, _programState.get(), kInstanceTextureUnit);
    _cullState->release();
}

void InstancedActorGroup::resizeGLObjectBuffers(unsigned maxSize)
{
    ActorGroup::resizeGLObjectBuffers(maxSize);
    _programState->resizeGLObjectBuffers(maxSize);
    _cullState->resizeGLObjectBuffers(maxSize);
}

void InstancedActorGroup::releaseGLObjects(osg::State* state) const
{
    ActorGroup::releaseGLObjects(state);
    _programState->releaseGLObjects(state);
    _cullState->releaseGLObjects(state);
}

} // namespace osgActor
