// Internal to the library (not installed, NOT API): what the cull of one actor goes through, found once and kept
// (issue 28). ActorCull used to find it every frame, reading every skeleton node's class, children, flags and matrix
// (most of a crowd's frame, since 31,000 nodes do not stay in the caches from one frame to the next). The plan
// lists, in the order the cull visitor would meet them, the actor's plain skeleton nodes, the plain geodes below
// them, their plain drawables, and the subtrees that need the ordinary traversal, with what the cull decided from.
//
// It stays true while nothing it decided from changes:
//  - children added, removed or replaced below the actor or a skeleton node, and a joint hidden or shown: both
//    classes tell their actor (ActorNode::dirtyCullPlan()), so the plan never reads their children or hidden flags;
//  - node masks, state sets, cull callbacks and culling flags, which OSG changes without telling anyone, and the
//    children of geodes, which are the user's: isCurrent() compares them, every frame, with what the plan saw.
//    On a skeleton node they lie in 32 bytes of osg::Node, compared at once, and the reference frame just after
//    them (osg::Transform's first member); most actors' joints have one block alike, and all of them are compared
//    with it together (allBlocksAre()). The cull of the actors before this one asks for those lines ahead, and for
//    the joints' matrices where the actor's last cull composed them.
// A subtree handed to the ordinary traversal is not looked into: the visitor finds what is below it every frame.
#ifndef OSGACTOR_DETAIL_ACTORCULLPLAN_H
#define OSGACTOR_DETAIL_ACTORCULLPLAN_H 1

#include <osgActor/SkeletonNode>
#include <osgActor/detail/CullArithmetic.h>

#include <osg/Drawable>
#include <osg/Geode>
#include <osg/Referenced>
#include <osg/ref_ptr>

#include <cstddef>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace osgActor {
namespace detail {

class ActorCullPlan : public osg::Referenced
{
public:
    /** The plan of the actor's children as they are now. */
    explicit ActorCullPlan(osg::Group& actor);

    /** osg::Node's bytes that hold what the plan compares at a node (its cull callback, culling flags, node mask
      * and state set, next to each other in the class), compared as one block where the layout puts them within
      * it (otherwise field by field, as geodes and drawables are). */
    static constexpr std::size_t kNodeFlagBytes = 32;
    /** Whether nothing the plan decided from that OSG does not report has changed since it was made. */
    bool isCurrent() const;
    /** Asks for the plan's own arrays that isCurrent() and composeModelViews() read, ahead of them. */
    void prefetchChecks() const;
    /** Asks for the nodes' flags that isCurrent() compares (the arrays read, so best once prefetchChecks() is done);
      * matrices: the joints' matrices and the top steps' bounds too, which a cull that is not a replay reads next.
      * With many actors the nodes have left the caches since the update: a crowd's cull asks for them an actor
      * ahead (ActorNode::prefetchCullAhead()). */
    void prefetchCheckedNodes(bool matrices) const;

    /** What the cull does at one step, in the visitor's order. A JOINT or GEODE step opens a subtree that ends
      * at step end (exclusive, its closing step end - 1). */
    enum Kind : unsigned char
    {
        JOINT,      // a plain skeleton node: its frame is joints[joint]
        END_JOINT,
        GEODE,      // a plain osg::Geode in the frame of joint (-1: the actor's)
        END_GEODE,
        DRAWABLE,   // a plain drawable of the geode it is in, in the frame of joint
        ORDINARY    // a node the visitor traverses itself, with the frame of joint pushed
    };
    /** Small: every step is read at every cull of every actor. */
    struct Step
    {
        Kind kind;
        /** The subtree holds an ORDINARY step: the node must be on the visitor's node path, which cull
          * callbacks below may read. */
        bool pathNeeded;
        /** Culling is on at the node (Node::isCullingActive() but for its bound's validity, tested where used). */
        bool cullingActive;
        /** DRAWABLE: neither it nor its state set is DYNAMIC, so it may share a batch's leaf. */
        bool batchable;
        int joint;              // the frame the step's node is in (for JOINT: its own)
        unsigned end;           // JOINT and GEODE: the step after the subtree's end
        osg::Node::NodeMask mask;
        osg::Node* node;        // kept alive by the plan
        osg::StateSet* stateSet;
    };
    /** A plain skeleton node: its matrix (local, the parent joint's frame) composes the frames below it. */
    struct Joint
    {
        SkeletonNode* node;
        int parent; // index into joints; -1: the actor's frame
        // A joint in the actor's frame (parent -1): the distinct plain geodes of its subtree, and whether every
        // joint below it has one of them in its own subtree, so that the subtree's spheres are at least as large
        // as the smallest geode's (smallestGeodeRadiusBelow()).
        unsigned firstGeode;
        unsigned numGeodes;
        bool geodeBelowEveryJoint;
    };

