#include <osgActor/detail/InstancedCull.h>

#include <osgActor/ActorNode>
#include <osgActor/detail/ActorCull.h>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/InstancedSkin.h>
#include <osgActor/detail/JointDrawBatch.h>
#include <osgActor/SkinnedMesh>

#include "../SkinnedMeshDrawState.h"

#include <osg/Material>
#include <osg/TextureBuffer>

#include <algorithm>
#include <iterator>
#include <typeinfo>

namespace osgActor {
namespace detail {

// --- InstancedFrame ---

InstancedFrame::InstancedFrame(osg::StateSet* programState, unsigned textureUnit)
    : _texels(new osg::Image), _stateSet(new osg::StateSet), _bufferStateSet(new osg::StateSet)
{
    _texels->allocateImage(256, 1, 1, GL_RGBA, GL_FLOAT);
    _texels->setInternalTextureFormat(GL_RGBA32F_ARB);
    osg::ref_ptr<osg::TextureBuffer> buffer = new osg::TextureBuffer(_texels.get());
    buffer->setInternalFormat(GL_RGBA32F_ARB);
    _stateSet->setTextureAttribute(textureUnit, buffer.get());
    _bufferStateSet->setTextureAttribute(textureUnit, buffer.get());
    _stateSet->merge(*programState);
}

bool InstancedFrame::isFree() const
{
    for (const osg::ref_ptr<InstancedDraw>& draw : _draws)
        if (draw->referenceCount() != 1) return false;
    return true;
}

float* InstancedFrame::reserveTexels(unsigned texels)
{
    if (static_cast<unsigned>(_texels->s()) < texels)
    {
        // Doubled, so that a growing crowd reallocates the buffer a few times, not every frame.
        unsigned size = static_cast<unsigned>(_texels->s());
        while (size < texels) size *= 2;
        _texels->allocateImage(static_cast<int>(size), 1, 1, GL_RGBA, GL_FLOAT);
    }
    return reinterpret_cast<float*>(_texels->data());
}

InstancedDraw* InstancedFrame::draw(unsigned i)
{
    while (_draws.size() <= i) _draws.push_back(new InstancedDraw);
    return _draws[i].get();
}

// --- InstancedCullState ---

void InstancedCullState::resizeGLObjectBuffers(unsigned maxSize)
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _frames) frame->getStateSet()->resizeGLObjectBuffers(maxSize);
}

void InstancedCullState::releaseGLObjects(osg::State* state) const
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _frames) frame->getStateSet()->releaseGLObjects(state);
}

// --- InstancedCull ---

namespace {

/** Culling active at the node, but for its bound's validity, tested where the bound is used (as ActorCullPlan). */
bool isCullingActive(const osg::Node& node)
{
    return node.getCullingActive() && node.getNumChildrenWithCullingDisabled() == 0;
}

} // namespace

bool InstancedCull::isInstanceableState(const osg::StateSet* state)
{
    if (!state) return true;
    if (!state->getTextureAttributeList().empty() || !state->getTextureModeList().empty() ||
        !state->getUniformList().empty() || state->getRenderBinMode() != osg::StateSet::INHERIT_RENDERBIN_DETAILS ||
        !state->getDefineList().empty())
        return false;
    for (const auto& attribute : state->getAttributeList())
    {
        const osg::Material* material = dynamic_cast<const osg::Material*>(attribute.second.first.get());
        if (!material || material->getColorMode() != osg::Material::OFF) return false;
    }
    return (state->getMode(GL_LIGHTING) & osg::StateAttribute::ON) != 0 ||
           state->getMode(GL_LIGHTING) == osg::StateAttribute::INHERIT;
}

