#include "NodeTestUtil"
#include "TestMath"

#include <osgActor/ActorUpdateCallback>
#include <osgActor/GlmOsg>
#include <osgActor/core/LocalMatricesJob>

#include <osg/MatrixTransform>

#include <cmath>
#include <fstream>
#include <sstream>
#include <cstdint>
#include <limits>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kQuarter = osg::PI_2;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

} // namespace

// --- refusals first ---

TEST(ActorNode, RefusesUnknownDofNamesAndNaN)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    EXPECT_FALSE(actor->setDof("elbow.rz", 1.0));
    EXPECT_FALSE(actor->setDof("upper.rx", 1.0)) << "upper has no rx";
    EXPECT_FALSE(actor->setDof(99u, 1.0));
    ASSERT_TRUE(actor->setDof("upper.rz", 0.5));
    EXPECT_FALSE(actor->setDof("upper.rz", kNaN));
    double value = 0.0;
    ASSERT_TRUE(actor->getDof("upper.rz", value));
    EXPECT_EQ(value, 0.5);
    EXPECT_FALSE(actor->getDof("nobody.rz", value));
    EXPECT_FALSE(actor->setDofs({1.0, 2.0}));
    EXPECT_EQ(actor->getDof(1u), 0.5);
}

TEST(ActorNode, RefusesNonFiniteTransforms)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->setPreTranslation(osg::Vec3d(1, 2, 3));
    actor->setPreTranslation(osg::Vec3d(kNaN, 0, 0));
    actor->setPostRotation(osg::Quat(0, 0, 0, 0));
    EXPECT_EQ(actor->getPreTranslation(), osg::Vec3d(1, 2, 3));
    EXPECT_EQ(actor->getPostRotation(), osg::Quat());
    EXPECT_TRUE(actor->getActorMatrix().valid());
}

TEST(ActorNode, SetTransformsRefusesEachBadValueOnItsOwn)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    ActorTransforms t;
    t.preTranslation = glm::dvec3(1, 2, 3);
    t.preRotation = glm::dquat(0, 0, 0, 0); // refused
    t.postTranslation = glm::dvec3(0, 0, 2 * kMaxDofMagnitude); // refused
    t.postRotation = glm::dquat(0, 0, 0, 1); // half a turn about Z
    EXPECT_FALSE(actor->setTransforms(t));
    EXPECT_EQ(actor->getTransforms().preTranslation, glm::dvec3(1, 2, 3));
    EXPECT_EQ(actor->getTransforms().preRotation, glm::dquat(1, 0, 0, 0)) << "the old value kept";
    EXPECT_EQ(actor->getTransforms().postTranslation, glm::dvec3(0, 0, 0)) << "the old value kept";
    EXPECT_EQ(actor->getPostRotation(), osg::Quat(0, 0, 1, 0)) << "the OSG getter reads the same value";
    // actor_m = T(1, 2, 3) * Rz(180).
    EXPECT_TRUE(matricesNear(toGlm(actor->getActorMatrix()), fromRows(-1, 0, 0, 1, 0, -1, 0, 2, 0, 0, 1, 3), 1e-15));
}

TEST(ActorNode, AnEmptyActorIsHarmless)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode;
    EXPECT_EQ(actor->getNumDofs(), 0u);
    EXPECT_EQ(actor->getNumSkeletonNodes(), 0u);
    EXPECT_EQ(actor->getSkeletonNode("x"), nullptr);
    EXPECT_FALSE(actor->setDof("x.rx", 0.0));
    runUpdate(*actor, 1);
}

// --- structure ---

