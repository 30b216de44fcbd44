/* Large actors (issue 25, item 4): the depth limit, refused with the joint and its line; an actor at the limit
 * through OSG's own recursive traversals and formats; and osgUtil::Optimizer, which osgviewer and osgconv run on every
 * file they load, leaving every joint in place. Removing joints one by one from a wide parent was the work that grew
 * with the square of the joint count, so these tests catch that regression by structure, not by time; the time per
 * joint at 10^3 to 10^5 joints is measured by osgactor_scale_bench (docs/performance.md, "Large actors and long motion"). */
#include <osgActor/ActorNode>
#include <osgActor/ActorSceneIO>
#include <osgActor/SkeletonNode>
#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/io/ActorReader>

#include <osg/FrameStamp>
#include <osg/Geode>
#include <osg/ShapeDrawable>
#include <osgDB/ReaderWriter>
#include <osgDB/Registry>
#include <osgUtil/Optimizer>
#include <osgUtil/RenderStage>
#include <osgUtil/SceneView>
#include <osgUtil/Statistics>
#include <osgUtil/UpdateVisitor>

#include <gtest/gtest.h>

#include <sstream>
#include <string>

using namespace osgActor;

namespace {

/** A chain of the given number of joints, j0 the root, each 1 cm above its parent with one rotation. */
BuildResult buildChain(unsigned length)
{
    ActorDefinitionBuilder builder("chain");
    builder.addJoint("j0").dofs(dofBit(Dof::RX));
    for (unsigned j = 1; j < length; ++j)
        builder.addJoint("j" + std::to_string(j), "j" + std::to_string(j - 1)).offset(0, 0, 0.01).dofs(dofBit(Dof::RZ));
    return builder.build();
}

/** One root with the given number of children, none of them holding geometry. */
ActorDefinitionPtr buildWide(unsigned children)
{
    ActorDefinitionBuilder builder("wide");
    builder.addJoint("root").dofs(dofBit(Dof::RX));
    for (unsigned j = 0; j < children; ++j)
        builder.addJoint("c" + std::to_string(j), "root").offset(0.1, 0, 0).dofs(dofBit(Dof::RZ));
    return builder.build().definition;
}

/** Counts the skeleton nodes below a node. */
class SkeletonNodeCounter : public osg::NodeVisitor
{
public:
    SkeletonNodeCounter() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
    void apply(osg::Transform& transform) override
    {
        if (dynamic_cast<SkeletonNode*>(&transform)) ++count;
        traverse(transform);
    }
    unsigned count = 0;
};

/** Each joint's skeleton node is in the scene graph, a child of its parent joint's node (of the actor for a root). */
void expectSkeletonInPlace(ActorNode& actor)
{
    const ActorDefinition& definition = *actor.getDefinition();
    SkeletonNodeCounter counter;
    actor.accept(counter);
    EXPECT_EQ(counter.count, definition.getNumJoints());
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
    {
        SkeletonNode* node = actor.getSkeletonNode(j);
        ASSERT_EQ(node->getNumParents(), 1u) << definition.getJointName(j);
        const int parent = definition.getParent(j);
        const osg::Group* expected = parent < 0 ? static_cast<osg::Group*>(&actor)
                                                : actor.getSkeletonNode(static_cast<unsigned>(parent));
        ASSERT_EQ(node->getParent(0), expected) << definition.getJointName(j);
    }
}

/** Writes a node in one of OSG's formats to memory and reads it back, both through osgDB's plugins. */
osg::ref_ptr<osg::Node> throughOsgFormat(const osg::Node& node, const std::string& extension)
{
    osgDB::ReaderWriter* rw = osgDB::Registry::instance()->getReaderWriterForExtension(extension);
    if (!rw) return nullptr;
    std::stringstream stream;
    const osgDB::ReaderWriter::WriteResult written = rw->writeNode(node, stream);
    EXPECT_TRUE(written.success()) << extension << ": " << written.message();
    return rw->readNode(stream).getNode();
}

} // namespace

TEST(DepthLimit, ASkeletonOneJointDeeperThanTheLimitIsRefusedNamingTheJoint)
{
    const BuildResult result = buildChain(kMaxJointDepth + 1);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error, "actor 'chain': joint 'j1000' is 1001 joints deep (its root included); a skeleton may "
                            "be at most 1000 deep");
    EXPECT_EQ(result.errorJoint, static_cast<int>(kMaxJointDepth));
}

TEST(DepthLimit, AnActorFileDeeperThanTheLimitIsRefusedAtTheJointsLine)
{
    std::string text = "osgactor 1\nactor chain {\n joint j0\n";
    for (unsigned j = 1; j <= kMaxJointDepth; ++j)
        text += " joint j" + std::to_string(j) + " { parent j" + std::to_string(j - 1) + " }\n";
    std::istringstream in(text + "}\n");
    const ActorReadResult result = readActor(in, "deep.actor");
    ASSERT_FALSE(result);
    // j1000 is written on line 3 + 1000.
    EXPECT_EQ(result.error.rfind("deep.actor:1003: ", 0), 0u) << result.error;
    EXPECT_NE(result.error.find("at most 1000 deep"), std::string::npos) << result.error;
}