InstancedCull::InstancedCull(osgUtil::CullVisitor& cv, InstancedCullState& state, osg::Group& group,
                             osg::StateSet* programState, unsigned textureUnit)
    : _cv(cv), _state(state), _programState(programState), _traversalMask(cv.getTraversalMask()),
      _maskOverride(cv.getNodeMaskOverride()),
      _smallFeatureCulling((cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::SMALL_FEATURE_CULLING) != 0),
      _computeNearFar(cv.getComputeNearFarMode() != osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR),
      _frustumCulling((cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::VIEW_FRUSTUM_CULLING) != 0),
      _smallFeaturePixelSize(cv.getCurrentCullingSet().getSmallFeatureCullingPixelSize())
{
    _state._statistics = InstancedCullState::Statistics();
    _state._stateVerdicts.clear();
    _state._skinStateVerdicts.clear();
    for (InstancedCullState::Batch& batch : _state._batches)
    {
        batch.data.clear();
        // A skinned mesh's setup may change between culls: found again when an actor first needs it.
        batch.texelsKnown = !batch.mesh;
    }
    // Verdicts of plans that only the cache still holds (their actors made new ones, or are gone) are dropped now and
    // then, never while a plan in use could be among them.
    if (_state._verdicts.size() > 2 * std::size_t(group.getNumChildren()) + 64)
        for (auto it = _state._verdicts.begin(); it != _state._verdicts.end();)
            it = it->second.plan->referenceCount() == 1 ? _state._verdicts.erase(it) : std::next(it);
    for (unsigned i = 0; i < group.getNumChildren(); ++i)
    {
        osg::Node& child = *group.getChild(i);
        if (typeid(child) == typeid(ActorNode)) cullChild(static_cast<ActorNode&>(child));
        else child.accept(cv);
    }
    emitBatches(textureUnit);
}

bool InstancedCull::isPlainActor(const ActorNode& actor)
{
    return actor.getCullMode() == ActorNode::CULL_AS_ONE && !actor.getCullCallback() && !actor.getStateSet() &&
           actor.getReferenceFrame() == osg::Transform::RELATIVE_RF && isCullingActive(actor);
}

void InstancedCull::cullChild(ActorNode& actor)
{
    // The actor's own cull state (one cull at a time: another thread may be culling the actor for another camera)
    // gives the plan its cull as one keeps: its joints, geodes and drawables in the visitor's order.
    ActorCullState& actorState = *actor._cullState;
    if (isPlainActor(actor) && actorState.tryAcquire())
    {
        const ActorCullPlan& plan =
            actorState.currentPlan(actor, actor._cullPlanVersion.load(std::memory_order_relaxed), true);
        const InstancedCullState::PlanVerdict* verdict = instanceableVerdict(plan);
        if (verdict && canInstanceSkins(actor, *verdict))
        {
            ++_state._statistics.actorsInstanced;
            // What the visitor does on its way into the actor: its mask, then its bound in the group's frame.
            if (_cv.validNodeMask(actor) && !_cv.isCulled(actor)) cullActor(actor, *verdict);
            actorState.release();
            return;
        }
        actorState.release();
    }
    ++_state._statistics.actorsOrdinary;
    actor.accept(_cv);
}

const InstancedCullState::PlanVerdict* InstancedCull::instanceableVerdict(const ActorCullPlan& plan)
{
    auto found = _state._verdicts.find(&plan);
    if (found == _state._verdicts.end())
    {
        InstancedCullState::PlanVerdict verdict{&plan, true, {}, {}, {}, {}};
        const osg::StateSet* geodeState = nullptr;
        auto note = [](std::vector<const osg::StateSet*>& states, const osg::StateSet* state) {
            if (state && std::find(states.begin(), states.end(), state) == states.end()) states.push_back(state);
        };
        for (const Step& step : plan.getSteps())
        {
            // A plain drawable of the plan is an osg::Geometry or osg::ShapeDrawable (ActorCullPlan::isPlainDrawable).
            const osg::Geometry* geometry =
                step.kind == ActorCullPlan::DRAWABLE ? static_cast<const osg::Geometry*>(step.node->asDrawable()) : nullptr;
            SkinnedMesh* mesh = InstancedSkin::meshOfStep(step);
            const bool plain = step.kind == ActorCullPlan::END_JOINT || step.kind == ActorCullPlan::END_GEODE ||
                               (step.kind == ActorCullPlan::JOINT && !step.stateSet) ||
                               step.kind == ActorCullPlan::GEODE || (geometry && InstancedDraw::canDraw(*geometry)) ||
                               mesh;
            verdict.plain = verdict.plain && plain;
            // The state sets a drawable is drawn with: its geode's and its own, checked as its kind is drawn.
            if (geometry) note(verdict.states, geodeState), note(verdict.states, step.stateSet);
            if (mesh) note(verdict.skinStates, geodeState); // the mesh's own is checked at each cull
            if (step.kind == ActorCullPlan::GEODE) geodeState = step.stateSet;
            if (step.kind == ActorCullPlan::END_GEODE) geodeState = nullptr;
            unsigned batch = 0;
            if (verdict.plain && geometry) batch = batchOf(geodeState, *geometry);
            if (verdict.plain && mesh) verdict.skinBatches.push_back(batch = skinBatchOf(geodeState, *mesh));
            verdict.batchOfStep.push_back(batch);
        }
        found = _state._verdicts.emplace(&plan, std::move(verdict)).first;
    }
    const InstancedCullState::PlanVerdict& verdict = found->second;
    if (!verdict.plain) return nullptr;
    for (const osg::StateSet* state : verdict.states)
        if (!isInstanceableNow(state)) return nullptr;
    for (const osg::StateSet* state : verdict.skinStates)
        if (!isSkinInstanceableNow(state)) return nullptr;
    return &verdict;
}

