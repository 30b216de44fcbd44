#include <osgActor/detail/InstancedCull.h>

#include <osgActor/ActorNode>
#include <osgActor/detail/ActorCull.h>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/DrawableBox.h>
#include <osgActor/detail/InstancedSkin.h>
#include <osgActor/detail/JointDrawBatch.h>
#include <osgActor/SkinnedMesh>

#include "../SkinnedMeshDrawState.h"
#include <osgActor/detail/Prefetch.h>
#include <osgActor/core/detail/HotPath.h>

#include <osg/Material>
#include <osg/Notify>
#include <osg/TextureBuffer>

#include <algorithm>
#include <cstring>
#include <iterator>
#include <typeinfo>

namespace osgActor {
namespace detail {

// --- InstancedFrame ---

InstancedFrame::InstancedFrame(osg::StateSet* programState, unsigned textureUnit, InstanceBufferLimit* limit)
    : _programState(programState), _textureUnit(textureUnit), _limit(limit)
{
    addBuffer();
    _buffers[0].texels->allocateImage(256, 1, 1, GL_RGBA, GL_FLOAT);
}

void InstancedFrame::addBuffer()
{
    Buffer made{new osg::Image, new osg::StateSet, new osg::StateSet};
    made.texels->allocateImage(1, 1, 1, GL_RGBA, GL_FLOAT);
    made.texels->setInternalTextureFormat(GL_RGBA32F_ARB);
    osg::ref_ptr<osg::TextureBuffer> buffer = new osg::TextureBuffer(made.texels.get());
    buffer->setInternalFormat(GL_RGBA32F_ARB);
    made.stateSet->setTextureAttribute(_textureUnit, buffer.get());
    made.bufferStateSet->setTextureAttribute(_textureUnit, buffer.get());
    made.stateSet->merge(*_programState);
    _buffers.push_back(std::move(made));
}

bool InstancedFrame::isFree() const
{
    for (const osg::ref_ptr<InstancedDraw>& draw : _draws)
        if (draw->referenceCount() != 1) return false;
    return true;
}

float* InstancedFrame::reserveTexels(unsigned texels)
{
    osg::Image& image = *_buffers[0].texels;
    if (static_cast<unsigned>(image.s()) < texels)
    {
        // Doubled, so that a growing crowd reallocates the buffer a few times, not every frame.
        unsigned size = static_cast<unsigned>(image.s());
        while (size < texels) size *= 2;
        image.allocateImage(static_cast<int>(size), 1, 1, GL_RGBA, GL_FLOAT);
        moved();
    }
    return reinterpret_cast<float*>(image.data());
}

float* InstancedFrame::growTexels(unsigned texels)
{
    const osg::Image& image = *_buffers[0].texels;
    if (static_cast<unsigned>(image.s()) >= texels) return reinterpret_cast<float*>(_buffers[0].texels->data());
    const float* data = reinterpret_cast<const float*>(image.data());
    const std::vector<float> kept(data, data + 4 * static_cast<std::size_t>(image.s()));
    float* out = reserveTexels(texels);
    std::copy(kept.begin(), kept.end(), out);
    return out;
}

void InstancedFrame::setWindow(unsigned i, unsigned first, unsigned texels)
{
    while (_buffers.size() <= i) addBuffer();
    unsigned char* data = _buffers[0].texels->data() + std::size_t(first) * 4 * sizeof(float);
    osg::Image& window = *_buffers[i].texels;
    if (window.data() == data && static_cast<unsigned>(window.s()) == texels) return; // as uploaded, if not dirtied
    // The window's image does not own its texels: buffer 0's image, which the window holds (a render graph may hold
    // the window's state set after the frame is gone), keeps them while the frame's draws are in the render graph
    // (the pool reserves them anew only for a free frame).
    if (window.getUserData() != _buffers[0].texels.get()) window.setUserData(_buffers[0].texels.get());
    window.setImage(static_cast<int>(texels), 1, 1, GL_RGBA32F_ARB, GL_RGBA, GL_FLOAT, data, osg::Image::NO_DELETE);
}

std::uint64_t InstancedFrame::beginWrites(std::uint64_t cull)
{
    const std::uint64_t holds = _contents == _writesContents + 1 ? _writesCull : 0;
    _writesContents = _contents;
    _writesCull = cull;
    return holds;
}

void InstancedFrame::dirtyAll()
{
    for (const Buffer& buffer : _buffers) buffer.texels->dirty();
}

void InstancedFrame::resizeGLObjectBuffers(unsigned maxSize)
{
    for (const Buffer& buffer : _buffers) buffer.stateSet->resizeGLObjectBuffers(maxSize);
}

void InstancedFrame::releaseGLObjects(osg::State* state) const
{
    for (const Buffer& buffer : _buffers) buffer.stateSet->releaseGLObjects(state);
}

InstancedDraw* InstancedFrame::draw(unsigned i)
{
    while (_draws.size() <= i)
    {
        _draws.push_back(new InstancedDraw);
        _draws.back()->setBufferLimit(_limit.get());
    }
    return _draws[i].get();
}

// --- InstancedCullState ---

InstancedCullState::InstancedCullState()
    : _serial([] {
          static std::atomic<std::uint64_t> counter{0};
          return counter.fetch_add(1, std::memory_order_relaxed) + 1; // 0: no state
      }()),
      _limit(new InstanceBufferLimit), _scratch(1)
{
    _busy.clear();
}

void InstancedCullState::resizeGLObjectBuffers(unsigned maxSize)
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _frames) frame->resizeGLObjectBuffers(maxSize);
}

void InstancedCullState::releaseGLObjects(osg::State* state) const
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _frames) frame->releaseGLObjects(state);
}

// --- InstancedCull ---

