// The actor culled as one (ActorNode::CULL_AS_ONE, issue 28) draws the very image the ordinary traversal draws,
// byte for byte, on OSMesa: a crowd with materials, a hidden limb, user nodes and figures cut by the frame's edges,
// with the viewer's near and far planes computed from what it draws, and without.
#include "ImageCompare.h"
#include "TestFigure.h"

#include <osgActor/Offscreen/ImageComparison>
#include <osgActor/Offscreen/OffscreenRenderer>

#include <osg/Group>
#include <osg/MatrixTransform>
#include <osg/Switch>

#include <gtest/gtest.h>


using namespace osgActor;
using namespace osgActor::test;

namespace {

const osg::Vec4 kBackground(0.55f, 0.65f, 0.8f, 1.0f);

/** Seven figures in a row, posed apart, one with a hidden arm, a switch and a transform of its own below joints,
  * and a figure whose parts carry no state at all (white under the default material). */
osg::ref_ptr<osg::Group> makeCrowd(std::vector<osg::ref_ptr<ActorNode>>& actors)
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(makeFloor(12.0f));
    for (unsigned a = 0; a < 7; ++a)
    {
        osg::ref_ptr<ActorNode> actor = makeTestFigure();
        actor->setPreTranslation(osg::Vec3d(0.9 * a - 2.7, 0.6 * (a % 3), 0.0));
        poseCrowdMember(*actor, a);
        actors.push_back(actor);
        scene->addChild(actor.get());
    }
    ActorNode& special = *actors[3];
    special.getSkeletonNode("l_shoulder")->setHidden(true);
    osg::ref_ptr<osg::Switch> choice = new osg::Switch;
    choice->addChild(makeJointBall(0.12f), true);
    special.getSkeletonNode("head")->addChild(choice.get());
    osg::ref_ptr<osg::MatrixTransform> sword = new osg::MatrixTransform(osg::Matrix::translate(0.0, -0.05, -0.3));
    sword->addChild(makeSegment(0.6f, 0.02f, osg::Vec4(0.8f, 0.8f, 0.85f, 1.0f)));
    special.getSkeletonNode("r_elbow")->addChild(sword.get());
    // Plain geometry, no state set anywhere: the drawables go to the actor's own state graph.
    ActorNode& plain = *actors[5];
    for (unsigned j = 0; j < plain.getNumSkeletonNodes(); ++j)
        for (unsigned c = 0; c < plain.getSkeletonNode(j)->getNumChildren(); ++c)
            if (osg::Geode* geode = plain.getSkeletonNode(j)->getChild(c)->asGeode()) geode->setStateSet(nullptr);
    return scene;
}

class CullAsOneImages : public ::testing::Test
{
protected:
    void SetUp() override
    {
        std::string error;
        renderer = OffscreenRenderer::create(320, 200, error);
        ASSERT_TRUE(renderer) << error;
        renderer->setBackground(kBackground);
        renderer->setScene(makeCrowd(actors).get());
        // Close enough that the figures at both ends are cut by the image's sides.
        renderer->setViewMatrixAsLookAt(osg::Vec3d(0.3, -5.0, 1.6), osg::Vec3d(0.0, 0.0, 0.8),
                                        osg::Vec3d(0.0, 0.0, 1.0));
    }

    osg::ref_ptr<osg::Image> renderWith(ActorNode::CullMode mode)
    {
        for (osg::ref_ptr<ActorNode>& actor : actors) actor->setCullMode(mode);
        return renderer->renderFrame(0.0);
    }

    /** Both modes' images, equal to the byte; minCrowdShare: the least share of the image that is not sky. */
    void expectTheSameBytes(double minCrowdShare)
    {
        const osg::ref_ptr<osg::Image> ordinary = renderWith(ActorNode::CULL_NODE_BY_NODE);
        const osg::ref_ptr<osg::Image> asOne = renderWith(ActorNode::CULL_AS_ONE);
        // The test can fail: the crowd and its floor cover part of the image.
        EXPECT_TRUE(isTheSameBytesCovering(*asOne, *ordinary, kBackground, minCrowdShare));
    }

    osg::ref_ptr<OffscreenRenderer> renderer;
    std::vector<osg::ref_ptr<ActorNode>> actors;
};

} // namespace

TEST_F(CullAsOneImages, CrowdIsTheSameBytesAsTheOrdinaryTraversal)
{
    expectTheSameBytes(0.5);
    EXPECT_TRUE(matchesReference(*renderWith(ActorNode::CULL_AS_ONE), "crowd_cull_as_one"));
}

TEST_F(CullAsOneImages, AStillCrowdDrawnFromTheLeavesKeptFromItsLastFrameIsTheSameBytes)
{
    // The first frame culls the crowd afresh; at the next ones nothing changed, and each actor gives the render graph
    // the leaves kept from its last cull (ActorCull), with the matrices computed then.
    renderWith(ActorNode::CULL_AS_ONE);
    expectTheSameBytes(0.5);
    expectTheSameBytes(0.5);
    // A pose changed between two frames: that actor is culled afresh, the others keep their leaves.
    actors[2]->setDof("l_elbow.rx", -1.4);
    actors[2]->setDof("r_shoulder.rx", 0.8);
    expectTheSameBytes(0.5);
}

TEST_F(CullAsOneImages, CrowdIsTheSameBytesWithoutNearFarComputation)
{
    renderer->getCamera()->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    renderer->getCamera()->setProjectionMatrixAsPerspective(30.0, 320.0 / 200.0, 0.5, 50.0);
    expectTheSameBytes(0.5);
}

TEST_F(CullAsOneImages, CrowdFromAfarIsTheSameBytes)
{
    // Small enough on screen for OSG's small-feature culling to drop the balls on the joints.
    renderer->setViewMatrixAsLookAt(osg::Vec3d(1.0, -60.0, 8.0), osg::Vec3d(0.0, 0.0, 0.8),
                                    osg::Vec3d(0.0, 0.0, 1.0));
    expectTheSameBytes(0.001);
}