    const std::vector<Step>& getSteps() const { return _steps; }
    const std::vector<Joint>& getJoints() const { return _joints; }
    /** The drawable classes whose drawing the plan may batch: no cull callback, and a class known not to cull in
      * its own way (a subclass such as SkinnedMesh overrides accept() to skin or upload before it is drawn). */
    static bool isPlainDrawable(const osg::Drawable& drawable);
    /** For a joint in the actor's frame: the smallest radius (local units of any rigid frame of its subtree) of a
      * plain geode's sphere below it, which every joint's and geode's sphere below it is at least; false where
      * that does not hold (a joint below without a geode, or a geode with no bound). */
    bool smallestGeodeRadiusBelow(const Joint& joint, double& radius) const;
    /** Each planned joint's model-view matrix, parents first, into modelViews[joint + 1] from the actor's in
      * modelViews[0] (composeModelView()). */
    void composeModelViews(osg::Matrixd* modelViews) const;
    /** For a step the cull keeps: whether it is a joint in the actor's frame below which SmallFeatureProof holds
      * (no small feature), for the actor frame's pixel-size vector, from the shape the joint's node keeps of its
      * subtree. */
    bool provesNoSmallFeatureBelow(const Step& step, const osg::Vec4& actorVector, float pixelSize) const;
    /** The DRAWABLE steps, in order. */
    const std::vector<unsigned>& getDrawableSteps() const { return _drawableSteps; }
    /** The steps at the top (not below another: joints and geodes in the actor's frame), in order. */
    const std::vector<unsigned>& getTopSteps() const { return _topSteps; }
    /** Whether a step gives a subtree the ordinary traversal (which may read or reset the visitor's near and far). */
    bool hasOrdinarySteps() const { return _hasOrdinarySteps; }
    /** Whether such a step is in the actor's own frame (not below a joint): its traversal needs the actor's frame on
      * the visitor's stacks, where one below a joint is traversed with the joint's matrix pushed. */
    bool hasOrdinaryStepsInActorFrame() const { return _hasOrdinaryStepsInActorFrame; }
    /** Whether a cull would test nothing below the top joints' own spheres, so that it culls nothing below them: no
      * joint, geode or drawable ruled out by the visitor's masks, and either no small-feature culling or every step at
      * the top a joint whose sphere is no small feature in the actor's frame (isSmallFeatureAtTop(), the visitor's
      * test there) and below which the proof holds, for the actor frame's pixel-size vector. */
    template <class SmallFeatureTest>
    bool needsNoTestBelowTopJoints(unsigned traversalMask, unsigned nodeMaskOverride, bool smallFeatureCulling,
                                   const osg::Vec4& actorVector, float pixelSize,
                                   SmallFeatureTest&& isSmallFeatureAtTop) const
    {
        for (osg::Node::NodeMask mask : _masks)
            if (isMaskedOut(traversalMask, nodeMaskOverride, mask)) return false;
        if (!smallFeatureCulling) return true;
        if (!_topStepsAllJoints) return false;
        for (unsigned i : _topSteps)
        {
            const Step& step = _steps[i];
            if (step.cullingActive && isSmallFeatureAtTop(step.node->getBound())) return false;
            if (!provesNoSmallFeatureBelow(step, actorVector, pixelSize)) return false;
        }
        return true;
    }

protected:
    ~ActorCullPlan() override = default;

private:
    /** What the plan decided from at one node (each geode and drawable once, however many times the plan meets it:
      * a geode may hang below every joint), as the plan saw it. */
    struct NodeCheck
    {
        const osg::Node* node;
        const osg::StateSet* stateSet;
        const osg::Callback* cullCallback;
        osg::Node::NodeMask mask;
        bool cullingActive;
        unsigned char referenceFrame; // skeleton nodes
        unsigned char dataVariance;   // drawables
        unsigned char kind;           // JOINT, GEODE or DRAWABLE
        unsigned firstChild, numChildren; // geodes: their children in _geodeChildren
    };
    /** What decides batching in a state set (each once), which OSG lets change in place: its render bin and its
      * data variance. */
    struct StateCheck
    {
        osg::ref_ptr<const osg::StateSet> stateSet; // held: it is read at every check
        osg::StateSet::RenderBinMode binMode;
        int binNumber;
        std::string binName;
        bool nestRenderBins;
        osg::Object::DataVariance dataVariance;
    };

