#include <osgActor/ActorNode>
#include <osgActor/ActorUpdateCallback>
#include <osgActor/GlmOsg>
#include <osgActor/core/LocalMatricesJob>
#include <osgActor/detail/ActorCull.h>
#include <osgActor/detail/AffineBound.h>
#include <osgActor/detail/ChildrenBound.h>
#include <osgActor/detail/PoseFollower.h>
#include <osgActor/detail/PlacedSkeletonNode.h>
#include <osgActor/detail/Prefetch.h>
#include <osgActor/detail/SkeletonNodeAccess.h>

#include <osg/FrameStamp>
#include <osg/Notify>
#include <osgUtil/CullVisitor>
#include <osgUtil/Optimizer>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <typeinfo>

namespace osgActor {

namespace {

constexpr unsigned kNoFrame = std::numeric_limits<unsigned>::max();
/** The simulation time of a frame without a frame stamp: controllers do not run. */
constexpr double kNoTime = std::numeric_limits<double>::quiet_NaN();

/** A CopyOp that always copies skeleton nodes (they carry one instance's matrices) and defers everything else to
  * the user's CopyOp, so an actor's copy is an independent instance that shares geometry by default. */
class SkeletonCopyOp : public osg::CopyOp
{
public:
    explicit SkeletonCopyOp(const osg::CopyOp& user) : osg::CopyOp(user.getCopyFlags()), _user(user) {}
    using osg::CopyOp::operator();
    osg::Node* operator()(const osg::Node* node) const override
    {
        if (const SkeletonNode* skeleton = dynamic_cast<const SkeletonNode*>(node))
            return new detail::PlacedSkeletonNode(*skeleton, *this);
        return _user(node);
    }

private:
    const osg::CopyOp& _user;
};

/** Collects the skeleton nodes below a group by joint index; false on a missing, repeated or foreign index. */
bool collectSkeletonNodes(osg::Group& group, std::vector<osg::ref_ptr<SkeletonNode>>& nodes)
{
    for (unsigned i = 0; i < group.getNumChildren(); ++i)
    {
        SkeletonNode* skeleton = dynamic_cast<SkeletonNode*>(group.getChild(i));
        if (!skeleton) continue; // attached geometry
        const unsigned joint = skeleton->getJointIndex();
        if (joint >= nodes.size() || nodes[joint].valid()) return false;
        nodes[joint] = skeleton;
        if (!collectSkeletonNodes(*skeleton, nodes)) return false;
    }
    return true;
}

using detail::SkeletonNodeAccess;

/** Dirties the bounds of a joint's ancestors, up to the first one already dirty (whose ancestors are too). */
inline void dirtyBoundsAbove(const int* parents, const osg::ref_ptr<SkeletonNode>* nodes, unsigned joint)
{
    int parent = parents[joint];
    while (parent >= 0 && SkeletonNodeAccess::markBoundDirty(*nodes[parent])) parent = parents[parent];
}

/** Marks a joint's node as written (the job wrote its matrix in place), and dirties its bound and its ancestors'. */
inline void writeDirtyingBounds(const int* parents, const osg::ref_ptr<SkeletonNode>* nodes, unsigned joint)
{
    if (SkeletonNodeAccess::matrixWritten(*nodes[joint])) dirtyBoundsAbove(parents, nodes, joint);
}

/** Each actor's phase for reduced-rate updates: consecutive actors take consecutive phases, so a crowd at half or
  * quarter rate spreads its pose work evenly over the frames. */
unsigned nextLodPhase()
{
    static std::atomic<unsigned> counter{0};
    return counter.fetch_add(1, std::memory_order_relaxed);
}

std::uint32_t floatBits(float value)
{
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return bits;
}

float bitsFloat(std::uint32_t bits)
{
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
}

/** Sets whether the node's bound covers its rotations, as the actor's bound mode and the joint's DOFs say. */
void giveBoundMode(SkeletonNode& node, const ActorDefinition& def, ActorNode::BoundMode mode)
{
    // A joint that translates moves its subtree's centre; one with no DOF never moves, and its bound following the
    // pose is then both exact and never dirtied.
    const DofMask dofs = def.getDofMask(node.getJointIndex());
    const bool covers =
        mode == ActorNode::BOUND_COVERS_ROTATIONS && (dofs & kRotationDofs) != 0 && (dofs & kTranslationDofs) == 0;
    node.setBoundCoversRotations(covers, toOsg(def.getOffsetTranslation(node.getJointIndex())));
}

} // namespace

ActorNode::ActorNode()
    : _lastControllerTime(std::numeric_limits<double>::quiet_NaN()), _cullState(new detail::ActorCullState),
      _cullPlanVersion(0), _poseVersion(0), _boundVersion(0), _transformMatricesDirty(true),
      _boundsToPropagate(false), _actorMatrixWritten(false), _blocked(false),
      _boundMode(BOUND_COVERS_ROTATIONS), _numUpdatesRun(0), _lastFrameNumber(kNoFrame), _cullMode(CULL_AS_ONE),
      _numUpdatesSkipped(0), _lodPhase(nextLodPhase()), _lastSeen(0)
{
    setDataVariance(osg::Object::DYNAMIC);
    setUpdateCallback(new ActorUpdateCallback);
}

ActorNode::ActorNode(ActorDefinitionPtr definition) : ActorNode()
{
    setDefinition(std::move(definition));
}

ActorNode::ActorNode(const ActorNode& actor, const osg::CopyOp& copyop)
    : osg::MatrixTransform(actor, SkeletonCopyOp(copyop)), _pose(actor._pose), _clipLibrary(actor._clipLibrary),
      _lastControllerTime(std::numeric_limits<double>::quiet_NaN()),
      _transforms(actor._transforms), _preTransformMatrix(actor._preTransformMatrix),
      _postTransformMatrix(actor._postTransformMatrix), _actorMatrix(actor._actorMatrix),
      _cullState(new detail::ActorCullState), _cullPlanVersion(0), _poseVersion(0), _boundVersion(0),
      _transformMatricesDirty(actor._transformMatricesDirty), _boundsToPropagate(false),
      _actorMatrixWritten(actor._actorMatrixWritten),
      _blocked(actor._blocked), _boundMode(actor._boundMode), _numUpdatesRun(0), _lastFrameNumber(kNoFrame),
      _cullMode(actor._cullMode), _updatePolicy(actor._updatePolicy), _numUpdatesSkipped(0),
      _lodPhase(nextLodPhase()), _lastSeen(0), _definitionObject(actor._definitionObject),
      _clipLibraryObject(actor._clipLibraryObject)
{
    for (const ControllerPtr& controller : actor._controllers)
        if (controller) _controllers.push_back(controller->cloneController());
    _ikChains = actor._ikChains; // immutable: shared
    rebindSkeletonNodes();
}

ActorNode::~ActorNode() = default;

bool ActorNode::reportEdit(bool edited)
{
    if (edited) dirtyCullPlan();
    return edited;
}

bool ActorNode::addChild(osg::Node* child) { return reportEdit(osg::MatrixTransform::addChild(child)); }

bool ActorNode::insertChild(unsigned int index, osg::Node* child)
{
    return reportEdit(osg::MatrixTransform::insertChild(index, child));
}

bool ActorNode::removeChildren(unsigned int pos, unsigned int numChildrenToRemove)
{
    return reportEdit(osg::MatrixTransform::removeChildren(pos, numChildrenToRemove));
}

bool ActorNode::setChild(unsigned int i, osg::Node* node) { return reportEdit(osg::MatrixTransform::setChild(i, node)); }

osg::BoundingSphere ActorNode::computeBound() const
{
    _boundVersion.fetch_add(1, std::memory_order_relaxed);
    // Computed at every frame where the root joint translates: without OSG's generic steps for this very class (a
    // subclass may compute its matrix otherwise).
    if (typeid(*this) != typeid(ActorNode)) return osg::MatrixTransform::computeBound();
    return detail::matrixTransformBound(*this, detail::childrenBound(_children));
}

void ActorNode::setDefinition(ActorDefinitionPtr definition)
{
    for (const osg::ref_ptr<SkeletonNode>& node : _skeletonNodes)
    {
        if (getDefinition() && getDefinition()->getParent(node->getJointIndex()) == kNoParent) removeChild(node.get());
    }
    releaseSkeletonNodes();
    // The nodes come first, each posed as it is made, so a fresh actor has correct bounds before its first frame;
    // the pose then takes their matrices where they are, and makes the model matrices on the first query. For a
    // large actor, whose nodes and pose do not fit the caches, every pass over them costs as much as its arithmetic:
    // the local matrices are written once, into memory the node's constructor has just written, and never copied.
    std::vector<double*> locals;
    if (definition) locals = buildSkeletonNodes(*definition);
    _pose = ActorPose(std::move(definition), ActorPose::LocalMatricesBuiltAt{std::move(locals)});
    updateSharedObjects();
    dropUnfittingIkChains();
    writeActorMatrix();
}

bool ActorNode::setDefinition(ActorDefinitionPtr definition, SkeletonNodePolicy policy)
{
    if (policy == BUILD_SKELETON_NODES)
    {
        setDefinition(std::move(definition));
        return true;
    }
    _pose = ActorPose(std::move(definition));
    updateSharedObjects();
    dropUnfittingIkChains();
    return rebindSkeletonNodes();
}

void ActorNode::setClipLibrary(ClipLibraryPtr library)
{
    _clipLibrary = std::move(library);
    updateSharedObjects();
}

void ActorNode::updateSharedObjects()
{
    _definitionObject = ActorDefinitionObject::of(getDefinition());
    _clipLibraryObject = ClipLibraryObject::of(_clipLibrary, _definitionObject.get());
}

void ActorNode::dropUnfittingIkChains()
{
    const ActorDefinition* def = getDefinition().get();
    _ikChains.erase(std::remove_if(_ikChains.begin(), _ikChains.end(),
                                   [def](const IkChainPtr& chain) { return !def || !chain->fits(*def); }),
                    _ikChains.end());
}

bool ActorNode::addIkChain(IkChainPtr chain)
{
    const ActorDefinition* def = getDefinition().get();
    std::string why;
    if (!chain) why = "a null IK chain";
    else if (!def || !chain->fits(*def)) why = "IK chain '" + chain->getName() + "', built for another skeleton";
    else if (findIkChain(chain->getName())) why = "a second IK chain named '" + chain->getName() + "'";
    if (!why.empty())
    {
        OSG_WARN << "osgActor: actor '" << getName() << "' refused " << why << std::endl;
        return false;
    }
    _ikChains.push_back(std::move(chain));
    return true;
}

bool ActorNode::removeIkChain(const std::string& name)
{
    const auto it = std::find_if(_ikChains.begin(), _ikChains.end(),
                                 [&name](const IkChainPtr& chain) { return chain->getName() == name; });
    if (it == _ikChains.end()) return false;
    _ikChains.erase(it);
    return true;
}

IkChainPtr ActorNode::findIkChain(const std::string& name) const
{
    for (const IkChainPtr& chain : _ikChains)
        if (chain->getName() == name) return chain;
    return IkChainPtr();
}

std::vector<double*> ActorNode::buildSkeletonNodes(const ActorDefinition& def)
{
    // Each node is made, posed, linked and given its bound mode in one visit, while its cache lines are fresh: a
    // large actor's nodes do not fit the caches, and every later pass over them would fetch them again.
    const unsigned numJoints = def.getNumJoints();
    const double* const defaultDofs = def.getDefaultDofs().data();
    // Each node's list of children made as long as it will be: grown child by child, it would be copied each time
    // it is full, and each copy touches every child (its reference count). [numJoints] counts this node's.
    std::vector<unsigned> numChildren(numJoints + 1, 0);
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const int parent = def.getParent(j);
        ++numChildren[parent == kNoParent ? numJoints : static_cast<unsigned>(parent)];
    }
    _children.reserve(_children.size() + numChildren[numJoints]);
    std::vector<double*> locals;
    locals.reserve(numJoints);
    _skeletonNodes.reserve(numJoints);
    // The nodes side by side in one block, in joint order: one allocation, not one per node.
    const detail::PlacedSkeletonNode::Batch batch(numJoints);
    for (unsigned j = 0; j < numJoints; ++j)
    {
        osg::ref_ptr<SkeletonNode> node = new detail::PlacedSkeletonNode(j, def.getJointName(j));
        if (numChildren[j] > 0) SkeletonNodeAccess::reserveChildren(*node, numChildren[j]);
        giveBoundMode(*node, def, _boundMode);
        // skl_m at the default DOFs (local space), written over the identity the constructor left: its inverse
        // must be made afresh.
        double* const matrix = SkeletonNodeAccess::matrixStorage(*node);
        writeJointMatrix(def.getKinematics(j), defaultDofs, matrix);
        SkeletonNodeAccess::matrixWritten(*node);
        locals.push_back(matrix);
        const int parent = def.getParent(j);
        // Not the skeleton node's addChild(): it would report each edit up its chain to this actor, a walk as deep
        // as the joint; the plan is dirtied once below.
        if (parent == kNoParent) osg::Group::addChild(node.get());
        else SkeletonNodeAccess::appendNewChild(*_skeletonNodes[static_cast<unsigned>(parent)], *node);
        _skeletonNodes.push_back(node);
    }
    dirtyCullPlan();
    // The nodes' matrices are new: a cull composes them afresh. No pass over the nodes to dirty them (a new node's
    // bound is not computed yet, nor are its parents').
    if (numJoints > 0) ++_poseVersion;
    _boundsToPropagate = true;
    return locals;
}