TEST(ActorNode, BuildsOneSkeletonNodePerJointNestedLikeTheBody)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    ASSERT_EQ(actor->getNumSkeletonNodes(), 4u);
    ASSERT_EQ(actor->getNumChildren(), 1u);
    EXPECT_EQ(actor->getChild(0), actor->getSkeletonNode(0u));
    for (unsigned j = 1; j < 4; ++j)
    {
        SkeletonNode* node = actor->getSkeletonNode(j);
        EXPECT_EQ(node->getJointIndex(), j);
        EXPECT_EQ(node->getName(), actor->getDefinition()->getJointName(j));
        ASSERT_EQ(node->getNumParents(), 1u);
        EXPECT_EQ(node->getParent(0), actor->getSkeletonNode(j - 1));
    }
    EXPECT_EQ(actor->getSkeletonNode("lower"), actor->getSkeletonNode(2u));
    EXPECT_EQ(actor->getUpdateCallback() != nullptr, true);
    EXPECT_NE(dynamic_cast<ActorUpdateCallback*>(actor->getUpdateCallback()), nullptr);
}

TEST(ActorNode, ItsSkeletonNodesCountWhatIsBelowThemAsOsgGroupsDo)
{
    // The build links each joint below its parent without osg::Group::insertChild(): the links must still carry
    // what OSG counts up the parents, as a callback or a disabled culling set on the deepest joint after the build.
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    for (unsigned j = 0; j < 4; ++j)
    {
        const SkeletonNode& node = *actor->getSkeletonNode(j);
        EXPECT_EQ(node.getNumChildrenRequiringUpdateTraversal(), 0u) << j;
        EXPECT_EQ(node.getNumChildrenRequiringEventTraversal(), 0u) << j;
        EXPECT_EQ(node.getNumChildrenWithCullingDisabled(), 0u) << j;
        EXPECT_EQ(node.getNumChildrenWithOccluderNodes(), 0u) << j;
    }
    struct Count : osg::NodeCallback
    {
        unsigned calls = 0;
        void operator()(osg::Node* node, osg::NodeVisitor* nv) override
        {
            ++calls;
            traverse(node, nv);
        }
    };
    osg::ref_ptr<Count> count = new Count;
    SkeletonNode& tip = *actor->getSkeletonNode(3u);
    tip.setUpdateCallback(count.get());
    tip.setCullingActive(false);
    for (unsigned j = 0; j < 3; ++j)
    {
        EXPECT_EQ(actor->getSkeletonNode(j)->getNumChildrenRequiringUpdateTraversal(), 1u) << j;
        EXPECT_EQ(actor->getSkeletonNode(j)->getNumChildrenWithCullingDisabled(), 1u) << j;
    }
    runUpdate(*actor, 1);
    EXPECT_EQ(count->calls, 1u);
    tip.setUpdateCallback(nullptr);
    EXPECT_EQ(actor->getSkeletonNode(0u)->getNumChildrenRequiringUpdateTraversal(), 0u);
}

namespace {

/** A user's actor class: the shared callback must still find the ActorNode in it. */
class DerivedActor : public ActorNode
{
public:
    using ActorNode::ActorNode;
};

} // namespace

TEST(ActorNode, TheUpdateCallbackDrivesSubclassesAndLeavesOtherNodesAlone)
{
    osg::ref_ptr<DerivedActor> derived = new DerivedActor(makePlanarArm());
    ASSERT_TRUE(derived->setDof("upper.rz", kQuarter));
    runUpdate(*derived, 1);
    EXPECT_EQ(derived->getNumUpdatesRun(), 1u);
    EXPECT_TRUE(vec3Near(osg::Vec3d(1, 0, 0) * derived->getSkeletonNode(1u)->getMatrix(), osg::Vec3d(1, 1, 0), 1e-15));

    // On a node that is no actor it only passes the traversal on (to a child's callback here).
    struct Counting : osg::NodeCallback
    {
        void operator()(osg::Node* node, osg::NodeVisitor* nv) override
        {
            ++count;
            traverse(node, nv);
        }
        int count = 0;
    };
    osg::ref_ptr<osg::Group> group = new osg::Group;
    group->setUpdateCallback(new ActorUpdateCallback);
    osg::ref_ptr<osg::Group> child = new osg::Group;
    osg::ref_ptr<Counting> counting = new Counting;
    child->setUpdateCallback(counting.get());
    group->addChild(child.get());
    runUpdate(*group, 1);
    EXPECT_EQ(counting->count, 1);
    osg::ref_ptr<ActorUpdateCallback> callback = new ActorUpdateCallback;
    (*callback)(nullptr, nullptr); // nothing to drive, and no crash
}