    /** What a joint's check compares of its flag block, as the plan saw it. Few distinct ones per plan (most
      * joints: no callback, no state set, the same mask), each kept once. Its reference frame is not kept: a joint
      * checked so is a plain one (isPlainJoint()), whose frame was RELATIVE_RF, so the check is that it still is. */
    struct JointFlags
    {
        /** The node's flag block, its padding bytes zero (NodeFlags::flagMask()). */
        alignas(16) unsigned char nodeFlags[kNodeFlagBytes];
        bool operator==(const JointFlags& other) const;
    };
    struct JointFlagsHash
    {
        std::size_t operator()(const JointFlags& flags) const;
    };
    typedef std::unordered_map<JointFlags, unsigned, JointFlagsHash> JointFlagsIndex;

    /** One allocation, cache-line aligned, holding in turn: each planned joint's node and its parent's index, which
      * composeModelViews() reads; each checked joint's node, where those are not the same (they are, unless
      * osg::Node's layout does not hold a joint's flags in one block); which distinct flags each checked joint had
      * (none where all had the same, as most actors' joints do; a byte each while there are at most 256 distinct
      * ones, else four); the distinct flags; the geodes' and drawables' checks; the geodes' children; the nodes of
      * the steps at the top, whose bounds a cull that is not a replay reads. */
    class PackedChecks
    {
    public:
        void pack(const std::vector<Joint>& joints, const std::vector<const SkeletonNode*>& jointNodes,
                  const std::vector<unsigned>& jointFlagIndices, const std::vector<JointFlags>& jointFlags,
                  const std::vector<NodeCheck>& checks, const std::vector<const osg::Node*>& geodeChildren,
                  const std::vector<const osg::Node*>& topNodes);
        std::size_t numFrames() const { return _numFrames; }
        const SkeletonNode* const* frameNodes() const { return at<const SkeletonNode*>(0); }
        const int* frameParents() const { return at<int>(_frameParentsAt); }
        std::size_t numJoints() const { return _numJoints; }
        const SkeletonNode* const* jointNodes() const { return at<const SkeletonNode*>(_jointNodesAt); }
        bool allAlike() const { return _allAlike; }
        /** Whether every checked joint's flag block and matrix each start a cache line (skeleton nodes an actor
          * built, placed so: PlacedSkeletonNode), so that the block and the reference frame after it are one line
          * and the matrix two. */
        bool linesPlaced() const { return _linesPlaced; }
        bool byteIndices() const { return _byteIndices; }
        const unsigned char* byteFlagIndices() const { return at<unsigned char>(_flagIndicesAt); }
        const unsigned* wordFlagIndices() const { return at<unsigned>(_flagIndicesAt); }
        const JointFlags* jointFlags() const { return at<JointFlags>(_jointFlagsAt); }
        const NodeCheck* checksBegin() const { return at<NodeCheck>(_checksAt); }
        const NodeCheck* checksEnd() const { return checksBegin() + _numChecks; }
        const osg::Node* const* geodeChildren() const { return at<const osg::Node*>(_geodeChildrenAt); }
        const osg::Node* const* topNodesBegin() const { return at<const osg::Node*>(_topNodesAt); }
        const osg::Node* const* topNodesEnd() const { return topNodesBegin() + _numTopNodes; }
        const void* data() const { return _lines.data(); }
        std::size_t bytes() const { return _lines.size() * sizeof(CacheLine); }