namespace {

/** Culling active at the node, but for its bound's validity, tested where the bound is used (as ActorCullPlan). */
bool isCullingActive(const osg::Node& node)
{
    return node.getCullingActive() && node.getNumChildrenWithCullingDisabled() == 0;
}

/** A rigid part's instance: its model-view matrix (eye space) as OSG hands a matrix to OpenGL (glLoadMatrixd, which
  * keeps floats): each double rounded to the nearest float, OSG's rows one after the other. */
void writeInstanceMatrix(const osg::Matrixd& modelView, float* out)
{
    const double* m = modelView.ptr();
#if defined(__GNUC__)
    // Four entries at a time, which a caller built for x86-64-v3 converts in one instruction (the compiler, left to
    // itself, converts them one by one); rounded to the nearest float either way.
    typedef double FourDoubles __attribute__((vector_size(32)));
    typedef float FourFloats __attribute__((vector_size(16)));
    for (int k = 0; k < 16; k += 4)
    {
        FourDoubles entries;
        std::memcpy(&entries, m + k, sizeof entries);
        const FourFloats rounded = __builtin_convertvector(entries, FourFloats);
        std::memcpy(out + k, &rounded, sizeof rounded);
    }
#else
    for (int k = 0; k < 16; ++k) out[k] = static_cast<float>(m[k]);
#endif
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
    : InstancedCull(cv, state, group, programState, textureUnit, Threads{nullptr, 0, 0})
{
}

InstancedCull::InstancedCull(osgUtil::CullVisitor& cv, InstancedCullState& state, osg::Group& group,
                             osg::StateSet* programState, unsigned textureUnit, const Threads& threads)
    : _cv(cv), _state(state), _programState(programState), _textureUnit(textureUnit), _scratch(&state._scratch[0]),
      _outcome(nullptr), _mayDecideShared(true), _deferred(false), _culledInParallel(false),
      _cullNumber(++state._culls), _frameHolds(0), _traversalMask(cv.getTraversalMask()),
      _maskOverride(cv.getNodeMaskOverride()),
      _smallFeatureCulling((cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::SMALL_FEATURE_CULLING) != 0),
      _computeNearFar(cv.getComputeNearFarMode() != osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR),
      _frustumCulling((cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::VIEW_FRUSTUM_CULLING) != 0),
      _smallFeaturePixelSize(cv.getCurrentCullingSet().getSmallFeatureCullingPixelSize()), _overflowed(false),
      _wroteTexels(false), _texelLimit(state._limit->texels()), _profile(skinningProfileOf(cv.getState())), _view(cv),
      _recording(nullptr)
{
    const ActorCullState::Key viewKey = ActorCullState::keyOf(_view, osg::Matrixd::identity());
    if (_state._view == 0 || !(viewKey == _state._viewKey))
    {
        _state._viewKey = viewKey;
        ++_state._view;
    }
    if (_state._entry == 0 || !sameBits(*cv.getModelViewMatrix(), _state._entryModelView))
    {
        _state._entryModelView = *cv.getModelViewMatrix();
        ++_state._entry;
    }
    _state._statistics = InstancedCullState::Statistics();
    _state._statistics.texelLimit = _texelLimit;
    _scratch->stateVerdicts.clear();
    _scratch->skinStateVerdicts.clear();
    placeBatches(textureUnit);
    if (_state._frame) _frameHolds = _state._frame->beginWrites(_cullNumber);
    // A skinned mesh's setup may change between culls: found again when an actor first needs it.
    for (InstancedCullState::Batch& batch : _state._batches) batch.texelsKnown = !batch.mesh;
    // Verdicts of plans that only the cache still holds (their actors made new ones, or are gone) are dropped now and
    // then, never while a plan in use could be among them.
    if (_state._verdicts.size() > 2 * std::size_t(group.getNumChildren()) + 64)
        for (auto it = _state._verdicts.begin(); it != _state._verdicts.end();)
            it = it->second.plan->referenceCount() == 1 ? _state._verdicts.erase(it) : std::next(it);
    _culledInParallel = threads.pool && cullInParallel(group, threads);
    if (!_culledInParallel) cullSerially(group);
    if (_overflowed) gatherOverflow(textureUnit);
    emitBatches();
    std::lock_guard<std::mutex> lock(_state._publishedMutex);
    _state._published = _state._statistics;
}

InstancedCull::InstancedCull(const InstancedCull& cull, unsigned thread) : InstancedCull(cull)
{
    _scratch = &_state._scratch[thread];
    _outcome = nullptr;
    _mayDecideShared = false;
    _recording = nullptr;
}

void InstancedCull::cullSerially(osg::Group& group)
{
    const unsigned numChildren = group.getNumChildren();
    for (unsigned i = 0; i < numChildren; ++i)
    {
        osg::Node& child = *group.getChild(i);
        if (typeid(child) == typeid(ActorNode))
        {
            // The actors after this one fetched ahead, a link of each one's chain at a time (the crowd's cull is
            // bound by memory latency), their kept instances too.
            const ActorNode& actor = static_cast<const ActorNode&>(child);
            for (unsigned ahead = 1; ahead <= ActorNode::kCullLookahead && i + ahead < numChildren; ++ahead)
            {
                const osg::Node& next = *group.getChild(i + ahead);
                actor.prefetchCullAhead(next, ahead);
                prefetchKeptAhead(next, ahead);
            }
            cullChild(static_cast<ActorNode&>(child));
        }
        else
            child.accept(_cv);
    }
}

void InstancedCull::prefetchKeptInstances(const osg::Node& node, unsigned ahead) const
{
    // After the cull state's own members (ahead 4, ActorNode::prefetchCullAhead()): its kept instances' lines, then
    // what they hold, read only while no other thread holds the state.
    if (typeid(node) != typeid(ActorNode)) return;
    ActorCullState& state = *static_cast<const ActorNode&>(node)._cullState;
    const ActorCullState::InstancedVerdict& kept = state._instancedVerdict;
    if (ahead == 3)
    {
        prefetchForRead(&kept, sizeof(kept));
        return;
    }
    if (!state.tryAcquire()) return;
    if (kept.kept)
    {
        prefetchForRead(kept.runs.data(), kept.runs.size() * sizeof(kept.runs[0]));
        if (!keptInFrame(kept)) prefetchForRead(kept.matrices.data(), kept.matrices.size() * sizeof(float));
    }
    state.release();
}

bool InstancedCull::isPlainActor(const ActorNode& actor)
{
    return actor.getCullMode() == ActorNode::CULL_AS_ONE && !actor.getCullCallback() && !actor.getStateSet() &&
           actor.getReferenceFrame() == osg::Transform::RELATIVE_RF && isCullingActive(actor);
}

bool InstancedCull::isOutOfView(ActorNode& actor)
{
    if (!_outcome) return !_cv.validNodeMask(actor) || _cv.isCulled(actor);
    // The same tests, without the writes the visitor's test of the bound makes (its planes' mask, which only near
    // and far from primitives read, never culled in parallel).
    return isMasked(actor.getNodeMask()) ||
           (actor.isCullingActive() && ActorCullView::isCulled(_cv.getCurrentCullingSet(), actor.getBound()));
}

void InstancedCull::tally(ActorOutcome::Kind kind)
{
    if (_outcome)
    {
        _outcome->kind = kind;
        return;
    }
    InstancedCullState::Statistics& statistics = _state._statistics;
    switch (kind)
    {
    case ActorOutcome::OUT_OF_VIEW: ++statistics.actorsOutOfView; break;
    case ActorOutcome::ORDINARY: ++statistics.actorsOrdinary; break;
    case ActorOutcome::INSTANCED: ++statistics.actorsInstanced; break;
    case ActorOutcome::KEPT: ++statistics.actorsKept; break; // counted instanced already
    default: break;
    }
}

void InstancedCull::cullChild(ActorNode& actor)
{
    // The actor's own cull state (one cull at a time: another thread may be culling the actor for another camera)
    // gives the plan its cull as one keeps: its joints, geodes and drawables in the visitor's order.
    ActorCullState& actorState = *actor._cullState;
    const bool plainActor = isPlainActor(actor);
    if (plainActor && actorState.tryAcquire())
    {
        // What the visitor does on its way into the actor, first: its mask, then its bound in the group's frame. An
        // actor out of view costs that test alone, not its plan's check (a cache line per joint).
        if (isOutOfView(actor))
        {
            tally(ActorOutcome::OUT_OF_VIEW);
            actorState.release();
            return;
        }
        ActorCullState::InstancedVerdict& kept = actorState._instancedVerdict;
        const ActorCullState::Versions versions =
            ActorCullState::versionsOf(actor._cullPlanVersion, actor._poseVersion, actor._boundVersion);
        // The kept instances are asked for where they may do, so that their fetches overlap the plan's check (the
        // joints' matrices, where they are composed, were asked for ahead with the nodes the check reads).
        const bool replayable = mayReplay(kept, versions);
        if (replayable)
        {
            prefetchForRead(kept.runs.data(), kept.runs.size() * sizeof(kept.runs[0]));
            if (!keptInFrame(kept)) prefetchForRead(kept.matrices.data(), kept.matrices.size() * sizeof(float));
        }
        const ActorCullPlan& plan = actorState.currentPlan(actor, versions.plan, !replayable);
        // The verdict the actor kept from this group's last cull, if made for the same plan; looked up otherwise
        // (on the cull thread: the lookup may make verdicts and batches).
        const bool verdictKept = kept.serial == _state._serial && kept.plan == &plan;
        const InstancedCullState::PlanVerdict* verdict = nullptr;
        if (verdictKept)
            verdict = instanceableNow(*static_cast<const InstancedCullState::PlanVerdict*>(kept.verdict));
        else if (_mayDecideShared)
            verdict = instanceableVerdict(plan, kept);
        else
            _deferred = true;
        if (verdict && canInstanceSkins(actor, *verdict))
        {
            tally(ActorOutcome::INSTANCED);
            cullActor(actor, *verdict, kept, versions);
            if (!_outcome) actorState.release(); // the parallel cull's last pass gives it back
            return;
        }
        actorState.release();
        if (_deferred) return;
    }
    else if (plainActor && !_mayDecideShared)
    {
        // Held (another camera's cull): looked at again on the cull thread, as the serial cull would.
        _deferred = true;
        return;
    }
    tally(ActorOutcome::ORDINARY);
    if (!_outcome) actor.accept(_cv); // the parallel cull's traversal in child order does it
}

const InstancedCullState::PlanVerdict* InstancedCull::instanceableVerdict(const ActorCullPlan& plan,
                                                                         ActorCullState::InstancedVerdict& kept)
{
    auto found = _state._verdicts.find(&plan);
    if (found == _state._verdicts.end())
    {
        InstancedCullState::PlanVerdict verdict;
        verdict.plan = &plan;
        verdict.plain = true;
        const osg::StateSet* geodeState = nullptr;
        bool inGeode = false;
        auto note = [](std::vector<const osg::StateSet*>& states, const osg::StateSet* state) {
            if (state && std::find(states.begin(), states.end(), state) == states.end()) states.push_back(state);
        };
        for (const Step& step : plan.getSteps())
        {
            // A plain drawable of the plan is an osg::Geometry or osg::ShapeDrawable (ActorCullPlan::isPlainDrawable).
            const osg::Geometry* geometry =
                step.kind == ActorCullPlan::DRAWABLE ? static_cast<const osg::Geometry*>(step.node->asDrawable()) : nullptr;
            SkinnedMesh* mesh = InstancedSkin::meshOfStep(step);
            // A node the visitor traverses itself, but for one in a geode (a drawable of another class: the geode's
            // state set would be pushed for it).
            const bool subtree = step.kind == ActorCullPlan::ORDINARY && !mesh && !inGeode;
            const bool plain = step.kind == ActorCullPlan::END_JOINT || step.kind == ActorCullPlan::END_GEODE ||
                               (step.kind == ActorCullPlan::JOINT && !step.stateSet) ||
                               step.kind == ActorCullPlan::GEODE || (geometry && InstancedDraw::canDraw(*geometry)) ||
                               mesh || subtree;
            verdict.plain = verdict.plain && plain;
            if (step.kind == ActorCullPlan::GEODE) inGeode = true;
            if (step.kind == ActorCullPlan::END_GEODE) inGeode = false;
            if (verdict.plain && subtree)
            {
                noteSubtree(verdict, static_cast<unsigned>(&step - plan.getSteps().data()));
                continue;
            }
            // The state sets a drawable is drawn with: its geode's and its own, checked as its kind is drawn.
            if (geometry) note(verdict.states, geodeState), note(verdict.states, step.stateSet);
            if (mesh) note(verdict.skinStates, geodeState); // the mesh's own is checked at each cull
            if (step.kind == ActorCullPlan::GEODE) geodeState = step.stateSet;
            if (step.kind == ActorCullPlan::END_GEODE) geodeState = nullptr;
            unsigned batch = 0;
            if (verdict.plain && geometry) batch = batchOf(geodeState, geometry, nullptr);
            if (verdict.plain && mesh) verdict.skinBatches.push_back(batch = batchOf(geodeState, nullptr, mesh));
            verdict.batchOfStep.push_back(batch);
        }
        if (verdict.compiled()) compilePlainInstances(verdict);
        found = _state._verdicts.emplace(&plan, std::move(verdict)).first;
    }
    // The map's entries stay where they are until erased, which the plan held here prevents.
    kept.serial = _state._serial;
    kept.plan = &plan;
    kept.verdict = &found->second;
    kept.kept = false; // instances of another group's cull, or of another plan
    return instanceableNow(found->second);
}

const InstancedCullState::PlanVerdict* InstancedCull::instanceableNow(const InstancedCullState::PlanVerdict& verdict)
{
    if (!verdict.plain) return nullptr;
    for (const osg::StateSet* state : verdict.states)
        if (!isInstanceableNow(state)) return nullptr;
    for (const osg::StateSet* state : verdict.skinStates)
        if (!isSkinInstanceableNow(state)) return nullptr;
    return &verdict;
}

bool InstancedCull::canInstanceSkins(ActorNode& actor, const InstancedCullState::PlanVerdict& verdict)
{
    _scratch->skinInstances.clear();
    if (verdict.skinBatches.empty()) return true;
    for (unsigned b : verdict.skinBatches)
    {
        InstancedCullState::Batch& batch = _state._batches[b];
        if (!batch.texelsKnown && !_mayDecideShared)
        {
            _deferred = true; // found before the parallel cull's first pass: a batch made since
            return false;
        }
        if (!batch.texelsKnown)
        {
            batch.texels = InstancedSkin::texelsPerInstance(*batch.mesh);
            batch.texelsKnown = true;
        }
        // The mesh's cull callback and state set, which the plan does not watch (the mesh is not a node it plans).
        SkinnedMesh& mesh = *batch.mesh;
        if (!batch.texels || mesh.getCullCallback() || !isSkinInstanceableNow(mesh.getStateSet())) return false;
        if (batch.texels > _texelLimit && !_state._oversizeNoticed && !_mayDecideShared)
        {
            _deferred = true; // the notice given on the cull thread
            return false;
        }
        if (batch.texels > _texelLimit)
        {
            // One instance is more than a texture buffer holds: its actors are drawn ordinarily.
            if (!_state._oversizeNoticed)
                OSG_NOTICE << "osgActor::InstancedActorGroup: an instance of skinned mesh \"" << mesh.getName()
                           << "\" needs " << batch.texels << " texels, more than a texture buffer holds ("
                           << _texelLimit << "): the actors wearing it are drawn one at a time" << std::endl;
            _state._oversizeNoticed = true;
            return false;
        }
        const SkinnedMeshInstance* instance = InstancedSkin::instanceOf(mesh, actor);
        if (!instance) return false;
        _scratch->skinInstances.push_back(instance);
    }
    return true;
}

unsigned InstancedCull::batchOf(const osg::StateSet* geodeState, const osg::Geometry* drawable, SkinnedMesh* mesh)
{
    const InstancedCullState::BatchKey key{geodeState, drawable ? static_cast<const osg::Drawable*>(drawable) : mesh};
    auto found = _state._batchOfKey.find(key);
    if (found != _state._batchOfKey.end()) return found->second;
    const unsigned batch = static_cast<unsigned>(_state._batches.size());
    InstancedCullState::Batch made;
    made.geodeState = geodeState;
    made.drawable = drawable;
    made.mesh = mesh;
    // A skinned mesh's texels per instance are found when an actor first needs them (canInstanceSkins()).
    made.texels = mesh ? 0u : 4u;
    made.texelsKnown = !mesh;
    _state._batches.push_back(std::move(made));
    _state._batchOfKey.emplace(key, batch);
    return batch;
}

bool InstancedCull::isInstanceableNow(const osg::StateSet* state)
{
    for (const auto& known : _scratch->stateVerdicts)
        if (known.first == state) return known.second;
    const bool verdict = isInstanceableState(state);
    _scratch->stateVerdicts.emplace_back(state, verdict);
    return verdict;
}

bool InstancedCull::isSkinInstanceableNow(const osg::StateSet* state)
{
    for (const auto& known : _scratch->skinStateVerdicts)
        if (known.first == state) return known.second;
    const bool verdict = InstancedSkin::isInstanceableState(state);
    _scratch->skinStateVerdicts.emplace_back(state, verdict);
    return verdict;
}

bool InstancedCull::isSmallFeature(const osg::BoundingSphere& bound, unsigned frame)
{
    return _scratch->pixelSizeVectors.isSmallFeature(bound, frame, *_cv.getViewport(), *_cv.getProjectionMatrix(),
                                                     _scratch->modelViews[frame], _smallFeaturePixelSize);
}

const osg::Vec4& InstancedCull::actorPixelSizeVector()
{
    return _scratch->pixelSizeVectors.vector(0, *_cv.getViewport(), *_cv.getProjectionMatrix(),
                                             _scratch->modelViews[0]);
}

void InstancedCull::cullActor(ActorNode& actor, const InstancedCullState::PlanVerdict& verdict,
                              ActorCullState::InstancedVerdict& kept, const ActorCullState::Versions& versions)
{
    const ActorCullPlan& plan = *verdict.plan;
    const std::vector<ActorCullPlan::Joint>& joints = plan.getJoints();
    const std::size_t numFrames = joints.size() + 1;
    std::vector<osg::Matrixd>& modelViews = _scratch->modelViews;
    modelViews.resize(numFrames);
    // The actor's frame, as the visitor's pushModelViewMatrix() makes it (MatrixTransform: actor_m * group's), or
    // the one kept where neither changed.
    const bool entryKept = keptEntry(actor, kept, versions);
    if (entryKept)
        modelViews[0] = kept.actorModelView;
    else
        composeModelView(actor.getMatrix().ptr(), _cv.getModelViewMatrix()->ptr(), modelViews[0].ptr());
    if (actor.getUpdatePolicy().onlyWhenSeen)
    {
        // Noted on the cull thread, in child order, in the parallel cull.
        if (!_outcome)
            actor.noteSeenInFrame(_cv, modelViews[0]);
        else
        {
            _outcome->seen = static_cast<unsigned>(_scratch->seenModelViews.size());
            _scratch->seenModelViews.push_back(modelViews[0]);
        }
    }
    // An actor with skinned meshes is culled anew at every cull: its palettes are kept by its meshes, not here. One
    // with subtrees keeps their frames with its instances, and the visitor traverses them again.
    if (verdict.skinBatches.empty())
    {
        if (replayKept(kept, versions, entryKept))
        {
            tally(ActorOutcome::KEPT);
            if (_computeNearFar && _outcome) _outcome->depths = kept.depths;
            else if (_computeNearFar) kept.depths.mergeInto(_cv);
            const std::size_t firstVisit = _scratch->subtreeVisits.size();
            for (const std::pair<unsigned, osg::Matrixd>& visit : kept.subtreeVisits)
                _scratch->subtreeVisits.push_back({&verdict, visit.first, visit.second});
            handOverSubtrees(actor, firstVisit);
            return;
        }
    }
    else
        kept.kept = false;
    _scratch->pixelSizeVectors.reset(numFrames);
    // Each joint's frame, parents first, as ActorCull composes them.
    plan.composeModelViews(modelViews.data());
    _actorDepths = DepthRange();
    _skinDepths = DepthRange();
    // With near and far computed the frustum is tested in the actor's frame (the top steps' spheres, and the boxes
    // below one not wholly inside): its planes moved there once, for the compiled list and the steps alike.
    if (_computeNearFar && _frustumCulling) moveFrustumIntoActorFrame();
    const std::size_t firstVisit = _scratch->subtreeVisits.size();
    if (addPlainInstances(verdict))
    {
        // Nothing tested below its top joints: every subtree is reached.
        for (unsigned k = 0; k < verdict.subtrees.size(); ++k) visitSubtree(verdict, k);
    }
    else
        cullSteps(verdict);
    handOverSubtrees(actor, firstVisit);
    if (_computeNearFar)
    {
        if (_outcome)
        {
            _outcome->skinDepths = _skinDepths;
            _outcome->depths = _actorDepths;
        }
        else
            _actorDepths.mergeInto(_cv);
        if (_recording) _recording->depths = _actorDepths;
    }
    _recording = nullptr;
}

void InstancedCull::cullSteps(const InstancedCullState::PlanVerdict& verdict)
{
    // The plan's steps as ActorCull::cull() follows them: a joint or geode masked out or too small in the frame it
    // is in is skipped with its subtree.
    const ActorCullPlan& plan = *verdict.plan;
    const std::vector<ActorCullPlan::Joint>& joints = plan.getJoints();
    const std::vector<Step>& steps = plan.getSteps();
    unsigned skin = 0;           // the next of the actor's skinned meshes
    unsigned subtree = 0;        // the next of its subtrees
    std::size_t provenUntil = 0; // the steps before it are below a joint with no small feature below it
    // With near and far computed each drawable's box is tested against the frustum (addDrawable()), but below a top
    // step whose sphere lies wholly inside every plane, as ActorCullState::prepareDrawablesByBounds() does: the
    // visitor tests that sphere so (the planes moved into the actor's frame) and then tests no plane below it.
    const bool boxesTested = _computeNearFar && _frustumCulling; // the planes moved by cullActor()
    std::size_t topEnd = 0; // the end of the top step the steps are below
    bool insideTop = false; // its sphere wholly inside the frustum
    for (std::size_t i = 0; i < steps.size();)
    {
        const Step& step = steps[i];
        if (boxesTested && i >= topEnd)
        {
            topEnd = step.end ? step.end : i + 1;
            insideTop = isInsideTop(step);
        }
        switch (step.kind)
        {
        case ActorCullPlan::JOINT:
        case ActorCullPlan::GEODE:
        {
            const unsigned frame = step.kind == ActorCullPlan::JOINT ? unsigned(joints[step.joint].parent + 1)
                                                                      : unsigned(step.joint + 1);
            const bool tested = _smallFeatureCulling && i >= provenUntil;
            if (isMasked(step.mask) || (tested && step.cullingActive && isSmallFeature(step.node->getBound(), frame)))
            {
                i = step.end;
                continue;
            }
            if (tested && plan.provesNoSmallFeatureBelow(step, actorPixelSizeVector(), _smallFeaturePixelSize))
                provenUntil = step.end;
            break;
        }
        case ActorCullPlan::DRAWABLE:
            if (!isMasked(step.mask)) addDrawable(step, verdict.batchOfStep[i], insideTop);
            break;
        case ActorCullPlan::ORDINARY:
            // A subtree for the visitor (its node's mask tested by its accept()), or a skinned mesh: its mask now, as
            // its accept() tests it (the plan does not watch it).
            if (verdict.batchOfStep[i] == InstancedCullState::PlanVerdict::kSubtree)
                visitSubtree(verdict, subtree++);
            else
            {
                if (!isMasked(step.node->getNodeMask()))
                    addSkinned(*_scratch->skinInstances[skin], verdict.batchOfStep[i]);
                ++skin;
            }
            break;
        default: break; // the ends
        }
        ++i;
    }
}

void InstancedCull::compilePlainInstances(InstancedCullState::PlanVerdict& verdict)
{
    const std::vector<Step>& steps = verdict.plan->getSteps();
    for (unsigned i : verdict.plan->getDrawableSteps())
    {
        const Step& step = steps[i];
        const unsigned batch = verdict.batchOfStep[i];
        verdict.plainInstances.push_back({static_cast<unsigned>(step.joint + 1), batch, step.node->asDrawable()});
        auto counted = std::find_if(verdict.instancesPerBatch.begin(), verdict.instancesPerBatch.end(),
                                    [batch](const std::pair<unsigned, unsigned>& entry) { return entry.first == batch; });
        if (counted == verdict.instancesPerBatch.end()) verdict.instancesPerBatch.emplace_back(batch, 1u);
        else ++counted->second;
    }
}

void InstancedCull::moveFrustumIntoActorFrame()
{
    _scratch->actorFramePlanes = _cv.getProjectionCullingStack().back().getFrustum().getPlaneList();
    for (osg::Plane& plane : _scratch->actorFramePlanes) plane.transformProvidingInverse(_scratch->modelViews[0]);
}

bool InstancedCull::addPlainInstances(const InstancedCullState::PlanVerdict& verdict)
{
    // What cullSteps() would test: a node a mask rules out, a top joint that is a small feature, a subtree below a
    // top joint with no proof that none of its spheres is one, and, with near and far computed, each drawable's box
    // against the frustum below a top step whose sphere is not wholly inside it (a visible crowd's actors are
    // mostly wholly inside: their near and far come from the list below). The instances being recorded for an idle
    // actor go through the steps too.
    if (!verdict.compiled() || _recording) return false;
    if (!verdict.plan->needsNoTestBelowTopJoints(
            _traversalMask, _maskOverride, _smallFeatureCulling,
            _smallFeatureCulling ? actorPixelSizeVector() : osg::Vec4(), _smallFeaturePixelSize,
            [this](const osg::BoundingSphere& bound) { return isSmallFeature(bound, 0); }))
        return false;
    if (_computeNearFar && _frustumCulling)
    {
        // The planes in the actor's frame (cullActor()).
        const std::vector<Step>& steps = verdict.plan->getSteps();
        for (unsigned i : verdict.plan->getTopSteps())
            if (!isInsideTop(steps[i])) return false;
    }
    // Then what addDrawable() does with a drawable it does not test against the frustum (isDrawn()), in step order,
    // so each batch's instances are in the order the steps would give them, and the actor's near and far gathered
    // from the same boxes in the same order.
    DepthRange* depths = _computeNearFar ? &_actorDepths : nullptr;
    if (_outcome)
    {
        // The parallel cull: into the thread's scratch (its last pass puts them in their regions, or where their
        // batches move).
        InstancedCullState::InstanceData& data = _scratch->data;
        const std::size_t start = data.size();
        float* const first = data.extend(16 * verdict.plainInstances.size());
        const float* const end = appendPlainInstances(verdict, _scratch->modelViews.data(), first, _scratch->runs,
                                                      _outcome->firstRun, depths);
        data.shrink(start + std::size_t(end - first));
        _wroteTexels = true;
        _outcome->compiled = true;
        return true;
    }
    // Every instance in its batch's region (nextInstance() moves a batch that outgrows it: the steps do that).
    std::vector<InstancedCullState::Batch>& batches = _state._batches;
    for (const std::pair<unsigned, unsigned>& counted : verdict.instancesPerBatch)
        if (!roomInRegion(batches[counted.first], counted.second)) return false;
    writePlainInstances(verdict, _scratch->modelViews.data(), batches.data(), _state._texels, depths);
    _wroteTexels = true;
    ++_state._statistics.actorsCompiled;
    return true;
}

// Built for x86-64-v3 too (the conversions to float four at a time): every instance of a moving crowd goes through
// it. The depths' and near and far's products and sums are not contracted (this file's options), so each clone gives
// the bits of the steps' addDrawable().
OSGACTOR_HOT_PATH void InstancedCull::writePlainInstances(const InstancedCullState::PlanVerdict& verdict,
                                                          const osg::Matrixd* modelViews,
                                                          InstancedCullState::Batch* batches, float* texels,
                                                          DepthRange* depths)
{
    // The loop made twice, with near and far and without, so that neither asks per instance.
    if (depths) writeEachPlainInstance<true>(verdict, modelViews, batches, texels, depths);
    else writeEachPlainInstance<false>(verdict, modelViews, batches, texels, nullptr);
}

template <bool WithDepths>
inline void InstancedCull::writeEachPlainInstance(const InstancedCullState::PlanVerdict& verdict,
                                                  const osg::Matrixd* modelViews, InstancedCullState::Batch* batches,
                                                  float* texels, DepthRange* depths)
{
    for (const InstancedCullState::PlanVerdict::PlainInstance& instance : verdict.plainInstances)
    {
        const osg::Matrixd& modelView = modelViews[instance.frame];
        if (!isDrawn(DrawableBox::of(*instance.drawable), modelView, WithDepths ? depths : nullptr)) continue;
        // Where the batch's next instance goes: its region has room for all of them (addPlainInstances() checked).
        InstancedCullState::Batch& batch = batches[instance.batch];
        writeInstanceMatrix(modelView, texels + 4 * (std::size_t(batch.base) + std::size_t(batch.texels) * batch.count));
        ++batch.count;
    }
}

// Built for x86-64-v3 too, as writePlainInstances(): the parallel cull's every instance of a moving crowd.
OSGACTOR_HOT_PATH float* InstancedCull::appendPlainInstances(const InstancedCullState::PlanVerdict& verdict,
                                                             const osg::Matrixd* modelViews, float* out,
                                                             std::vector<InstancedCullState::ActorRun>& runs,
                                                             std::size_t firstRun, DepthRange* depths)
{
    return depths ? appendEachPlainInstance<true>(verdict, modelViews, out, runs, firstRun, depths)
                  : appendEachPlainInstance<false>(verdict, modelViews, out, runs, firstRun, nullptr);
}

template <bool WithDepths>
inline float* InstancedCull::appendEachPlainInstance(const InstancedCullState::PlanVerdict& verdict,
                                                     const osg::Matrixd* modelViews, float* out,
                                                     std::vector<InstancedCullState::ActorRun>& runs,
                                                     std::size_t firstRun, DepthRange* depths)
{
    for (const InstancedCullState::PlanVerdict::PlainInstance& instance : verdict.plainInstances)
    {
        const osg::Matrixd& modelView = modelViews[instance.frame];
        if (!isDrawn(DrawableBox::of(*instance.drawable), modelView, WithDepths ? depths : nullptr)) continue;
        writeInstanceMatrix(modelView, out);
        out += 16;
        countIntoRuns(runs, firstRun, instance.batch);
    }
    return out;
}

bool InstancedCull::keptEntry(const ActorNode& actor, const ActorCullState::InstancedVerdict& kept,
                              const ActorCullState::Versions& versions) const
{
    // The actor's bound has not been recomputed since the kept matrix was composed (the counters count its
    // recomputations, and kept instances are dropped when they change), so neither has its matrix, whose every setter
    // dirties it, unless a callback computes its bound instead; the group's was entered with the same matrix.
    return mayReplay(kept, versions) && kept.entry == _state._entry && !actor.getComputeBoundingSphereCallback();
}

bool InstancedCull::replayKept(ActorCullState::InstancedVerdict& kept, const ActorCullState::Versions& versions,
                               bool entryKept)
{
    // With near and far computed (from bounding volumes), the kept range is merged again.
    const bool unchanged = kept.versions == versions;
    kept.versions = versions;
    if (!unchanged)
    {
        kept.kept = false;
        return false;
    }
    const osg::Matrixd& actorModelView = _scratch->modelViews[0];
    if (mayReplay(kept, versions) && (entryKept || sameBits(kept.actorModelView, actorModelView)))
    {
        kept.entry = _state._entry;
        if (!_outcome)
            addKeptRuns(kept);
        else
            // The parallel cull: added by its last pass, where the runs go among their batches' instances.
            for (const ActorCullState::InstancedVerdict::Run& run : kept.runs)
                _scratch->runs.push_back({run.batch, run.count, 0u});
        return true;
    }
    // Unchanged since the cull before, but not kept, or kept for another view: culled now, and kept.
    kept.kept = true;
    kept.view = _state._view;
    kept.entry = _state._entry;
    kept.actorModelView = actorModelView;
    kept.runs.clear();
    kept.matrices.clear();
    kept.subtreeVisits.clear();
    kept.placedSince = 1; // added nowhere yet
    kept.placedUntil = 0;
    _recording = &kept;
    return false;
}

void InstancedCull::addKeptRuns(ActorCullState::InstancedVerdict& kept)
{
    // Run by run of instances of one batch (an actor's parts of one drawable follow one another): none written where
    // the run is found where this frame's last cull added it; one copy where the batch's region has room for it; one
    // instance at a time where it may not.
    const bool inFrame = keptInFrame(kept);
    bool samePlaces = true;
    const float* matrix = kept.matrices.data();
    for (ActorCullState::InstancedVerdict::Run& run : kept.runs)
    {
        InstancedCullState::Batch& into = _state._batches[run.batch];
        if (float* out = roomInRegion(into, run.count))
        {
            const unsigned at = into.base + into.count * into.texels;
            if (!inFrame || run.at != at)
            {
                samePlaces = samePlaces && run.at == at;
                std::memcpy(out, matrix, 16 * sizeof(float) * run.count);
                run.at = at;
                _wroteTexels = true;
            }
            into.count += run.count;
            matrix += 16 * std::size_t(run.count);
        }
        else
        {
            for (unsigned k = 0; k < run.count; ++k, matrix += 16)
                std::memcpy(nextInstance(run.batch), matrix, 16 * sizeof(float));
            samePlaces = samePlaces && run.at == ~0u;
            run.at = ~0u;
        }
    }
    notePlaced(kept, samePlaces);
}

void InstancedCull::addDrawable(const Step& step, unsigned batch, bool insideTop)
{
    const osg::Geometry& drawable = *static_cast<const osg::Geometry*>(step.node->asDrawable());
    const osg::Matrixd& modelView = _scratch->modelViews[static_cast<std::size_t>(step.joint + 1)];
    // As ActorCull::addDrawable(): near and far from what is drawn, the box against the frustum before; from
    // bounding volumes, gathered for the actor (a drawable wholly behind the eye dropped, as the visitor drops it).
    const osg::BoundingBox& box = drawable.getBoundingBox();
    if (_computeNearFar && box.valid() && _frustumCulling && step.cullingActive && !insideTop &&
        isOutsideFrustum(box, modelView, _cv.getProjectionCullingStack().back().getFrustum()))
        return;
    if (!isDrawn(box, modelView, _computeNearFar ? &_actorDepths : nullptr)) return; // the visitor drops it too
    float* out = nextInstance(batch);
    writeInstanceMatrix(modelView, out);
    if (_recording)
    {
        std::vector<ActorCullState::InstancedVerdict::Run>& runs = _recording->runs;
        if (!runs.empty() && runs.back().batch == batch)
            ++runs.back().count;
        else
            runs.push_back({batch, 1u, ~0u});
        _recording->matrices.insert(_recording->matrices.end(), out, out + 16);
    }
}

float* InstancedCull::nextInstance(unsigned batch)
{
    if (_outcome) return appendInstance(batch);
    InstancedCullState::Batch& into = _state._batches[batch];
    const std::size_t floats = 4 * std::size_t(into.texels);
    float* out = roomInRegion(into, 1);
    if (!out)
    {
        into.overflow.resize(into.overflow.size() + floats);
        out = into.overflow.data() + into.overflow.size() - floats;
        _overflowed = true;
    }
    ++into.count;
    _wroteTexels = true;
    return out;
}

// Out of line: the serial cull's nextInstance(), which every instance of a moving crowd goes through, stays as small.
#if defined(__GNUC__)
__attribute__((noinline))
#endif
float* InstancedCull::appendInstance(unsigned batch)
{
    addToRuns(batch);
    _wroteTexels = true;
    return _scratch->data.extend(4 * std::size_t(_state._batches[batch].texels));
}

void InstancedCull::addToRuns(unsigned batch) { countIntoRuns(_scratch->runs, _outcome->firstRun, batch); }

void InstancedCull::addSkinned(const SkinnedMeshInstance& instance, unsigned b)
{
    InstancedCullState::Batch& batch = _state._batches[b];
    SkinnedMesh& mesh = *batch.mesh;
    // As SkinnedMesh's cull: drawn from the actor's first update on, its bound (model space, the actor's frame)
    // against the view.
    if (!InstancedSkin::hasMatrices(instance)) return;
    const osg::Matrixd& modelView = _scratch->modelViews[0];
    const osg::Polytope& frustum = _cv.getProjectionCullingStack().back().getFrustum();
    if (_frustumCulling && mesh.isCullingActive() && isOutsideFrustum(InstancedSkin::boundOf(instance), modelView, frustum))
        return;
    // Then what the visitor does with the bind-pose geometry it is handed, whose box is the union of the actors'
    // bounds: the box against the frustum, near and far from it, its depth.
    const osg::Geometry& geometry = *InstancedSkin::geometryOf(mesh, _profile);
    const osg::BoundingBox& box = geometry.getBoundingBox();
    if (_frustumCulling && geometry.isCullingActive() && isOutsideFrustum(box, modelView, frustum)) return;
    // In the parallel cull (near and far from bounding volumes, the visitor's own arithmetic for them), gathered for
    // the cull thread to merge where the actor comes.
    if (_computeNearFar && box.valid() &&
        !(_outcome ? _skinDepths.addBox(box, modelView) : _cv.updateCalculatedNearFar(modelView, geometry, true)))
        return;
    if (hasNoDepth(box, modelView)) return;
    InstancedSkin::writeInstance(mesh, instance, modelView, nextInstance(b));
}

InstancedFrame* InstancedCull::acquireFrame(unsigned textureUnit)
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _state._frames)
        if (frame->isFree())
        {
            frame->taken();
            return frame.get();
        }
    _state._frames.push_back(new InstancedFrame(_programState, textureUnit, _state._limit.get()));
    _state._frames.back()->taken();
    return _state._frames.back().get();
}

