// Internal to the library (not installed, NOT API): the cull traversal of one actor as one (issue 28).
//
// osgUtil::CullVisitor, walking an actor node by node, pushes and pops a model-view matrix and a culling set (its
// frustum's planes transformed into the node's frame) at every skeleton node and tests every node's, geode's and
// drawable's bound against them: most of a crowd's frame. The visitor has already tested the actor's bound once,
// on its way into the actor, and pushed actor_m; ActorCull then follows the actor's cull plan (ActorCullPlan: the
// plain skeleton nodes, geodes and drawables below it, and the subtrees that need the ordinary traversal, in the
// order the visitor would meet them) and:
//  - computes every planned joint's model-view matrix in eye space in one pass, parents first, with the very
//    product the visitor makes (osg::Matrixd::preMult, as MatrixTransform::computeLocalToWorldMatrix does, so the
//    bits are the same), and pushes no matrix and no culling set;
//  - hands the plain drawables straight to the render graph, an actor's drawables of one state graph in one render
//    leaf (JointDrawBatch), with the depth the visitor computes; state sets on the way are pushed as the visitor
//    pushes them, when a drawable needs them, so the drawables land in the same state graphs and render bins;
//  - gives everything else (cull callbacks, hidden joints, LOD and switch nodes, a user's nodes, other classes)
//    the ordinary traversal, with the joint's model-view matrix pushed, so it sees what it would see below the
//    joint, the node path included.
// What may change the image is culled as the visitor culls it: node masks, small features (the same pixel-size test
// with the same pixel-size vector), and, while the visitor computes near and far planes from what it draws, each
// drawable's box against the frustum (in eye space: all eight corners outside one plane, the visitor's test, in
// another frame) before it counts for near and far. What only saves work is skipped: spheres against the frustum,
// so a drawable outside the view may reach the render graph, where OpenGL clips it, and the statistics count it.
// Near and far from bounding volumes (osgViewer's default) are gathered by prepare() with the visitor's arithmetic
// (DepthRange, the drawables behind the eye dropped as it drops them) and merged into the visitor's once per actor,
// which gives its values to the bit (each is a least or greatest value); from primitives, or with an ordinary
// subtree among the steps, each drawable's are asked of the visitor as it is added. From primitives the visitor
// searches a drawable's triangles against the frustum planes its culling set in the drawable's frame holds active
// (none: the box's corners count), which its tests of the spheres and boxes in that frame decide: the cull makes
// those tests on planes moved as the visitor moves them, in its order, and asks for each drawable with its planes,
// so that near and far are the ordinary traversal's to the bit (such a cull is never replayed).
//
// The work is in two parts. prepare() touches no visitor: it checks the plan, computes the model-view matrices and
// decides what small features, and what lies outside the frustum, are culled, and each drawable's depth, from a
// view (ActorCullView: what the visitor holds, taken once) and the actor's model-view matrix. ActorCull (the visitor's
// thread) then makes the calls to the visitor from what was prepared. An actor culls itself with both in turn; an
// ActorGroup prepares its actors on its threads first, then the visitor meets them in child order as it would, and
// each finds its cull prepared, provided the visitor holds what the preparation was made for (it is checked).
//
// What a cull did to the visitor (state sets pushed and popped, leaves added, subtrees traversed) is kept as a
// list of calls. When the actor is culled again with nothing it depends on changed (the same plan, no joint
// matrix written, no bound below recomputed, the same model-view matrix on entry, the same projection, viewport
// and culling settings: an idle actor before a still camera; near and far not from primitives), the calls are
// made again with the same leaves and
// matrices, which were only read since, and the near and far they gave merged again: no joint is read but for the
// flags the plan compares.
#ifndef OSGACTOR_DETAIL_ACTORCULL_H
#define OSGACTOR_DETAIL_ACTORCULL_H 1

#include <osgActor/detail/ActorCullPlan.h>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/JointDrawBatch.h>

#include <osg/Matrixd>
#include <osg/Polytope>
#include <osgUtil/CullVisitor>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <utility>
#include <vector>

