// Internal to the library (not installed, NOT API): the cull of an InstancedActorGroup's actors (issue 28).
//
// Per cull, every actor child that can be drawn instanced (its own class, culled as one, and a cull plan, the one its
// cull as one keeps (ActorCullPlan), with nothing for the ordinary traversal, no state set on a joint, and state sets
// on geodes and drawables that light as the instanced program lights) is culled as the ordinary traversal would cull
// it, following its plan as ActorCull does (its mask and bound; each joint's and geode's mask and small-feature test in
// its frame; while near and far are computed, each drawable's box against the frustum but below a top joint whose
// sphere lies wholly inside it, and near and far from it, gathered per actor (from bounding volumes: near and far from
// primitives are culled ordinarily, InstancedActorGroup)), its joints' model-view matrices composed with the visitor's
// own products (CullArithmetic.h), and each drawable that survives adds one instance, its joint's model-view matrix, to
// the batch of its (geode state set, drawable). An actor of rigid parts whose cull would test nothing below its top
// joints (no mask rules out a node, no small feature below them, and, while near and far are computed, every top
// joint's sphere wholly inside the frustum, so that no drawable's box is tested) adds its drawables from its plan's
// compiled list in one loop, with their near and far in the same loop, in the order and with the arithmetic the steps
// would (addPlainInstances()). The actors that cannot be taken so get the ordinary traversal, in child order. Then
// each batch becomes one leaf: an InstancedDraw of the drawable for all its instances, under the geode's and the
// drawable's state sets and the frame's state set (the program and the texture buffer of all instances' matrices, as
// floats, 4 texels each). A skinned mesh in the actor's frame (InstancedSkin.h) adds one instance to the
// batch of its (geode state set, mesh): its model-view matrix and its palette, drawn by one instanced draw of the
// mesh's bind-pose geometry under the mesh's instanced program, in the same texture buffer after the rigid parts'
// matrices.
//
// The matrices of a frame live in an InstancedFrame taken from a pool: one the render graph no longer holds (every
// draw of it held by the pool alone), so that with osgViewer drawing on another thread the cull of the next frame
// never writes what the draw of this one reads (each frame its own texture buffer).
//
// An actor that did not change since the cull before (its counters, its model-view matrix, the view) adds the
// instances it kept (ActorCullState::InstancedVerdict) rather than being culled again, and, with near and far
// computed from bounding volumes, merges the near and far its drawables gave into the visitor's; where the frame's buffer still
// holds them at the texels this cull gives them, nothing is written, and a frame whose cull wrote nothing is not
// marked for upload. The culls are numbered, and the actor keeps the run of culls, one after the other, that added
// its instances at the same texels; a frame knows which cull took it last and whether its buffer changed since
// (InstancedFrame::beginWrites()). So a still crowd before a still camera writes and uploads nothing, whether the
// viewer draws each frame before the next cull (one frame, culled again) or draws on a thread of its own while the
// next frame is culled (osgViewer's DrawThreadPerContext: two frames or more, taken in turn, each written once).
//
// With an ActorGroup's threads (from its getMinActorsForParallelCull() actors on), each actor child's part of the cull
// runs on them, with the same code, and the result is the serial cull's: InstancedCullParallel.cpp says how.
#ifndef OSGACTOR_DETAIL_INSTANCEDCULL_H
#define OSGACTOR_DETAIL_INSTANCEDCULL_H 1

#include <osgActor/SkinningShaders>
#include <osgActor/detail/ActorCull.h>
#include <osgActor/detail/ActorCullPlan.h>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/InstanceBufferLimit.h>
#include <osgActor/detail/InstancedDraw.h>

#include <osg/Image>
#include <osg/Matrixd>
#include <osg/StateSet>
#include <osgUtil/CullVisitor>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

namespace osgActor {

class ActorNode;
class WorkerPool;
class SkinnedMesh;
class SkinnedMeshInstance;

namespace detail {

/** The texture buffers of one frame's instance data and the draws that read them. Buffer 0 is the one the cull
  * writes; a frame whose data is more than one buffer may hold (InstanceBufferLimit) is drawn from buffers 1 and on,
  * each a window of buffer 0's texels within the limit (its image points into buffer 0's), so that no instance is
  * copied whatever the limit. */
class InstancedFrame : public osg::Referenced
{
public:
    InstancedFrame(osg::StateSet* programState, unsigned textureUnit, InstanceBufferLimit* limit);