TEST(ActorNode, AFreshActorIsPosedBeforeItsFirstFrame)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    EXPECT_TRUE(vec3Near(actor->getSkeletonNode(3u)->getMatrix().getTrans(), osg::Vec3d(0.5, 0, 0)));
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(3), osg::Vec3d(2.5, 0, 0)));
}

TEST(ActorNode, AFreshActorsSkeletonNodesGiveTheInverseOfTheirPoseBeforeItsFirstFrame)
{
    // The nodes' matrices are written in place as the actor is made, not through setMatrix(): their inverses must
    // be made from those matrices, not kept from the identity the nodes were made with.
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    EXPECT_TRUE(vec3Near(actor->getSkeletonNode(1u)->getInverseMatrix().getTrans(), osg::Vec3d(-1, 0, 0)));
    EXPECT_TRUE(vec3Near(actor->getSkeletonNode(2u)->getInverseMatrix().getTrans(), osg::Vec3d(-1, 0, 0)));
    EXPECT_TRUE(vec3Near(actor->getSkeletonNode(3u)->getInverseMatrix().getTrans(), osg::Vec3d(-0.5, 0, 0)));
}

// --- DOFs reach the node matrices in the update traversal ---

TEST(ActorNode, UpdateTraversalWritesTheJointMatrices)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    ASSERT_TRUE(actor->setDof("upper.rz", kQuarter));
    // Before the update traversal the node still shows the old pose...
    EXPECT_TRUE(vec3Near(actor->getSkeletonNode(2u)->getMatrix().getTrans(), osg::Vec3d(1, 0, 0)));
    runUpdate(*actor, 1);
    // ...after it, skl_m = T(1,0,0) * Rz(90): X axis along +Y.
    const osg::Matrixd& m = actor->getSkeletonNode(1u)->getMatrix();
    EXPECT_TRUE(vec3Near(osg::Vec3d(1, 0, 0) * m - m.getTrans(), osg::Vec3d(0, 1, 0), 1e-15));
    EXPECT_TRUE(vec3Near(m.getTrans(), osg::Vec3d(1, 0, 0)));
    // The matrix written is exactly the core's.
    const ActorDefinition& def = *actor->getDefinition();
    EXPECT_EQ(m, toOsg(computeJointMatrix(def.getKinematics(1), actor->getDofs().data())));
}

TEST(ActorNode, UpdatedFlagRecomputesOnlyTheMovedJoint)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    const std::uint64_t start = actor->getPose().getTotalRecomputedJoints();
    EXPECT_EQ(start, 4u) << "construction computes every joint once";
    runUpdate(*actor, 1);
    EXPECT_EQ(actor->getPose().getTotalRecomputedJoints(), start) << "an idle actor recomputes nothing";
    actor->setDof("lower.rz", 0.3);
    runUpdate(*actor, 2);
    EXPECT_EQ(actor->getPose().getTotalRecomputedJoints(), start + 1);
    actor->setDof("base.rz", 0.3);
    runUpdate(*actor, 3);
    EXPECT_EQ(actor->getPose().getTotalRecomputedJoints(), start + 2) << "children move without recomputation";
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(1), osg::Vec3d(std::cos(0.3), std::sin(0.3), 0)));
}

TEST(ActorNode, LimitsAreEnforcedOnWrite)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    EXPECT_TRUE(actor->setDof("upper.rz", 5.0));
    EXPECT_EQ(actor->getDof(1u), 2.0);
}