namespace osgActor {
namespace detail {

/** What the cull of an actor reads of the cull visitor, but the actor's own model-view matrix and pixel-size
  * vector: the view, the masks and settings, and where the actor's leaves go. Taken from the visitor where it enters
  * the actor, or where it enters the ActorGroup above it (it then holds the same, or the actor's cull finds that it
  * does not and prepares again). Points into the visitor: valid while its cull goes on. */
struct ActorCullView
{
    explicit ActorCullView(osgUtil::CullVisitor& cv);

    osg::Matrixd projection;
    const osg::Viewport* viewport;
    const osg::Polytope* frustum; // the projection's culling set's, eye space
    unsigned traversalMask;
    unsigned nodeMaskOverride;
    unsigned cullingMask;          // the current culling set's
    unsigned cullingMode;          // the visitor's, which made the projection's frustum
    float smallFeaturePixelSize;
    int computeNearFarMode;
    int binNumber;
    int binSortMode;

    bool smallFeatureCulling() const { return (cullingMask & osg::CullingSet::SMALL_FEATURE_CULLING) != 0; }
    bool frustumCulling() const { return (cullingMask & osg::CullingSet::VIEW_FRUSTUM_CULLING) != 0; }
    bool computeNearFar() const { return computeNearFarMode != osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR; }
    /** What the visitor's isCulled(node) answers for a bound in the culling set's frame (frustum planes in its
      * current mask, and small features), without the writes osg::CullingSet::isCulled() makes: any thread. */
    static bool isCulled(const osg::CullingSet& set, const osg::BoundingSphere& bound);
};

/** What one actor keeps from one cull to the next: its plan, the calls of its last cull, and the batches and
  * matrices those calls gave the render graph. One cull visitor at a time (tryAcquire()). */
class ActorCullState : public osg::Referenced
{
public:
    ActorCullState();

    /** Claims the state for one cull; false while another thread culls the actor (it then takes the ordinary
      * traversal). */
    bool tryAcquire() { return !_busy.test_and_set(std::memory_order_acquire); }
    void release() { _busy.clear(std::memory_order_release); }
    /** Claims it for a visitor's whole traversal of an ActorGroup (its preparation on the group's threads, then
      * its cull), and gives it back after: isHeldBy(visitor) in between. */
    bool tryAcquireFor(const void* visitor)
    {
        if (!tryAcquire()) return false;
        _holder.store(visitor, std::memory_order_relaxed);
        return true;
    }
    bool isHeldBy(const void* visitor) const { return _holder.load(std::memory_order_relaxed) == visitor; }
    void releaseFrom(const void* visitor)
    {
        if (!isHeldBy(visitor)) return;
        _prepared = false;
        _preparedModelViews = nullptr;
        _holder.store(nullptr, std::memory_order_relaxed);
        release();
    }

    /** Counters of what the actor changed (ActorNode's counters of plan-changing edits, joint-matrix writes and
      * bound recomputations): the last cull's calls are replayed only for the same ones, and the same view. */
    struct Versions
    {
        unsigned plan = 0;
        unsigned pose = 0;
        unsigned bound = 0;
        bool operator==(const Versions& other) const
        {
            return plan == other.plan && pose == other.pose && bound == other.bound;
        }
    };
    /** An actor's counters now, read from its atomic ones. */
    static Versions versionsOf(const std::atomic<unsigned>& plan, unsigned pose, const std::atomic<unsigned>& bound)
    {
        return {plan.load(std::memory_order_relaxed), pose, bound.load(std::memory_order_relaxed)};
    }

    /** Everything of the actor's cull that does not touch the visitor, for a view and the actor's model-view
      * matrix (eye space) and pixel-size vector (as the visitor computes them on its way into the actor), with
      * the state acquired; any thread, one actor per thread. The actor's bound is computed already. */
    void prepare(const ActorCullView& view, const osg::Matrixd& actorModelView, const osg::Vec4& pixelSizeVector,
                 osg::Group& actor, const Versions& versions);