bool InstancedCull::canInstanceSkins(ActorNode& actor, const InstancedCullState::PlanVerdict& verdict)
{
    _state._skinInstances.clear();
    if (verdict.skinBatches.empty()) return true;
    // The instanced program is of the compatibility profile (GLSL 1.50 compatibility).
    if (skinningProfileOf(_cv.getState()) != SkinningProfile::Compatibility) return false;
    for (unsigned b : verdict.skinBatches)
    {
        InstancedCullState::Batch& batch = _state._batches[b];
        if (!batch.texelsKnown)
        {
            batch.texels = InstancedSkin::texelsPerInstance(*batch.mesh);
            batch.texelsKnown = true;
        }
        // The mesh's cull callback and state set, which the plan does not watch (the mesh is not a node it plans).
        SkinnedMesh& mesh = *batch.mesh;
        if (!batch.texels || mesh.getCullCallback() || !isSkinInstanceableNow(mesh.getStateSet())) return false;
        const SkinnedMeshInstance* instance = InstancedSkin::instanceOf(mesh, actor);
        if (!instance) return false;
        _state._skinInstances.push_back(instance);
    }
    return true;
}

unsigned InstancedCull::batchOf(const osg::StateSet* geodeState, const osg::Geometry& drawable)
{
    const InstancedCullState::BatchKey key{geodeState, &drawable};
    auto found = _state._batchOfKey.find(key);
    if (found != _state._batchOfKey.end()) return found->second;
    const unsigned batch = static_cast<unsigned>(_state._batches.size());
    _state._batches.push_back({geodeState, &drawable, nullptr, {}, 4u, true});
    _state._batchOfKey.emplace(key, batch);
    return batch;
}

unsigned InstancedCull::skinBatchOf(const osg::StateSet* geodeState, SkinnedMesh& mesh)
{
    const InstancedCullState::BatchKey key{geodeState, &mesh};
    auto found = _state._batchOfKey.find(key);
    if (found != _state._batchOfKey.end()) return found->second;
    const unsigned batch = static_cast<unsigned>(_state._batches.size());
    _state._batches.push_back({geodeState, nullptr, &mesh, {}, 0u, false});
    _state._batchOfKey.emplace(key, batch);
    return batch;
}

bool InstancedCull::isInstanceableNow(const osg::StateSet* state)
{
    for (const auto& known : _state._stateVerdicts)
        if (known.first == state) return known.second;
    const bool verdict = isInstanceableState(state);
    _state._stateVerdicts.emplace_back(state, verdict);
    return verdict;
}

bool InstancedCull::isSkinInstanceableNow(const osg::StateSet* state)
{
    for (const auto& known : _state._skinStateVerdicts)
        if (known.first == state) return known.second;
    const bool verdict = InstancedSkin::isInstanceableState(state);
    _state._skinStateVerdicts.emplace_back(state, verdict);
    return verdict;
}

bool InstancedCull::isSmallFeature(const osg::BoundingSphere& bound, unsigned frame)
{
    return _state._pixelSizeVectors.isSmallFeature(bound, frame, *_cv.getViewport(), *_cv.getProjectionMatrix(),
                                                   _state._modelViews[frame], _smallFeaturePixelSize);
}