TEST(ActorNode, ANewActorShowsItsDefaultPoseAndABlockedOneComposesItOnTheFirstQuery)
{
    // Each joint turned a quarter about z by default, each child one unit along its parent's x (model units).
    ActorDefinitionBuilder b("bent");
    b.addJoint("base").dofs(dofBit(Dof::RZ)).defaultValue(Dof::RZ, kQuarter);
    b.addJoint("upper", "base").offset(1, 0, 0).dofs(dofBit(Dof::RZ)).defaultValue(Dof::RZ, kQuarter);
    b.addJoint("hand", "upper").offset(1, 0, 0);
    osg::ref_ptr<ActorNode> actor = new ActorNode(b.build().definition);
    // The nodes hold the local matrices (local space): upper one unit along x, x turned onto y.
    const osg::Matrixd& upper = actor->getSkeletonNode(1)->getMatrix();
    EXPECT_TRUE(vec3Near(upper.getTrans(), osg::Vec3d(1, 0, 0)));
    EXPECT_TRUE(vec3Near(osg::Vec3d(1, 0, 0) * osg::Matrixd::rotate(upper.getRotate()), osg::Vec3d(0, 1, 0), 1e-15));
    // Blocked before any query or frame: the model matrices are composed from the nodes' on the first query.
    actor->setBlocked(true);
    EXPECT_TRUE(vec3Near(actor->getJointModelMatrix(1).getTrans(), osg::Vec3d(0, 1, 0), 1e-15));
    EXPECT_TRUE(vec3Near(actor->getJointModelMatrix(2).getTrans(), osg::Vec3d(-1, 1, 0), 1e-15)) << "turned twice";
}

TEST(ActorNode, BlockFreezesTheActorUntilUnblocked)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->setBlocked(true);
    actor->setDof("base.rz", kQuarter);
    actor->setPreTranslation(osg::Vec3d(0, 0, 5));
    runUpdate(*actor, 1);
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(3), osg::Vec3d(2.5, 0, 0))) << "frozen";
    EXPECT_TRUE(actor->getMatrix().isIdentity());
    EXPECT_EQ(actor->getDof(0u), kQuarter) << "the write is kept";
    actor->setBlocked(false);
    runUpdate(*actor, 2);
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(3), osg::Vec3d(0, 2.5, 5), 1e-14));
    EXPECT_TRUE(vec3Near(actor->getMatrix().getTrans(), osg::Vec3d(0, 0, 5)));
}

// --- pre- and post-transforms ---

TEST(ActorNode, ActorMatrixIsPreTimesPost)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->setPreTranslation(osg::Vec3d(0, 5, 0));
    actor->setPreRotation(osg::Quat(kQuarter, osg::Vec3d(0, 0, 1)));
    actor->setPostTranslation(osg::Vec3d(0, 0, 1));
    // A point p of the skeleton frame goes to pretr_m * posttr_m * p: (1,0,0) -> (1,0,1) -> (0,1,1) -> (0,6,1).
    EXPECT_TRUE(vec3Near(osg::Vec3d(1, 0, 0) * actor->getActorMatrix(), osg::Vec3d(0, 6, 1), 1e-14));
    EXPECT_TRUE(vec3Near(osg::Vec3d(1, 0, 0) * actor->getPostTransformMatrix(), osg::Vec3d(1, 0, 1)));
    EXPECT_TRUE(vec3Near(osg::Vec3d(1, 0, 0) * actor->getPreTransformMatrix(), osg::Vec3d(0, 6, 0), 1e-14));
    runUpdate(*actor, 1);
    EXPECT_EQ(actor->getMatrix(), actor->getActorMatrix());
}