    /** Whether the render graph holds none of its draws. */
    bool isFree() const;
    /** Room for texels RGBA32F texels in buffer 0; what was written before is lost if the buffer grows. */
    float* reserveTexels(unsigned texels);
    /** The same, keeping what was written. */
    float* growTexels(unsigned texels);
    /** Buffer i (1 and on), made on first use, made the window of texels texels of buffer 0 from its texel first
      * (within buffer 0's room), marked for upload where it was another. Valid until buffer 0 is reserved or grown
      * again. */
    void setWindow(unsigned i, unsigned first, unsigned texels);
    /** The draw for batch i, made on first use. */
    InstancedDraw* draw(unsigned i);
    /** Marks every buffer's texels (buffer 0's and the windows', in use or not) written, for upload. */
    void dirtyAll();
    /** What buffer 0 holds is numbered anew for each cull that takes the frame (taken()), and wherever what was
      * written moves or is lost (moved(): its texels reserved anew, a batch moved). Texels written while it was n are
      * there still while it is n + 1, where the cull finds them at the same place (beginWrites()). */
    void taken() { ++_contents; }
    void moved() { ++_contents; }
    /** A cull that took the frame begins writing (its buffer placed), numbered cull by the group's cull state: the
      * number of the frame's cull before, whose texels, from its own beginWrites() on, buffer 0 holds still (no cull
      * took the frame between, nothing moved or was lost since), or 0. */
    std::uint64_t beginWrites(std::uint64_t cull);
    /** Buffer i and the rigid parts' program. */
    osg::StateSet* getStateSet(unsigned i = 0) const { return _buffers[i].stateSet.get(); }
    /** Buffer i alone, for the skinned meshes' draws, under their own programs. */
    osg::StateSet* getBufferStateSet(unsigned i = 0) const { return _buffers[i].bufferStateSet.get(); }

    /** As osg::Node's: the buffers' texture objects. */
    void resizeGLObjectBuffers(unsigned maxSize);
    void releaseGLObjects(osg::State* state) const;

protected:
    ~InstancedFrame() override = default;

private:
    struct Buffer
    {
        osg::ref_ptr<osg::Image> texels;
        osg::ref_ptr<osg::StateSet> stateSet;
        osg::ref_ptr<osg::StateSet> bufferStateSet;
    };
    void addBuffer();

    osg::ref_ptr<osg::StateSet> _programState;
    unsigned _textureUnit;
    osg::ref_ptr<InstanceBufferLimit> _limit;
    std::vector<Buffer> _buffers;
    std::vector<osg::ref_ptr<InstancedDraw>> _draws;
    std::uint64_t _contents = 0;       // the number of what buffer 0 holds (taken(), moved())
    std::uint64_t _writesContents = 0; // _contents when the last cull began writing (beginWrites())
    std::uint64_t _writesCull = 0;     // that cull's number
};

/** What an InstancedActorGroup keeps from one cull to the next: the pool of frames and the cull's working space. One
  * cull visitor at a time (tryAcquire()). */
class InstancedCullState : public osg::Referenced
{
public:
    InstancedCullState();

    bool tryAcquire() { return !_busy.test_and_set(std::memory_order_acquire); }
    void release() { _busy.clear(std::memory_order_release); }

    /** What the last finished cull did (a copy made as it ends, under a lock: another camera's cull thread may be
      * counting the next while the application reads): actors drawn instanced (of them, those whose instances were added again, kept, and
      * those added from their plan's compiled list, InstancedCull::addPlainInstances()) and ordinarily, instanced
      * draws of rigid parts and of skinned meshes and the instances they drew, the texture buffers the draws read and
      * the texels one could hold. */
    struct Statistics
    {
        unsigned actorsInstanced = 0;
        unsigned actorsOrdinary = 0;
        unsigned actorsOutOfView = 0;
        unsigned actorsKept = 0;
        unsigned actorsCompiled = 0;
        unsigned draws = 0;
        unsigned instances = 0;
        unsigned skinnedDraws = 0;
        unsigned skinnedInstances = 0;
        unsigned buffers = 0;
        unsigned texelLimit = 0;
    };
    Statistics getStatistics() const
    {
        std::lock_guard<std::mutex> lock(_publishedMutex);
        return _published;
    }

    /** The texels one buffer may hold: the contexts' limits, and a cap (0: none). */
    InstanceBufferLimit& getBufferLimit() { return *_limit; }

    /** As osg::Node's: the frames' texture buffers. */
    void resizeGLObjectBuffers(unsigned maxSize);
    void releaseGLObjects(osg::State* state) const;

protected:
    ~InstancedCullState() override = default;

private:
    friend class InstancedCull;