void InstancedCull::cullActor(ActorNode& actor, const InstancedCullState::PlanVerdict& verdict)
{
    const ActorCullPlan& plan = *verdict.plan;
    const std::vector<ActorCullPlan::Joint>& joints = plan.getJoints();
    const std::size_t numFrames = joints.size() + 1;
    std::vector<osg::Matrixd>& modelViews = _state._modelViews;
    modelViews.resize(numFrames);
    _state._pixelSizeVectors.reset(numFrames);
    // The actor's frame, as the visitor's pushModelViewMatrix() makes it (MatrixTransform: actor_m * group's), then
    // each joint's, parents first, as ActorCull composes them.
    composeModelView(actor.getMatrix().ptr(), _cv.getModelViewMatrix()->ptr(), modelViews[0].ptr());
    for (std::size_t j = 0; j < joints.size(); ++j)
        composeModelView(joints[j].node->getMatrix().ptr(),
                         modelViews[static_cast<std::size_t>(joints[j].parent + 1)].ptr(), modelViews[j + 1].ptr());
    if (actor.getUpdatePolicy().onlyWhenSeen)
    {
        // The update policy notes the view with the actor's frame on the visitor's stack, as its own cull does.
        _cv.pushModelViewMatrix(new osg::RefMatrix(modelViews[0]), osg::Transform::RELATIVE_RF);
        actor.noteSeen(_cv);
        _cv.popModelViewMatrix();
    }
    // The plan's steps as ActorCull::cull() follows them: a joint or geode masked out or too small in the frame it
    // is in is skipped with its subtree.
    const std::vector<Step>& steps = plan.getSteps();
    unsigned skin = 0; // the next of the actor's skinned meshes
    for (std::size_t i = 0; i < steps.size();)
    {
        const Step& step = steps[i];
        switch (step.kind)
        {
        case ActorCullPlan::JOINT:
        case ActorCullPlan::GEODE:
        {
            const unsigned frame = step.kind == ActorCullPlan::JOINT ? unsigned(joints[step.joint].parent + 1)
                                                                      : unsigned(step.joint + 1);
            if (isMasked(step.mask) ||
                (_smallFeatureCulling && step.cullingActive && isSmallFeature(step.node->getBound(), frame)))
            {
                i = step.end;
                continue;
            }
            break;
        }
        case ActorCullPlan::DRAWABLE:
            if (!isMasked(step.mask)) addDrawable(step, verdict.batchOfStep[i]);
            break;
        case ActorCullPlan::ORDINARY:
            // A skinned mesh (the only ORDINARY step of an instanceable plan): its mask now, as its accept() tests it
            // (the plan does not watch it).
            if (!isMasked(step.node->getNodeMask())) addSkinned(*_state._skinInstances[skin], verdict.batchOfStep[i]);
            ++skin;
            break;
        default: break; // the ends
        }
        ++i;
    }
}

void InstancedCull::addDrawable(const Step& step, unsigned batch)
{
    const osg::Geometry& drawable = *static_cast<const osg::Geometry*>(step.node->asDrawable());
    const osg::Matrixd& modelView = _state._modelViews[static_cast<std::size_t>(step.joint + 1)];
    // As ActorCull::addDrawable(): near and far from what is drawn, the box against the frustum before.
    const osg::BoundingBox& box = drawable.getBoundingBox();
    if (_computeNearFar && box.valid())
    {
        if (_frustumCulling && step.cullingActive &&
            isOutsideFrustum(box, modelView, _cv.getProjectionCullingStack().back().getFrustum()))
            return;
        if (!_cv.updateCalculatedNearFar(modelView, drawable, true)) return;
    }
    if (box.valid() && osg::isNaN(eyeDepth(box.center(), modelView))) return; // the visitor drops it too
    std::vector<float>& matrices = _state._batches[batch].data;
    const double* m = modelView.ptr();
    // As OSG hands a matrix to OpenGL (glLoadMatrixd, which keeps floats): each double rounded to the nearest float.
    for (int k = 0; k < 16; ++k) matrices.push_back(static_cast<float>(m[k]));
}

