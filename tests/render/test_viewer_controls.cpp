// osgactorviewer's parts, driven without a window: keys through the real event handler, overlays, the clock.
#include "ActorControls.h"
#include "ActorFinder.h"
#include "ClipControls.h"
#include "TestFigure.h"
#include "nodes/NodeTestUtil"

#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipLibrary>

#include <osg/Group>
#include <osgViewer/View>

#include <gtest/gtest.h>

using namespace osgActor;
using namespace osgActor::test;
using namespace osgActorViewer;

namespace {

class ViewerControls : public ::testing::Test
{
protected:
    void SetUp() override
    {
        figure = makeTestFigure();
        ASSERT_TRUE(figure.valid());
        overlay = new SkeletonOverlay(figure.get());
        panel = new InfoPanel(640, 480);
        controls = new ActorControls({figure}, {overlay}, clock, panel.get());
    }

    void press(int key)
    {
        osg::ref_ptr<osgGA::GUIEventAdapter> event = new osgGA::GUIEventAdapter;
        event->setEventType(osgGA::GUIEventAdapter::KEYDOWN);
        event->setKey(key);
        controls->handle(*event, *view, nullptr, nullptr);
    }

    /** Selects a joint by pressing j until it is selected. */
    void selectJoint(const std::string& name)
    {
        const int wanted = figure->getJointIndex(name);
        ASSERT_GE(wanted, 0);
        for (unsigned i = 0; i < figure->getNumSkeletonNodes() && controls->getSelectedJoint() != wanted; ++i)
            press('j');
        ASSERT_EQ(controls->getSelectedJoint(), wanted);
    }

    unsigned overlayVertices()
    {
        overlay->rebuild();
        const osg::Geometry* geometry = overlay->getDrawable(0)->asGeometry();
        return geometry->getVertexArray()->getNumElements();
    }

    osg::ref_ptr<ActorNode> figure;
    osg::ref_ptr<SkeletonOverlay> overlay;
    osg::ref_ptr<InfoPanel> panel;
    PlaybackClock clock;
    osg::ref_ptr<ActorControls> controls;
    osg::ref_ptr<osgViewer::View> view = new osgViewer::View;
};

} // namespace

TEST(ViewerControlsWithoutActors, KeysDoNothingHarmful)
{
    PlaybackClock clock;
    osg::ref_ptr<ActorControls> controls = new ActorControls({}, {}, clock, nullptr);
    osg::ref_ptr<osgViewer::View> view = new osgViewer::View;
    for (int key : {int('a'), int('j'), int('J'), int('d'), int('D'), int('r'), int('v'), int('x'), int('k'), int('i'),
                    int(osgGA::GUIEventAdapter::KEY_Up)})
    {
        osg::ref_ptr<osgGA::GUIEventAdapter> event = new osgGA::GUIEventAdapter;
        event->setEventType(osgGA::GUIEventAdapter::KEYDOWN);
        event->setKey(key);
        controls->handle(*event, *view, nullptr, nullptr);
    }
    EXPECT_EQ(controls->getSelectedActor(), nullptr);
    EXPECT_EQ(controls->getSelectedDof(), -1);
}

TEST_F(ViewerControls, JointSelectionWrapsBothWays)
{
    EXPECT_EQ(controls->getSelectedJoint(), 0);
    press('J');
    EXPECT_EQ(controls->getSelectedJoint(), int(figure->getNumSkeletonNodes()) - 1);
    press('j');
    EXPECT_EQ(controls->getSelectedJoint(), 0);
}

TEST_F(ViewerControls, ArrowKeysTurnTheSelectedDofWithinItsLimits)
{
    selectJoint("l_elbow"); // one DOF, rx in [-2.6, 0]
    const int dof = figure->getDofIndex("l_elbow.rx");
    EXPECT_EQ(controls->getSelectedDof(), dof);
    press(osgGA::GUIEventAdapter::KEY_Down);
    EXPECT_NEAR(figure->getDof(unsigned(dof)), -osg::DegreesToRadians(5.0), 1e-12);
    for (int i = 0; i < 60; ++i) press(osgGA::GUIEventAdapter::KEY_Down);
    EXPECT_DOUBLE_EQ(figure->getDof(unsigned(dof)), -2.6);
    press(osgGA::GUIEventAdapter::KEY_Up);
    EXPECT_NEAR(figure->getDof(unsigned(dof)), -2.6 + osg::DegreesToRadians(5.0), 1e-12);
    press('r');
    EXPECT_DOUBLE_EQ(figure->getDof(unsigned(dof)), 0.0);
}

