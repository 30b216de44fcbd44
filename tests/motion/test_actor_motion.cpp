#include "../nodes/NodeTestUtil"

#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipPlayer>
#include <osgActor/core/Trajectory>
#include <osgActor/mocap/TrajectoryCsv>

#include <gtest/gtest.h>

#include <glm/ext/scalar_constants.hpp>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A cockroach: a body and one leg 1 along X that swings about Z. */
ActorDefinitionPtr makeCockroach()
{
    ActorDefinitionBuilder b("cockroach");
    b.addJoint("body");
    b.addJoint("leg", "body").dofs(dofBit(Dof::RZ));
    b.addJoint("foot", "leg").offset(1, 0, 0);
    return b.build().definition;
}

/** The leg turning from 0 to 90 degrees over the first second. */
ClipPtr makeGait()
{
    ClipBuilder gait("gait");
    const unsigned leg = gait.addChannel("leg.rz");
    gait.addKey(leg, 0.0, 0.0);
    gait.addKey(leg, 1.0, glm::pi<double>() / 2);
    return gait.build().clip;
}

/** The body's path (motion/data/cockroach.csv): (0, 0) to (2, 0) facing +X in the first second, then to (2, 2)
  * facing +Y. */
TrajectoryPtr readCockroachPath()
{
    return readTrajectoryCsvFile(std::string(OSGACTOR_TEST_SOURCE_DIR) + "/motion/data/cockroach.csv").trajectory;
}

} // namespace

TEST(ActorMotion, ATrajectoryMovesTheBodyWhileAClipMovesTheLegs)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makeCockroach());
    ClipLibraryPtr library = std::make_shared<ClipLibrary>();
    ASSERT_TRUE(library->addClip(makeGait()));
    actor->setClipLibrary(library);

    auto legs = std::make_shared<ClipPlayer>(actor->getClipLibrary()->getClip("gait"));
    legs->setPlayMode(PlayMode::Once);
    const TrajectoryPtr path = readCockroachPath();
    ASSERT_TRUE(path);
    auto body = std::make_shared<TrajectoryPlayer>(path);
    body->setPlayMode(PlayMode::Once);
    actor->addController(body);
    actor->addController(legs);

    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(actor.get());
    runUpdate(*root, 0);  // t = 0
    runUpdate(*root, 30); // t = 0.5 s: body at (1, 0, 0) facing +X, leg turned 45 degrees
    EXPECT_LT((actor->getPreTranslation() - osg::Vec3d(1, 0, 0)).length(), 1e-12);
    const double half = std::sqrt(0.5);
    EXPECT_LT((actor->getJointWorldPosition(2) - osg::Vec3d(1 + half, half, 0)).length(), 1e-12);
    runUpdate(*root, 120); // t = 2 s: body at (2, 2, 0) facing +Y, leg at 90 degrees: the foot points to -X
    EXPECT_LT((actor->getJointWorldPosition(2) - osg::Vec3d(1, 2, 0)).length(), 1e-12);
    EXPECT_LT((actor->getMatrix().getTrans() - osg::Vec3d(2, 2, 0)).length(), 1e-12) << "written to the node";
}

TEST(ActorMotion, PlayersFollowSimulationTimeBackwards)
{
    // A viewer scrubbing back sends earlier frame stamps: clip and trajectory play heads go back with them, so the
    // actor shows the pose of the time shown.
    osg::ref_ptr<ActorNode> actor = new ActorNode(makeCockroach());
    const TrajectoryPtr path = readCockroachPath();
    ASSERT_TRUE(path);
    actor->addController(std::make_shared<TrajectoryPlayer>(path));
    auto legs = std::make_shared<ClipPlayer>(makeGait());
    legs->setPlayMode(PlayMode::Once);
    actor->addController(legs);

    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(actor.get());
    runUpdate(*root, 0);
    runUpdate(*root, 60);  // t = 1 s: leg at 90 degrees
    runUpdate(*root, 30);  // back to t = 0.5 s: body at (1, 0, 0), leg at 45 degrees, as on the way there
    EXPECT_DOUBLE_EQ(legs->getPlayTime(), 0.5);
    EXPECT_LT((actor->getPreTranslation() - osg::Vec3d(1, 0, 0)).length(), 1e-12);
    const double half = std::sqrt(0.5);
    EXPECT_LT((actor->getJointWorldPosition(2) - osg::Vec3d(1 + half, half, 0)).length(), 1e-12);
}