    /** The plan of the actor's children: the one kept if the actor's plan version is the same and it is current, or
      * a new one (then the kept calls are not replayed). For the cull that holds the state (tryAcquire()); the
      * instanced cull (InstancedCull) goes by it too. composing: the cull goes on to compose the joints' matrices
      * (it is no replay), which the look-ahead of the actor's next cull then asks for with the nodes' flags, as an
      * actor moving now most likely still moves then; where no look-ahead asked for them, they are asked for here. */
    const ActorCullPlan& currentPlan(osg::Group& actor, unsigned planVersion, bool composing = false);

    /** For the look-ahead of a crowd's cull (ActorNode::prefetchCullAhead()): the stages of what a replay of this
      * actor's cull reads, each fetched once the one before it is in the caches. */
    enum AheadStage
    {
        AHEAD_STATE,      // this state's own members
        AHEAD_PLAN,       // the plan and the kept calls
        AHEAD_PLAN_ARRAYS,// the plan's arrays the check reads
        AHEAD_NODES       // the nodes the check reads (and the joints' matrices, where the last cull composed them)
    };
    /** A hint, from any thread: the stages past the first only where no other thread holds the state. */
    void prefetchAhead(AheadStage stage);

protected:
    ~ActorCullState() override = default;

private:
    friend class ActorCull;
    friend class InstancedCull;
    friend class InstancedCullState;

    /** What the calls depend on of the visitor's settings: the same for every actor a visitor culls. */
    struct View
    {
        osg::Matrixd projection;
        double viewport[4] = {};
        unsigned traversalMask = 0;
        unsigned nodeMaskOverride = 0;
        unsigned cullingMask = 0;   // the current culling set's
        unsigned cullingMode = 0;   // the visitor's, which made the projection's frustum
        float smallFeaturePixelSize = 0.0f;
        int computeNearFar = 0;
        int binNumber = 0;
        int binSortMode = 0;
        bool operator==(const View& other) const;
    };
    static View viewOf(const ActorCullView& view);
    /** A View made once and shared by the keys of every actor culled with it (keyOf()), so that an actor keeps a
      * pointer rather than a copy (fewer lines of its state read per cull) and a replay compares the visitor's view
      * with an object every actor's check has just read. Never changed once made. */
    struct SharedView : osg::Referenced
    {
        explicit SharedView(const View& v) : view(v) {}
        const View view;

    protected:
        ~SharedView() override = default;
    };
    /** What the calls depend on beyond the actor: the visitor's settings and where it enters the actor. */
    struct Key
    {
        osg::ref_ptr<const SharedView> view; // first: the replay reads it and not the matrix
        osg::Matrixd actorModelView;
        bool operator==(const Key& other) const;
        /** The same but for the actor's model-view matrix. */
        bool sameViewAs(const Key& other) const;
    };
    static Key keyOf(const ActorCullView& view, const osg::Matrixd& actorModelView);
    /** prepare() for the key of the view and the actor's model-view matrix (its actorModelView). */
    void prepare(const Key& key, const ActorCullView& view, const osg::Vec4& pixelSizeVector, osg::Group& actor,
                 const Versions& versions);
    /** One call the cull made to the visitor. */
    struct Call
    {
        enum Kind : unsigned char { PUSH_STATE, POP_STATE, PUSH_PATH, POP_PATH, ADD_LEAF, NEAR_FAR, TRAVERSE };
        Kind kind;
        float depth;                 // ADD_LEAF
        osg::Referenced* object;     // the state set, node or drawable
        osg::RefMatrix* matrix;      // ADD_LEAF, TRAVERSE (null: the actor's own, on the stack already)
        const osg::Matrixd* modelView; // NEAR_FAR
    };

    /** Objects the render graph holds until drawn: one with no other holder than this state is free to change. */
    template <class Object>
    struct Pool
    {
        std::vector<osg::ref_ptr<Object>> objects;
        std::size_t next = 0;
        Object* acquire();
    };