    /** What decides whether an actor of a plan can be drawn instanced, found once per plan (plans are rebuilt, not
      * changed, when what they were made from changes): no step for the ordinary traversal, no state set on a joint,
      * drawables InstancedDraw draws, skinned meshes InstancedSkin may take; and the distinct state sets of its geodes,
      * drawables and skinned meshes, whose contents OSG lets change in place, so checked at every cull
      * (isInstanceableState() or InstancedSkin::isInstanceableState(), once per state set per cull). */
    struct PlanVerdict
    {
        osg::ref_ptr<const ActorCullPlan> plan; // held, so that no other plan is made at its address
        bool plain = true;
        std::vector<const osg::StateSet*> states;
        std::vector<const osg::StateSet*> skinStates;
        /** Per step, for its drawables and skinned meshes: the batch it adds to (batches are kept, so the indices stay
          * valid). */
        std::vector<unsigned> batchOfStep;
        /** The batches of its skinned meshes, in step order. */
        std::vector<unsigned> skinBatches;
        /** Its ORDINARY steps other than skinned meshes, in step order: nodes below a joint or in the actor's frame
          * (not in a geode) that the visitor traverses itself, with that frame's model-view matrix pushed, while the
          * rest of the actor is instanced (traverseSubtrees()); their batchOfStep is kSubtree. For subtree k, the
          * skeleton nodes above it, the actor's child first, are subtreePath[subtreePathStart[k]] up to
          * subtreePath[subtreePathStart[k + 1]] (the visitor's node path holds them in the ordinary traversal). */
        static constexpr unsigned kSubtree = ~0u;
        std::vector<unsigned> subtrees;
        std::vector<unsigned> subtreePathStart{0u};
        std::vector<osg::Node*> subtreePath;
        /** A plan of rigid parts only, compiled for the cull that need test nothing below its top joints
          * (addPlainInstances()): its drawables in step order, each with its frame and batch, and the batches with
          * their instances per actor. */
        struct PlainInstance
        {
            unsigned frame; // the joint's + 1
            unsigned batch;
            const osg::Drawable* drawable;
        };
        bool compiled() const { return plain && skinBatches.empty(); }
        std::vector<PlainInstance> plainInstances;
        std::vector<std::pair<unsigned, unsigned>> instancesPerBatch;
    };
    /** The drawables of one (geode state set, drawable) or (geode state set, skinned mesh) and their instances' data
      * this cull: a rigid part's model-view matrices (4 texels, 16 floats, OSG's rows one after the other), or a
      * skinned mesh's matrices and palettes (InstancedSkin::texelsPerInstance()). They are written where the draw
      * reads them, in the frame's texture buffer, in a region as large as the batch's data of the previous cull; those
      * that do not fit wait in overflow, and the batch is moved to the buffer's end before it is drawn. */
    struct Batch
    {
        const osg::StateSet* geodeState = nullptr;
        const osg::Geometry* drawable = nullptr;
        SkinnedMesh* mesh = nullptr;
        /** Texels per instance. Skinned: this cull's InstancedSkin::texelsPerInstance() (0: the mesh cannot be drawn
          * instanced), once found (texelsKnown); the last cull's until then. Rigid: 4. */
        unsigned texels = 4;
        bool texelsKnown = true;
        unsigned base = 0;     // the region's first texel in the buffer
        unsigned capacity = 0; // the region's size in texels
        unsigned count = 0;    // this cull's instances
        std::vector<float> overflow;
    };
    struct BatchKey
    {
        const osg::StateSet* geodeState;
        const osg::Drawable* drawable;
        bool operator==(const BatchKey& other) const
        {
            return geodeState == other.geodeState && drawable == other.drawable;
        }
    };
    struct BatchKeyHash
    {
        std::size_t operator()(const BatchKey& key) const
        {
            return std::hash<const void*>()(key.geodeState) ^ (std::hash<const void*>()(key.drawable) << 1);
        }
    };

    std::atomic_flag _busy;
    /** Tells this state from every other, for the verdict an actor keeps (ActorCullState::InstancedVerdict). */
    const std::uint64_t _serial;
    std::vector<osg::ref_ptr<InstancedFrame>> _frames;
    /** The culls so far: the last one's number (ActorCullState::InstancedVerdict::placedSince). */
    std::uint64_t _culls = 0;
    osg::ref_ptr<InstanceBufferLimit> _limit;
    /** Whether the notices of a frame split over several buffers, and of a mesh whose instance alone is more than a
      * buffer holds, were given (once per group). */
    bool _splitNoticed = false;
    bool _oversizeNoticed = false;
    /** The statistics the cull in progress counts, and those of the last finished one. */
    Statistics _statistics;
    Statistics _published;
    mutable std::mutex _publishedMutex;
    std::unordered_map<const ActorCullPlan*, PlanVerdict> _verdicts;
    // The working space of one cull, kept so that a steady frame allocates nothing.
    /** A run of an actor's instances of one batch in the parallel cull (InstancedCull::cullInParallel()), and where
      * the first goes among the batch's instances of the cull (given in child order, between the passes). */
    struct ActorRun
    {
        unsigned batch;
        unsigned count;
        unsigned first;
    };
    /** Floats appended without being set first (a std::vector sets them): the instances' data a thread's actors add
      * in the parallel cull, written where appended. */
    class InstanceData
    {
    public:
        std::size_t size() const { return _size; }
        const float* data() const { return _floats.get(); }
        void clear() { _size = 0; }
        /** n more floats, for the caller to write (valid until the next extend()). */
        float* extend(std::size_t n)
        {
            if (_size + n > _capacity) grow(_size + n);
            float* out = _floats.get() + _size;
            _size += n;
            return out;
        }
        /** The first size floats kept, the others dropped. */
        void shrink(std::size_t size) { _size = size; }