void ActorNode::bindLocalMatricesToNodes()
{
    std::vector<double*> targets;
    targets.reserve(_skeletonNodes.size());
    for (const osg::ref_ptr<SkeletonNode>& node : _skeletonNodes)
        targets.push_back(SkeletonNodeAccess::matrixStorage(*node));
    // Only fails on a count that does not match the definition, which both callers have ruled out.
    _pose.redirectLocalMatrices(targets);
    applyBoundMode();
}

void ActorNode::setBoundMode(BoundMode mode)
{
    _boundMode = mode;
    applyBoundMode();
}

void ActorNode::applyBoundMode()
{
    const ActorDefinition* def = getDefinition().get();
    if (!def) return;
    // Set on every node, changed or not: a new definition bound to the same nodes may move a joint's centre.
    for (const osg::ref_ptr<SkeletonNode>& node : _skeletonNodes) giveBoundMode(*node, *def, _boundMode);
}

void ActorNode::releaseSkeletonNodes()
{
    _pose.ownLocalMatrices();
    _skeletonNodes.clear();
}

bool ActorNode::rebindSkeletonNodes()
{
    releaseSkeletonNodes();
    const ActorDefinition* def = getDefinition().get();
    if (!def) return true;
    std::vector<osg::ref_ptr<SkeletonNode>> nodes(def->getNumJoints());
    bool complete = collectSkeletonNodes(*this, nodes);
    for (const osg::ref_ptr<SkeletonNode>& node : nodes) complete = complete && node.valid();
    if (!complete)
    {
        OSG_WARN << "osgActor: actor '" << getName() << "': its skeleton nodes do not match its definition"
                 << std::endl;
        return false;
    }
    _skeletonNodes.swap(nodes);
    bindLocalMatricesToNodes();
    // The nodes may hold stale matrices (a reader made them): write every joint at the next update.
    _pose.markAllJointsDirty();
    _actorMatrixWritten = false;
    return true;
}