    /** Whether the decisions below hold for a cull seeing _key. */
    bool isPrepared(const Key& key, const Versions& versions) const
    {
        return _prepared && _preparedVersions == versions && _preparedKey == key;
    }
    bool isSmallFeature(const osg::BoundingSphere& bound, unsigned frame, const ActorCullView& view);
    bool isOutsideFrustum(const osg::BoundingBox& box, const osg::Matrixd& modelView, const ActorCullView& view) const;
    /** For prepare(), no joint or geode culled, near and far from bounding volumes: each drawable's decision (outside
      * the frustum, when frustumCulling, or wholly behind the eye: culled, counted in _preparedDropped), its near and
      * far into _preparedDepths and its depth; true where a depth kept is not a number. */
    bool prepareDrawablesByBounds(const ActorCullView& view, bool frustumCulling);

    // What an idle actor's replay reads (replayBeforeEntering()), together from the start of the object up to its
    // key's view (prefetchAhead() asks for these lines); the key's matrix and the rest after them.
    std::atomic_flag _busy;
    std::atomic<const void*> _holder;
    osg::ref_ptr<ActorCullPlan> _plan;
    unsigned _planVersion;
    bool _replayable;
    bool _prepared = false;      // what prepare() decided (below) is for the cull that follows
    bool _callsTraverse = false; // a TRAVERSE among the kept calls
    /** The model-view matrix the visitor held where it entered the actor for the kept calls, when the key's
      * actorModelView is the actor's matrix composed with it as the visitor composes it (an ActorNode in a relative
      * frame): while the actor's matrix stays (its bound is not recomputed) the replay compares this one alone. */
    bool _entryKnown = false;
    /** The last cull composed the joints' matrices (currentPlan()): prefetchAhead() asks for them too. */
    bool _composing = false;
    /** prefetchAhead() asked for the joints' flags and matrices since the last cull: currentPlan() does not. */
    bool _jointsAskedFor = false;
    Versions _versions;
    /** The near and far distances the kept calls' drawables gave, merged into the visitor's after the calls, where
      * prepare() gathered them (near and far from bounding volumes, no ordinary subtree); empty otherwise. */
    DepthRange _keptDepths;
    std::vector<Call> _calls;
    osg::Matrixd _entryModelView;
    Key _key;
    Pool<JointModelViews> _modelViews;
    Pool<JointDrawBatch> _batches;
    Pool<osg::RefMatrix> _matrices;
    /** The matrices the kept calls refer to. */
    osg::ref_ptr<JointModelViews> _keptModelViews;
    // What prepare() decided, for the cull that follows: replay the kept calls, or make new ones with these
    // matrices and, per step, whether it is culled (JOINT, GEODE, DRAWABLE) and the drawable's depth.
    bool _preparedReplay = false;
    Key _preparedKey;
    Versions _preparedVersions;
    osg::ref_ptr<JointModelViews> _preparedModelViews;
    std::vector<unsigned char> _stepCulled;
    std::vector<float> _stepDepths;
    /** Near and far from bounding volumes gathered by prepare() (DepthRange), the drawables behind the eye among
      * those culled; false: the calls ask the visitor for each drawable, if near and far are computed. */
    bool _preparedDepthsByBounds = false;
    DepthRange _preparedDepths;
    std::vector<osg::Plane> _actorFramePlanes; // the frustum's planes in the actor's frame, for prepare()
    unsigned _preparedDropped = 0;             // the drawables prepareDrawablesByBounds() dropped
    // A cull's working space, kept so that a frame allocates nothing. Per frame (the actor's, then each planned
    // joint's): its matrix for the render graph, or null; its pixel-size vector.
    std::vector<osg::RefMatrix*> _leafMatrices;
    FramePixelSizeVectors _pixelSizeVectors;
    std::vector<osg::StateSet*> _wantedStates;
    std::vector<osg::StateSet*> _appliedStates;
    /** Near and far from primitives: per planned joint, the frustum as the visitor's culling set in its frame holds
      * it (ActorCull::jointFrustum()); index joint + 1, the actor's own frame being the visitor's set. */
    std::vector<osg::Polytope> _jointFrustums;
    /** What the last InstancedActorGroup cull to take the actor found for its plan (InstancedCull), so that the
      * next cull of that group finds it without a lookup: the group's cull state (its serial), the plan (held, so
      * that no other plan is made at its address while it is named here), and the verdict. */
    struct InstancedVerdict
    {
        std::uint64_t serial = 0;
        osg::ref_ptr<const ActorCullPlan> plan;
        const void* verdict = nullptr;
        // The actor's instances of that cull, in runs of one batch, each instance's matrix (16 floats), kept where
        // it had not changed since the cull before, and added again while nothing they depend on changes (the
        // counters, the actor's model-view matrix and the rest of the key, the view's, which the group's cull state
        // numbers): an idle actor before a still camera.
        Versions versions;
        bool kept = false;
        std::uint64_t view = 0;
        /** The number the group's cull state gave the model-view matrix it was entered with (the actor's parent's)
          * when actorModelView was composed: while it and the actor's bound (which every setter of the actor's matrix
          * dirties) stay, actorModelView is the actor's model-view matrix, not composed again. */
        std::uint64_t entry = 0;
        osg::Matrixd actorModelView;
        /** A run of instances of one batch, and the texel of the frames' buffers it was last added at (or ~0u). */
        struct Run
        {
            unsigned batch;
            unsigned count;
            unsigned at;
        };
        std::vector<Run> runs;
        std::vector<float> matrices;
        /** Its subtrees that cull reached (InstancedActorGroup hands them to the visitor): each one's index among its
          * verdict's, and its frame's model-view matrix. */
        std::vector<std::pair<unsigned, osg::Matrixd>> subtreeVisits;
        /** The group's culls that added the runs (numbered by its cull state), one after the other, each at the
          * same texels (Run::at), from placedSince to placedUntil (none where placedSince > placedUntil): a frame one
          * of them took holds them there still while no cull took it since and nothing moved in its buffer
          * (InstancedFrame::beginWrites()), whichever of the pool's frames the next cull takes (with osgViewer's
          * draw thread the frames alternate). */
        std::uint64_t placedSince = 1;
        std::uint64_t placedUntil = 0;
        /** With near and far computed from bounding volumes (the view's, which the kept instances' view number
          * counts), the near and far distances the kept instances' drawables gave (DepthRange), merged into the
          * visitor's again where they are added again. */
        DepthRange depths;
    };
    InstancedVerdict _instancedVerdict;