void InstancedCull::placeBatches(unsigned textureUnit)
{
    unsigned texels = 0;
    for (InstancedCullState::Batch& batch : _state._batches)
    {
        batch.base = texels;
        batch.capacity = batch.count * batch.texels;
        batch.count = 0;
        batch.overflow.clear();
        texels += batch.capacity;
    }
    _state._frame = texels ? acquireFrame(textureUnit) : nullptr;
    _state._texels = texels ? _state._frame->reserveTexels(texels) : nullptr;
}

void InstancedCull::gatherOverflow(unsigned textureUnit)
{
    // Each batch that overflowed is moved whole past every region; the next cull's regions are this cull's data.
    unsigned end = 0, moved = 0;
    for (const InstancedCullState::Batch& batch : _state._batches)
    {
        end += batch.capacity;
        if (!batch.overflow.empty()) moved += batch.count * batch.texels;
    }
    if (!_state._frame) _state._frame = acquireFrame(textureUnit);
    float* texels = _state._frame->growTexels(end + moved);
    // The batches the draws read moved: no instance is taken for in place at the next cull (their first texels
    // are kept, but the next cull need not rely on it).
    _state._frame->moved();
    _wroteTexels = true;
    for (InstancedCullState::Batch& batch : _state._batches)
    {
        if (batch.overflow.empty()) continue;
        // The instances that fit the region (as many as its size in this cull's instances), then the overflow.
        const std::size_t inRegion = 4 * std::size_t(batch.capacity / batch.texels * batch.texels);
        float* out = std::copy_n(texels + 4 * std::size_t(batch.base), inRegion, texels + 4 * std::size_t(end));
        std::copy(batch.overflow.begin(), batch.overflow.end(), out);
        batch.base = end;
        end += batch.count * batch.texels;
    }
}

