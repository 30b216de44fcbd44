// The project's own actors (data/*.actor, read through osgdb_actor) rendered offscreen: reference images, and the
// humanoid's joints projected onto its pixels.
#include "ImageCompare.h"

#include <osgActor/ActorNode>
#include <osgActor/Offscreen/OffscreenRenderer>

#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <cmath>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const osg::Vec4 kBackground(0.55f, 0.65f, 0.8f, 1.0f);

osg::ref_ptr<ActorNode> readActor(const std::string& name)
{
    const std::string file = std::string(OSGACTOR_TEST_DATA_DIR) + "/" + name;
    osg::ref_ptr<ActorNode> actor = dynamic_cast<ActorNode*>(osgDB::readRefNodeFile(file).get());
    EXPECT_TRUE(actor.valid()) << "cannot read " << file << " as an actor (is OSG_LIBRARY_PATH the build's lib?)";
    return actor;
}

bool isBackground(const osg::Image& image, int x, int y)
{
    const unsigned char* pixel = image.data(x, y);
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(pixel[c]) - int(std::lround(kBackground[c] * 255.0f))) > 2) return false;
    return true;
}

class DataActors : public ::testing::Test
{
protected:
    void SetUp() override
    {
        std::string error;
        renderer = OffscreenRenderer::create(320, 240, error);
        ASSERT_TRUE(renderer) << error;
        renderer->setBackground(kBackground);
    }

    /** Renders an actor at t = 0 from the auto-framed camera. */
    osg::ref_ptr<osg::Image> renderFramed(ActorNode& actor)
    {
        renderer->setScene(&actor);
        renderer->update(0.0);
        renderer->frameScene();
        return renderer->draw();
    }

    osg::ref_ptr<OffscreenRenderer> renderer;
};

} // namespace

TEST_F(DataActors, HumanoidMatchesItsReference)
{
    osg::ref_ptr<ActorNode> humanoid = readActor("humanoid.actor");
    ASSERT_TRUE(humanoid.valid());
    humanoid->setDof("l_shoulder.ry", -1.3); // the left arm out sideways (+X), the right one forwards
    humanoid->setDof("r_shoulder.rx", -1.2);
    humanoid->setDof("r_elbow.rx", -1.0);
    humanoid->setDof("l_hip.rx", -0.5);
    humanoid->setDof("l_knee.rx", 0.9);
    EXPECT_TRUE(matchesReference(*renderFramed(*humanoid), "humanoid_posed"));
}

TEST_F(DataActors, InsectMatchesItsReference)
{
    osg::ref_ptr<ActorNode> insect = readActor("insect.actor");
    ASSERT_TRUE(insect.valid());
    EXPECT_TRUE(matchesReference(*renderFramed(*insect), "insect_rest"));
}

TEST_F(DataActors, RobotArmMatchesItsReference)
{
    osg::ref_ptr<ActorNode> arm = readActor("robot_arm.actor");
    ASSERT_TRUE(arm.valid());
    EXPECT_TRUE(matchesReference(*renderFramed(*arm), "robot_arm_rest"));
}

TEST_F(DataActors, HumanoidJointsProjectOntoItsPixelsAndHiddenLimbsVanish)
{
    osg::ref_ptr<ActorNode> humanoid = readActor("humanoid.actor");
    ASSERT_TRUE(humanoid.valid());
    humanoid->setDof("l_shoulder.ry", -1.3);
    humanoid->setDof("r_shoulder.ry", 1.3);
    const osg::ref_ptr<osg::Image> image = renderFramed(*humanoid);

    const auto pixelOf = [&](const char* joint) {
        const int index = humanoid->getJointIndex(joint);
        EXPECT_GE(index, 0) << joint;
        return renderer->projectToWindow(humanoid->getJointWorldPosition(unsigned(index)));
    };
    for (const char* joint : {"HumanoidRoot", "l_knee", "r_knee", "l_wrist", "r_wrist", "skullbase"})
    {
        const osg::Vec3d p = pixelOf(joint);
        EXPECT_FALSE(isBackground(*image, int(p.x()), int(p.y()))) << joint << " projects onto background";
    }

    // Hide the left arm: the left wrist's pixel turns to background, the right one's does not.
    humanoid->getSkeletonNode("l_shoulder")->setHidden(true);
    const osg::ref_ptr<osg::Image> hidden = renderer->renderFrame(1.0 / 30.0);
    const osg::Vec3d left = pixelOf("l_wrist");
    const osg::Vec3d right = pixelOf("r_wrist");
    EXPECT_TRUE(isBackground(*hidden, int(left.x()), int(left.y())));
    EXPECT_FALSE(isBackground(*hidden, int(right.x()), int(right.y())));
}