    // Last, so that the members an idle actor's replay reads keep their places (and cache lines; its look-ahead
    // fetches them by address range).
    /** Where each kept ADD_LEAF call's leaf came from: its (first) drawable's frame and step and, for a batch, its
      * entries (a range of _keptEntries; none: a drawable's own leaf). With _callsReshapable (the cull that made the
      * calls culled no joint or geode, asked the visitor for no drawable's near and far and traversed no subtree), a
      * moving actor seen with the same plan and view but for its own model-view matrix, whose cull drops the same
      * drawables (_keptCulled: outside the frustum or behind the eye, near and far computed), makes the same calls
      * with its new matrices and depths (ActorCull::replayReshaped()) instead of following its plan step by step. */
    struct KeptLeaf
    {
        unsigned frame;
        unsigned step;
        unsigned firstEntry;
        unsigned numEntries;
    };
    std::vector<KeptLeaf> _keptLeaves;
    std::vector<JointDrawBatch::Entry> _keptEntries;
    unsigned _keptDropped = 0;              // the drawables the cull that made the kept calls dropped
    std::vector<unsigned char> _keptCulled; // and its _stepCulled, where it dropped any
    bool _callsReshapable = false;
    // What prepare() decided besides: replay the kept calls with the prepared matrices and depths; nothing culled
    // below the top joints (every step's decision skipped).
    bool _preparedReshape = false;
    bool _preparedPlain = false;
};

class ActorCull
{
public:
    /** Whether the visitor can take the actor as one: its own class (a subclass may draw otherwise), and no
      * occluders or state frustums in the current culling set (they need each drawable's box in its own frame). */
    static bool canCullAsOne(osgUtil::CullVisitor& cv);
    /** Whether the visitor computes near and far from primitives (reading its current culling set's frustum, which
      * the calls made before entering the actor would not hold). */
    static bool nearFarFromPrimitives(const osgUtil::CullVisitor& cv);