void InstancedCull::emitBatches()
{
    if (!_state._frame) return;
    InstancedFrame& frame = *_state._frame;
    _state._frame = nullptr;
    _state._texels = nullptr;
    // The texels the draws read: up to the end of the last batch with instances.
    unsigned texels = 0;
    for (const InstancedCullState::Batch& batch : _state._batches)
        if (batch.count) texels = std::max(texels, batch.base + batch.count * batch.texels);
    if (texels == 0) return;
    if (texels > _texelLimit)
    {
        emitSplit(frame, texels);
        return;
    }
    unsigned drawIndex = 0;
    for (const InstancedCullState::Batch& batch : _state._batches)
        if (batch.count) emitDraw(batch, frame, drawIndex++, 0, batch.base, batch.count);
    if (_wroteTexels) frame.dirtyAll();
    _state._statistics.buffers = 1;
}

void InstancedCull::emitSplit(InstancedFrame& frame, unsigned texels)
{
    // Told once, when the limit is a context's or the cap; a first frame split under OpenGL's minimum, before any
    // draw asked its context, is the usual start of a large crowd, not worth a notice.
    if (!_state._splitNoticed && _state._limit->isKnown())
    {
        OSG_NOTICE << "osgActor::InstancedActorGroup: a frame's instances need " << texels
                   << " texels, more than a texture buffer holds (" << _texelLimit
                   << "): drawn from several buffers, a batch's instances over several draws" << std::endl;
        _state._splitNoticed = true;
    }
    // The batches' instances drawn where the cull wrote them, from windows of buffer 0 within the limit (buffers 1,
    // 2, ...), in batch order: a run of a batch's instances from the window that holds it whole, a new window from
    // the first instance the last one does not hold. Every instance fits one window (canInstanceSkins()). Where the
    // batches lie one after the other (every frame but one whose crowd changed) the windows follow one another, the
    // runs and their bases those of the same instances packed into buffers of the limit.
    unsigned buffer = 0, drawIndex = 0;
    unsigned windowStart = 0;
    for (const InstancedCullState::Batch& batch : _state._batches)
    {
        if (batch.texels > _texelLimit) continue; // no instance: canInstanceSkins() drew its actors ordinarily
        for (unsigned first = 0; first < batch.count;)
        {
            const unsigned at = batch.base + first * batch.texels;
            if (buffer == 0 || at < windowStart || at - windowStart > _texelLimit - batch.texels)
            {
                // The next window, from this instance: as large as what is left or the limit.
                windowStart = at;
                frame.setWindow(++buffer, windowStart, std::min(texels - windowStart, _texelLimit));
            }
            const unsigned run = std::min(batch.count - first, (_texelLimit - (at - windowStart)) / batch.texels);
            emitDraw(batch, frame, drawIndex++, buffer, at - windowStart, run);
            first += run;
        }
    }
    // Every buffer, those not drawn from this frame too: what they show of buffer 0 changed.
    if (_wroteTexels) frame.dirtyAll();
    _state._statistics.buffers = buffer;
}

