// Offscreen renders of actors through OSMesa: reference images, joint projections, the hide flag, animation time.
#include "ImageCompare.h"
#include "TestFigure.h"

#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipPlayer>
#include <osgActor/core/Controller>
#include <osgActor/Offscreen/ImageComparison>
#include <osgActor/Offscreen/OffscreenRenderer>

#include <osg/Group>

#include <gtest/gtest.h>

#include <cmath>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const int kWidth = 320;
const int kHeight = 240;
const osg::Vec4 kBackground(0.55f, 0.65f, 0.8f, 1.0f);

/** The test camera: in front of the figure (which faces -Y), a little to its left and above. */
void placeFigureCamera(OffscreenRenderer& renderer)
{
    renderer.setViewMatrixAsLookAt(osg::Vec3d(1.5, -4.6, 1.7), osg::Vec3d(0.0, 0.0, 0.85), osg::Vec3d(0.0, 0.0, 1.0));
}

/** Arms and legs away from the body, so that every limb shows. */
void poseFigure(ActorNode& figure)
{
    figure.setDof("pelvis.rz", 0.3);
    figure.setDof("l_shoulder.ry", -1.2);     // left arm out sideways
    figure.setDof("l_elbow.rx", -0.9);
    figure.setDof("r_shoulder.rx", -1.1);     // right arm forwards
    figure.setDof("r_elbow.rx", -1.3);
    figure.setDof("l_hip.rx", -0.7);          // left leg forwards, knee bent
    figure.setDof("l_knee.rx", 1.0);
    figure.setDof("r_hip.ry", 0.25);          // right leg out
}

bool isBackground(const osg::Image& image, int x, int y)
{
    const unsigned char* pixel = image.data(x, y);
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(pixel[c]) - int(std::lround(kBackground[c] * 255.0f))) > 2) return false;
    return true;
}

class OffscreenRender : public ::testing::Test
{
protected:
    void SetUp() override
    {
        std::string error;
        renderer = OffscreenRenderer::create(kWidth, kHeight, error);
        ASSERT_TRUE(renderer) << error;
        renderer->setBackground(kBackground);
        figure = makeTestFigure();
        ASSERT_TRUE(figure.valid());
        scene = new osg::Group;
        scene->addChild(figure.get());
        renderer->setScene(scene.get());
        placeFigureCamera(*renderer);
    }

    /** The window position (pixels, bottom-left origin) of a joint in the current pose. */
    osg::Vec3d projectJoint(const std::string& joint) const
    {
        const int index = figure->getJointIndex(joint);
        EXPECT_GE(index, 0) << joint;
        return renderer->projectToWindow(figure->getJointWorldPosition(unsigned(index)));
    }

    osg::ref_ptr<OffscreenRenderer> renderer;
    osg::ref_ptr<ActorNode> figure;
    osg::ref_ptr<osg::Group> scene;
};

/** Drives the right arm with the simulation time: a wave of 1 rad amplitude, one cycle every 2 s. */
class WaveController : public Controller
{
public:
    void update(const ControllerContext& context, ControllerTarget& target) override
    {
        const int shoulder = target.pose.getDefinition()->findDof("r_shoulder.ry");
        if (shoulder >= 0) writeDof(target.pose, unsigned(shoulder), 1.6 + std::sin(M_PI * context.time));
    }
    std::shared_ptr<Controller> cloneController() const override { return std::make_shared<WaveController>(*this); }
};

/** A player of a clip that bends the left elbow linearly from 0 to -2 rad over 1 s: it advances by the frame's
  * delta time, so only a run through the frames before t shows the pose of t (-2 t rad). */
std::shared_ptr<ClipPlayer> makeElbowClipPlayer()
{
    ClipBuilder builder("bend");
    const unsigned elbow = builder.addChannel("l_elbow.rx");
    builder.addKey(elbow, 0.0, 0.0);
    builder.addKey(elbow, 1.0, -2.0);
    const ClipBuildResult built = builder.build();
    EXPECT_TRUE(built) << built.error;
    auto player = std::make_shared<ClipPlayer>(built.clip);
    player->setPlayMode(PlayMode::Once);
    return player;
}

} // namespace

TEST(OffscreenContext, RefusesAnEmptyBuffer)
{
    std::string error;
    EXPECT_FALSE(OffscreenRenderer::create(0, 10, error));
    EXPECT_NE(error.find("0x10"), std::string::npos) << error;
    EXPECT_FALSE(OffscreenRenderer::create(10, -1, error));
}