    /** Culls the children of the actor node the visitor is in now (its model-view matrix on top of the stack),
      * with the state the caller acquired, from what prepare() made for this visitor or, if it made nothing for
      * what the visitor holds now, after preparing it here. versions: the actor's counters now. */
    ActorCull(osgUtil::CullVisitor& cv, ActorCullState& state, osg::Group& actor,
              const ActorCullState::Versions& versions);

    /** For an actor (culled as one, no cull callback or state set, a relative frame) the visitor is about to enter
      * (ActorNode::accept()), with the state acquired: if its last cull's calls hold for what the visitor holds now
      * (the key with the actor's model-view matrix as the visitor will compute it, the same counters and a current
      * plan), none of them traverses a subtree in the actor's own frame (which would need that frame on the
      * visitor's stacks; one below a joint pushes the joint's matrix) and near and far are not computed from
      * primitives, tests the actor's bound as CullVisitor::apply(osg::Transform&) does
      * and, if it is seen, makes the calls again and merges the near and far its drawables gave (the same: the same
      * matrices); true then. false, having made no call, where the visitor must enter the actor. Where the actor is
      * seen, seenModelView points to its model-view matrix (in the state, while held) after the call, and is left as
      * it was otherwise; so for the two below. */
    static bool replayBeforeEntering(osgUtil::CullVisitor& cv, ActorCullState& state, osg::MatrixTransform& actor,
                                     const ActorCullState::Versions& versions, const osg::Matrixd*& seenModelView);
    /** The same for an actor that moved (its pose or its place): where its last cull's calls keep their shape for
      * what the visitor holds now (the same plan and view but for the actor's model-view matrix, no test needed
      * below its top joints, no depth not a number, near and far not computed from primitives, and, where they are
      * computed from bounding volumes, the same drawables outside the frustum or behind the eye), tests the actor's
      * bound as the visitor would and, if it is seen, makes them again with the new matrices and depths
      * (replayReshaped()) and merges the near and far gathered with the new matrices; true then. Otherwise false,
      * having made no call, the cull left prepared for the visitor entering the actor. */
    static bool replayReshapedBeforeEntering(osgUtil::CullVisitor& cv, ActorCullState& state,
                                             osg::MatrixTransform& actor, const ActorCullState::Versions& versions,
                                             const osg::Matrixd*& seenModelView);
    /** For an actor whose cull an ActorGroup prepared on its threads for this visitor (the state held by it), which
      * the visitor is about to enter (ActorNode::accept(); culled as one, no cull callback or state set, a relative
      * frame): where the preparation holds for what the visitor holds now and its calls need neither the actor's
      * frame on the visitor's stacks (no subtree traversed ordinarily in the actor's own frame; those below a joint
      * push the joint's matrix) nor its culling set (near and far not computed from primitives), tests the actor's
      * bound as CullVisitor::apply(osg::Transform&) does and, if it is seen, makes the calls; true then. Otherwise
      * false, having made no call: the visitor enters the actor and finds the cull prepared. Saves the visitor's pushes and pops of the actor's matrix and culling set, which on
      * the group's threads are work left on the cull thread. */
    static bool cullPreparedBeforeEntering(osgUtil::CullVisitor& cv, ActorCullState& state,
                                           osg::MatrixTransform& actor, const ActorCullState::Versions& versions,
                                           const osg::Matrixd*& seenModelView);
    /** For the look-ahead of a crowd's cull: asks for the render leaf the visitor will reuse `ahead` leaves from
      * now (from those it kept from its previous cull), which the replay of an actor culled after this one sets. */
    static void prefetchReusedLeaf(const osgUtil::CullVisitor& cv, unsigned ahead);

private:
    using Step = ActorCullPlan::Step;
    using Call = ActorCullState::Call;