TEST(ActorNode, WorldQueriesGoThroughTransformsAboveTheActor)
{
    osg::ref_ptr<osg::MatrixTransform> above = new osg::MatrixTransform(osg::Matrixd::translate(10, 0, 0));
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    above->addChild(actor.get());
    actor->setPreTranslation(osg::Vec3d(0, 5, 0));
    actor->setPreRotation(osg::Quat(kQuarter, osg::Vec3d(0, 0, 1)));
    actor->setPostTranslation(osg::Vec3d(0, 0, 1));
    // Joint "upper" is at (1,0,0) in the skeleton frame: world (10,6,1), before any update traversal.
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(1), osg::Vec3d(10, 6, 1), 1e-14));
    // After the update, OSG's own accumulation of the node path agrees.
    actor->setDof("upper.rz", 0.7);
    runUpdate(*above, 1);
    for (unsigned j = 0; j < actor->getNumSkeletonNodes(); ++j)
    {
        const osg::Matrixd fromGraph = actor->getSkeletonNode(j)->getWorldMatrices().front();
        const osg::Matrixd fromQuery = actor->getJointWorldMatrix(j);
        for (int k = 0; k < 16; ++k) EXPECT_NEAR(fromGraph.ptr()[k], fromQuery.ptr()[k], 1e-12) << "joint " << j;
    }
}

TEST(ActorNode, WorldQueriesAreCurrentBetweenFramesAndLeaveTheGraphConsistent)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE); // bounds that show where the hand is
    actor->getSkeletonNode(3u)->addChild(makeBox(osg::Vec3(), 0.1f)); // a hand at the tip, (2.5, 0, 0)
    EXPECT_TRUE(vec3Near(actor->getBound().center(), osg::Vec3d(2.5, 0, 0), 1e-6));
    actor->setDof("base.rz", kQuarter);
    EXPECT_TRUE(actor->getSkeletonNode(0u)->getMatrix().isIdentity()) << "a DOF write alone touches no node";
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(3), osg::Vec3d(0, 2.5, 0), 1e-14));
    // The query ran FK, which writes the nodes in place; their bounds follow at once, as with setMatrix().
    EXPECT_TRUE(vec3Near(osg::Vec3d(1, 0, 0) * actor->getSkeletonNode(0u)->getMatrix(), osg::Vec3d(0, 1, 0), 1e-15));
    EXPECT_TRUE(vec3Near(actor->getBound().center(), osg::Vec3d(0, 2.5, 0), 1e-6)) << "the bound follows the hand";
    runUpdate(*actor, 1);
    EXPECT_TRUE(vec3Near(actor->getBound().center(), osg::Vec3d(0, 2.5, 0), 1e-6));
}

TEST(ActorNode, RunsOncePerFrameWithSeveralParents)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::MatrixTransform> left = new osg::MatrixTransform(osg::Matrixd::translate(-5, 0, 0));
    osg::ref_ptr<osg::MatrixTransform> right = new osg::MatrixTransform(osg::Matrixd::translate(5, 0, 0));
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    left->addChild(actor.get());
    right->addChild(actor.get());
    root->addChild(left.get());
    root->addChild(right.get());
    runUpdate(*root, 1);
    EXPECT_EQ(actor->getNumUpdatesRun(), 1u);
    runUpdate(*root, 2);
    EXPECT_EQ(actor->getNumUpdatesRun(), 2u);
    // Without a frame stamp (a hand-made visitor) every visit does the work.
    osgUtil::UpdateVisitor bare;
    root->accept(bare);
    EXPECT_EQ(actor->getNumUpdatesRun(), 4u);
}

TEST(ActorNode, UserCallbacksBelowTheActorStillRun)
{
    struct Counter : osg::NodeCallback
    {
        unsigned calls = 0;
        void operator()(osg::Node* node, osg::NodeVisitor* nv) override
        {
            ++calls;
            traverse(node, nv);
        }
    };
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    osg::ref_ptr<Counter> counter = new Counter;
    osg::ref_ptr<osg::Geode> sword = makeBox(osg::Vec3(), 0.1f);
    sword->setUpdateCallback(counter.get());
    actor->getSkeletonNode("tip")->addChild(sword.get());
    runUpdate(*actor, 1);
    EXPECT_EQ(counter->calls, 1u);
}