TEST(OffscreenContext, GlResolvesIntoOsMesaInThisProcess)
{
    std::string error;
    EXPECT_TRUE(OffscreenRenderer::glResolvesToOsMesa(error)) << error;
}

TEST_F(OffscreenRender, EmptySceneIsAllBackground)
{
    renderer->setScene(new osg::Group);
    const osg::ref_ptr<osg::Image> image = renderer->renderFrame(0.0);
    ASSERT_EQ(image->s(), kWidth);
    ASSERT_EQ(image->t(), kHeight);
    for (int y = 0; y < kHeight; y += 7)
        for (int x = 0; x < kWidth; x += 5) ASSERT_TRUE(isBackground(*image, x, y)) << x << ", " << y;
}

TEST_F(OffscreenRender, PosedFigureMatchesItsReference)
{
    scene->addChild(makeFloor(4.0f));
    poseFigure(*figure);
    EXPECT_TRUE(matchesReference(*renderer->renderFrame(0.0), "figure_posed"));
}

TEST_F(OffscreenRender, RestPoseFromTheDefaultCameraMatchesItsReference)
{
    // The auto-framed camera, as osgactorrender uses it by default.
    renderer->update(0.0);
    renderer->frameScene();
    EXPECT_TRUE(matchesReference(*renderer->draw(), "figure_rest_autoframed"));
}

TEST_F(OffscreenRender, HiddenLimbMatchesItsReference)
{
    scene->addChild(makeFloor(4.0f));
    poseFigure(*figure);
    figure->getSkeletonNode("l_shoulder")->setHidden(true);
    EXPECT_TRUE(matchesReference(*renderer->renderFrame(0.0), "figure_posed_left_arm_hidden"));
}

TEST_F(OffscreenRender, RenderingIsRepeatable)
{
    poseFigure(*figure);
    const osg::ref_ptr<osg::Image> first = renderer->renderFrame(0.0);
    const osg::ref_ptr<osg::Image> second = renderer->renderFrame(0.0);
    const ImageComparison difference = compareImages(*first, *second, 0);
    ASSERT_TRUE(difference.comparable);
    EXPECT_EQ(difference.numOverTolerance, 0u);
}

TEST_F(OffscreenRender, JointsProjectOntoTheActorsPixels)
{
    poseFigure(*figure);
    const osg::ref_ptr<osg::Image> image = renderer->renderFrame(0.0);
    unsigned numChecked = 0;
    for (const char* joint : {"l_shoulder", "l_elbow", "r_shoulder", "r_elbow", "l_hip", "l_knee", "r_hip", "r_knee"})
    {
        const osg::Vec3d window = projectJoint(joint);
        const int x = int(std::floor(window.x()));
        const int y = int(std::floor(window.y()));
        ASSERT_TRUE(x >= 0 && x < kWidth && y >= 0 && y < kHeight) << joint << " projects off the image";
        EXPECT_FALSE(isBackground(*image, x, y)) << joint << " projects onto background at " << x << ", " << y;
        ++numChecked;
    }
    EXPECT_EQ(numChecked, 8u);

    // The check can fail: half a unit beside the left elbow, away from the body, there is only background.
    const osg::Matrixd elbow = figure->getJointWorldMatrix(unsigned(figure->getJointIndex("l_elbow")));
    const osg::Vec3d beside = renderer->projectToWindow(elbow.getTrans() + osg::Vec3d(0.0, 0.0, 0.5));
    EXPECT_TRUE(isBackground(*image, int(beside.x()), int(beside.y())));
}