    /** For replayReshapedBeforeEntering() and cullPreparedBeforeEntering(): the calls of the cull prepared, without
      * the visitor in the actor (entry: where it would enter it, the model-view matrix on top of its stack). */
    ActorCull(osgUtil::CullVisitor& cv, ActorCullState& state, osg::Group& actor,
              const ActorCullState::Versions& versions, const osg::Matrixd& entry);
    /** The calls of the cull prepared for this visitor (a replay, the kept calls reshaped, or the plan followed),
      * kept for the next cull with where the visitor entered the actor (entry; null if not known). */
    void makePreparedCalls(const ActorCullState::Versions& versions, const osg::Group& actor,
                           const osg::Matrixd* entry);
    /** The actor's model-view matrix as CullVisitor::apply(osg::Transform&) will compute it (the same bits). */
    static osg::Matrixd modelViewOnEntering(osgUtil::CullVisitor& cv, osg::MatrixTransform& actor);
    /** What the constructors leave for the next cull once the calls are made: the calls and matrices kept for
      * the key and counters prepared, and where the visitor entered the actor (entry; null if not known). */
    void keepCalls(const ActorCullState::Versions& versions, const osg::Group& actor, const osg::Matrixd* entry);

    void replay() { replayCalls(_cv, _state._calls); }
    static void replayCalls(osgUtil::CullVisitor& cv, const std::vector<Call>& calls);
    static void replayCall(osgUtil::CullVisitor& cv, const Call& call);
    /** The kept calls made again, each leaf with this cull's matrix and depth (and a batch of this cull's matrices,
      * with the same entries): their shape holds (ActorCullState::prepare() decided it). */
    void replayReshaped();
    /** Notes what replayReshaped() needs of the calls cull() just made, if their shape holds for other matrices. */
    void keepLeafSources();
    /** The plan followed afresh from the prepared decisions, every call kept for the next frame. */
    void cull();
    /** Keeps where the visitor entered the actor (entry, null if not known) for the calls just kept
      * (ActorCullState::_entryModelView). */
    void noteEntry(const osg::Group& actor, const osg::Matrixd* entry);
    void addDrawable(const Step& step, unsigned stepIndex, osg::Polytope::ClippingMask planes);
    void traverseOrdinarily(const Step& step);

    // Near and far from primitives. The visitor queues a drawable whose box may widen them with the planes its
    // culling set in the drawable's frame holds active where it meets it (Polytope::getResultMask(): those the last
    // frustum test there found the bound across; none: the box's corners are taken as they are), and searches the
    // drawable's triangles against those planes. So the tests the visitor makes in each frame (the spheres of
    // joints and geodes, the drawables' boxes, with their masks pushed and popped) are made here, in the same order,
    // on polytopes made as its culling sets are, and each drawable's near and far asked with the planes it would
    // hold.
    /** The frame's frustum: the visitor's culling set's for the actor's own (frame 0), the one made here below. */
    osg::Polytope& frameFrustum(unsigned frame)
    {
        return frame ? _state._jointFrustums[frame] : _cv.getCurrentCullingSet().getFrustum();
    }
    /** A JOINT or GEODE step met (the step's decision not yet applied): the visitor's test of its sphere and, where
      * the visitor goes on into it, its mask pushed (and a joint's frustum made). */
    void enterFrustum(const Step& step, std::size_t stepIndex);
    void leaveFrustum(const Step& step, std::size_t stepIndex);
    /** Whether the visitor makes no test at the step: below a subtree it found outside, or the node masked out. */
    bool frustumSkips(const Step& step, std::size_t stepIndex) const;
    /** The frame (joint + 1; 0 the actor's) of the culling set the visitor tests a step's node in: a joint's node,
      * entered or left, in its parent's, a geode in its joint's. */
    unsigned frustumFrameOf(const Step& step) const;
    /** A DRAWABLE step met: the visitor's test of its box; the planes then active. */
    osg::Polytope::ClippingMask testDrawableBox(const Step& step, std::size_t stepIndex);
    /** CullVisitor::updateCalculatedNearFar() for the drawable with the planes of its frame's frustum given (that
      * frustum's active-plane bits): its billboard form, which takes the planes from the projection's culling set
      * (in its current mask) moved into the matrix's frame and queues the drawable when the current culling set
      * holds any plane active, is asked with both set to these planes for the call. */
    bool updateNearFarWithPlanes(const osg::Matrixd& modelView, osg::Drawable& drawable, unsigned frame,
                                 osg::Polytope::ClippingMask planes);
    /** The frame's model-view matrix as the render graph holds it, made at its first use this cull. */
    osg::RefMatrix* leafMatrix(unsigned frame);