void InstancedCull::addSkinned(const SkinnedMeshInstance& instance, unsigned b)
{
    InstancedCullState::Batch& batch = _state._batches[b];
    SkinnedMesh& mesh = *batch.mesh;
    // As SkinnedMesh's cull: drawn from the actor's first update on, its bound (model space, the actor's frame)
    // against the view.
    if (!InstancedSkin::hasMatrices(instance)) return;
    const osg::Matrixd& modelView = _state._modelViews[0];
    const osg::Polytope& frustum = _cv.getProjectionCullingStack().back().getFrustum();
    if (_frustumCulling && mesh.isCullingActive() && isOutsideFrustum(InstancedSkin::boundOf(instance), modelView, frustum))
        return;
    // Then what the visitor does with the bind-pose geometry it is handed, whose box is the union of the actors'
    // bounds: the box against the frustum, near and far from it, its depth.
    const osg::Geometry& geometry = *InstancedSkin::geometryOf(mesh);
    const osg::BoundingBox& box = geometry.getBoundingBox();
    if (_frustumCulling && geometry.isCullingActive() && isOutsideFrustum(box, modelView, frustum)) return;
    if (_computeNearFar && box.valid() && !_cv.updateCalculatedNearFar(modelView, geometry, true)) return;
    if (box.valid() && osg::isNaN(eyeDepth(box.center(), modelView))) return;
    std::vector<float>& data = batch.data;
    const std::size_t at = data.size();
    data.resize(at + 4 * std::size_t(batch.texels));
    InstancedSkin::writeInstance(mesh, instance, modelView, data.data() + at);
}

InstancedFrame* InstancedCull::acquireFrame(unsigned textureUnit)
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _state._frames)
        if (frame->isFree()) return frame.get();
    _state._frames.push_back(new InstancedFrame(_programState, textureUnit));
    return _state._frames.back().get();
}

void InstancedCull::emitBatches(unsigned textureUnit)
{
    std::size_t texels = 0;
    for (const InstancedCullState::Batch& batch : _state._batches) texels += batch.data.size() / 4;
    if (texels == 0) return;
    InstancedFrame& frame = *acquireFrame(textureUnit);
    float* out = frame.reserveTexels(static_cast<unsigned>(texels));
    unsigned base = 0, drawIndex = 0;
    for (const InstancedCullState::Batch& batch : _state._batches)
    {
        const unsigned count = batch.data.empty() ? 0u : static_cast<unsigned>(batch.data.size() / (4 * batch.texels));
        if (count == 0) continue;
        std::copy(batch.data.begin(), batch.data.end(), out + 4 * std::size_t(base));
        InstancedDraw& draw = *frame.draw(drawIndex++);
        const osg::Geometry* geometry = batch.mesh ? InstancedSkin::geometryOf(*batch.mesh) : batch.drawable;
        draw.set(geometry, static_cast<int>(base), count, static_cast<int>(batch.texels));
        // A dynamic drawable makes osgViewer's next update wait until it is drawn: so does its instanced draw.
        const osg::Drawable& drawn = batch.mesh ? static_cast<const osg::Drawable&>(*batch.mesh) : *batch.drawable;
        draw.setDataVariance(drawn.getDataVariance() == osg::Object::DYNAMIC ? osg::Object::DYNAMIC
                                                                              : osg::Object::STATIC);
        base += batch.texels * count;
        emitLeaf(batch, draw, frame);
        if (batch.mesh)
        {
            ++_state._statistics.skinnedDraws;
            _state._statistics.skinnedInstances += count;
        }
        else
        {
            ++_state._statistics.draws;
            _state._statistics.instances += count;
        }
    }
    frame.dirty();
}

void InstancedCull::emitLeaf(const InstancedCullState::Batch& batch, InstancedDraw& draw, InstancedFrame& frame)
{
    // The drawable's states as the ordinary traversal pushes them (the geode's, then its own), then the frame's.
    unsigned pushed = 0;
    auto push = [&](const osg::StateSet* state) {
        if (!state) return;
        _cv.pushStateSet(state);
        ++pushed;
    };
    push(batch.geodeState);
    if (batch.mesh)
    {
        // As SkinnedMesh's cull: its own state set, then the program of the variant the state in effect asks for
        // (the lights on, a fragment-only program), here its instanced variant, which reads the palettes from the
        // frame's buffer.
        push(batch.mesh->getStateSet());
        SkinningProgramKey key = InstancedSkin::programKey(*batch.mesh);
        applyDrawState(_cv.getCurrentStateGraph(), key);
        push(getSkinningProgramStateSet(key));
        push(frame.getBufferStateSet());
    }
    else
    {
        push(batch.drawable->getStateSet());
        push(frame.getStateSet());
    }
    // The leaf's matrix is the group's: the program takes each instance's from the buffer, the projection from the
    // leaf.
    _cv.addDrawableAndDepth(&draw, _cv.getModelViewMatrix(), 0.0f);
    for (unsigned i = 0; i < pushed; ++i) _cv.popStateSet();
}

} // namespace detail
} // namespace osgActor