TEST_F(OffscreenRender, HiddenLimbsPixelsDisappearButItStaysPosed)
{
    poseFigure(*figure);
    const osg::ref_ptr<osg::Image> shown = renderer->renderFrame(0.0);
    const osg::Vec3d elbowShown = projectJoint("l_elbow");
    ASSERT_FALSE(isBackground(*shown, int(elbowShown.x()), int(elbowShown.y())));

    figure->getSkeletonNode("l_shoulder")->setHidden(true);
    figure->setDof("l_elbow.rx", -1.5); // still posed while hidden
    const osg::ref_ptr<osg::Image> hidden = renderer->renderFrame(1.0 / 30.0);
    const osg::Vec3d elbowHidden = projectJoint("l_elbow");
    EXPECT_TRUE(isBackground(*hidden, int(elbowHidden.x()), int(elbowHidden.y())));
    const osg::Vec3d rightElbow = projectJoint("r_elbow");
    EXPECT_FALSE(isBackground(*hidden, int(rightElbow.x()), int(rightElbow.y()))) << "only the left arm hides";

    // Shown again, the arm is drawn in the pose it was given while hidden.
    figure->getSkeletonNode("l_shoulder")->setHidden(false);
    const osg::ref_ptr<osg::Image> again = renderer->renderFrame(2.0 / 30.0);
    const osg::Vec3d wrist = renderer->projectToWindow(
        figure->getJointWorldMatrix(unsigned(figure->getJointIndex("l_elbow"))).preMult(osg::Vec3d(0, 0, -0.2)));
    EXPECT_FALSE(isBackground(*again, int(wrist.x()), int(wrist.y())));
}

TEST_F(OffscreenRender, ControllersAnimateWithTheFrameStampsSimulationTime)
{
    figure->addController(std::make_shared<WaveController>());
    const osg::ref_ptr<osg::Image> atStart = renderer->renderFrame(0.0);
    const osg::ref_ptr<osg::Image> later = renderer->renderFrame(0.5);
    EXPECT_TRUE(matchesReference(*atStart, "figure_wave_t0000"));
    EXPECT_TRUE(matchesReference(*later, "figure_wave_t0500"));
    const ImageComparison difference = compareImages(*atStart, *later, 24);
    ASSERT_TRUE(difference.comparable);
    EXPECT_GT(difference.numOverTolerance, 200u) << "the arm did not move between t = 0 and t = 0.5";

    // Going back to t = 0 gives the first image again.
    const ImageComparison back = compareImages(*atStart, *renderer->renderFrame(0.0), 0);
    EXPECT_EQ(back.numOverTolerance, 0u);
}

TEST_F(OffscreenRender, SteppingToATimeShowsWhatTheFramesFromZeroShow)
{
    // The frame at t = 0.5 s of a clip player stepped there at 20 frames per second ...
    figure->addController(makeElbowClipPlayer());
    renderer->stepTo(0.5, 20.0);
    double elbow = 0.0;
    ASSERT_TRUE(figure->getDof("l_elbow.rx", elbow));
    EXPECT_NEAR(elbow, -1.0, 1e-9) << "half way through the clip, not its first frame";
    const osg::ref_ptr<osg::Image> stepped = renderer->draw();

    // ... looks like the figure posed by hand at -1 rad ...
    osg::ref_ptr<ActorNode> posed = makeTestFigure();
    posed->setDof("l_elbow.rx", -1.0);
    osg::ref_ptr<osg::Group> posedScene = new osg::Group;
    posedScene->addChild(posed.get());
    renderer->setScene(posedScene.get());
    const osg::ref_ptr<osg::Image> byHand = renderer->renderFrame(0.0);
    const ImageComparison fromHand = compareImages(*stepped, *byHand, 0);
    ASSERT_TRUE(fromHand.comparable);
    EXPECT_EQ(fromHand.numOverTolerance, 0u);
    posed->setDof("l_elbow.rx", 0.0);
    EXPECT_GT(compareImages(*stepped, *renderer->renderFrame(0.0), 0).numOverTolerance, 200u)
        << "the elbow's bend shows: the first frame of the clip looks different";

    // ... and like frame 10 of frames 0..10 at 20 frames per second, drawn one after the other by a new renderer.
    std::string error;
    osg::ref_ptr<OffscreenRenderer> sequence = OffscreenRenderer::create(kWidth, kHeight, error);
    ASSERT_TRUE(sequence) << error;
    sequence->setBackground(kBackground);
    placeFigureCamera(*sequence);
    osg::ref_ptr<ActorNode> played = makeTestFigure();
    played->addController(makeElbowClipPlayer());
    osg::ref_ptr<osg::Group> playedScene = new osg::Group;
    playedScene->addChild(played.get());
    sequence->setScene(playedScene.get());
    osg::ref_ptr<osg::Image> frame;
    for (unsigned i = 0; i <= 10; ++i)
    {
        sequence->stepTo(i / 20.0, 20.0);
        frame = sequence->draw();
    }
    EXPECT_EQ(compareImages(*stepped, *frame, 0).numOverTolerance, 0u);
    EXPECT_EQ(played->getDof(unsigned(played->getDofIndex("l_elbow.rx"))), elbow) << "the same frames, the same pose";
}