    // The state sets wanted on the visitor's stack, pushed and popped only when a leaf or a traversal needs them:
    // the geodes under an actor's joints mostly carry one state set, and a pop followed by a push of the same
    // set leaves the visitor where it was.
    // How many state sets at the bottom of the wanted ones are those on the visitor's stack (_statesInCommon) is
    // kept as they are wanted and unwanted, so that a drawable wanting what is pushed already (most do) finds it
    // without comparing the two lists.
    void wantState(osg::StateSet* state)
    {
        std::vector<osg::StateSet*>& wanted = _state._wantedStates;
        const std::vector<osg::StateSet*>& applied = _state._appliedStates;
        if (_statesInCommon == wanted.size() && wanted.size() < applied.size() && applied[wanted.size()] == state)
            ++_statesInCommon;
        wanted.push_back(state);
    }
    void unwantState()
    {
        _state._wantedStates.pop_back();
        _statesInCommon = std::min(_statesInCommon, _state._wantedStates.size());
    }
    /** Pushes and pops what the visitor's stack needs to hold the wanted state sets: nothing, mostly, found inline. */
    void applyWantedStates()
    {
        if (_statesInCommon == _state._wantedStates.size() && _statesInCommon == _state._appliedStates.size()) return;
        changeToWantedStates();
    }
    void changeToWantedStates();

    void call(Call::Kind kind, osg::Referenced* object, osg::RefMatrix* matrix = nullptr, float depth = 0.0f,
              const osg::Matrixd* modelView = nullptr)
    {
        _state._calls.push_back({kind, depth, object, matrix, modelView});
        if (kind == Call::TRAVERSE) _state._callsTraverse = true;
    }

    /** The batch open for the current state graph, or null. */
    JointDrawBatch* openBatch(osgUtil::StateGraph* graph) const;
    void closeBatch(osgUtil::StateGraph* graph);

    osgUtil::CullVisitor& _cv;
    ActorCullState& _state;
    const ActorCullPlan* _plan;
    /** Near and far computed, each drawable's asked of the visitor as it is added (not gathered by prepare()). */
    bool _nearFarByVisitor;
    /** Near and far from primitives: the visitor's frustum tests followed (frameFrustum()). */
    bool _planesTracked = false;
    /** The steps before it are in a subtree whose sphere the visitor found outside the frustum: it tests nothing
      * there. */
    std::size_t _untestedUntil = 0;
    JointModelViews* _modelViews;
    /** The batches this actor is filling, by state graph: a drawable goes into its graph's open batch, which is
      * closed when anything else may land in that graph (a drawable that is not batched, an ordinary traversal),
      * so the graph's leaves keep the order the ordinary traversal gives them. */
    struct OpenBatch
    {
        osgUtil::StateGraph* graph;
        JointDrawBatch* batch;
    };
    static constexpr unsigned kMaxOpenBatches = 8;
    OpenBatch _open[kMaxOpenBatches];
    unsigned _numOpen;
    /** The wanted state sets' first ones that are on the visitor's stack, in the same order (both lists start a
      * cull empty). */
    std::size_t _statesInCommon = 0;
};

} // namespace detail
} // namespace osgActor

#endif
