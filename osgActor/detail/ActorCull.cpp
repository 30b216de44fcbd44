#include <osgActor/detail/ActorCull.h>

#include <osgActor/ActorNode>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/Prefetch.h>

#include <osg/Math>

#include <cstring>
#include <typeinfo>

namespace osgActor {
namespace detail {

// --- ActorCullState ---

ActorCullView::ActorCullView(osgUtil::CullVisitor& cv)
    : projection(*cv.getProjectionMatrix()), viewport(cv.getViewport()),
      frustum(&cv.getProjectionCullingStack().back().getFrustum()), traversalMask(cv.getTraversalMask()),
      nodeMaskOverride(cv.getNodeMaskOverride()), cullingMask(cv.getCurrentCullingSet().getCullingMask()),
      cullingMode(cv.getCullingMode()),
      smallFeaturePixelSize(cv.getCurrentCullingSet().getSmallFeatureCullingPixelSize()),
      computeNearFarMode(cv.getComputeNearFarMode()), binNumber(cv.getCurrentRenderBin()->getBinNum()),
      binSortMode(cv.getCurrentRenderBin()->getSortMode())
{
}

bool ActorCullView::isCulled(const osg::CullingSet& set, const osg::BoundingSphere& bound)
{
    // osg::CullingSet::isCulled(const BoundingSphere&) and osg::Polytope::contains(), term for term, but for the
    // mask of planes left to test below, which contains() writes and nothing reads before the next test rewrites it.
    const osg::CullingSet::Mask mask = set.getCullingMask();
    if (mask & osg::CullingSet::VIEW_FRUSTUM_CULLING)
    {
        const osg::Polytope& frustum = set.getFrustum();
        const osg::Polytope::ClippingMask selected = frustum.getCurrentMask();
        osg::Polytope::ClippingMask selector = 0x1;
        for (const osg::Plane& plane : frustum.getPlaneList())
        {
            if ((selected & selector) && plane.intersect(bound) < 0) return true;
            selector <<= 1;
        }
    }
    if ((mask & osg::CullingSet::SMALL_FEATURE_CULLING) &&
        detail::isSmallFeature(bound, set.getPixelSizeVector(), set.getSmallFeatureCullingPixelSize()))
        return true;
    return false; // no occluders where an actor is culled as one (ActorCull::canCullAsOne())
}

ActorCullState::ActorCullState() : _holder(nullptr), _planVersion(0), _replayable(false)
{
    _busy.clear();
}

const ActorCullPlan& ActorCullState::currentPlan(osg::Group& actor, unsigned planVersion, bool composing)
{
    _composing = composing;
    const bool kept = _plan && _planVersion == planVersion;
    // Where no look-ahead asked for the joints (an ActorGroup's cull on its threads, an actor alone, one that was
    // idle), they are asked for now, so that the fetches of the check and of the matrices overlap.
    if (kept && composing && !_jointsAskedFor) _plan->prefetchCheckedNodes(true);
    _jointsAskedFor = false;
    if (!kept || !_plan->isCurrent())
    {
        _plan = new ActorCullPlan(actor); // made while the old one lives: never at its address
        _planVersion = planVersion;
        _replayable = false;
    }
    return *_plan;
}

void ActorCullState::prefetchAhead(AheadStage stage)
{
    if (stage == AHEAD_STATE)
    {
        // The members a replay reads, from the flag to the key's view.
        const char* const first = reinterpret_cast<const char*>(this);
        prefetchForRead(first, static_cast<std::size_t>(reinterpret_cast<const char*>(&_key.view + 1) - first));
        return;
    }
    // The plan may be replaced under a cull on another thread: read only while holding the state.
    if (!tryAcquire()) return;
    if (const ActorCullPlan* plan = _plan.get())
    {
        switch (stage)
        {
        case AHEAD_PLAN:
            prefetchForRead(plan, sizeof(ActorCullPlan));
            prefetchForRead(_calls.data(), _calls.size() * sizeof(Call));
            break;
        case AHEAD_PLAN_ARRAYS:
            plan->prefetchChecks();
            // What the kept calls' leaves count references to: the batch or drawable and the matrix.
            for (const Call& call : _calls)
                if (call.kind == Call::ADD_LEAF)
                {
                    prefetchLine<true>(call.object);
                    prefetchLine<true>(call.matrix);
                }
            break;
        case AHEAD_NODES:
            plan->prefetchCheckedNodes(_composing);
            _jointsAskedFor = _composing;
            break;
        default: break;
        }
    }
    release();
}

ActorCullState::View ActorCullState::viewOf(const ActorCullView& view)
{
    View key;
    key.projection = view.projection;
    key.cullingMode = view.cullingMode;
    // With near and far computed, the viewer clamps the camera's projection to them after each cull (SceneView does
    // it in place, CullVisitor::clampProjectionMatrix() rewriting the third column): that column changes from frame
    // to frame by a rounding. It enters no leaf while the near and far planes are not culled: the pixel-size vector
    // and the frustum's sides are made of the other columns.
    if ((key.cullingMode & (osg::CullSettings::NEAR_PLANE_CULLING | osg::CullSettings::FAR_PLANE_CULLING)) == 0)
        for (int row = 0; row < 4; ++row) key.projection(row, 2) = 0.0;
    if (view.viewport)
    {
        key.viewport[0] = view.viewport->x();
        key.viewport[1] = view.viewport->y();
        key.viewport[2] = view.viewport->width();
        key.viewport[3] = view.viewport->height();
    }
    key.traversalMask = view.traversalMask;
    key.nodeMaskOverride = view.nodeMaskOverride;
    key.cullingMask = view.cullingMask;
    key.smallFeaturePixelSize = view.smallFeaturePixelSize;
    key.computeNearFar = view.computeNearFarMode;
    key.binNumber = view.binNumber;
    key.binSortMode = view.binSortMode;
    return key;
}

ActorCullState::Key ActorCullState::keyOf(const ActorCullView& view, const osg::Matrixd& actorModelView)
{
    // The view this thread made last, shared by the keys of the actors culled after it while it stays the same;
    // keys made on other threads hold equal views in other objects, compared by value.
    static thread_local osg::ref_ptr<const SharedView> last;
    const View current = viewOf(view);
    if (!last || !(last->view == current)) last = new SharedView(current);
    Key key;
    key.view = last;
    key.actorModelView = actorModelView;
    return key;
}

bool ActorCullState::View::operator==(const View& other) const
{
    // Bit for bit: the calls kept are those of these very matrices and numbers.
    return sameBits(projection, other.projection) &&
           std::memcmp(viewport, other.viewport, sizeof viewport) == 0 && traversalMask == other.traversalMask &&
           nodeMaskOverride == other.nodeMaskOverride && cullingMask == other.cullingMask &&
           cullingMode == other.cullingMode &&
           std::memcmp(&smallFeaturePixelSize, &other.smallFeaturePixelSize, sizeof(float)) == 0 &&
           computeNearFar == other.computeNearFar && binNumber == other.binNumber &&
           binSortMode == other.binSortMode;
}

bool ActorCullState::Key::sameViewAs(const Key& other) const
{
    return view == other.view || (view && other.view && view->view == other.view->view);
}

bool ActorCullState::Key::operator==(const Key& other) const
{
    return sameBits(actorModelView, other.actorModelView) && sameViewAs(other);
}

template <class Object>
Object* ActorCullState::Pool<Object>::acquire()
{
    // Free: held by nothing but the pool. Taken in turn, so that in the steady state the next one is free at once
    // even while the render graph of a frame being drawn on another thread holds the previous frame's.
    const std::size_t count = objects.size();
    for (std::size_t k = 0; k < count; ++k)
    {
        const std::size_t i = next + k < count ? next + k : next + k - count;
        if (objects[i]->referenceCount() == 1)
        {
            next = i + 1 < count ? i + 1 : 0;
            return objects[i].get();
        }
    }
    objects.push_back(new Object);
    next = 0;
    return objects.back().get();
}

// --- ActorCull ---

bool ActorCull::canCullAsOne(osgUtil::CullVisitor& cv)
{
    if (typeid(cv) != typeid(osgUtil::CullVisitor)) return false;
    return cv.getOccluderList().empty() && cv.getCurrentCullingSet().getStateFrustumList().empty();
}

ActorCull::ActorCull(osgUtil::CullVisitor& cv, ActorCullState& state, osg::Group& actor,
                     const ActorCullState::Versions& versions)
    : _cv(cv), _state(state), _plan(nullptr), _nearFarByVisitor(false), _modelViews(nullptr), _open(), _numOpen(0)
{
    const ActorCullView view(cv);
    const ActorCullState::Key key = ActorCullState::keyOf(view, *cv.getModelViewMatrix());
    if (!_state.isPrepared(key, versions))
        _state.prepare(key, view, cv.getCurrentCullingSet().getPixelSizeVector(), actor, versions);
    // The visitor is in the actor: the model-view matrix below the actor's on its stack is where it entered.
    const osg::CullStack::MatrixStack& stack = _cv.getModelViewStack();
    makePreparedCalls(versions, actor, stack.size() >= 2 ? stack._stack.back().get() : nullptr);
}

ActorCull::ActorCull(osgUtil::CullVisitor& cv, ActorCullState& state, osg::Group& actor,
                     const ActorCullState::Versions& versions, const osg::Matrixd& entry)
    : _cv(cv), _state(state), _plan(nullptr), _nearFarByVisitor(false), _modelViews(nullptr), _open(), _numOpen(0)
{
    makePreparedCalls(versions, actor, &entry);
}

void ActorCull::makePreparedCalls(const ActorCullState::Versions& versions, const osg::Group& actor,
                                  const osg::Matrixd* entry)
{
    _state._prepared = false;
    _plan = _state._plan.get();
    if (_state._preparedReplay)
    {
        replay();
        _state._keptDepths.mergeInto(_cv);
        return;
    }
    _nearFarByVisitor = _cv.getComputeNearFarMode() != osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR &&
                        !_state._preparedDepthsByBounds;
    _planesTracked = _nearFarByVisitor && nearFarFromPrimitives(_cv);
    _modelViews = _state._preparedModelViews.get();
    if (_state._preparedReshape)
        replayReshaped();
    else
        cull();
    keepCalls(versions, actor, entry);
    _state._keptDepths.mergeInto(_cv);
}

void ActorCull::keepCalls(const ActorCullState::Versions& versions, const osg::Group& actor,
                          const osg::Matrixd* entry)
{
    _state._keptModelViews = _modelViews;
    _state._preparedModelViews = nullptr;
    _state._key = _state._preparedKey;
    _state._versions = versions;
    _state._keptDepths = _state._preparedDepths;
    // What the reshaped calls compare their drops with.
    _state._keptDropped = _state._preparedDropped;
    if (_state._keptDropped) _state._keptCulled = _state._stepCulled;
    // Near and far from primitives, the calls are made afresh each cull: the visitor's frustum tests are followed
    // as they are made (the planes each drawable's search is given), which a replay would not do.
    _state._replayable = !_planesTracked;
    noteEntry(actor, entry);
}

void ActorCull::noteEntry(const osg::Group& actor, const osg::Matrixd* entry)
{
    // Kept where the key's model-view matrix is the actor's matrix composed with the entry as
    // replayBeforeEntering() composes them, bit for bit; otherwise the replay composes and compares the whole key.
    _state._entryKnown = false;
    if (!entry || typeid(actor) != typeid(ActorNode)) return;
    const ActorNode& node = static_cast<const ActorNode&>(actor);
    if (node.getReferenceFrame() != osg::Transform::RELATIVE_RF) return;
    osg::Matrixd composed;
    composeModelView(node.getMatrix().ptr(), entry->ptr(), composed.ptr());
    if (!sameBits(composed, _state._key.actorModelView)) return;
    _state._entryModelView = *entry;
    _state._entryKnown = true;
}

void ActorCullState::prepare(const ActorCullView& view, const osg::Matrixd& actorModelView,
                             const osg::Vec4& pixelSizeVector, osg::Group& actor, const Versions& versions)
{
    prepare(keyOf(view, actorModelView), view, pixelSizeVector, actor, versions);
}

void ActorCullState::prepare(const Key& key, const ActorCullView& view, const osg::Vec4& pixelSizeVector,
                             osg::Group& actor, const Versions& versions)
{
    const osg::Matrixd& actorModelView = key.actorModelView;
    const bool planKept = _plan && _planVersion == versions.plan;
    bool replayable = planKept && _replayable && _versions == versions && _key == key;
    // Not a replay: the joints' matrices are composed after the plan is checked, which the look-ahead of the actor's
    // next cull is told (the crowd's look-ahead asked for them with the flags the check reads, if the actor's last
    // cull composed them too).
    const ActorCullPlan* kept = _plan.get();
    currentPlan(actor, versions.plan, !replayable);
    if (_plan.get() != kept) replayable = false;
    _prepared = true;
    _preparedReplay = replayable;
    _preparedReshape = false;
    _preparedPlain = false;
    _preparedKey = key;
    _preparedVersions = versions;
    if (replayable) return;
    // The kept calls may keep their shape (the same plan and view, the actor or its joints moved): decided once the
    // steps' decisions are known, the calls cleared otherwise.
    const bool mayReshape = planKept && _plan.get() == kept && _replayable && _callsReshapable && _key.sameViewAs(key);
    _replayable = false;
    const auto forgetCalls = [this] {
        _calls.clear();
        _callsTraverse = false;
        _callsReshapable = false;
    };
    if (!mayReshape) forgetCalls();
    _keptModelViews = nullptr; // free for the pool again once the render graph lets go of it

    // Every planned joint's model-view matrix, parents first.
    _preparedModelViews = _modelViews.acquire();
    const std::vector<ActorCullPlan::Joint>& joints = _plan->getJoints();
    std::vector<osg::Matrixd>& matrices = _preparedModelViews->matrices;
    matrices.resize(joints.size() + 1);
    matrices[0] = actorModelView;
    const bool smallFeatureCulling = view.smallFeatureCulling();
    _plan->composeModelViews(matrices.data());

    const std::size_t numFrames = joints.size() + 1;
    _leafMatrices.assign(numFrames, nullptr);
    _pixelSizeVectors.reset(numFrames);
    _pixelSizeVectors.set(0, pixelSizeVector);

    // What the visitor would cull and the drawables' depths.
    const std::vector<ActorCullPlan::Step>& steps = _plan->getSteps();
    const std::size_t numSteps = steps.size();
    _stepCulled.assign(numSteps, 0);
    _stepDepths.resize(numSteps);
    const ActorCullPlan::Step* stepData = steps.data();
    unsigned char* culled = _stepCulled.data();
    float* depths = _stepDepths.data();
    const ActorCullPlan::Joint* jointData = joints.data();
    const osg::Matrixd* frames = matrices.data();
    std::size_t provenUntil = 0; // the steps before it are below a joint with no small feature below it
    const bool frustumCullingForNearFar = view.computeNearFar() && view.frustumCulling();
    // Near and far from bounding volumes, where no step gives a subtree the ordinary traversal (which may read them,
    // or reset and restore them): gathered here as the visitor gathers them, drawable by drawable, and merged into
    // the visitor's once the calls are made (DepthRange), the drawables wholly behind the eye, which the visitor
    // drops, dropped here. Otherwise (from primitives, which read the visitor's culling set) the calls ask the
    // visitor for each drawable.
    const bool depthsByBounds =
        view.computeNearFarMode == osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES &&
        !_plan->hasOrdinarySteps();
    _preparedDepthsByBounds = depthsByBounds;
    _preparedDepths = DepthRange();
    _preparedDropped = 0;
    if ((!frustumCullingForNearFar || depthsByBounds) &&
        _plan->needsNoTestBelowTopJoints(view.traversalMask, view.nodeMaskOverride,
                                         smallFeatureCulling, pixelSizeVector,
                                         view.smallFeaturePixelSize, [&](const osg::BoundingSphere& bound) {
                                             return isSmallFeature(bound, 0, view);
                                         }))
    {
        // No joint or geode culled (as the loop below would find, step by step): the drawables' depths alone, or with
        // near and far from bounding volumes, those the visitor keeps and their near and far.
        bool nanDepth = false;
        if (depthsByBounds)
            nanDepth = prepareDrawablesByBounds(view, frustumCullingForNearFar);
        else
            for (unsigned i : _plan->getDrawableSteps())
            {
                const ActorCullPlan::Step& step = stepData[i];
                const osg::BoundingBox& box = static_cast<const osg::Drawable*>(step.node)->getBoundingBox();
                depths[i] = box.valid() ? eyeDepth(box.center(), frames[step.joint + 1]) : 0.0f;
                nanDepth = nanDepth || osg::isNaN(depths[i]);
            }
        // The kept calls were made for the same steps, no joint or geode culled: so are this cull's, and where it
        // drops the same drawables (none, mostly) the calls keep their shape.
        _preparedPlain = true;
        _preparedReshape = mayReshape && !nanDepth && _preparedDropped == _keptDropped &&
                           (_keptDropped == 0 || _stepCulled == _keptCulled);
        if (mayReshape && !_preparedReshape) forgetCalls();
        return;
    }
    if (mayReshape) forgetCalls();
    for (std::size_t i = 0; i < numSteps; ++i)
    {
        const ActorCullPlan::Step& step = stepData[i];
        switch (step.kind)
        {
        case ActorCullPlan::JOINT:
        case ActorCullPlan::GEODE:
        {
            // As Node::accept() would: a node the visitor's mask rules out is skipped with its subtree. The visitor
            // tests the node's sphere in the frame the node is in; a small feature is culled with its subtree.
            const unsigned frame = step.kind == ActorCullPlan::JOINT ? unsigned(jointData[step.joint].parent + 1)
                                                                      : unsigned(step.joint + 1);
            const bool tested = smallFeatureCulling && i >= provenUntil;
            if (isMaskedOut(view.traversalMask, view.nodeMaskOverride, step.mask) ||
                (tested && step.cullingActive && isSmallFeature(step.node->getBound(), frame, view)))
            {
                culled[i] = 1;
                i = step.end - 1; // its steps are skipped, and left undecided
            }
            else if (tested && _plan->provesNoSmallFeatureBelow(step, pixelSizeVector, view.smallFeaturePixelSize))
                provenUntil = step.end;
            break;
        }
        case ActorCullPlan::DRAWABLE:
        {
            // What CullVisitor::apply(osg::Drawable&) decides for a drawable without a cull callback, with the
            // frustum test kept where it changes the image: near and far planes computed from what is drawn.
            const bool masked = isMaskedOut(view.traversalMask, view.nodeMaskOverride, step.mask);
            const osg::BoundingBox& box = static_cast<const osg::Drawable*>(step.node)->getBoundingBox();
            const osg::Matrixd& modelView = frames[step.joint + 1];
            culled[i] = masked || (frustumCullingForNearFar && box.valid() && step.cullingActive &&
                                   isOutsideFrustum(box, modelView, view));
            if (!culled[i] && depthsByBounds && box.valid() && !_preparedDepths.addBox(box, modelView)) culled[i] = 1;
            depths[i] = box.valid() ? eyeDepth(box.center(), modelView) : 0.0f;
            break;
        }
        default: break;
        }
    }
}

bool ActorCullState::prepareDrawablesByBounds(const ActorCullView& view, bool frustumCulling)
{
    // What CullVisitor::apply(osg::Drawable&) decides for each drawable, no joint or geode culled above it: its box
    // against the frustum, then near and far from it (dropped if wholly behind the eye), then its depth. The boxes
    // are tested against the frustum but below a top step (a joint or geode in the actor's frame) whose sphere lies
    // wholly inside every plane: the visitor tests it so (the planes moved into the actor's frame) and then tests no
    // plane below it, where no box can be outside one (each bound holds its children's).
    const ActorCullPlan::Step* steps = _plan->getSteps().data();
    const osg::Matrixd* frames = _preparedModelViews->matrices.data();
    unsigned char* culled = _stepCulled.data();
    float* depths = _stepDepths.data();
    if (frustumCulling)
    {
        _actorFramePlanes = view.frustum->getPlaneList();
        for (osg::Plane& plane : _actorFramePlanes) plane.transformProvidingInverse(frames[0]);
    }
    std::size_t topEnd = 0;  // the end of the top step the drawables are below
    bool insideTop = false; // its sphere wholly inside the frustum
    bool nanDepth = false;
    for (unsigned i : _plan->getDrawableSteps())
    {
        const ActorCullPlan::Step& step = steps[i];
        const osg::BoundingBox& box = static_cast<const osg::Drawable*>(step.node)->getBoundingBox();
        const osg::Matrixd& modelView = frames[step.joint + 1];
        while (frustumCulling && topEnd <= i)
        {
            const ActorCullPlan::Step& top = steps[topEnd];
            topEnd = top.end ? top.end : topEnd + 1;
            insideTop = top.cullingActive && isWhollyInside(top.node->getBound(), _actorFramePlanes);
        }
        if (!box.valid())
        {
            depths[i] = 0.0f;
            continue;
        }
        if ((frustumCulling && !insideTop && step.cullingActive && isOutsideFrustum(box, modelView, view)) ||
            !_preparedDepths.addBox(box, modelView))
        {
            culled[i] = 1;
            ++_preparedDropped;
            continue;
        }
        depths[i] = eyeDepth(box.center(), modelView);
        nanDepth = nanDepth || osg::isNaN(depths[i]);
    }
    return nanDepth;
}

namespace {

/** The visitor's render leaves kept for reuse (protected in osgUtil::CullVisitor). Never instantiated. */
struct ReusedLeaves : osgUtil::CullVisitor
{
    static const osgUtil::RenderLeaf* at(const osgUtil::CullVisitor& cv, unsigned ahead)
    {
        const RenderLeafList osgUtil::CullVisitor::*const leaves = &ReusedLeaves::_reuseRenderLeafList;
        const unsigned int osgUtil::CullVisitor::*const next = &ReusedLeaves::_currentReuseRenderLeafIndex;
        const std::size_t index = std::size_t(cv.*next) + ahead;
        return index < (cv.*leaves).size() ? (cv.*leaves)[index].get() : nullptr;
    }
};

} // namespace

void ActorCull::prefetchReusedLeaf(const osgUtil::CullVisitor& cv, unsigned ahead)
{
    if (const osgUtil::RenderLeaf* leaf = ReusedLeaves::at(cv, ahead))
    {
        prefetchLine<true>(leaf);
        prefetchLine<true>(reinterpret_cast<const char*>(leaf) + sizeof(osgUtil::RenderLeaf) - 1);
    }
}

bool ActorCull::nearFarFromPrimitives(const osgUtil::CullVisitor& cv)
{
    const osg::CullSettings::ComputeNearFarMode mode = cv.getComputeNearFarMode();
    return mode == osg::CullSettings::COMPUTE_NEAR_FAR_USING_PRIMITIVES ||
           mode == osg::CullSettings::COMPUTE_NEAR_USING_PRIMITIVES;
}

inline osg::Matrixd ActorCull::modelViewOnEntering(osgUtil::CullVisitor& cv, osg::MatrixTransform& actor)
{
    // The actor's model-view matrix as CullVisitor::apply(osg::Transform&) computes it: for an ActorNode (relative,
    // the caller checked), MatrixTransform's preMult, the same bits inline; another class's own call.
    osg::Matrixd actorModelView;
    if (typeid(actor) == typeid(ActorNode))
        composeModelView(actor.getMatrix().ptr(), cv.getModelViewMatrix()->ptr(), actorModelView.ptr());
    else
    {
        actorModelView = *cv.getModelViewMatrix();
        actor.computeLocalToWorldMatrix(actorModelView, &cv);
    }
    return actorModelView;
}

bool ActorCull::replayBeforeEntering(osgUtil::CullVisitor& cv, ActorCullState& state, osg::MatrixTransform& actor,
                                     const ActorCullState::Versions& versions, const osg::Matrixd*& seenModelView)
{
    // What ActorCull's constructor would find, ahead: kept calls for this key and these counters, the plan current.
    // Near and far computed from primitives take the current culling set's frustum, the actor's when entered: only
    // without them (from bounding volumes, the visitor's call takes the matrix given, and the actor's kept range no
    // frame at all). A kept traversal of a subtree below a joint pushes the joint's matrix, from which the visitor
    // derives all it culls the subtree with (as cullPreparedBeforeEntering() finds); one in the actor's own frame
    // needs the visitor in the actor.
    const bool planKept = state._plan && state._planVersion == versions.plan;
    if (state._prepared || !planKept || !state._replayable || !(state._versions == versions) ||
        nearFarFromPrimitives(cv) || (state._callsTraverse && state._plan->hasOrdinaryStepsInActorFrame()))
        return false;
    if (!state._key.view || !(ActorCullState::viewOf(ActorCullView(cv)) == state._key.view->view)) return false;
    // For an ActorNode (relative, the caller checked) whose bound has not been recomputed, its matrix is the one the
    // kept key was composed from (every setter of a MatrixTransform's matrix dirties its bound, and the versions
    // counted its recomputations), unless a callback computes its bound instead: the key holds where the visitor
    // entered then, and the visitor's matrix now is compared with it. Otherwise the actor's model-view matrix is
    // composed as the visitor would and compared with the key's.
    const bool entryKept =
        typeid(actor) == typeid(ActorNode) && state._entryKnown && !actor.getComputeBoundingSphereCallback();
    if (entryKept ? !sameBits(*cv.getModelViewMatrix(), state._entryModelView)
                  : !sameBits(modelViewOnEntering(cv, actor), state._key.actorModelView))
        return false;
    const ActorCullPlan* kept = state._plan.get();
    state.currentPlan(actor, versions.plan);
    if (state._plan.get() != kept) return false; // changed: culled afresh, the visitor in the actor
    // The visitor's own test on its way in (the mask was tested by accept()), its writes included; a culled actor
    // adds nothing.
    if (!cv.isCulled(actor))
    {
        replayCalls(cv, state._calls);
        state._keptDepths.mergeInto(cv);
        seenModelView = &state._key.actorModelView;
    }
    return true;
}

bool ActorCull::replayReshapedBeforeEntering(osgUtil::CullVisitor& cv, ActorCullState& state,
                                             osg::MatrixTransform& actor, const ActorCullState::Versions& versions,
                                             const osg::Matrixd*& seenModelView)
{
    // What prepare() needs to reshape the kept calls, ahead (it checks them all again): a kept plan, complete calls
    // of a shape that holds for other matrices, no near and far computed from primitives (the actor's culling set
    // would be read).
    const bool planKept = state._plan && state._planVersion == versions.plan;
    if (state._prepared || !planKept || !state._replayable || !state._callsReshapable || nearFarFromPrimitives(cv))
        return false;
    const ActorCullView view(cv);
    const ActorCullState::Key key = ActorCullState::keyOf(view, modelViewOnEntering(cv, actor));
    if (!state._key.sameViewAs(key)) return false;
    // The visitor's own test on its way in (the mask was tested by accept()), its writes included; a culled actor
    // adds nothing, and its kept calls stay as they were.
    if (cv.isCulled(actor)) return true;
    // The pixel-size vector the visitor's pushCullingSet() would compute in the actor's frame.
    const osg::Vec4 pixelSizeVector =
        osg::CullingSet::computePixelSizeVector(*view.viewport, view.projection, key.actorModelView);
    state.prepare(key, view, pixelSizeVector, actor, versions);
    if (!state._preparedReshape) return false; // prepared for the visitor, which enters the actor and finds it so
    const ActorCull reshaped(cv, state, actor, versions, *cv.getModelViewMatrix());
    seenModelView = &state._key.actorModelView; // the prepared key's
    return true;
}

bool ActorCull::cullPreparedBeforeEntering(osgUtil::CullVisitor& cv, ActorCullState& state,
                                           osg::MatrixTransform& actor, const ActorCullState::Versions& versions,
                                           const osg::Matrixd*& seenModelView)
{
    // The calls of a cull prepared for what the visitor holds now need the actor's frame on its stacks only to
    // traverse a subtree in that frame, and its culling set only to compute near and far from primitives: without
    // either, they are made from the prepared matrices alone (a replay, the kept calls reshaped, or calls made afresh;
    // the kept calls are those of the same plan). A subtree below a joint is traversed with the joint's matrix pushed,
    // from which, for a relative frame, OSG's CullStack::pushModelViewMatrix() derives the eye and view points (the
    // reference view point is inherited, the same at the group as in a relative actor) and the culling set (from the
    // projection's): the same whether or not the actor's frame lies below it.
    if (!state._prepared || nearFarFromPrimitives(cv) || state._plan->hasOrdinaryStepsInActorFrame()) return false;
    if (!state.isPrepared(ActorCullState::keyOf(ActorCullView(cv), modelViewOnEntering(cv, actor)), versions))
        return false;
    // The visitor's own test on its way in (the mask was tested by accept()), its writes included; a culled actor
    // adds nothing (the group gives back its preparation).
    if (cv.isCulled(actor)) return true;
    const ActorCull prepared(cv, state, actor, versions, *cv.getModelViewMatrix());
    seenModelView = &state._key.actorModelView; // the prepared key's (a replay's is the same)
    return true;
}

void ActorCull::replayCalls(osgUtil::CullVisitor& cv, const std::vector<Call>& calls)
{
    for (const Call& c : calls) replayCall(cv, c);
}

inline void ActorCull::replayCall(osgUtil::CullVisitor& cv, const Call& c)
{
    switch (c.kind)
    {
    case Call::PUSH_STATE: cv.pushStateSet(static_cast<osg::StateSet*>(c.object)); break;
    case Call::POP_STATE: cv.popStateSet(); break;
    case Call::PUSH_PATH: cv.pushOntoNodePath(static_cast<osg::Node*>(c.object)); break;
    case Call::POP_PATH: cv.popFromNodePath(); break;
    case Call::ADD_LEAF: cv.addDrawableAndDepth(static_cast<osg::Drawable*>(c.object), c.matrix, c.depth); break;
    case Call::NEAR_FAR: cv.updateCalculatedNearFar(*c.modelView, *static_cast<osg::Drawable*>(c.object), true); break;
    case Call::TRAVERSE:
        if (c.matrix) cv.pushModelViewMatrix(c.matrix, osg::Transform::RELATIVE_RF);
        static_cast<osg::Node*>(c.object)->accept(cv);
        if (c.matrix) cv.popModelViewMatrix();
        break;
    }
}

void ActorCull::replayReshaped()
{
    // Each leaf is given to the visitor as soon as it is remade, so that the pools see it held and give the next
    // leaf another batch or matrix.
    const float* depths = _state._stepDepths.data();
    const ActorCullState::KeptLeaf* kept = _state._keptLeaves.data();
    for (Call& c : _state._calls)
    {
        if (c.kind == Call::ADD_LEAF)
        {
            const ActorCullState::KeptLeaf& leaf = *kept++;
            if (leaf.numEntries)
            {
                JointDrawBatch* batch = _state._batches.acquire();
                batch->reset(_plan, _modelViews);
                batch->add(_state._keptEntries.data() + leaf.firstEntry, leaf.numEntries);
                c.object = batch;
            }
            c.matrix = leafMatrix(leaf.frame);
            c.depth = depths[leaf.step];
        }
        replayCall(_cv, c);
    }
}

void ActorCull::keepLeafSources()
{
    // The calls keep their shape for other matrices of the same plan and view where nothing was culled and no
    // drawable dropped (prepare()'s plain steps, no depth not a number), without near and far (which may drop a
    // drawable) and with no subtree traversed ordinarily (its calls are not kept).
    if (!_state._callsReshapable) return;
    if (!_state._preparedPlain || _nearFarByVisitor || _state._callsTraverse)
    {
        _state._callsReshapable = false;
        return;
    }
    // The batches' entries, complete now.
    std::vector<ActorCullState::KeptLeaf>& leaves = _state._keptLeaves;
    std::vector<JointDrawBatch::Entry>& entries = _state._keptEntries;
    entries.clear();
    std::size_t k = 0;
    for (const Call& c : _state._calls)
    {
        if (c.kind != Call::ADD_LEAF) continue;
        ActorCullState::KeptLeaf& leaf = leaves[k++];
        if (!leaf.numEntries) continue;
        const std::vector<JointDrawBatch::Entry>& batched = static_cast<const JointDrawBatch*>(c.object)->getEntries();
        leaf.firstEntry = static_cast<unsigned>(entries.size());
        leaf.numEntries = static_cast<unsigned>(batched.size());
        entries.insert(entries.end(), batched.begin(), batched.end());
    }
}

void ActorCull::cull()
{
    _state._keptLeaves.clear();
    _state._callsReshapable = true; // until found otherwise
    _untestedUntil = 0;
    if (_planesTracked && _state._jointFrustums.size() < _plan->getJoints().size() + 1)
        _state._jointFrustums.resize(_plan->getJoints().size() + 1);
    const Step* steps = _plan->getSteps().data();
    const std::size_t numSteps = _plan->getSteps().size();
    const unsigned char* culled = _state._stepCulled.data();
    for (std::size_t i = 0; i < numSteps;)
    {
        const Step& step = steps[i];
        switch (step.kind)
        {
        case ActorCullPlan::JOINT:
        case ActorCullPlan::GEODE:
            if (_planesTracked) enterFrustum(step, i);
            if (culled[i])
            {
                i = step.end;
                continue;
            }
            // Cull callbacks and user nodes below may read the node path: kept as the ordinary traversal keeps it.
            if (step.pathNeeded)
            {
                _cv.pushOntoNodePath(step.node);
                call(Call::PUSH_PATH, step.node);
            }
            if (step.stateSet) wantState(step.stateSet);
            break;
        case ActorCullPlan::END_JOINT:
        case ActorCullPlan::END_GEODE:
            if (_planesTracked) leaveFrustum(step, i);
            if (step.stateSet) unwantState();
            if (step.pathNeeded)
            {
                _cv.popFromNodePath();
                call(Call::POP_PATH, nullptr);
            }
            break;
        case ActorCullPlan::DRAWABLE:
        {
            const osg::Polytope::ClippingMask planes = _planesTracked ? testDrawableBox(step, i) : 0;
            if (!culled[i]) addDrawable(step, static_cast<unsigned>(i), planes);
            break;
        }
        case ActorCullPlan::ORDINARY: traverseOrdinarily(step); break;
        }
        ++i;
    }
    applyWantedStates(); // pops what is left
    keepLeafSources();
}

void ActorCull::addDrawable(const Step& step, unsigned stepIndex, osg::Polytope::ClippingMask planes)
{
    // What CullVisitor::apply(osg::Drawable&) does for a drawable without a cull callback, from what prepare()
    // decided.
    osg::Drawable& drawable = *step.node->asDrawable();
    const unsigned frame = static_cast<unsigned>(step.joint + 1);
    const osg::Matrixd& modelView = _modelViews->matrices[frame];
    if (_planesTracked && drawable.getBoundingBox().valid())
    {
        if (!updateNearFarWithPlanes(modelView, drawable, frame, planes)) return;
    }
    else if (_nearFarByVisitor && drawable.getBoundingBox().valid())
    {
        // The visitor takes the box's nearest and farthest corners along the view in the frame of the matrix it last
        // pushed, which here is the actor's, not the joint's: its billboard form finds them from the matrix given,
        // with the same arithmetic pushModelViewMatrix() uses, so the corners are those of the ordinary traversal
        // (from bounding volumes nothing else is read; from primitives, updateNearFarWithPlanes() above).
        if (!_cv.updateCalculatedNearFar(modelView, drawable, true)) return;
        call(Call::NEAR_FAR, &drawable, nullptr, 0.0f, &modelView);
    }
    const float depth = _state._stepDepths[stepIndex];
    if (osg::isNaN(depth))
    {
        _state._callsReshapable = false;
        return; // the visitor drops it too (with a notice)
    }
    if (step.stateSet) wantState(step.stateSet);
    applyWantedStates();
    osgUtil::StateGraph* graph = _cv.getCurrentStateGraph();
    // Batched where the bin draws its state graphs' leaves in the order they came: a bin sorted by state. Dynamic
    // drawables keep a leaf of their own, which tells a viewer drawing on another thread to wait for them.
    const bool batchable =
        step.batchable && _cv.getCurrentRenderBin()->getSortMode() == osgUtil::RenderBin::SORT_BY_STATE;
    JointDrawBatch* batch = batchable ? openBatch(graph) : nullptr;
    if (batch)
        batch->add(drawable, frame);
    else
    {
        osg::RefMatrix* matrix = leafMatrix(frame);
        if (batchable)
        {
            // The batch's leaf carries the first drawable's matrix, so the state graph's state is applied under the
            // matrix it would be applied under without the batch.
            batch = _state._batches.acquire();
            batch->reset(_plan, _modelViews);
            batch->add(drawable, frame);
            _cv.addDrawableAndDepth(batch, matrix, depth);
            call(Call::ADD_LEAF, batch, matrix, depth);
            _state._keptLeaves.push_back({frame, stepIndex, 0, 1}); // its entries noted at the end
            if (_numOpen == kMaxOpenBatches) closeBatch(_open[0].graph);
            _open[_numOpen++] = {graph, batch};
        }
        else
        {
            closeBatch(graph);
            _cv.addDrawableAndDepth(&drawable, matrix, depth);
            call(Call::ADD_LEAF, &drawable, matrix, depth);
            _state._keptLeaves.push_back({frame, stepIndex, 0, 0});
        }
    }
    if (step.stateSet) unwantState();
}

void ActorCull::traverseOrdinarily(const Step& step)
{
    _numOpen = 0; // the traversal may add leaves to any state graph: no batch may take drawables after them
    applyWantedStates();
    // The actor's own frame is on the visitor's stacks already (it pushed actor_m on its way in).
    osg::RefMatrix* matrix = step.joint < 0 ? nullptr : leafMatrix(static_cast<unsigned>(step.joint + 1));
    call(Call::TRAVERSE, step.node, matrix);
    if (matrix) _cv.pushModelViewMatrix(matrix, osg::Transform::RELATIVE_RF);
    if (!matrix || !_planesTracked)
        step.node->accept(_cv);
    else
    {
        // The visitor would traverse the subtree in the joint's culling set, with the masks it holds there: the
        // set just pushed (the same planes) is given them, and its tests' result taken back.
        osg::Polytope& pushed = _cv.getCurrentCullingSet().getFrustum();
        osg::Polytope& tracked = frameFrustum(static_cast<unsigned>(step.joint + 1));
        pushed.setResultMask(tracked.getCurrentMask());
        pushed.pushCurrentMask();
        pushed.setResultMask(tracked.getResultMask());
        step.node->accept(_cv);
        // The subtree's own culling sets may have grown the visitor's stack of them, moving the one pushed above.
        osg::Polytope& after = _cv.getCurrentCullingSet().getFrustum();
        tracked.setResultMask(after.getResultMask());
        after.popCurrentMask();
    }
    if (matrix) _cv.popModelViewMatrix();
}

void ActorCull::enterFrustum(const Step& step, std::size_t stepIndex)
{
    // CullVisitor::apply(osg::Transform&) and apply(osg::Geode&): isCulled(node) in the frame the node is in, then,
    // going on, pushCurrentMask() there and (a transform) a culling set of its own.
    if (frustumSkips(step, stepIndex)) return;
    osg::Polytope& frustum = frameFrustum(frustumFrameOf(step));
    const osg::BoundingSphere& bound = step.node->getBound();
    if (step.cullingActive && bound.valid())
    {
        if ((_cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::VIEW_FRUSTUM_CULLING) &&
            !frustum.contains(bound))
        {
            _untestedUntil = step.end;
            return;
        }
    }
    else
        frustum.setResultMask(frustum.getCurrentMask()); // CullingSet::resetCullingMask()
    if (_state._stepCulled[stepIndex]) return; // a small feature: not entered
    frustum.pushCurrentMask();
    if (step.kind != ActorCullPlan::JOINT) return;
    // CullStack::pushCullingSet(): the projection's frustum moved into the joint's frame.
    osg::Polytope& joint = _state._jointFrustums[step.joint + 1];
    joint.setAndTransformProvidingInverse(_cv.getProjectionCullingStack().back().getFrustum(),
                                          _modelViews->matrices[step.joint + 1]);
}

void ActorCull::leaveFrustum(const Step& step, std::size_t stepIndex)
{
    if (!frustumSkips(step, stepIndex)) frameFrustum(frustumFrameOf(step)).popCurrentMask();
}

bool ActorCull::frustumSkips(const Step& step, std::size_t stepIndex) const
{
    return stepIndex < _untestedUntil || isMaskedOut(_cv.getTraversalMask(), _cv.getNodeMaskOverride(), step.mask);
}

unsigned ActorCull::frustumFrameOf(const Step& step) const
{
    const bool jointNode = step.kind == ActorCullPlan::JOINT || step.kind == ActorCullPlan::END_JOINT;
    return static_cast<unsigned>(jointNode ? _plan->getJoints()[step.joint].parent + 1 : step.joint + 1);
}

osg::Polytope::ClippingMask ActorCull::testDrawableBox(const Step& step, std::size_t stepIndex)
{
    // CullVisitor::apply(osg::Drawable&): drawable.isCullingActive() && isCulled(box), in the drawable's frame.
    osg::Polytope& frustum = frameFrustum(static_cast<unsigned>(step.joint + 1));
    if (stepIndex >= _untestedUntil && !isMaskedOut(_cv.getTraversalMask(), _cv.getNodeMaskOverride(), step.mask))
    {
        const osg::BoundingBox& box = static_cast<const osg::Drawable*>(step.node)->getBoundingBox();
        if (step.cullingActive && box.valid() &&
            (_cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::VIEW_FRUSTUM_CULLING))
            frustum.contains(box);
    }
    return frustum.getResultMask();
}

bool ActorCull::updateNearFarWithPlanes(const osg::Matrixd& modelView, osg::Drawable& drawable, unsigned frame,
                                        osg::Polytope::ClippingMask planes)
{
    osg::Polytope& current = _cv.getCurrentCullingSet().getFrustum();
    osg::Polytope& projection = _cv.getProjectionCullingStack().back().getFrustum();
    osg::Polytope::ClippingMask& projectionMask = projection.getCurrentMask();
    const osg::Polytope::ClippingMask currentResult = current.getResultMask();
    const osg::Polytope::ClippingMask projectionActive = projectionMask;
    // The frame's planes are the projection's active ones, in their order: as many (a culling set copied and moved,
    // each plane where it was) or only those (CullingSet::set(), which keeps the active planes alone).
    osg::Polytope::ClippingMask selected = planes;
    if (frameFrustum(frame).getPlaneList().size() != projection.getPlaneList().size())
    {
        selected = 0;
        osg::Polytope::ClippingMask next = 0x1;
        for (osg::Polytope::ClippingMask bit = 0x1; bit && bit <= projectionActive; bit <<= 1)
        {
            if (!(projectionActive & bit)) continue;
            if (planes & next) selected |= bit;
            next <<= 1;
        }
    }
    projectionMask = selected;
    current.setResultMask(planes);
    const bool kept = _cv.updateCalculatedNearFar(modelView, drawable, true);
    current.setResultMask(currentResult);
    projectionMask = projectionActive;
    return kept;
}

void ActorCull::changeToWantedStates()
{
    std::vector<osg::StateSet*>& wanted = _state._wantedStates;
    std::vector<osg::StateSet*>& applied = _state._appliedStates;
    const std::size_t common = _statesInCommon;
    while (applied.size() > common)
    {
        _cv.popStateSet();
        call(Call::POP_STATE, nullptr);
        applied.pop_back();
    }
    while (applied.size() < wanted.size())
    {
        osg::StateSet* state = wanted[applied.size()];
        _cv.pushStateSet(state);
        call(Call::PUSH_STATE, state);
        applied.push_back(state);
    }
    _statesInCommon = applied.size();
}

osg::RefMatrix* ActorCull::leafMatrix(unsigned frame)
{
    // The actor's own matrix too is one of the actor's (not the visitor's, which it reuses for other matrices):
    // the calls kept for the next frame give the render graph the same matrix again.
    osg::RefMatrix*& matrix = _state._leafMatrices[frame];
    if (!matrix)
    {
        matrix = _state._matrices.acquire();
        matrix->set(_modelViews->matrices[frame]);
    }
    return matrix;
}

JointDrawBatch* ActorCull::openBatch(osgUtil::StateGraph* graph) const
{
    for (unsigned i = 0; i < _numOpen; ++i)
        if (_open[i].graph == graph) return _open[i].batch;
    return nullptr;
}

void ActorCull::closeBatch(osgUtil::StateGraph* graph)
{
    for (unsigned i = 0; i < _numOpen; ++i)
        if (_open[i].graph == graph)
        {
            _open[i] = _open[--_numOpen];
            return;
        }
}

bool ActorCullState::isSmallFeature(const osg::BoundingSphere& bound, unsigned frame, const ActorCullView& view)
{
    return _pixelSizeVectors.isSmallFeature(bound, frame, *view.viewport, view.projection,
                                            _preparedModelViews->matrices[frame], view.smallFeaturePixelSize);
}

bool ActorCullState::isOutsideFrustum(const osg::BoundingBox& box, const osg::Matrixd& modelView,
                                      const ActorCullView& view) const
{
    return detail::isOutsideFrustum(box, modelView, *view.frustum);
}

} // namespace detail
} // namespace osgActor