    private:
        void grow(std::size_t least);
        std::unique_ptr<float[]> _floats;
        std::size_t _size = 0;
        std::size_t _capacity = 0;
    };
    /** One thread's working space for the actors it culls; the cull thread's, the first, is the serial cull's. On a
      * cache line of its own, as the threads grow its lists. */
    struct alignas(64) ActorScratch
    {
        std::vector<std::pair<const osg::StateSet*, bool>> stateVerdicts;     // this cull's
        std::vector<std::pair<const osg::StateSet*, bool>> skinStateVerdicts; // this cull's
        std::vector<const SkinnedMeshInstance*> skinInstances; // the actor's, in step order
        std::vector<osg::Matrixd> modelViews;     // per frame: the actor's (0), each joint's (joint + 1)
        FramePixelSizeVectors pixelSizeVectors;   // per frame, made where a test needs it
        std::vector<osg::Plane> actorFramePlanes; // the frustum's planes in the actor's frame (cullSteps())
        // The parallel cull's: the runs of instances of the thread's actors and the instances' data, one after the
        // other; the model-view matrices of the actors whose update policy notes the view; whether its second pass
        // wrote any texel.
        std::vector<ActorRun> runs;
        InstanceData data;
        std::vector<osg::Matrixd> seenModelViews;
        bool wrote = false;
        /** The subtrees its actors' cull reached (the serial cull's: the actor's being culled), for the visitor to
          * traverse on the cull thread: which verdict's subtree, in which frame. */
        struct SubtreeVisit
        {
            const PlanVerdict* verdict;
            unsigned subtree;
            osg::Matrixd modelView;
        };
        std::vector<SubtreeVisit> subtreeVisits;
    };
    std::vector<ActorScratch> _scratch; // per thread, at least one
    /** What the parallel cull's first pass found for an actor child, for the passes that follow (its instances' runs
      * and data in a thread's scratch). */
    struct ActorOutcome
    {
        enum Kind : unsigned char
        {
            OUT_OF_VIEW,
            ORDINARY,  // the ordinary traversal
            INSTANCED, // culled now
            KEPT,      // its kept instances added again
            DEFERRED   // what a worker may not decide: culled on the cull thread, in child order
        };
        Kind kind;
        bool wrote;      // data written (the frame marked for upload)
        bool compiled;   // its instances added from its plan's compiled list
        unsigned thread; // whose scratch holds its runs and data
        unsigned firstRun;
        unsigned numRuns;
        unsigned seen; // its model-view matrix among the thread's seenModelViews, or ~0u
        unsigned firstSubtree; // its subtrees among the thread's subtreeVisits
        unsigned numSubtrees;
        std::size_t firstData;
        /** With near and far from bounding volumes, merged into the visitor's in this order, where the actor comes
          * among the children: its skinned meshes' (the visitor's own updates, gathered), then its drawables'. */
        DepthRange skinDepths;
        DepthRange depths;
    };
    std::vector<ActorOutcome> _outcomes; // per actor child
    /** The group's children that are exactly ActorNode, by index, and whether one is a child twice, for the
      * children of the version _childrenVersion (listed: _childrenListed). */
    std::vector<unsigned> _actorChildren;
    bool _childrenRepeat = false;
    bool _childrenListed = false;
    unsigned _childrenVersion = 0;
    /** Per batch, for the parallel cull: the texel its instances are moved to where they outgrew its region, or ~0u. */
    std::vector<unsigned> _movedBase;
    std::vector<Batch> _batches; // in order of first use; emptied, not freed, per cull
    std::unordered_map<BatchKey, unsigned, BatchKeyHash> _batchOfKey;
    InstancedFrame* _frame = nullptr; // this cull's, if any batch has a region
    float* _texels = nullptr;         // its buffer
    /** The view of the last cull (the key of an actor culled as one, but for the actor's model-view matrix), and
      * its number, which changes with it. */
    ActorCullState::Key _viewKey;
    std::uint64_t _view = 0;
    /** The model-view matrix the visitor entered the group with at the last cull, and its number, which changes
      * with it (ActorCullState::InstancedVerdict::entry). */
    osg::Matrixd _entryModelView;
    std::uint64_t _entry = 0;
};

class InstancedCull
{
public:
    /** Culls the children of group (the visitor's model-view matrix is the group's): the actors that can be, into
      * instanced draws under programState (the program and the sampler on textureUnit), the others ordinarily. */
    InstancedCull(osgUtil::CullVisitor& cv, InstancedCullState& state, osg::Group& group, osg::StateSet* programState,
                  unsigned textureUnit);
    /** The group's threads for the parallel cull: the pool (taken for this cull), from how many actor children on,
      * and the version of the group's children (ActorGroup::getChildrenVersion()). */
    struct Threads
    {
        WorkerPool* pool;
        unsigned minActors;
        unsigned childrenVersion;
    };
    /** The same, each actor's part of the cull on the threads where the pool is given and the children are at least
      * threads.minActors actors (cullInParallel()); the render graph, the frame's texels and the statistics those of
      * the cull on this thread alone. */
    InstancedCull(osgUtil::CullVisitor& cv, InstancedCullState& state, osg::Group& group, osg::StateSet* programState,
                  unsigned textureUnit, const Threads& threads);
    /** Whether the actors were culled on the threads. */
    bool culledInParallel() const { return _culledInParallel; }