TEST_F(ViewerControls, DofKeysCycleThroughTheJointsDofs)
{
    selectJoint("r_shoulder"); // rx, ry, rz
    EXPECT_EQ(controls->getSelectedDof(), figure->getDofIndex("r_shoulder.rx"));
    press('d');
    EXPECT_EQ(controls->getSelectedDof(), figure->getDofIndex("r_shoulder.ry"));
    press('D');
    press('D');
    EXPECT_EQ(controls->getSelectedDof(), figure->getDofIndex("r_shoulder.rz"));
    selectJoint("chest"); // no DOF
    EXPECT_EQ(controls->getSelectedDof(), -1);
}

TEST_F(ViewerControls, VHidesAndShowsTheSelectedLimb)
{
    selectJoint("r_shoulder");
    press('v');
    EXPECT_TRUE(figure->getSkeletonNode("r_shoulder")->getHidden());
    EXPECT_FALSE(figure->getSkeletonNode("l_shoulder")->getHidden());
    press('v');
    EXPECT_FALSE(figure->getSkeletonNode("r_shoulder")->getHidden());
}

TEST_F(ViewerControls, OverlayShowsSkeletonLinesAndAxes)
{
    const unsigned numJoints = figure->getNumSkeletonNodes();
    EXPECT_EQ(overlayVertices(), 6u); // the selected joint's axes only
    press('k');
    EXPECT_EQ(overlayVertices(), 6u + 2u * (numJoints - 1)); // one line per joint with a parent
    press('x');
    EXPECT_EQ(overlayVertices(), 6u + 2u * (numJoints - 1) + 6u * numJoints);
    press('k');
    press('x');
    EXPECT_EQ(overlayVertices(), 6u);

    // The lines end at the joints' world positions, and follow the pose.
    press('k');
    figure->setDof("l_knee.rx", 1.0);
    overlay->rebuild();
    const osg::Vec3Array* vertices =
        static_cast<const osg::Vec3Array*>(overlay->getDrawable(0)->asGeometry()->getVertexArray());
    const osg::Vec3d knee = figure->getJointWorldPosition(unsigned(figure->getJointIndex("l_knee")));
    bool found = false;
    for (const osg::Vec3& v : *vertices) found = found || (osg::Vec3d(v) - knee).length() < 1e-5;
    EXPECT_TRUE(found);
}

TEST_F(ViewerControls, PlaybackKeysDriveTheClock)
{
    EXPECT_TRUE(clock.isPlaying());
    press('p');
    EXPECT_FALSE(clock.isPlaying());
    press('p');
    press('>');
    EXPECT_DOUBLE_EQ(clock.getSpeed(), 2.0);
    press('<');
    press('<');
    EXPECT_DOUBLE_EQ(clock.getSpeed(), 0.5);
    clock.setTime(1.0);
    press(osgGA::GUIEventAdapter::KEY_Left);
    EXPECT_FALSE(clock.isPlaying());
    EXPECT_DOUBLE_EQ(clock.getTime(), 1.0 - PlaybackClock::kStepSeconds);
}

TEST(PlaybackClock, AdvancesOnlyWhilePlayingAndCapsStalls)
{
    PlaybackClock clock;
    clock.advance(0.05);
    EXPECT_DOUBLE_EQ(clock.getTime(), 0.05);
    clock.advance(-1.0);
    EXPECT_DOUBLE_EQ(clock.getTime(), 0.05);
    clock.advance(3.0); // a stall counts as one short step
    EXPECT_DOUBLE_EQ(clock.getTime(), 0.05 + PlaybackClock::kMaxStepSeconds);
    clock.setPlaying(false);
    clock.advance(0.05);
    EXPECT_DOUBLE_EQ(clock.getTime(), 0.05 + PlaybackClock::kMaxStepSeconds);
    clock.scrub(-100);
    EXPECT_DOUBLE_EQ(clock.getTime(), 0.0);
    clock.setSpeed(1000.0);
    EXPECT_DOUBLE_EQ(clock.getSpeed(), 64.0);
}

