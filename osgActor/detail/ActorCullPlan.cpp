#include <osgActor/detail/ActorCullPlan.h>
#include <osgActor/ActorNode>
#include <osgActor/detail/PlacedSkeletonNode.h>
#include <osgActor/detail/Prefetch.h>
#include <osgActor/detail/SkeletonNodeAccess.h>
#include <osgActor/core/detail/HotPath.h>

#include <osg/Geometry>
#include <osg/ShapeDrawable>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <typeinfo>
#include <vector>

namespace osgActor {
namespace detail {

namespace {

/** No cull callback: the visitor would do nothing else at the node than push its state set. */
bool hasNoCullCallback(const osg::Node& node) { return !node.getCullCallback(); }

osg::Object::DataVariance dataVarianceOf(const osg::StateSet* state)
{
    return state ? state->getDataVariance() : osg::Object::UNSPECIFIED;
}

/** The address of a node's mask, for prefetching: osg::Node's flags the plan compares share its cache line.
  * Never instantiated; a pointer to a protected member formed in a derived class may be used on any node. */
struct NodeFlags : osg::Node
{
    static const void* maskAddress(const osg::Node& node)
    {
        const osg::Node::NodeMask osg::Node::*const mask = &NodeFlags::_nodeMask;
        return &(node.*mask);
    }
    static const void* boundAddress(const osg::Node& node)
    {
        const osg::BoundingSphere osg::Node::*const bound = &NodeFlags::_boundingSphere;
        return &(node.*bound);
    }
    /** Where the block of a node's flags the plan compares begins (ActorCullPlan::kNodeFlagBytes from its cull
      * callback). */
    static const unsigned char* flagBlock(const osg::Node& node)
    {
        const osg::ref_ptr<osg::Callback> osg::Node::*const callback = &NodeFlags::_cullCallback;
        return reinterpret_cast<const unsigned char*>(&(node.*callback));
    }
    /** Calls field(address, size) for each of the node's fields the plan compares in its flag block: its cull
      * callback, culling flags, node mask and state set. */
    template <class Field>
    static void forEachFlagField(const osg::Node& node, Field&& field)
    {
        const osg::ref_ptr<osg::Callback> osg::Node::*const callback = &NodeFlags::_cullCallback;
        const bool osg::Node::*const active = &NodeFlags::_cullingActive;
        const unsigned int osg::Node::*const disabled = &NodeFlags::_numChildrenWithCullingDisabled;
        const osg::Node::NodeMask osg::Node::*const mask = &NodeFlags::_nodeMask;
        const osg::ref_ptr<osg::StateSet> osg::Node::*const state = &NodeFlags::_stateset;
        field(&(node.*callback), sizeof(osg::ref_ptr<osg::Callback>));
        field(&(node.*active), sizeof(bool));
        field(&(node.*disabled), sizeof(unsigned int));
        field(&(node.*mask), sizeof(osg::Node::NodeMask));
        field(&(node.*state), sizeof(osg::ref_ptr<osg::StateSet>));
    }
    /** Whether those fields lie within the node's flag block, so that comparing the block (its other bytes masked
      * out: flagMask()) compares them. */
    static bool holdsFlags(const osg::Node& node, std::size_t blockBytes)
    {
        const unsigned char* const begin = flagBlock(node);
        bool within = true;
        forEachFlagField(node, [&](const void* member, std::size_t size) {
            const unsigned char* const first = static_cast<const unsigned char*>(member);
            within = within && first >= begin && first + size <= begin + blockBytes;
        });
        return within;
    }
    /** The bytes of a node's flag block that belong to those fields (0xff), not to the padding between them (0):
      * padding holds whatever the heap held before the node, so two nodes with the same flags may differ there. The
      * layout is osg::Node's, the same for every node: taken from the first one asked, which holdsFlags(). */
    static const unsigned char* flagMask(const osg::Node& node, std::size_t blockBytes)
    {
        static const std::vector<unsigned char> mask = [&] {
            std::vector<unsigned char> bytes(blockBytes, 0);
            const unsigned char* const begin = flagBlock(node);
            forEachFlagField(node, [&](const void* member, std::size_t size) {
                const std::ptrdiff_t first = static_cast<const unsigned char*>(member) - begin;
                std::fill_n(bytes.begin() + first, size, static_cast<unsigned char>(0xff));
            });
            return bytes;
        }();
        return mask.data();
    }
    /** Node::isCullingActive() but for its bound's validity, which reads the bound (two more cache lines of a
      * skeleton node); the cull tests validity where it uses the bound. */
    static bool cullingActive(const osg::Node& node)
    {
        const bool osg::Node::*const active = &NodeFlags::_cullingActive;
        const unsigned int osg::Node::*const disabled = &NodeFlags::_numChildrenWithCullingDisabled;
        return node.*active && node.*disabled == 0;
    }
};

/** Appends node to held. osg::ref_ptr has no move constructor, so a vector of them that grows copies each one, and
  * each copy and each destruction of the old one touches its node (its reference count): the nodes held, one or two
  * a joint, would all be fetched again at each growth. Grown here by swapping the pointers across instead. */
void hold(std::vector<osg::ref_ptr<osg::Node>>& held, osg::Node& node)
{
    if (held.size() == held.capacity())
    {
        std::vector<osg::ref_ptr<osg::Node>> grown;
        grown.reserve(2 * held.size() + 16);
        for (osg::ref_ptr<osg::Node>& old : held)
        {
            grown.emplace_back();
            grown.back().swap(old);
        }
        held.swap(grown); // grown now holds only null pointers
    }
    held.push_back(&node);
}

/** A block of ActorCullPlan::kNodeFlagBytes held in registers: one vector where the compiler has them (one register
  * in the x86-64-v3 clones of OSGACTOR_HOT_PATH, two elsewhere), words otherwise. The operations are bytewise, so
  * the words' order never changes an answer; they return nothing, so no vector crosses a call. */
class Block
{
public:
    Block() { std::memset(&_words, 0, sizeof(Words)); }
    explicit Block(const unsigned char* bytes) { std::memcpy(&_words, bytes, sizeof(Words)); }
#if defined(__GNUC__)
    void operator^=(const Block& other) { _words ^= other._words; }
    void operator|=(const Block& other) { _words |= other._words; }
    void operator&=(const Block& other) { _words &= other._words; }
#else
    void operator^=(const Block& other)
    {
        for (std::size_t w = 0; w < kWords; ++w) _words[w] ^= other._words[w];
    }
    void operator|=(const Block& other)
    {
        for (std::size_t w = 0; w < kWords; ++w) _words[w] |= other._words[w];
    }
    void operator&=(const Block& other)
    {
        for (std::size_t w = 0; w < kWords; ++w) _words[w] &= other._words[w];
    }
#endif
    bool isZero() const
    {
        Word any = 0;
        for (std::size_t w = 0; w < kWords; ++w) any |= _words[w];
        return any == 0;
    }

private:
    typedef std::uint64_t Word;
    static constexpr std::size_t kWords = ActorCullPlan::kNodeFlagBytes / sizeof(Word);
    static_assert(ActorCullPlan::kNodeFlagBytes % sizeof(Word) == 0, "whole words a block");
#if defined(__GNUC__)
    typedef Word Words __attribute__((vector_size(ActorCullPlan::kNodeFlagBytes)));
#else
    typedef Word Words[kWords];
#endif
    Words _words;
};

static_assert(osg::Transform::RELATIVE_RF == 0, "a checked joint's frame is RELATIVE_RF while the frames' OR is 0");

/** Whether every node's flag block is flags where mask is set, and its frame RELATIVE_RF (a checked joint's, as it
  * was planned). The blocks' bitwise OR and AND, both started from flags, are flags there only if every block is: a
  * bit set in a block but not in flags shows in the OR, a bit clear in a block but set in flags in the AND. So a node
  * costs two operations on its block, taken from memory once, and one on its frame, with no branch: the loads of one
  * node do not wait on the comparison of the one before. Most actors' joints all have the same flags. */
OSGACTOR_HOT_PATH bool allBlocksAre(const SkeletonNode* const* nodes, std::size_t numNodes, const unsigned char* flags,
                                    const unsigned char* mask)
{
    const Block expected(flags);
    Block any = expected, all = expected;
    unsigned frames = 0;
    for (std::size_t j = 0; j < numNodes; ++j)
    {
        const Block block(NodeFlags::flagBlock(*nodes[j]));
        any |= block;
        all &= block;
        frames |= static_cast<unsigned>(nodes[j]->getReferenceFrame());
    }
    any ^= expected;
    all ^= expected;
    any |= all;
    any &= Block(mask);
    return any.isZero() && frames == 0;
}

/** Asks for the lines of each node's flag block and reference frame (LinesPlaced: one line, that the block starts;
  * else the block's first and the frame's) and, Matrices, its matrix's (LinesPlaced: two, that it starts). */
template <bool LinesPlaced, bool Matrices>
void prefetchJointLines(const SkeletonNode* const* nodes, std::size_t numNodes)
{
    static_assert(2 * ActorCullPlan::kNodeFlagBytes <= 64, "a block and its reference frame within a line it starts");
    for (std::size_t j = 0; j < numNodes; ++j)
    {
        const unsigned char* const block = NodeFlags::flagBlock(*nodes[j]);
        prefetchLine(block);
        if (!LinesPlaced) prefetchLine(block + 2 * ActorCullPlan::kNodeFlagBytes - 1);
        if (Matrices)
        {
            const char* const matrix = reinterpret_cast<const char*>(nodes[j]->getMatrix().ptr());
            prefetchLine(matrix);
            if (!LinesPlaced) prefetchLine(matrix + 64);
            prefetchLine(matrix + sizeof(osg::Matrixd) - 1);
        }
    }
}


} // namespace

ActorCullPlan::ActorCullPlan(osg::Group& actor)
{
    // Room for an actor's joints made at once: grown joint by joint, a large actor's lists would be copied each time
    // they fill, fetching what they hold again.
    if (const ActorNode* node = dynamic_cast<const ActorNode*>(&actor))
    {
        const std::size_t numJoints = node->getNumSkeletonNodes();
        _joints.reserve(numJoints);
        _steps.reserve(2 * numJoints); // JOINT and END_JOINT
        _jointCheckNodes.reserve(numJoints);
        _jointCheckFlags.reserve(numJoints);
    }
    for (unsigned i = 0; i < actor.getNumChildren(); ++i) addChild(*actor.getChild(i), -1);
    std::unordered_set<const osg::Referenced*>().swap(_checked);
    JointFlagsIndex().swap(_distinctJointFlags);
    noteShape();
    std::vector<const osg::Node*> topNodes;
    for (unsigned i : _topSteps)
        if (_steps[i].kind == JOINT || _steps[i].kind == GEODE) topNodes.push_back(_steps[i].node);
    _packed.pack(_joints, _jointCheckNodes, _jointCheckFlags, _jointFlags, _checks, _geodeChildren, topNodes);
    std::vector<const SkeletonNode*>().swap(_jointCheckNodes);
    std::vector<unsigned>().swap(_jointCheckFlags);
    std::vector<JointFlags>().swap(_jointFlags);
    std::vector<NodeCheck>().swap(_checks);
    std::vector<const osg::Node*>().swap(_geodeChildren);
}

namespace {

/** Where an array of count T starts after `offset` bytes, at T's alignment. */
template <class T>
std::size_t placeAfter(std::size_t& offset, std::size_t count)
{
    const std::size_t at = (offset + alignof(T) - 1) / alignof(T) * alignof(T);
    offset = at + count * sizeof(T);
    return at;
}

template <class T>
void copyTo(unsigned char* block, std::size_t at, const std::vector<T>& values)
{
    if (!values.empty()) std::memcpy(block + at, values.data(), values.size() * sizeof(T));
}

} // namespace

void ActorCullPlan::PackedChecks::pack(const std::vector<Joint>& joints,
                                       const std::vector<const SkeletonNode*>& jointNodes,
                                       const std::vector<unsigned>& jointFlagIndices,
                                       const std::vector<JointFlags>& jointFlags, const std::vector<NodeCheck>& checks,
                                       const std::vector<const osg::Node*>& geodeChildren,
                                       const std::vector<const osg::Node*>& topNodes)
{
    static_assert(std::is_trivially_copyable<NodeCheck>::value && std::is_trivially_copyable<JointFlags>::value,
                  "copied as bytes");
    _numJoints = static_cast<unsigned>(jointNodes.size());
    _numChecks = static_cast<unsigned>(checks.size());
    _numTopNodes = static_cast<unsigned>(topNodes.size());
    _allAlike = jointFlags.size() == 1;
    const auto startsLine = [](const void* address) {
        return reinterpret_cast<std::uintptr_t>(address) % sizeof(CacheLine) == 0;
    };
    _linesPlaced = std::all_of(jointNodes.begin(), jointNodes.end(), [&](const SkeletonNode* node) {
        return startsLine(NodeFlags::flagBlock(*node)) && startsLine(node->getMatrix().ptr());
    });
    _byteIndices = jointFlags.size() <= 256;
    const std::size_t numIndices = _allAlike ? 0 : jointNodes.size();
    _numFrames = static_cast<unsigned>(joints.size());
    std::vector<const SkeletonNode*> frameNodes;
    std::vector<int> frameParents;
    for (const Joint& joint : joints)
    {
        frameNodes.push_back(joint.node);
        frameParents.push_back(joint.parent);
    }
    std::size_t size = 0;
    placeAfter<const SkeletonNode*>(size, frameNodes.size());
    _frameParentsAt = static_cast<unsigned>(placeAfter<int>(size, frameParents.size()));
    // The checked joints are the planned ones, in the same order, unless some were checked field by field.
    _jointNodesAt = frameNodes == jointNodes
                        ? 0u
                        : static_cast<unsigned>(placeAfter<const SkeletonNode*>(size, jointNodes.size()));
    _flagIndicesAt = static_cast<unsigned>(_byteIndices ? placeAfter<unsigned char>(size, numIndices)
                                                        : placeAfter<unsigned>(size, numIndices));
    _jointFlagsAt = static_cast<unsigned>(placeAfter<JointFlags>(size, jointFlags.size()));
    _checksAt = static_cast<unsigned>(placeAfter<NodeCheck>(size, checks.size()));
    _geodeChildrenAt = static_cast<unsigned>(placeAfter<const osg::Node*>(size, geodeChildren.size()));
    _topNodesAt = static_cast<unsigned>(placeAfter<const osg::Node*>(size, topNodes.size()));
    _lines.assign((size + sizeof(CacheLine) - 1) / sizeof(CacheLine), CacheLine());
    unsigned char* const block = reinterpret_cast<unsigned char*>(_lines.data());
    copyTo(block, 0, frameNodes);
    copyTo(block, _frameParentsAt, frameParents);
    if (_jointNodesAt != 0) copyTo(block, _jointNodesAt, jointNodes);
    if (_allAlike)
    {
        // No index: every joint had the first flags.
    }
    else if (_byteIndices)
        for (std::size_t j = 0; j < jointFlagIndices.size(); ++j)
            block[_flagIndicesAt + j] = static_cast<unsigned char>(jointFlagIndices[j]);
    else
        copyTo(block, _flagIndicesAt, jointFlagIndices);
    copyTo(block, _jointFlagsAt, jointFlags);
    copyTo(block, _checksAt, checks);
    copyTo(block, _geodeChildrenAt, geodeChildren);
    copyTo(block, _topNodesAt, topNodes);
}

void ActorCullPlan::noteShape()
{
    for (unsigned i = 0; i < _steps.size(); i = _steps[i].end ? _steps[i].end : i + 1)
    {
        _topSteps.push_back(i);
        if (_steps[i].kind != JOINT) _topStepsAllJoints = false;
    }
    for (unsigned i = 0; i < _steps.size(); ++i)
    {
        const Step& step = _steps[i];
        if (step.kind == ORDINARY) _hasOrdinarySteps = true;
        if (step.kind == ORDINARY && step.joint < 0) _hasOrdinaryStepsInActorFrame = true;
        if (step.kind != JOINT && step.kind != GEODE && step.kind != DRAWABLE) continue;
        if (std::find(_masks.begin(), _masks.end(), step.mask) == _masks.end()) _masks.push_back(step.mask);
        if (step.kind == DRAWABLE) _drawableSteps.push_back(i);
    }
}

bool ActorCullPlan::isPlainJoint(const SkeletonNode& joint)
{
    return hasNoCullCallback(joint) && !joint.getHidden() && joint.getReferenceFrame() == osg::Transform::RELATIVE_RF;
}

bool ActorCullPlan::isPlainDrawable(const osg::Drawable& drawable)
{
    const std::type_info& type = typeid(drawable);
    return hasNoCullCallback(drawable) && (type == typeid(osg::Geometry) || type == typeid(osg::ShapeDrawable));
}

ActorCullPlan::Step& ActorCullPlan::addStep(Kind kind, osg::Node& node, int joint)
{
    Step step;
    step.kind = kind;
    step.pathNeeded = false;
    step.cullingActive = NodeFlags::cullingActive(node);
    step.stateSet = node.getStateSet();
    step.batchable = node.getDataVariance() != osg::Object::DYNAMIC &&
                     dataVarianceOf(step.stateSet) != osg::Object::DYNAMIC;
    step.joint = joint;
    step.end = 0;
    step.mask = node.getNodeMask();
    step.node = &node;
    _steps.push_back(step);
    if (kind == JOINT || kind == GEODE || kind == DRAWABLE)
    {
        hold(_held, node);
        addCheck(kind, node);
    }
    return _steps.back();
}

void ActorCullPlan::addCheck(Kind kind, osg::Node& node)
{
    // A skeleton node is met once per parent, nearly always once: its check is not looked up (one under two parents
    // is checked twice, to the same effect). Geodes and state sets are often shared, by every joint at times.
    if (kind != JOINT && !_checked.insert(&node).second) return;
    if (kind == JOINT && addJointCheck(static_cast<const SkeletonNode&>(node)))
    {
        addStateCheck(node.getStateSet());
        return;
    }
    addNodeCheck(kind, node);
}

void ActorCullPlan::addNodeCheck(Kind kind, osg::Node& node)
{
    NodeCheck check;
    check.node = &node;
    check.stateSet = node.getStateSet();
    check.cullCallback = node.getCullCallback();
    check.mask = node.getNodeMask();
    check.cullingActive = NodeFlags::cullingActive(node);
    const osg::Transform* transform = node.asTransform();
    check.referenceFrame =
        static_cast<unsigned char>(transform ? transform->getReferenceFrame() : osg::Transform::RELATIVE_RF);
    check.dataVariance = static_cast<unsigned char>(node.getDataVariance());
    check.kind = kind;
    check.firstChild = static_cast<unsigned>(_geodeChildren.size());
    check.numChildren = 0;
    if (kind == GEODE)
    {
        const osg::Group& geode = *node.asGroup();
        check.numChildren = geode.getNumChildren();
        for (unsigned i = 0; i < geode.getNumChildren(); ++i) _geodeChildren.push_back(geode.getChild(i));
    }
    _checks.push_back(check);
    addStateCheck(check.stateSet);
}

bool ActorCullPlan::addJointCheck(const SkeletonNode& node)
{
    if (!NodeFlags::holdsFlags(node, kNodeFlagBytes)) return false;
    if (!_flagMask) _flagMask = NodeFlags::flagMask(node, kNodeFlagBytes);
    JointFlags flags;
    const unsigned char* const block = NodeFlags::flagBlock(node);
    for (std::size_t i = 0; i < kNodeFlagBytes; ++i) flags.nodeFlags[i] = block[i] & _flagMask[i];
    // Its frame, RELATIVE_RF (a plain joint), is not kept: the check is that every checked joint's still is.
    // Most joints have the flags of the joint checked before them; others are found in a hash map while planning: an
    // actor may have as many distinct ones as joints (a state set each). Not emplace(), which allocates an entry
    // before it looks.
    if (!_jointCheckFlags.empty() && _jointFlags[_jointCheckFlags.back()] == flags)
    {
        _jointCheckFlags.push_back(_jointCheckFlags.back());
    }
    else
    {
        const auto found = _distinctJointFlags.try_emplace(flags, static_cast<unsigned>(_jointFlags.size()));
        if (found.second) _jointFlags.push_back(flags);
        _jointCheckFlags.push_back(found.first->second);
    }
    _jointCheckNodes.push_back(&node);
    return true;
}

bool ActorCullPlan::JointFlags::operator==(const JointFlags& other) const
{
    return std::memcmp(nodeFlags, other.nodeFlags, kNodeFlagBytes) == 0;
}

std::size_t ActorCullPlan::JointFlagsHash::operator()(const JointFlags& flags) const
{
    // FNV-1a over the block's bytes.
    std::uint64_t hash = 14695981039346656037ull;
    for (unsigned char byte : flags.nodeFlags) hash = (hash ^ byte) * 1099511628211ull;
    return static_cast<std::size_t>(hash);
}

void ActorCullPlan::addStateCheck(const osg::StateSet* state)
{
    if (!state || !_checked.insert(state).second) return;
    _stateChecks.push_back({state, state->getRenderBinMode(), state->getBinNumber(), state->getBinName(),
                            state->getNestRenderBins(), state->getDataVariance()});
}

void ActorCullPlan::addChild(osg::Node& child, int joint)
{
    // Exact classes only: a subclass may traverse, cull or draw in its own way.
    const std::type_info& type = typeid(child);
    if ((type == typeid(PlacedSkeletonNode) || type == typeid(SkeletonNode)) &&
        isPlainJoint(static_cast<SkeletonNode&>(child)))
        addJoint(static_cast<SkeletonNode&>(child), joint);
    else if (type == typeid(osg::Geode) && hasNoCullCallback(child))
        addGeode(static_cast<osg::Geode&>(child), joint);
    else
        addOrdinary(child, joint);
}

void ActorCullPlan::addJoint(SkeletonNode& node, int parent)
{
    const int joint = static_cast<int>(_joints.size());
    _joints.push_back({&node, parent, 0, 0, false});
    const unsigned index = static_cast<unsigned>(_steps.size());
    addStep(JOINT, node, joint);
    _open.push_back(index);
    for (unsigned i = 0; i < node.getNumChildren(); ++i) addChild(*node.getChild(i), joint);
    _open.pop_back();
    addStep(END_JOINT, node, joint).pathNeeded = _steps[index].pathNeeded;
    _steps[index].end = static_cast<unsigned>(_steps.size());
    if (parent < 0) noteGeodesBelow(index);
}

namespace {

// Built for x86-64-v3 too (four doubles a lane): every actor's every joint goes through it at every cull. The file is
// compiled without contracting products and sums into fused multiply-adds, so each clone gives the same bits.
OSGACTOR_HOT_PATH void composeJointModelViews(const SkeletonNode* const* nodes, const int* parents,
                                              std::size_t numJoints, osg::Matrixd* modelViews)
{
    for (std::size_t j = 0; j < numJoints; ++j)
        composeModelView(nodes[j]->getMatrix().ptr(), modelViews[static_cast<std::size_t>(parents[j] + 1)].ptr(),
                         modelViews[j + 1].ptr());
}

} // namespace

void ActorCullPlan::composeModelViews(osg::Matrixd* modelViews) const
{
    // From the packed arrays, which the check has just read or which were asked for with it: not from _joints.
    composeJointModelViews(_packed.frameNodes(), _packed.frameParents(), _packed.numFrames(), modelViews);
}

bool ActorCullPlan::provesNoSmallFeatureBelow(const Step& step, const osg::Vec4& actorVector, float pixelSize) const
{
    if (step.kind != JOINT) return false;
    const Joint& joint = _joints[static_cast<std::size_t>(step.joint)];
    double smallestRadius;
    // The joint's node keeps its subtree's shape with its bound, so the joints below are not read.
    return joint.parent < 0 && smallestGeodeRadiusBelow(joint, smallestRadius) &&
           SmallFeatureProof::holds(joint.node->getBound(), SkeletonNodeAccess::subtreeShape(*joint.node),
                                    actorVector, pixelSize, smallestRadius);
}

void ActorCullPlan::noteGeodesBelow(unsigned jointStep)
{
    Joint& top = _joints[static_cast<std::size_t>(_steps[jointStep].joint)];
    top.firstGeode = static_cast<unsigned>(_geodesBelow.size());
    top.geodeBelowEveryJoint = true;
    std::unordered_set<const osg::Node*> seen;
    // Each joint below, with whether a geode follows it within its subtree (joints and geodes in the visitor's
    // order, so a subtree is the steps up to its end).
    std::vector<unsigned> open;
    std::vector<bool> geodeFound;
    for (unsigned i = jointStep + 1; i + 1 < _steps[jointStep].end; ++i)
    {
        const Step& step = _steps[i];
        if (step.kind == JOINT)
        {
            open.push_back(step.end);
            geodeFound.push_back(false);
        }
        else if (step.kind == GEODE)
        {
            std::fill(geodeFound.begin(), geodeFound.end(), true);
            if (seen.insert(step.node).second) _geodesBelow.push_back(step.node);
        }
        while (!open.empty() && open.back() == i + 1)
        {
            top.geodeBelowEveryJoint = top.geodeBelowEveryJoint && geodeFound.back();
            open.pop_back();
            geodeFound.pop_back();
        }
    }
    top.numGeodes = static_cast<unsigned>(_geodesBelow.size()) - top.firstGeode;
}

bool ActorCullPlan::smallestGeodeRadiusBelow(const Joint& joint, double& radius) const
{
    if (joint.parent >= 0 || !joint.geodeBelowEveryJoint || joint.numGeodes == 0) return false;
    radius = std::numeric_limits<double>::max();
    for (unsigned g = joint.firstGeode; g < joint.firstGeode + joint.numGeodes; ++g)
    {
        const osg::BoundingSphere& bound = _geodesBelow[g]->getBound();
        if (!bound.valid()) return false;
        radius = std::min(radius, double(bound.radius()));
    }
    return true;
}

void ActorCullPlan::addGeode(osg::Geode& geode, int joint)
{
    const unsigned index = static_cast<unsigned>(_steps.size());
    addStep(GEODE, geode, joint);
    _open.push_back(index);
    for (unsigned i = 0; i < geode.getNumChildren(); ++i)
    {
        osg::Node& child = *geode.getChild(i);
        osg::Drawable* drawable = child.asDrawable();
        if (drawable && isPlainDrawable(*drawable)) addStep(DRAWABLE, *drawable, joint);
        else addOrdinary(child, joint);
    }
    _open.pop_back();
    addStep(END_GEODE, geode, joint).pathNeeded = _steps[index].pathNeeded;
    _steps[index].end = static_cast<unsigned>(_steps.size());
}

void ActorCullPlan::addOrdinary(osg::Node& node, int joint)
{
    hold(_held, node);
    addStep(ORDINARY, node, joint);
    notePathNeeded();
    // A joint of the actor's own classes handed to the ordinary traversal for what it holds now (a cull callback, an
    // absolute frame): watched, each field apart, so that undoing that makes a plan that takes it again.
    const std::type_info& type = typeid(node);
    if (type == typeid(PlacedSkeletonNode) || type == typeid(SkeletonNode)) addNodeCheck(JOINT, node);
}

void ActorCullPlan::notePathNeeded()
{
    for (unsigned index : _open) _steps[index].pathNeeded = true;
}

namespace {

template <class T>
void prefetchArray(const std::vector<T>& array)
{
    prefetchForRead(array.data(), array.size() * sizeof(T));
}

} // namespace

void ActorCullPlan::prefetchChecks() const
{
    prefetchForRead(_packed.data(), _packed.bytes());
    prefetchArray(_stateChecks);
}

void ActorCullPlan::prefetchCheckedNodes(bool matrices) const
{
    const SkeletonNode* const* nodes = _packed.jointNodes();
    const std::size_t n = _packed.numJoints();
    if (_packed.linesPlaced())
        matrices ? prefetchJointLines<true, true>(nodes, n) : prefetchJointLines<true, false>(nodes, n);
    else
        matrices ? prefetchJointLines<false, true>(nodes, n) : prefetchJointLines<false, false>(nodes, n);
    for (const NodeCheck* check = _packed.checksBegin(); check != _packed.checksEnd(); ++check)
        prefetchLine(NodeFlags::maskAddress(*check->node));
    // The top steps' spheres, which such a cull tests (small features), where a replay tests the actor's alone.
    if (matrices)
        for (const osg::Node* const* node = _packed.topNodesBegin(); node != _packed.topNodesEnd(); ++node)
            prefetchForRead(NodeFlags::boundAddress(**node), sizeof(osg::BoundingSphere) + sizeof(bool));
}

bool ActorCullPlan::isCurrent() const
{
    // The joints compared without a branch, so that their loads overlap; the nodes were asked for ahead, by the
    // cull of the actors before this one (ActorNode::prefetchCullAhead()).
    const SkeletonNode* const* nodes = _packed.jointNodes();
    const std::size_t numJoints = _packed.numJoints();
    const unsigned char* const byteIndices = _packed.byteFlagIndices();
    const unsigned* const wordIndices = _packed.wordFlagIndices();
    if (numJoints != 0 &&
        !(_packed.allAlike()      ? allBlocksAre(nodes, numJoints, _packed.jointFlags()[0].nodeFlags, _flagMask)
          : _packed.byteIndices() ? jointsUnchanged([byteIndices](std::size_t j) { return unsigned(byteIndices[j]); })
                                  : jointsUnchanged([wordIndices](std::size_t j) { return wordIndices[j]; })))
        return false;
    for (const NodeCheck* check = _packed.checksBegin(); check != _packed.checksEnd(); ++check)
        if (!isUnchanged(*check)) return false;
    for (const StateCheck& check : _stateChecks)
        if (!isUnchanged(check)) return false;
    return true;
}

template <class FlagIndex>
bool ActorCullPlan::jointsUnchanged(FlagIndex flagIndex) const
{
    // Every joint compared with its own flags, the differences gathered with no branch (the loads of one node do not
    // wait on the comparison of the one before), the padding between the fields masked out once at the end.
    const SkeletonNode* const* nodes = _packed.jointNodes();
    const JointFlags* seen = _packed.jointFlags();
    Block difference;
    unsigned frames = 0;
    for (std::size_t j = 0, n = _packed.numJoints(); j < n; ++j)
    {
        Block block(NodeFlags::flagBlock(*nodes[j]));
        block ^= Block(seen[flagIndex(j)].nodeFlags);
        difference |= block;
        frames |= static_cast<unsigned>(nodes[j]->getReferenceFrame());
    }
    difference &= Block(_flagMask);
    return difference.isZero() && frames == 0;
}

bool ActorCullPlan::isUnchanged(const NodeCheck& check) const
{
    const osg::Node& node = *check.node;
    if (node.getNodeMask() != check.mask || node.getStateSet() != check.stateSet ||
        node.getCullCallback() != check.cullCallback || NodeFlags::cullingActive(node) != check.cullingActive)
        return false;
    switch (check.kind)
    {
    case JOINT:
        // Its class and children are the actor's to watch; its reference frame is the one flag osg::Transform
        // keeps in the same cache line as the node's.
        return static_cast<const SkeletonNode&>(node).getReferenceFrame() == check.referenceFrame;
    case GEODE:
    {
        const osg::Group& geode = static_cast<const osg::Group&>(node);
        if (geode.getNumChildren() != check.numChildren) return false;
        for (unsigned i = 0; i < check.numChildren; ++i)
            if (geode.getChild(i) != _packed.geodeChildren()[check.firstChild + i]) return false;
        return true;
    }
    default: return node.getDataVariance() == check.dataVariance;
    }
}

bool ActorCullPlan::isUnchanged(const StateCheck& check)
{
    const osg::StateSet& state = *check.stateSet;
    return state.getDataVariance() == check.dataVariance && state.getRenderBinMode() == check.binMode &&
           state.getBinNumber() == check.binNumber && state.getNestRenderBins() == check.nestRenderBins &&
           state.getBinName() == check.binName;
}

} // namespace detail
} // namespace osgActor