    /** Whether a state set (a geode's or a drawable's, or none) lights its drawables as the instanced program does:
      * no program, textures, uniforms or render bin of its own, and no attribute but a material without colour
      * tracking; lighting not turned off. */
    static bool isInstanceableState(const osg::StateSet* state);

private:
    using Step = ActorCullPlan::Step;
    using ActorOutcome = InstancedCullState::ActorOutcome;

    /** A worker's copy of the cull, for the actors one thread culls in the parallel cull's first pass: the same view
      * and settings, the thread's scratch, nothing to the visitor. */
    InstancedCull(const InstancedCull& cull, unsigned thread);

    /** The children one after the other, on this thread. */
    void cullSerially(osg::Group& group);
    /** The parallel cull, where it may be (enough actors, none a child twice):
      * first, on the threads, each actor child's part that touches neither the visitor nor what other actors share
      * (its bound, its verdict, its model-view matrices and tests, its instances' data into the thread's scratch);
      * then, on this thread, in child order, what is left (the ordinary traversals, the other children, the actors
      * a worker could not decide, the near and far merged, each actor's place among its batches' instances); then, on
      * the threads, each actor's data written at its place in the frame's buffer. false, nothing done, where not. */
    bool cullInParallel(osg::Group& group, const Threads& threads);
    /** Lists the group's actor children for its children's version, unless listed already. */
    void listActorChildren(osg::Group& group, unsigned childrenVersion);
    /** Each skinned batch's texels per instance for this cull and its geometry's box, found before the threads read
      * them. */
    void prepareSkinnedBatches();
    /** The first pass for one actor child, into outcome, on a thread (or on the cull thread for one DEFERRED). */
    void cullChildInto(ActorNode& actor, ActorOutcome& outcome);
    /** The last pass for one actor: its instances written where its runs go, its cull state given back. */
    void writeActor(ActorNode& actor, const ActorOutcome& outcome, bool& wrote) const;
    /** count instances of a batch, the first the batch's instance first, from data: in its region where it has room
      * for them, as the serial cull adds them, and where the batch was moved if it outgrew its region. kept: the kept
      * run they are, or null; inFrame: whether the kept instances lie in this cull's buffer (keptInFrame()). */
    void writeRun(unsigned batch, unsigned first, unsigned count, const float* data,
                  ActorCullState::InstancedVerdict::Run* kept, bool inFrame, bool& wrote) const;
    /** Counts an actor of the kind into the statistics (the serial cull), or notes it in its outcome. */
    void tally(ActorOutcome::Kind kind);
    /** Whether the actor is out of view (its mask, its bound) as the visitor finds it on its way in. */
    bool isOutOfView(ActorNode& actor);