SkeletonNode* ActorNode::getSkeletonNode(const std::string& jointName)
{
    const int joint = getJointIndex(jointName);
    return joint < 0 || static_cast<unsigned>(joint) >= _skeletonNodes.size()
               ? nullptr
               : _skeletonNodes[static_cast<unsigned>(joint)].get();
}

int ActorNode::getJointIndex(const std::string& jointName) const
{
    return getDefinition() ? getDefinition()->findJoint(jointName) : -1;
}

// --- DOFs ---

int ActorNode::getDofIndex(const std::string& name) const
{
    return getDefinition() ? getDefinition()->findDof(name) : -1;
}

bool ActorNode::getDof(const std::string& name, double& value) const
{
    const int index = getDofIndex(name);
    if (index < 0) return false;
    value = _pose.getDof(static_cast<unsigned>(index));
    return true;
}

bool ActorNode::reportRefusal(DofWriteStatus status, const std::string& what) const
{
    if (succeeded(status)) return true;
    OSG_WARN << "osgActor: actor '" << getName() << "': " << what;
    switch (status)
    {
    case DofWriteStatus::NotFinite: OSG_WARN << " refused a NaN or infinite value; the old value is kept"; break;
    case DofWriteStatus::NoSuchDof: OSG_WARN << ": there is no such DOF"; break;
    case DofWriteStatus::SizeMismatch: OSG_WARN << " was refused: the actor has " << getNumDofs() << " DOFs"; break;
    default: break;
    }
    OSG_WARN << std::endl;
    return false;
}