TEST(ActorFinder, FindsEveryActorOnceWhereverItIs)
{
    osg::ref_ptr<ActorNode> horse = makeTestFigure();
    osg::ref_ptr<ActorNode> rider = makeTestFigure();
    horse->getSkeletonNode("chest")->addChild(rider.get()); // an actor below another's joint
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(horse.get());
    root->addChild(horse.get()); // the same actor under two parents
    osg::ref_ptr<osg::Group> switchedOff = new osg::Group;
    switchedOff->setNodeMask(0);
    osg::ref_ptr<ActorNode> third = makeTestFigure();
    switchedOff->addChild(third.get());
    root->addChild(switchedOff.get());
    const std::vector<osg::ref_ptr<ActorNode>> actors = findActors(*root);
    ASSERT_EQ(actors.size(), 3u);
    EXPECT_EQ(actors[0], horse);
    EXPECT_EQ(actors[1], rider);
    EXPECT_EQ(actors[2], third);
    osg::ref_ptr<osg::Group> empty = new osg::Group;
    EXPECT_TRUE(findActors(*empty).empty());
}

TEST_F(ViewerControls, ClipKeysSayWhenThereAreNoClips)
{
    press('n');
    EXPECT_EQ(findClipPlayer(*figure), nullptr);
}

TEST_F(ViewerControls, ClipKeysCycleThroughTheClipLibrary)
{
    // Two keyed clips on the elbow: "bend" holds it at -1, "reach" at -2.
    osgActor::ClipLibraryPtr library = std::make_shared<osgActor::ClipLibrary>();
    for (const auto& clip : {std::make_pair("bend", -1.0), std::make_pair("reach", -2.0)})
    {
        osgActor::ClipBuilder builder(clip.first);
        const unsigned channel = builder.addChannel("l_elbow.rx");
        builder.addKey(channel, 0.0, clip.second);
        builder.addKey(channel, 1.0, clip.second);
        const osgActor::ClipBuildResult built = builder.build();
        ASSERT_TRUE(built) << built.error;
        library->addClip(built.clip);
    }
    figure->setClipLibrary(library);

    press('n');
    std::shared_ptr<osgActor::ClipPlayer> player = findClipPlayer(*figure);
    ASSERT_NE(player, nullptr);
    EXPECT_EQ(player->getClip()->getName(), "bend");
    figure->runControllers(0.1);
    EXPECT_NEAR(figure->getDof(unsigned(figure->getDofIndex("l_elbow.rx"))), -1.0, 1e-9);
    press('n');
    EXPECT_EQ(player->getClip()->getName(), "reach");
    figure->runControllers(0.2);
    EXPECT_NEAR(figure->getDof(unsigned(figure->getDofIndex("l_elbow.rx"))), -2.0, 1e-9);
    press('N');
    EXPECT_EQ(player->getClip()->getName(), "bend");
    EXPECT_EQ(describeClip(*figure).rfind("bend", 0), 0u) << describeClip(*figure);
    EXPECT_EQ(figure->getControllers().size(), 1u) << "one player, reused";
}

TEST_F(ViewerControls, GWithoutADraggerSaysSo)
{
    press('g');
    EXPECT_EQ(figure->getControllers().size(), 0u);
}

TEST_F(ViewerControls, GPutsAnIkGoalThatTheChainFollows)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::Group> goals = new osg::Group;
    root->addChild(figure.get());
    root->addChild(goals.get());
    const auto dragger = std::make_shared<IkGoalDragger>(goals.get());
    controls->setIkGoalDragger(dragger);

    selectJoint("l_elbow"); // chain chest .. l_elbow: the shoulder's three rotations move the elbow
    press('g');
    ASSERT_TRUE(dragger->isAttached());
    EXPECT_EQ(goals->getNumChildren(), 1u);
    ASSERT_EQ(figure->getControllers().size(), 1u);
    const unsigned elbow = unsigned(figure->getJointIndex("l_elbow"));
    const osg::Vec3d shoulder = figure->getJointWorldPosition(unsigned(figure->getJointIndex("l_shoulder")));
    // The goal starts on the elbow: nothing moves until it is dragged.
    EXPECT_TRUE(vec3Near(osg::Vec3d(dragger->getGoalNode()->getMatrix().getTrans()),
                         figure->getJointWorldPosition(elbow), 1e-9));

    // Drag the goal (as the dragger does, through the goal node's matrix) to hold the arm out forwards.
    const osg::Vec3d goal = shoulder + osg::Vec3d(0.0, -0.3, 0.0);
    dragger->getGoalNode()->setMatrix(osg::Matrixd::translate(goal));
    for (unsigned frame = 1; frame <= 5; ++frame) runUpdate(*root, frame);
    EXPECT_TRUE(vec3Near(figure->getJointWorldPosition(elbow), goal, 1e-3));

    press('g');
    EXPECT_FALSE(dragger->isAttached());
    EXPECT_EQ(goals->getNumChildren(), 0u);
    EXPECT_EQ(figure->getControllers().size(), 0u);
}