TEST(ActorNode, SetDofsWritesTheWholePose)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    ASSERT_TRUE(actor->setDofs({kQuarter, 0.0, -kQuarter}));
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(3), osg::Vec3d(0.5, 2, 0), 1e-14));
    actor->resetDofs();
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(3), osg::Vec3d(2.5, 0, 0), 1e-14));
}

TEST(ActorNode, SetDefinitionRebuildsTheSkeletonAndKeepsOtherChildren)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    osg::ref_ptr<osg::Geode> marker = makeBox(osg::Vec3(), 0.1f);
    actor->addChild(marker.get());
    ActorDefinitionBuilder b;
    b.addJoint("only").dofs(dofBit(Dof::TX));
    actor->setDefinition(b.build().definition);
    EXPECT_EQ(actor->getNumSkeletonNodes(), 1u);
    EXPECT_EQ(actor->getNumChildren(), 2u);
    EXPECT_TRUE(actor->containsNode(marker.get()));
    EXPECT_EQ(actor->getDofIndex("only.tx"), 0);
}

// --- controllers run in the update traversal, before forward kinematics ---

namespace {

/** Turns base.rz at one radian per second and walks the reference point along X at 2 units per second. */
class SpinController : public Controller
{
public:
    void update(const ControllerContext& context, ControllerTarget& target) override
    {
        writeDof(target.pose, 0, context.time);
        target.transforms.preTranslation.x = 2.0 * context.time;
        target.transformsChanged = true;
        deltas.push_back(context.deltaTime);
    }
    std::shared_ptr<Controller> cloneController() const override { return std::make_shared<SpinController>(); }
    std::vector<double> deltas;
};

} // namespace

TEST(ActorNode, ControllersDriveDofsAndTransformsFromTheFrameStamp)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    auto spin = std::make_shared<SpinController>();
    spin->setName("spin");
    actor->addController(spin);
    EXPECT_EQ(actor->findController("spin"), spin);
    runUpdate(*actor, 30); // simulation time 0.5 s
    EXPECT_EQ(actor->getDof(0u), 0.5);
    EXPECT_TRUE(vec3Near(actor->getMatrix().getTrans(), osg::Vec3d(1, 0, 0)));
    EXPECT_TRUE(vec3Near(osg::Vec3d(1, 0, 0) * actor->getSkeletonNode(0u)->getMatrix(),
                         osg::Vec3d(std::cos(0.5), std::sin(0.5), 0), 1e-15));
    runUpdate(*actor, 60);
    EXPECT_EQ(spin->deltas, (std::vector<double>{0.0, 0.5}));
    EXPECT_TRUE(vec3Near(actor->getJointWorldPosition(1), osg::Vec3d(2 + std::cos(1.0), std::sin(1.0), 0), 1e-14));

    // A clone gets its own controller instance.
    osg::ref_ptr<ActorNode> copy = osg::clone(actor.get(), osg::CopyOp::SHALLOW_COPY);
    ASSERT_EQ(copy->getControllers().size(), 1u);
    EXPECT_NE(copy->getControllers()[0], spin);

    EXPECT_TRUE(actor->removeController(spin));
    EXPECT_FALSE(actor->removeController(spin));
    runUpdate(*actor, 90);
    EXPECT_EQ(actor->getDof(0u), 1.0) << "no controller, no motion";
}

TEST(ActorNode, TheSkeletonNodesItBuildsOrCopiesHaveMatricesThatStartACacheLine)
{
    // A performance property (docs/performance.md), checked here because nothing else would notice its loss.
    osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
    osg::ref_ptr<ActorNode> clone = osg::clone(actor.get(), osg::CopyOp::DEEP_COPY_NODES);
    std::vector<const SkeletonNode*> nodes;
    for (unsigned j = 0; j < actor->getNumSkeletonNodes(); ++j)
    {
        nodes.push_back(actor->getSkeletonNode(j));
        nodes.push_back(clone->getSkeletonNode(j));
    }
    for (const SkeletonNode* node : nodes)
    {
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(node->getMatrix().ptr()) % 64, 0u) << node->getName();
        EXPECT_STREQ(node->className(), "SkeletonNode") << "what osgDB writes it as";
    }
    EXPECT_NE(clone->getSkeletonNode(1u), actor->getSkeletonNode(1u)) << "the clone has nodes of its own";
}