bool ActorNode::setDof(unsigned index, double value)
{
    const DofWriteStatus status = _pose.setDof(index, value);
    if (succeeded(status)) return true; // the common case builds no message
    const std::string name = index < getNumDofs() ? "DOF '" + getDefinition()->getDofName(index) + "'"
                                                  : "DOF #" + std::to_string(index);
    return reportRefusal(status, name);
}

bool ActorNode::setDof(const std::string& name, double value)
{
    const int index = getDofIndex(name);
    if (index < 0) return reportRefusal(DofWriteStatus::NoSuchDof, "DOF '" + name + "'");
    return setDof(static_cast<unsigned>(index), value);
}

bool ActorNode::setDofs(const std::vector<double>& values)
{
    const DofWriteStatus status = _pose.setDofs(values.data(), values.size());
    return reportRefusal(status, "a pose of " + std::to_string(values.size()) + " values");
}

void ActorNode::resetDofs() { _pose.resetDofs(); }

// --- pre- and post-transforms ---

template <class Value>
bool ActorNode::storeTransform(const Value& value, Value& member, bool (*valid)(const Value&), const char* what)
{
    if (!valid(value))
    {
        OSG_WARN << "osgActor: actor '" << getName() << "' refused a zero, non-finite or out-of-range (beyond +-"
                 << kMaxDofMagnitude << ") " << what << std::endl;
        return false;
    }
    member = value;
    _transformMatricesDirty = true;
    _actorMatrixWritten = false;
    return true;
}

void ActorNode::setPreTranslation(const osg::Vec3d& translation)
{
    storeTransform(toGlm(translation), _transforms.preTranslation, isValidTransformTranslation, "pre-translation");
}

void ActorNode::setPreRotation(const osg::Quat& rotation)
{
    storeTransform(toGlm(rotation), _transforms.preRotation, isValidTransformRotation, "pre-rotation");
}

void ActorNode::setPostTranslation(const osg::Vec3d& translation)
{
    storeTransform(toGlm(translation), _transforms.postTranslation, isValidTransformTranslation, "post-translation");
}

void ActorNode::setPostRotation(const osg::Quat& rotation)
{
    storeTransform(toGlm(rotation), _transforms.postRotation, isValidTransformRotation, "post-rotation");
}

osg::Vec3d ActorNode::getPreTranslation() const { return toOsg(_transforms.preTranslation); }
osg::Quat ActorNode::getPreRotation() const { return toOsg(_transforms.preRotation); }
osg::Vec3d ActorNode::getPostTranslation() const { return toOsg(_transforms.postTranslation); }
osg::Quat ActorNode::getPostRotation() const { return toOsg(_transforms.postRotation); }

bool ActorNode::setTransforms(const ActorTransforms& transforms)
{
    // Each on its own, as the four setters would: a controller's NaN is refused like a user's.
    bool stored = storeTransform(transforms.preTranslation, _transforms.preTranslation, isValidTransformTranslation,
                                 "pre-translation");
    stored = storeTransform(transforms.preRotation, _transforms.preRotation, isValidTransformRotation,
                            "pre-rotation") && stored;
    stored = storeTransform(transforms.postTranslation, _transforms.postTranslation, isValidTransformTranslation,
                            "post-translation") && stored;
    stored = storeTransform(transforms.postRotation, _transforms.postRotation, isValidTransformRotation,
                            "post-rotation") && stored;
    return stored;
}

void ActorNode::updateTransformMatrices() const
{
    if (!_transformMatricesDirty) return;
    _preTransformMatrix = toOsg(computePreTransformMatrix(_transforms));
    _postTransformMatrix = toOsg(computePostTransformMatrix(_transforms));
    _actorMatrix = toOsg(computeActorMatrix(_transforms));
    _transformMatricesDirty = false;
}

const osg::Matrixd& ActorNode::getPreTransformMatrix() const
{
    updateTransformMatrices();
    return _preTransformMatrix;
}