    /** Whether the actor node itself lets its children be culled here: its own class, culled as one, no cull
      * callback or state set, a relative frame, culling on. */
    static bool isPlainActor(const ActorNode& actor);
    /** Culls one actor child: instanced if its plan allows, ordinarily otherwise. */
    void cullChild(ActorNode& actor);
    /** What decides whether an actor of the plan can be drawn instanced now, or null if it cannot; kept: where the
      * actor keeps it for the next cull. */
    const InstancedCullState::PlanVerdict* instanceableVerdict(const ActorCullPlan& plan,
                                                               ActorCullState::InstancedVerdict& kept);
    /** The verdict if its state sets light as the instanced program does now, or null. */
    const InstancedCullState::PlanVerdict* instanceableNow(const InstancedCullState::PlanVerdict& verdict);
    /** The batch of a (geode state set, drawable) or (geode state set, skinned mesh), made on first use. */
    unsigned batchOf(const osg::StateSet* geodeState, const osg::Geometry* drawable, SkinnedMesh* mesh);
    bool isInstanceableNow(const osg::StateSet* state);
    bool isSkinInstanceableNow(const osg::StateSet* state);
    /** Whether each of the actor's skinned meshes (the verdict's) draws it instanced this cull: their states in
      * _skinInstances, in step order. */
    bool canInstanceSkins(ActorNode& actor, const InstancedCullState::PlanVerdict& verdict);
    /** Culls an instanceable actor by its plan and adds its drawables' instances; the actor's bound was found
      * visible. */
    void cullActor(ActorNode& actor, const InstancedCullState::PlanVerdict& verdict,
                   ActorCullState::InstancedVerdict& kept, const ActorCullState::Versions& versions);
    /** The plan's steps followed one by one, as ActorCull::cull() follows them, its joints' model-view matrices
      * composed already. */
    void cullSteps(const InstancedCullState::PlanVerdict& verdict);
    /** Adds the plan's step at stepIndex to the verdict's subtrees, with the joints above it. */
    static void noteSubtree(InstancedCullState::PlanVerdict& verdict, unsigned stepIndex);
    /** Notes subtree k of the verdict for traverseSubtrees(), in the frame of its step. */
    void visitSubtree(const InstancedCullState::PlanVerdict& verdict, unsigned k);
    /** The subtrees the actor's cull noted from firstVisit on: to the outcome of the parallel cull, for its pass in
      * child order, or traversed now (traverseSubtrees()). */
    void handOverSubtrees(ActorNode& actor, std::size_t firstVisit);
    /** On the cull thread: the visitor traverses the subtrees an actor's cull noted (count from first in the
      * thread's scratch), each with its frame's model-view matrix pushed and the actor and the skeleton nodes above it
      * on the node path, as the ordinary traversal would. */
    void traverseSubtrees(ActorNode& actor, const InstancedCullState::ActorScratch& scratch, unsigned first,
                          unsigned count);
    /** Compiles, once per verdict, what addPlainInstances() goes by (PlanVerdict::plainInstances and the rest). */
    static void compilePlainInstances(InstancedCullState::PlanVerdict& verdict);
    /** For a compiled plan whose model-view matrices are composed: where this cull would test nothing below the
      * top joints (no mask rules out a node, no top joint is a small feature and the small-feature proof holds below
      * each; with near and far computed and the frustum culling, every top step's sphere wholly inside it, so that no
      * drawable's box is tested; every batch's region has room, nothing recorded), adds each drawable's instance
      * straight from the compiled list, as the steps would add them, with near and far from its box where computed;
      * returns false, having added nothing, where it cannot. */
    bool addPlainInstances(const InstancedCullState::PlanVerdict& verdict);
    /** addPlainInstances()'s writes, each instance where its batch's region has room (it checked), in the buffer
      * texels, from the actor's frames modelViews; near and far gathered into depths, where computed (else null). */
    static void writePlainInstances(const InstancedCullState::PlanVerdict& verdict, const osg::Matrixd* modelViews,
                                    InstancedCullState::Batch* batches, float* texels, DepthRange* depths);
    /** writePlainInstances()'s loop, with near and far gathered (WithDepths) or not, inlined into each of its
      * clones. */
    template <bool WithDepths>
    static void writeEachPlainInstance(const InstancedCullState::PlanVerdict& verdict, const osg::Matrixd* modelViews,
                                       InstancedCullState::Batch* batches, float* texels, DepthRange* depths);
    /** The parallel cull's form of writePlainInstances(): each instance drawn after the one before from out (the
      * thread's scratch), counted into the actor's runs (those of runs from firstRun on); returns the end. */
    static float* appendPlainInstances(const InstancedCullState::PlanVerdict& verdict, const osg::Matrixd* modelViews,
                                       float* out, std::vector<InstancedCullState::ActorRun>& runs,
                                       std::size_t firstRun, DepthRange* depths);
    template <bool WithDepths>
    static float* appendEachPlainInstance(const InstancedCullState::PlanVerdict& verdict,
                                          const osg::Matrixd* modelViews, float* out,
                                          std::vector<InstancedCullState::ActorRun>& runs, std::size_t firstRun,
                                          DepthRange* depths);
    /** The frustum's planes moved into the actor's frame (_scratch->actorFramePlanes), where the visitor tests the
      * top steps' spheres. */
    void moveFrustumIntoActorFrame();
    /** Whether a top step's sphere lies wholly inside the frustum (the planes moved into the actor's frame), so that
      * the visitor tests nothing below it against the frustum. */
    bool isInsideTop(const Step& step) const
    {
        return step.cullingActive && isWhollyInside(step.node->getBound(), _scratch->actorFramePlanes);
    }
    /** Whether the kept instances of an actor with these counters may hold for this cull (its model-view matrix
      * still to compare). */
    bool mayReplay(const ActorCullState::InstancedVerdict& kept, const ActorCullState::Versions& versions) const
    {
        return kept.kept && kept.serial == _state._serial && kept.view == _state._view && kept.versions == versions;
    }
    /** The kept instances of the actor `ahead` actors after the one culled now, asked for (ActorNode's look-ahead
      * stages): at stages 3 and 2, the others costing no call. */
    void prefetchKeptAhead(const osg::Node& node, unsigned ahead) const
    {
        if (ahead == 3 || ahead == 2) prefetchKeptInstances(node, ahead);
    }
    void prefetchKeptInstances(const osg::Node& node, unsigned ahead) const;
    /** Adds the kept instances of an actor that did not change, if they hold for this cull (the actor's model-view
      * matrix in modelViews[0], the kept one where entryKept); in the parallel cull, notes their runs for the passes
      * that follow. */
    bool replayKept(ActorCullState::InstancedVerdict& kept, const ActorCullState::Versions& versions, bool entryKept);
    /** The serial cull's copy of the kept instances into their batches. */
    void addKeptRuns(ActorCullState::InstancedVerdict& kept);
    /** Whether the kept instances lie in this cull's buffer where the last cull of its frame added them: the culls
      * that added them at the same texels, one after the other, reach this one and include the frame's last, whose
      * texels its buffer holds still. */
    bool keptInFrame(const ActorCullState::InstancedVerdict& kept) const
    {
        return kept.placedUntil + 1 == _cullNumber && kept.placedSince <= _frameHolds;
    }
    /** Notes that this cull added the kept runs, each where it was before if samePlaces. */
    void notePlaced(ActorCullState::InstancedVerdict& kept, bool samePlaces) const
    {
        if (!samePlaces || kept.placedUntil + 1 != _cullNumber) kept.placedSince = _cullNumber;
        kept.placedUntil = _cullNumber;
    }
    /** Whether kept.actorModelView is the actor's model-view matrix now, not composed again (its bound counted in
      * versions). */
    bool keptEntry(const ActorNode& actor, const ActorCullState::InstancedVerdict& kept,
                   const ActorCullState::Versions& versions) const;
    bool isMasked(osg::Node::NodeMask mask) const { return isMaskedOut(_traversalMask, _maskOverride, mask); }
    bool isSmallFeature(const osg::BoundingSphere& bound, unsigned frame);
    /** The pixel-size vector of the actor's own frame. */
    const osg::Vec4& actorPixelSizeVector();
    /** insideTop: the drawable is below a top step whose sphere lies wholly inside the frustum (its box untested). */
    void addDrawable(const Step& step, unsigned batch, bool insideTop);
    /** The actor's instance of a skinned mesh, culled as the mesh's own cull culls it. */
    void addSkinned(const SkinnedMeshInstance& instance, unsigned batch);
    /** Where the batch's next count instances go in its region, in this cull's buffer, or null where the region has
      * no room for them. */
    float* roomInRegion(const InstancedCullState::Batch& batch, unsigned count) const
    {
        return roomInRegion(batch, count, _state._texels);
    }
    static float* roomInRegion(const InstancedCullState::Batch& batch, unsigned count, float* texels)
    {
        if ((batch.count + count) * batch.texels > batch.capacity) return nullptr;
        return texels + 4 * (std::size_t(batch.base) + std::size_t(batch.texels) * batch.count);
    }
    /** Where the next instance of a batch goes: its region, or its overflow; in the parallel cull, the thread's
      * scratch (appendInstance()). */
    float* nextInstance(unsigned batch);
    /** The actor's next instance of a batch in the thread's scratch, after its others. */
    float* appendInstance(unsigned batch);
    /** Counts the actor's next instance of a batch into its runs in the thread's scratch. */
    void addToRuns(unsigned batch);
    /** The same into an actor's runs (those of runs from firstRun on). */
    static void countIntoRuns(std::vector<InstancedCullState::ActorRun>& runs, std::size_t firstRun, unsigned batch)
    {
        if (runs.size() > firstRun && runs.back().batch == batch)
            ++runs.back().count;
        else
            runs.push_back({batch, 1u, 0u});
    }
    /** Whether the visitor drops a drawable of this box in a frame of this model-view matrix: its depth not a
      * number. */
    static bool hasNoDepth(const osg::BoundingBox& box, const osg::Matrixd& modelView)
    {
        return box.valid() && osg::isNaN(eyeDepth(box.center(), modelView));
    }
    /** What the visitor does with a drawable of this box that it did not cull against the frustum, in a frame of this
      * model-view matrix: with near and far computed (depths, else null), near and far from its box, the drawable
      * dropped where it lies wholly behind the eye; then dropped where its depth is not a number. Whether it is
      * drawn. */
    static bool isDrawn(const osg::BoundingBox& box, const osg::Matrixd& modelView, DepthRange* depths)
    {
        if (depths && box.valid() && !depths->addBox(box, modelView)) return false;
        return !hasNoDepth(box, modelView);
    }
    /** Gives each batch its region in a frame's buffer, as large as its data of the previous cull. */
    void placeBatches(unsigned textureUnit);
    /** Moves the batches that overflowed their regions to the buffer's end, whole. */
    void gatherOverflow(unsigned textureUnit);
    /** One leaf per batch, with this frame's texture buffer; where the frame's data is more than a buffer holds, one
      * leaf per run of a batch's instances within one of the frame's split buffers. */
    void emitBatches();
    /** Makes windows of buffer 0 within the limit (buffers 1 and on) and emits a leaf per run of a batch's
      * instances within one. */
    void emitSplit(InstancedFrame& frame, unsigned texels);
    /** Sets up the draw of count instances of a batch from texel base of buffer, and emits its leaf. */
    void emitDraw(const InstancedCullState::Batch& batch, InstancedFrame& frame, unsigned drawIndex, unsigned buffer,
                  unsigned base, unsigned count);
    /** Pushes the state sets a batch's drawable is drawn with (the geode's and its own; a skinned mesh's program),
      * adds its leaf, pops them. */
    void emitLeaf(const InstancedCullState::Batch& batch, InstancedDraw& draw, InstancedFrame& frame, unsigned buffer);
    InstancedFrame* acquireFrame(unsigned textureUnit);