#if defined(__linux__)
namespace {

/** The flags /proc/self/smaps gives the mapping that holds address ("hg": advised to use huge pages), or "" where
  * none holds it. */
std::string mappingFlags(const void* address)
{
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(address);
    std::ifstream smaps("/proc/self/smaps");
    bool inside = false;
    for (std::string line; std::getline(smaps, line);)
    {
        std::uintptr_t begin = 0, end = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> begin >> dash >> end && dash == '-' && line.find(' ') != std::string::npos &&
            line.find(':') > line.find(' '))
            inside = begin <= at && at < end;
        else if (inside && line.compare(0, 8, "VmFlags:") == 0)
            return line.substr(8) + " ";
    }
    return std::string();
}

} // namespace

TEST(ActorNode, ALargeActorsSkeletonNodesLieSideBySideOnMemoryAdvisedForHugePages)
{
    // A performance property (docs/performance.md: a large actor builds with a page fault per huge page, not per
    // small page), checked here because nothing else would notice its loss; and the nodes in such a block behave.
    constexpr unsigned kJoints = 6000; // more than 2 MB of nodes
    ActorDefinitionBuilder builder("long chain");
    builder.reserve(kJoints);
    builder.addJoint("j0").dofs(dofBit(Dof::RZ));
    for (unsigned j = 1; j < kJoints; ++j)
        builder.addJoint("j" + std::to_string(j), "j" + std::to_string(j % 500 == 1 ? 0 : j - 1))
            .offset(0.1, 0.0, 0.0)
            .dofs(dofBit(Dof::RZ));
    const BuildResult built = builder.build();
    ASSERT_TRUE(built) << built.error;
    osg::ref_ptr<ActorNode> actor = new ActorNode(built.definition);
    ASSERT_EQ(actor->getNumSkeletonNodes(), kJoints);

    const char* first = reinterpret_cast<const char*>(actor->getSkeletonNode(0u));
    const std::ptrdiff_t stride = reinterpret_cast<const char*>(actor->getSkeletonNode(1u)) - first;
    EXPECT_GT(stride, 0);
    EXPECT_EQ(stride % 64, 0);
    for (unsigned j = 0; j < kJoints; ++j)
        ASSERT_EQ(reinterpret_cast<const char*>(actor->getSkeletonNode(j)) - first, stride * j) << "joint " << j;
    // The block starts a huge page, the first node just after the block's header.
    const char* inHugePage = first;
    const std::string thp = [] {
        std::ifstream enabled("/sys/kernel/mm/transparent_hugepage/enabled");
        std::string text;
        std::getline(enabled, text);
        return text;
    }();
    if (!thp.empty() && thp.find("[never]") == std::string::npos)
    {
        EXPECT_NE(mappingFlags(inHugePage).find(" hg "), std::string::npos) << mappingFlags(inHugePage);
    }

    // Posed, edited and given back like any other.
    actor->setDof(actor->getDefinition()->getFirstDof(kJoints - 1), 0.5);
    actor->update(nullptr);
    EXPECT_NEAR(actor->getSkeletonNode(kJoints - 1)->getMatrix()(0, 1), std::sin(0.5), 1e-12);
    osg::ref_ptr<SkeletonNode> kept = actor->getSkeletonNode(kJoints / 2);
    actor = nullptr;
    EXPECT_EQ(kept->getName(), "j" + std::to_string(kJoints / 2)) << "a node outlives its actor";
}
#endif