const osg::Matrixd& ActorNode::getPostTransformMatrix() const
{
    updateTransformMatrices();
    return _postTransformMatrix;
}

const osg::Matrixd& ActorNode::getActorMatrix() const
{
    updateTransformMatrices();
    return _actorMatrix;
}

// --- controllers ---

void ActorNode::addController(ControllerPtr controller)
{
    if (controller) _controllers.push_back(std::move(controller));
}

bool ActorNode::removeController(const ControllerPtr& controller)
{
    const auto it = std::find(_controllers.begin(), _controllers.end(), controller);
    if (it == _controllers.end()) return false;
    _controllers.erase(it);
    return true;
}

ControllerPtr ActorNode::findController(const std::string& name) const
{
    for (const ControllerPtr& controller : _controllers)
        if (controller->getName() == name) return controller;
    return ControllerPtr();
}

void ActorNode::runControllers(double time)
{
    if (_controllers.empty() || !std::isfinite(time)) return;
    ControllerContext context;
    context.time = time;
    // Negative when simulation time went back (a viewer scrubbing): players then move their play heads back.
    context.deltaTime = std::isnan(_lastControllerTime) ? 0.0 : time - _lastControllerTime;
    _lastControllerTime = time;

    ActorTransforms transforms = _transforms;
    if (std::any_of(_controllers.begin(), _controllers.end(),
                    [](const ControllerPtr& c) { return c && c->getEnabled() && c->usesWorldSpace(); }))
        context.parentToWorld = toGlm(computeParentWorldMatrix());
    ControllerTarget target{_pose, transforms};
    osgActor::runControllers(_controllers, context, target);
    if (target.transformsChanged) setTransforms(transforms);
}

// --- queries ---

void ActorNode::updatePose() const
{
    // A blocked actor applies no new DOF values but still answers with the pose its nodes show.
    if (_blocked)
    {
        _pose.updateModelMatrices();
        return;
    }
    if (_pose.updateMatrices() == 0) return;
    // FK wrote the changed matrices into the nodes in place: dirty the bounds now rather than at the next update.
    // Non-const work on behalf of a const query, like osg::Node::getBound() computing its cached bound.
    ActorNode* self = const_cast<ActorNode*>(this);
    self->writeJointMatrices();
    self->propagateBounds();
}

osg::Matrixd ActorNode::getJointModelMatrix(unsigned joint) const
{
    updatePose();
    return toOsg(_pose.getModelMatrix(joint));
}

osg::Matrixd ActorNode::getJointWorldMatrix(unsigned joint) const
{
    // actor_m is taken fresh rather than from our own node matrix, which only the update traversal writes.
    const osg::Matrixd& actor = _blocked ? getMatrix() : getActorMatrix();
    return getJointModelMatrix(joint) * actor * computeParentWorldMatrix();
}

osg::Matrixd ActorNode::computeParentWorldMatrix() const
{
    // The graph above us, through the first parent path; identity for an actor with no parent.
    const osg::NodePathList paths = getParentalNodePaths();
    if (paths.empty()) return osg::Matrixd();
    osg::NodePath above = paths.front();
    above.pop_back(); // this node
    return osg::computeLocalToWorld(above);
}

// --- per-frame work ---

void ActorNode::update(const osg::NodeVisitor* nv)
{
    const osg::FrameStamp* stamp = nv ? nv->getFrameStamp() : nullptr;
    if (!claimFrame(stamp)) return;
    if (poseWorkDue(stamp)) computeFrame(stamp ? stamp->getSimulationTime() : kNoTime);
    writeJointMatrices();
    writeActorMatrix();
}

unsigned char ActorNode::updateWithinGroup(const osg::FrameStamp* stamp)
{
    unsigned char left = hasUpdateTraversalWorkBeyondOwnUpdate() ? GROUP_WORK_VISIT : GROUP_WORK_NONE;
    if (!claimFrame(stamp)) return left;
    if (poseWorkDue(stamp)) computeFrame(stamp ? stamp->getSimulationTime() : kNoTime);
    writeJointMatrices();
    if (stamp) runPoseFollowers(stamp->getFrameNumber());
    // Nothing to write for a still actor_m whose bounds below stayed clean (the covering bounds' usual frame):
    // the update thread then need not touch this actor at all.
    if (!_actorMatrixWritten || _boundsToPropagate) left |= GROUP_WORK_WRITE_ACTOR_MATRIX;
    return left;
}

void ActorNode::runPoseFollowers(unsigned frameNumber)
{
    if (_poseFollowers.empty()) return;
    // Followers read the model matrices. With joints still dirty (pose work left for a later frame while DOFs were
    // written), bringing them up to date would write skeleton nodes and dirty bounds up shared parents: the update
    // traversal does it then, on its own thread.
    if (_pose.hasDirtyJoints()) return;
    bool posed = false;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < _poseFollowers.size(); ++i)
    {
        detail::PoseFollower& follower = *_poseFollowers[i];
        if (follower._lastMetFrame + 1 != frameNumber)
        {
            follower._listed = false; // no longer met by the traversal: removed, or its actor changed
            continue;
        }
        if (!posed) _pose.updateMatrices(); // no dirty joint: model matrices only, no node written
        posed = true;
        follower.followPose(*this, frameNumber);
        if (kept != i) _poseFollowers[kept] = _poseFollowers[i];
        ++kept;
    }
    _poseFollowers.resize(kept);
}