void InstancedCull::emitDraw(const InstancedCullState::Batch& batch, InstancedFrame& frame, unsigned drawIndex,
                             unsigned buffer, unsigned base, unsigned count)
{
    InstancedDraw& draw = *frame.draw(drawIndex);
    const osg::Geometry* geometry = batch.mesh ? InstancedSkin::geometryOf(*batch.mesh, _profile) : batch.drawable;
    draw.set(geometry, static_cast<int>(base), count, static_cast<int>(batch.texels));
    draw.setBindScale(batch.mesh ? InstancedSkin::bindScaleOf(*batch.mesh) : 1.0f);
    // A dynamic drawable makes osgViewer's next update wait until it is drawn: so does its instanced draw.
    const osg::Drawable& drawn = batch.mesh ? static_cast<const osg::Drawable&>(*batch.mesh) : *batch.drawable;
    draw.setDataVariance(drawn.getDataVariance() == osg::Object::DYNAMIC ? osg::Object::DYNAMIC : osg::Object::STATIC);
    emitLeaf(batch, draw, frame, buffer);
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

void InstancedCull::emitLeaf(const InstancedCullState::Batch& batch, InstancedDraw& draw, InstancedFrame& frame,
                             unsigned buffer)
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
        SkinningProgramKey key = InstancedSkin::programKey(*batch.mesh, _profile);
        applyDrawState(_cv.getCurrentStateGraph(), key);
        push(getSkinningProgramStateSet(key));
        push(frame.getBufferStateSet(buffer));
    }
    else
    {
        push(batch.drawable->getStateSet());
        push(frame.getStateSet(buffer));
    }
    // The leaf's matrix is the group's: the program takes each instance's from the buffer, the projection from the
    // leaf.
    _cv.addDrawableAndDepth(&draw, _cv.getModelViewMatrix(), 0.0f);
    for (unsigned i = 0; i < pushed; ++i) _cv.popStateSet();
}

} // namespace detail
} // namespace osgActor