    osgUtil::CullVisitor& _cv;
    InstancedCullState& _state;
    osg::StateSet* _programState;
    unsigned _textureUnit;
    /** The working space of the thread culling actors with this object. */
    InstancedCullState::ActorScratch* _scratch;
    /** In the parallel cull, the outcome of the actor being culled (its instances go to the thread's scratch); null
      * in the serial cull (straight to the frame's buffer). */
    ActorOutcome* _outcome;
    /** Whether the actor's cull may make plan verdicts and batches and find batches' texels (this thread's alone):
      * not on a worker, whose actors that need them are DEFERRED. */
    bool _mayDecideShared;
    bool _deferred;
    bool _culledInParallel;
    /** This cull's number, and that of the cull before of the frame the actors' instances go to, whose texels its
      * buffer holds still as the placing of the batches left it (InstancedFrame::beginWrites()), or 0. */
    std::uint64_t _cullNumber;
    std::uint64_t _frameHolds;
    unsigned _traversalMask;
    unsigned _maskOverride;
    bool _smallFeatureCulling;
    /** Near and far computed, from bounding volumes (never from primitives: InstancedActorGroup culls each actor as one
      * then): each instanced actor's drawables' near and far gathered as the visitor gathers them (_actorDepths) and
      * merged into the visitor's once per actor, which gives its values to the bit, and kept with its instances. */
    bool _computeNearFar;
    DepthRange _actorDepths;
    /** In the parallel cull, the actor's skinned meshes' near and far (the serial cull gives them to the visitor). */
    DepthRange _skinDepths;
    bool _frustumCulling;
    float _smallFeaturePixelSize;
    bool _overflowed;
    /** Whether this cull wrote any texel of the frame's buffer (if not, the buffers are uploaded as they were). */
    bool _wroteTexels;
    /** The texels one buffer may hold this cull. */
    const unsigned _texelLimit;
    /** The skinned meshes' program and geometry profile, as the state the visitor culls for has it. */
    const SkinningProfile _profile;
    const ActorCullView _view;
    /** The actor's kept instances being recorded, or null. */
    ActorCullState::InstancedVerdict* _recording;
};

} // namespace detail
} // namespace osgActor

#endif