bool ActorNode::hasUpdateTraversalWorkBeyondOwnUpdate() const
{
    if (getNumChildrenRequiringUpdateTraversal() > 0) return true;
    const osg::Callback* callback = getUpdateCallback();
    if (!callback) return false;
    return typeid(*callback) != typeid(ActorUpdateCallback) || callback->getNestedCallback();
}

bool ActorNode::claimFrame(const osg::FrameStamp* stamp)
{
    if (stamp)
    {
        if (stamp->getFrameNumber() == _lastFrameNumber) return false;
        _lastFrameNumber = stamp->getFrameNumber();
    }
    if (_blocked) return false;
    ++_numUpdatesRun;
    return true;
}

void ActorNode::computeFrame(double time)
{
    // The skeleton nodes are written after the controllers and the local-matrices job have run: start fetching
    // them now, and the pointers to their matrices the job will write through.
    if (!_controllers.empty() || _pose.hasDirtyJoints())
    {
        const osg::ref_ptr<SkeletonNode>* nodes = _skeletonNodes.data();
        const std::size_t numNodes = _skeletonNodes.size();
        detail::prefetchForRead(_pose.getLocalMatrixTargets(), numNodes * sizeof(double*));
        // Two loops, so that neither tests the mode per node.
        if (_boundMode == BOUND_FOLLOWS_POSE)
            for (std::size_t j = 0; j < numNodes; ++j) SkeletonNodeAccess::prefetchForMatrixWrite(*nodes[j], true);
        else
            for (std::size_t j = 0; j < numNodes; ++j) SkeletonNodeAccess::prefetchForMatrixWrite(*nodes[j], false);
    }
    runControllers(time); // does nothing for kNoTime
    // Local matrices only: the scene graph composes them; model matrices wait for a query (updatePose()).
    _pose.updateLocalMatrices();
}

bool ActorNode::poseWorkDue(const osg::FrameStamp* stamp)
{
    if (!_updatePolicy.onlyWhenSeen || !stamp || _numUpdatesRun <= 1) return true; // always pose the first frame
    for (const ControllerPtr& controller : _controllers)
        if (controller && controller->getEnabled() && !controller->canSkipFrames()) return true;
    const std::uint64_t seen = _lastSeen.load(std::memory_order_relaxed);
    const unsigned frame = stamp->getFrameNumber();
    const unsigned seenFrame = static_cast<unsigned>(seen >> 32); // plus one; 0: never seen
    bool due = seenFrame != 0 && frame - (seenFrame - 1) <= 1; // seen at the previous frame or this one
    if (due)
    {
        const float size = bitsFloat(static_cast<std::uint32_t>(seen));
        const unsigned period = size < _updatePolicy.quarterRateBelowPixels ? 4u
                                : size < _updatePolicy.halfRateBelowPixels  ? 2u
                                                                             : 1u;
        due = (frame + _lodPhase) % period == 0;
    }
    if (!due) ++_numUpdatesSkipped;
    return due;
}

void ActorNode::prefetchCullAhead(const osg::Node& node, unsigned ahead) const
{
    if (ahead >= kCullLookahead)
    {
        // What accept() reads of the node, at the offsets of this actor's members: an address, not a read, so any
        // class of node may be asked for.
        const char* const self = reinterpret_cast<const char*>(this);
        const char* const other = reinterpret_cast<const char*>(&node);
        const auto span = [&](const void* first, const void* end) {
            const char* const begin = static_cast<const char*>(first);
            detail::prefetchForRead(other + (begin - self), static_cast<std::size_t>(static_cast<const char*>(end) - begin));
        };
        detail::prefetchLine(other); // its class
        span(&_boundingSphere, &_boundingSphereComputed + 1);
        // The flags and the reference frame; not actor_m, which the replay of an unchanged actor does not read.
        span(&_cullCallback, &_referenceFrame + 1);
        span(&_cullState, &_updatePolicy.onlyWhenSeen + 1); // the cull state and counters, cull mode and policy
        return;
    }
    if (typeid(node) != typeid(ActorNode)) return;
    static const detail::ActorCullState::AheadStage kStages[] = {
        detail::ActorCullState::AHEAD_NODES, detail::ActorCullState::AHEAD_PLAN_ARRAYS,
        detail::ActorCullState::AHEAD_PLAN, detail::ActorCullState::AHEAD_STATE};
    static_assert(sizeof(kStages) / sizeof(kStages[0]) + 1 == kCullLookahead, "a stage an actor");
    static_cast<const ActorNode&>(node)._cullState->prefetchAhead(kStages[ahead - 1]);
}