    private:
        struct alignas(64) CacheLine
        {
            unsigned char bytes[64];
        };
        template <class T>
        const T* at(std::size_t offset) const
        {
            return reinterpret_cast<const T*>(reinterpret_cast<const unsigned char*>(_lines.data()) + offset);
        }
        std::vector<CacheLine> _lines;
        unsigned _numJoints = 0;
        unsigned _numFrames = 0;
        unsigned _numChecks = 0;
        unsigned _numTopNodes = 0;
        unsigned _frameParentsAt = 0, _jointNodesAt = 0;
        unsigned _flagIndicesAt = 0, _jointFlagsAt = 0, _checksAt = 0, _geodeChildrenAt = 0, _topNodesAt = 0;
        bool _allAlike = false;
        bool _byteIndices = true;
        bool _linesPlaced = false;
    };
    /** Whether every checked joint's flags are those it had, flagIndex(j) saying which of the distinct ones, and its
      * frame still RELATIVE_RF. */
    template <class FlagIndex>
    bool jointsUnchanged(FlagIndex flagIndex) const;
    /** Adds a joint's check to the packed ones; false where its flags are not in one block. */
    bool addJointCheck(const SkeletonNode& node);

    void addChild(osg::Node& child, int joint);
    void addJoint(SkeletonNode& node, int parent);
    void addGeode(osg::Geode& geode, int joint);
    void addOrdinary(osg::Node& node, int joint);
    Step& addStep(Kind kind, osg::Node& node, int joint);
    void addCheck(Kind kind, osg::Node& node);
    /** The check of a node's fields one by one (NodeCheck), whatever its flags' layout. */
    void addNodeCheck(Kind kind, osg::Node& node);
    void addStateCheck(const osg::StateSet* state);
    static bool isPlainJoint(const SkeletonNode& joint);
    /** Marks the steps open above the newest one as needing the node path. */
    void notePathNeeded();
    /** The geodes of each joint in the actor's frame, once its subtree is planned. */
    void noteGeodesBelow(unsigned jointStep);
    bool isUnchanged(const NodeCheck& check) const;
    static bool isUnchanged(const StateCheck& check);

    /** Once planned: the distinct masks of the JOINT, GEODE and DRAWABLE steps, the steps at the top (and whether
      * each is a joint: _topStepsAllJoints) and the DRAWABLE steps. */
    void noteShape();

    // First, so that the check reads the plan's first lines only.
    /** Everything isCurrent() reads of the plan but the state sets' checks, packed in one allocation in the order
      * it is read (PackedChecks), so that an idle actor's check reads a few whole lines of the plan, not a part of
      * five arrays' each. Made from the planning's arrays below once the plan is made. */
    PackedChecks _packed;
    /** Which bytes of a flag block are fields (osg::Node's layout); null until a joint is checked as a block. */
    const unsigned char* _flagMask = nullptr;
    std::vector<StateCheck> _stateChecks;
    std::vector<Step> _steps;
    std::vector<Joint> _joints;
    std::vector<osg::Node::NodeMask> _masks;
    std::vector<unsigned> _topSteps;
    bool _topStepsAllJoints = true;
    bool _hasOrdinarySteps = false;
    bool _hasOrdinaryStepsInActorFrame = false;
    std::vector<unsigned> _drawableSteps;
    std::vector<const osg::Node*> _geodesBelow; // runs of Joint::firstGeode, numGeodes
    /** While planning: per checked joint its node and which of _jointFlags it had; the distinct flags (where each
      * one is: _distinctJointFlags); the geodes' and drawables' checks, and each checked geode's children, in
      * order (consecutive runs, one per geode). Packed into _packed, then emptied. */
    std::vector<const SkeletonNode*> _jointCheckNodes;
    std::vector<unsigned> _jointCheckFlags;
    std::vector<JointFlags> _jointFlags;
    JointFlagsIndex _distinctJointFlags;
    std::vector<NodeCheck> _checks;
    std::vector<const osg::Node*> _geodeChildren;
    /** Every node a step names, held so that none of them is freed while the plan is kept. */
    std::vector<osg::ref_ptr<osg::Node>> _held;
    std::vector<unsigned> _open; // while planning: the JOINT and GEODE steps whose subtree is being planned
    /** While planning: the geodes, drawables and state sets checked already, so that finding one is not a search of
      * the checks (which made planning an actor of n joints take n^2/2 comparisons). Emptied once the plan is made. */
    std::unordered_set<const osg::Referenced*> _checked;
};

} // namespace detail
} // namespace osgActor

#endif