TEST(DepthLimit, ASkeletonExactlyAsDeepAsTheLimitBuilds)
{
    const BuildResult result = buildChain(kMaxJointDepth);
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(result.definition->getNumJoints(), kMaxJointDepth);
}

TEST(DepthLimit, AnActorAsDeepAsAllowedGoesThroughOsgsRecursiveFormatsUpdateAndCull)
{
    const BuildResult chain = buildChain(kMaxJointDepth);
    ASSERT_TRUE(chain) << chain.error;
    osg::ref_ptr<ActorNode> actor = new ActorNode(chain.definition);
    for (const char* extension : {"osgb", "osgt"})
    {
        osg::ref_ptr<osg::Node> back = throughOsgFormat(*actor, extension);
        ActorNode* backActor = dynamic_cast<ActorNode*>(back.get());
        ASSERT_NE(backActor, nullptr) << extension;
        ASSERT_EQ(backActor->getDefinition()->getNumJoints(), kMaxJointDepth) << extension;
        expectSkeletonInPlace(*backActor);
    }

    // A frame as osgViewer makes one (update, then cull, which needs no graphics context), with a ball on the tip:
    // the bound is computed through every level, and cull goes down all of them to collect the ball's drawable,
    // 999 cm above the root, where forward kinematics puts the tip.
    osg::ref_ptr<osg::Geode> ball = new osg::Geode;
    ball->addDrawable(new osg::ShapeDrawable(new osg::Sphere(osg::Vec3(), 0.5f)));
    actor->getSkeletonNode(kMaxJointDepth - 1)->addChild(ball.get());
    osg::ref_ptr<osg::FrameStamp> stamp = new osg::FrameStamp;
    stamp->setFrameNumber(1);
    osg::ref_ptr<osgUtil::UpdateVisitor> update = new osgUtil::UpdateVisitor;
    update->setFrameStamp(stamp.get());
    update->setTraversalNumber(1);
    actor->accept(*update);
    osg::ref_ptr<osgUtil::SceneView> view = new osgUtil::SceneView;
    view->setDefaults(osgUtil::SceneView::NO_SCENEVIEW_LIGHT);
    view->setSceneData(actor.get());
    view->setFrameStamp(stamp.get());
    view->setViewport(0, 0, 640, 640);
    view->setProjectionMatrixAsPerspective(45.0, 1.0, 0.1, 100.0);
    view->setViewMatrixAsLookAt(osg::Vec3d(0, -20, 5), osg::Vec3d(0, 0, 5), osg::Vec3d(0, 0, 1));
    view->cull();
    osgUtil::Statistics statistics;
    view->getRenderStage()->getStats(statistics);
    EXPECT_EQ(statistics.numDrawables, 1u);
    const osg::Vec3d tip = actor->getJointWorldPosition(kMaxJointDepth - 1);
    EXPECT_NEAR(tip.z(), 0.01 * (kMaxJointDepth - 1), 1e-9);
    // The default bound mode gives each joint a ball about its origin that holds it in any rotation.
    const osg::BoundingSphere& bound = actor->getBound();
    EXPECT_GE(bound.radius(), (bound.center() - osg::Vec3(tip)).length() + 0.5f - 1e-4f);
}

TEST(OsgUtilOptimizer, KeepsEveryJointOfAnActorWhoseJointsHoldNoGeometry)
{
    // osgUtil::Optimizer's default passes, as osgviewer and osgconv run them, and every other pass too: each
    // childless skeleton node was once removed, and a wide parent's children were removed one by one.
    for (unsigned options : {unsigned(osgUtil::Optimizer::DEFAULT_OPTIMIZATIONS),
                             unsigned(osgUtil::Optimizer::ALL_OPTIMIZATIONS)})
    {
        osg::ref_ptr<ActorNode> wide = new ActorNode(buildWide(2000));
        osg::ref_ptr<ActorNode> chain = new ActorNode(buildChain(300).definition);
        osg::ref_ptr<osg::Group> scene = new osg::Group;
        scene->addChild(wide.get());
        scene->addChild(chain.get());
        osgUtil::Optimizer().optimize(scene.get(), options);
        ASSERT_EQ(scene->getNumChildren(), 2u);
        expectSkeletonInPlace(*wide);
        expectSkeletonInPlace(*chain);
    }
}

TEST(OsgUtilOptimizer, LeavesAnActorThatOsgsFormatsWriteAndReadBack)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(buildWide(50));
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(actor.get());
    osgUtil::Optimizer().optimize(scene.get());
    osg::ref_ptr<osg::Node> back = throughOsgFormat(*actor, "osgt");
    ActorNode* backActor = dynamic_cast<ActorNode*>(back.get());
    ASSERT_NE(backActor, nullptr);
    EXPECT_EQ(backActor->getDefinition()->getNumJoints(), 51u);
    expectSkeletonInPlace(*backActor);
}