void ActorNode::prefetchSiblingsAhead(osg::NodeVisitor& nv) const
{
    // This actor's index among the children of the parent traversing it, found from the last actor this thread
    // culled (a crowd's actors are culled in child order), or else among the first few children: a bounded search.
    struct Cursor
    {
        const osg::Group* parent;
        unsigned index;
    };
    static thread_local Cursor cursor{nullptr, 0};
    const osg::NodePath& path = nv.getNodePath();
    const osg::Group* parent = path.size() >= 2 ? path[path.size() - 2]->asGroup() : nullptr;
    if (!parent) return;
    const unsigned numChildren = parent->getNumChildren();
    const auto find = [&](unsigned from) {
        const unsigned end = std::min(numChildren, from + kCullLookahead);
        for (unsigned i = from; i < end; ++i)
            if (parent->getChild(i) == this) return i;
        return numChildren;
    };
    unsigned index = cursor.parent == parent ? find(cursor.index + 1) : numChildren;
    if (index == numChildren) index = find(0);
    if (index == numChildren)
    {
        cursor.parent = nullptr;
        return;
    }
    cursor = {parent, index};
    for (unsigned ahead = 1; ahead <= kCullLookahead && index + ahead < numChildren; ++ahead)
        prefetchCullAhead(*parent->getChild(index + ahead), ahead);
    // The render leaf an idle actor two ahead will set, if each adds one (a batch), as a crowd of one kind does.
    if (nv.asCullVisitor()) detail::ActorCull::prefetchReusedLeaf(*nv.asCullVisitor(), 2);
}

void ActorNode::accept(osg::NodeVisitor& nv)
{
    if (!nv.validNodeMask(*this)) return;
    nv.pushOntoNodePath(this);
    osgUtil::CullVisitor* cv = nv.getVisitorType() == osg::NodeVisitor::CULL_VISITOR ? nv.asCullVisitor() : nullptr;
    // The actors after this one among its siblings, fetched ahead (a crowd's cull is bound by memory latency).
    if (cv && _cullMode == CULL_AS_ONE) prefetchSiblingsAhead(nv);
    // Only where the visitor would do nothing but test the bound, push the actor's frame and cull it as one: no cull
    // callback or state set here, a relative frame.
    const bool culledBeforeEntering = cv && _cullMode == CULL_AS_ONE && !getCullCallback() && !getStateSet() &&
                                      getReferenceFrame() == RELATIVE_RF && cullBeforeEntering(*cv);
    if (!culledBeforeEntering) nv.apply(*this);
    nv.popFromNodePath();
}

bool ActorNode::cullBeforeEntering(osgUtil::CullVisitor& cv)
{
    // Held already when an ActorGroup above prepared this cull on its threads: the group gives it back after.
    const bool held = _cullState->isHeldBy(&cv);
    if (!held && (!detail::ActorCull::canCullAsOne(cv) || !_cullState->tryAcquire())) return false;
    getBound(); // as the ordinary way computes it first: a recomputed bound is a change
    const detail::ActorCullState::Versions versions =
        detail::ActorCullState::versionsOf(_cullPlanVersion, _poseVersion, _boundVersion);
    const osg::Matrixd* seenModelView = nullptr;
    const bool done =
        held ? detail::ActorCull::cullPreparedBeforeEntering(cv, *_cullState, *this, versions, seenModelView)
             : detail::ActorCull::replayBeforeEntering(cv, *_cullState, *this, versions, seenModelView) ||
                   detail::ActorCull::replayReshapedBeforeEntering(cv, *_cullState, *this, versions, seenModelView);
    // What traverse() would note, from the matrix in the state: while it is held.
    if (seenModelView && _updatePolicy.onlyWhenSeen) noteSeenInFrame(cv, *seenModelView);
    if (!held) _cullState->release();
    return done;
}

void ActorNode::traverse(osg::NodeVisitor& nv)
{
    if (nv.getVisitorType() != osg::NodeVisitor::CULL_VISITOR)
    {
        // The optimizer's visitors are plain node visitors: the update traversal pays one comparison here.
        if (nv.getVisitorType() == osg::NodeVisitor::NODE_VISITOR &&
            dynamic_cast<osgUtil::Optimizer::RemoveEmptyNodesVisitor*>(&nv))
            return;
        osg::MatrixTransform::traverse(nv);
        return;
    }
    // The visitor found our bound visible to come here.
    osgUtil::CullVisitor* cv = nv.asCullVisitor();
    if (_updatePolicy.onlyWhenSeen && cv)
        noteSeen(*cv, *cv->getModelViewMatrix(), cv->getCurrentCullingSet().getPixelSizeVector());
    // Held already when an ActorGroup above prepared this cull on its threads: the group gives it back after.
    const bool held = cv && _cullState->isHeldBy(cv);
    if (_cullMode == CULL_AS_ONE && cv && detail::ActorCull::canCullAsOne(*cv) && (held || _cullState->tryAcquire()))
    {
        // The bound computed (the visitor did unless culling is off here): a change below recomputes it.
        getBound();
        detail::ActorCull(*cv, *_cullState, *this,
                          detail::ActorCullState::versionsOf(_cullPlanVersion, _poseVersion, _boundVersion));
        if (!held) _cullState->release();
    }
    else
        // Another visitor's cull, or one of another thread culling this actor for another camera at this moment.
        osg::MatrixTransform::traverse(nv);
}

bool ActorNode::prepareCullWithinGroup(const detail::ActorCullView& view, const osg::Matrixd& groupModelView,
                                       const osg::CullingSet& groupCullingSet, const void* visitor)
{
    // What the visitor will do on its way in (CullVisitor::apply(osg::Transform&)), foreseen; where it does
    // otherwise, the actor's cull finds nothing prepared for what the visitor holds and prepares it then.
    if (_cullMode != CULL_AS_ONE || getCullCallback() || (view.traversalMask & (view.nodeMaskOverride | getNodeMask())) == 0)
        return false;
    if (isCullingActive() && detail::ActorCullView::isCulled(groupCullingSet, getBound())) return false;
    if (!_cullState->tryAcquireFor(visitor)) return false; // another camera's cull has it
    osg::Matrixd modelView = groupModelView;
    computeLocalToWorldMatrix(modelView, nullptr); // the visitor's call, so the same bits
    const osg::Vec4 pixelSizeVector =
        osg::CullingSet::computePixelSizeVector(*view.viewport, view.projection, modelView); // as pushCullingSet()
    _cullState->prepare(view, modelView, pixelSizeVector, *this,
                        detail::ActorCullState::versionsOf(_cullPlanVersion, _poseVersion, _boundVersion));
    return true;
}

void ActorNode::releaseCullWithinGroup(const void* visitor) { _cullState->releaseFrom(visitor); }

void ActorNode::noteSeenInFrame(const osgUtil::CullVisitor& cv, const osg::Matrixd& modelView)
{
    noteSeen(cv, modelView,
             osg::CullingSet::computePixelSizeVector(*cv.getViewport(), *cv.getProjectionMatrix(), modelView));
}

void ActorNode::noteSeen(const osg::NodeVisitor& nv, const osg::Matrixd& modelView, const osg::Vec4& pixelSizeVector)
{
    const osg::FrameStamp* stamp = nv.getFrameStamp();
    if (!stamp) return;
    // Distance and size at the root joint's origin (the body, which may walk away from the reference point), in
    // this node's frame; the size as osg::CullingSet::clampedPixelSize() computes it.
    const osg::Vec3d root = _skeletonNodes.empty() ? osg::Vec3d() : _skeletonNodes.front()->getMatrix().getTrans();
    const osg::Vec3d eye = root * modelView;
    if (!(eye.length() <= _updatePolicy.maxDistance)) return;
    const float size = std::fabs(getBound().radius() / (osg::Vec3(root) * pixelSizeVector));
    const std::uint64_t frame = static_cast<std::uint64_t>(stamp->getFrameNumber()) + 1u;
    // Several cull threads may see the actor in one frame: keep the largest size of the latest frame.
    std::uint64_t old = _lastSeen.load(std::memory_order_relaxed);
    for (;;)
    {
        const bool sameFrame = (old >> 32) == frame;
        if (sameFrame && !(bitsFloat(static_cast<std::uint32_t>(old)) < size)) return;
        if (!sameFrame && (old >> 32) > frame) return; // a later frame noted already
        const std::uint64_t noted = (frame << 32) | floatBits(std::isfinite(size) ? size : std::numeric_limits<float>::max());
        if (_lastSeen.compare_exchange_weak(old, noted, std::memory_order_relaxed)) return;
    }
}

void ActorNode::writeJointMatrices()
{
    // Nothing written since the last call (an idle actor): nothing read past the pose's flag.
    if (!_pose.hasChangedLocals()) return;
    if (_boundMode == BOUND_COVERS_ROTATIONS)
    {
        writeJointMatricesKeepingBalls();
        return;
    }
    const int* parents = getDefinition() ? getDefinition()->getParents().data() : nullptr;
    const osg::ref_ptr<SkeletonNode>* nodes = _skeletonNodes.data();
    const std::size_t numNodes = _skeletonNodes.size();
    bool dirtied = false; // a local, not the member, inside the loop: it then stays in a register
    _pose.consumeChangedLocals([&](unsigned joint, double*) {
        if (joint >= numNodes) return;
        writeDirtyingBounds(parents, nodes, joint);
        dirtied = true;
    });
    if (dirtied)
    {
        _boundsToPropagate = true;
        ++_poseVersion;
    }
}

void ActorNode::writeJointMatricesKeepingBalls()
{
    const int* parents = getDefinition() ? getDefinition()->getParents().data() : nullptr;
    const osg::ref_ptr<SkeletonNode>* nodes = _skeletonNodes.data();
    const std::size_t numNodes = _skeletonNodes.size();
    bool dirtied = false;
    bool written = false;
    _pose.consumeChangedLocals([&](unsigned joint, double*) {
        if (joint >= numNodes) return;
        written = true;
        // A ball that holds every rotation of the joint does not change as it turns: no bound to dirty, here or
        // above. (The flag shares a cache line with the inverse's flag, which is written anyway.)
        SkeletonNode& node = *nodes[joint];
        if (!node.getBoundCoversRotations()) writeDirtyingBounds(parents, nodes, joint);
        else if (SkeletonNodeAccess::matrixWrittenKeepingBall(node)) dirtyBoundsAbove(parents, nodes, joint);
        else return;
        dirtied = true;
    });
    if (dirtied) _boundsToPropagate = true;
    if (written) ++_poseVersion; // the cull composes the joints' matrices afresh
}

void ActorNode::writeActorMatrix()
{
    if (!_actorMatrixWritten)
    {
        setMatrix(getActorMatrix()); // dirties this node's bound and its parents'
        _actorMatrixWritten = true;
        _boundsToPropagate = false;
    }
    propagateBounds();
}

void ActorNode::propagateBounds()
{
    if (!_boundsToPropagate) return;
    dirtyBound();
    _boundsToPropagate = false;
}

} // namespace osgActor
