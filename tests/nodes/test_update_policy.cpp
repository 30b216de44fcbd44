// Update only what is seen (ActorNode::UpdatePolicy, issue 28): an actor no view saw at the previous frame skips its
// controllers and forward kinematics but keeps its time, so the frame it is seen again its pose is the one it
// would have had; animation level of detail by size on screen; every camera that culls it counts as a view.
#include "CullProbe"
#include "NodeTestUtil"
#include "render/TestFigure.h"

#include <osgActor/ActorGroup>
#include <osgActor/ActorNode>
#include <osgActor/ActorSceneIO>
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipPlayer>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <gtest/gtest.h>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A looping clip that swings the left elbow, the right shoulder and the pelvis, 1.3 s long (not a multiple of a
  * frame, so the play heads of skipped and updated actors land between keys). */
ClipPtr makeSwingClip()
{
    ClipBuilder builder("swing");
    const unsigned elbow = builder.addChannel("l_elbow.rx");
    const unsigned shoulder = builder.addChannel("r_shoulder.ry");
    const unsigned pelvis = builder.addChannel("pelvis.rz");
    const double keys[3][3][2] = {{{0.0, 0.0}, {0.55, -1.9}, {1.3, 0.0}},
                                  {{0.0, 0.2}, {0.7, 1.2}, {1.3, 0.2}},
                                  {{0.0, -0.4}, {0.9, 0.5}, {1.3, -0.4}}};
    const unsigned channels[3] = {elbow, shoulder, pelvis};
    for (unsigned c = 0; c < 3; ++c)
        for (const auto& key : keys[c]) builder.addKey(channels[c], key[0], key[1]);
    const ClipBuildResult built = builder.build();
    EXPECT_TRUE(built) << built.error;
    return built.clip;
}

osg::ref_ptr<ActorNode> makeSwingingFigure(const osg::Vec3d& where, bool onlyWhenSeen)
{
    osg::ref_ptr<ActorNode> actor = makeTestFigure();
    actor->setPreTranslation(where);
    auto player = std::make_shared<ClipPlayer>(makeSwingClip());
    player->setPlayMode(PlayMode::Loop);
    player->play();
    actor->addController(player);
    ActorNode::UpdatePolicy policy;
    policy.onlyWhenSeen = onlyWhenSeen;
    actor->setUpdatePolicy(policy);
    return actor;
}

/** A controller that starts from the last pose (as IK does): it cannot skip frames. */
class Accumulator : public Controller
{
public:
    void update(const ControllerContext&, ControllerTarget& target) override
    {
        const unsigned dof = unsigned(target.pose.getDefinition()->findDof("l_knee.rx"));
        target.pose.setDof(dof, target.pose.getDof(dof) + 0.001);
    }
    std::shared_ptr<Controller> cloneController() const override { return std::make_shared<Accumulator>(*this); }
};

void expectSamePose(const ActorNode& actual, const ActorNode& expected)
{
    ASSERT_EQ(actual.getNumDofs(), expected.getNumDofs());
    for (unsigned d = 0; d < actual.getNumDofs(); ++d)
        EXPECT_NEAR(actual.getDof(d), expected.getDof(d), 1e-9) << actual.getDefinition()->getDofName(d);
    for (unsigned j = 0; j < actual.getNumSkeletonNodes(); ++j)
    {
        const osg::Matrixd a = actual.getSkeletonNode(j)->getMatrix();
        const osg::Matrixd e = expected.getSkeletonNode(j)->getMatrix();
        for (int k = 0; k < 16; ++k) EXPECT_NEAR(a.ptr()[k], e.ptr()[k], 1e-9) << "joint " << j;
    }
}

/** An always-updated figure in view at the origin, and one that updates only when seen, far off to the side. */
struct TwoFigures
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    osg::ref_ptr<ActorNode> always = makeSwingingFigure(osg::Vec3d(), false);
    osg::ref_ptr<ActorNode> whenSeen = makeSwingingFigure(osg::Vec3d(40.0, 0.0, 0.0), true);
    CullProbe probe{scene.get()};

    TwoFigures()
    {
        scene->addChild(always.get());
        scene->addChild(whenSeen.get());
        lookAtAlways();
    }
    void lookAtAlways() { probe.lookAt(osg::Vec3d(0.0, -6.0, 1.0), osg::Vec3d(0.0, 0.0, 0.9)); }
    void lookAtWhenSeen() { probe.lookAt(osg::Vec3d(40.0, -6.0, 1.0), osg::Vec3d(40.0, 0.0, 0.9)); }
    /** Frames first..last: update, then cull, as a viewer runs them. */
    void run(unsigned first, unsigned last)
    {
        for (unsigned frame = first; frame <= last; ++frame)
        {
            runUpdate(*scene, frame);
            probe.cull(frame);
        }
    }
};

} // namespace

TEST(UpdatePolicy, IsOffByDefault)
{
    osg::ref_ptr<ActorNode> actor = makeTestFigure();
    EXPECT_FALSE(actor->getUpdatePolicy().onlyWhenSeen);
    // Not culled by anyone, updated every frame.
    actor->addController(std::make_shared<ClipPlayer>(makeSwingClip()));
    for (unsigned frame = 1; frame <= 5; ++frame) runUpdate(*actor, frame);
    EXPECT_EQ(actor->getNumUpdatesSkipped(), 0u);
}

TEST(UpdatePolicy, ControllersThatCannotSkipFramesKeepAnUnseenActorUpdated)
{
    TwoFigures figures;
    figures.whenSeen->addController(std::make_shared<Accumulator>());
    figures.run(1, 10);
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), 0u);
}

TEST(UpdatePolicy, AnUnseenActorSkipsItsPoseAndComesBackWithThePoseItWouldHaveHad)
{
    TwoFigures figures;
    figures.run(1, 40);
    // Posed at the first frame only: every later one was skipped.
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), 39u);
    EXPECT_GT(std::abs(figures.whenSeen->getDof(unsigned(figures.whenSeen->getDofIndex("l_elbow.rx"))) -
                       figures.always->getDof(unsigned(figures.always->getDofIndex("l_elbow.rx")))),
              0.1);
    // The camera turns to it: seen at frame 41's cull, so posed at frame 42's update.
    figures.lookAtWhenSeen();
    figures.run(41, 41);
    runUpdate(*figures.scene, 42);
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), 40u);
    expectSamePose(*figures.whenSeen, *figures.always);
    // And from then on every frame while it stays in view.
    figures.probe.cull(42);
    figures.run(43, 50);
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), 40u);
    expectSamePose(*figures.whenSeen, *figures.always);
}

TEST(UpdatePolicy, AnyCameraThatCullsTheActorCountsAsAView)
{
    // The main camera looks away; a second one (a slave's, a shadow map's) sees it.
    TwoFigures figures;
    CullProbe second(figures.scene.get());
    second.lookAt(osg::Vec3d(40.0, -6.0, 1.0), osg::Vec3d(40.0, 0.0, 0.9));
    for (unsigned frame = 1; frame <= 20; ++frame)
    {
        runUpdate(*figures.scene, frame);
        figures.probe.cull(frame);
        second.cull(frame);
    }
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), 0u);
    expectSamePose(*figures.whenSeen, *figures.always);
}

TEST(UpdatePolicy, BeyondTheMaximumDistanceAViewDoesNotCount)
{
    TwoFigures figures;
    figures.lookAtWhenSeen(); // 6 units in front of it
    ActorNode::UpdatePolicy policy = figures.whenSeen->getUpdatePolicy();
    policy.maxDistance = 5.0;
    figures.whenSeen->setUpdatePolicy(policy);
    figures.run(1, 10);
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), 9u);
    policy.maxDistance = 7.0;
    figures.whenSeen->setUpdatePolicy(policy);
    figures.run(11, 20);
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), 10u); // frame 11 still went by frame 10's cull
    expectSamePose(*figures.whenSeen, *figures.always);
}

TEST(UpdatePolicy, SmallOnScreenTheActorUpdatesEverySecondOrFourthFrameOnTime)
{
    TwoFigures figures;
    figures.lookAtWhenSeen();
    ActorNode::UpdatePolicy policy = figures.whenSeen->getUpdatePolicy();
    policy.halfRateBelowPixels = 1e6f; // whatever its size
    figures.whenSeen->setUpdatePolicy(policy);
    figures.run(1, 4);
    const unsigned skippedBefore = figures.whenSeen->getNumUpdatesSkipped();
    unsigned updated = 0;
    for (unsigned frame = 5; frame <= 12; ++frame)
    {
        const unsigned skipped = figures.whenSeen->getNumUpdatesSkipped();
        figures.run(frame, frame);
        if (figures.whenSeen->getNumUpdatesSkipped() == skipped)
        {
            ++updated;
            expectSamePose(*figures.whenSeen, *figures.always); // on the frames it updates, it is on time
        }
    }
    EXPECT_EQ(updated, 4u);
    EXPECT_GE(figures.whenSeen->getNumUpdatesSkipped(), skippedBefore + 4u);

    policy.quarterRateBelowPixels = 1e6f;
    figures.whenSeen->setUpdatePolicy(policy);
    const unsigned skippedAtQuarter = figures.whenSeen->getNumUpdatesSkipped();
    figures.run(13, 20);
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), skippedAtQuarter + 6u);

    // Larger on screen than both thresholds: every frame again.
    policy.halfRateBelowPixels = policy.quarterRateBelowPixels = 1.0f;
    figures.whenSeen->setUpdatePolicy(policy);
    const unsigned skippedAtFull = figures.whenSeen->getNumUpdatesSkipped();
    figures.run(21, 28);
    EXPECT_EQ(figures.whenSeen->getNumUpdatesSkipped(), skippedAtFull);
}

TEST(UpdatePolicy, ActorGroupsSkipUnseenActorsOnTheirThreads)
{
    // An always-updated figure in view beside a group of eight out of view, under the group's policy.
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    osg::ref_ptr<ActorNode> always = makeSwingingFigure(osg::Vec3d(), false);
    scene->addChild(always.get());
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    scene->addChild(group.get());
    std::vector<osg::ref_ptr<ActorNode>> unseen;
    for (unsigned a = 0; a < 8; ++a)
    {
        unseen.push_back(makeSwingingFigure(osg::Vec3d(40.0 + a, 0.0, 0.0), false));
        group->addChild(unseen.back().get());
    }
    EXPECT_EQ(group->getActorUpdatePolicy(), nullptr);
    ActorNode::UpdatePolicy policy;
    policy.onlyWhenSeen = true;
    group->setActorUpdatePolicy(policy);
    ASSERT_NE(group->getActorUpdatePolicy(), nullptr);

    CullProbe probe(scene.get());
    probe.lookAt(osg::Vec3d(0.0, -6.0, 1.0), osg::Vec3d(0.0, 0.0, 0.9));
    for (unsigned frame = 1; frame <= 10; ++frame)
    {
        runUpdate(*scene, frame);
        probe.cull(frame);
    }
    for (const osg::ref_ptr<ActorNode>& actor : unseen)
    {
        EXPECT_TRUE(actor->getUpdatePolicy().onlyWhenSeen);
        EXPECT_EQ(actor->getNumUpdatesSkipped(), 9u);
    }
    probe.lookAt(osg::Vec3d(43.5, -12.0, 1.0), osg::Vec3d(43.5, 0.0, 0.9));
    probe.cull(10);
    runUpdate(*scene, 11);
    for (const osg::ref_ptr<ActorNode>& actor : unseen)
    {
        EXPECT_EQ(actor->getNumUpdatesSkipped(), 9u);
        expectSamePose(*actor, *always);
    }
}

TEST(UpdatePolicy, AGroupCullingOnItsThreadsNotesWhatItSeesAsTheSerialCullDoes)
{
    // Two groups alike, one culled on its two threads (the actors' culls prepared there, then made without the
    // visitor entering them), the other serially: figures in a line away from the camera, at full, half and quarter
    // rate by their size on screen, the last beyond the maximum distance.
    ActorNode::UpdatePolicy policy;
    policy.onlyWhenSeen = true;
    policy.maxDistance = 100.0;
    policy.halfRateBelowPixels = 60.0f;
    policy.quarterRateBelowPixels = 30.0f;
    struct Line
    {
        osg::ref_ptr<ActorGroup> group = new ActorGroup;
        std::vector<osg::ref_ptr<ActorNode>> actors;
        CullProbe probe{group.get()};
    };
    Line lines[2];
    for (Line& line : lines)
    {
        line.group->setNumThreads(2);
        for (unsigned a = 0; a < 6; ++a)
        {
            line.actors.push_back(makeSwingingFigure(osg::Vec3d(0.3 * a, 4.0 * double(1u << a), 0.0), false));
            line.group->addChild(line.actors.back().get());
        }
        line.group->setActorUpdatePolicy(policy);
        line.probe.lookAt(osg::Vec3d(0.0, -2.0, 1.0), osg::Vec3d(0.0, 10.0, 0.9));
    }
    lines[0].group->setMinActorsForParallelCull(1);
    lines[1].group->setMinActorsForParallelCull(1000);
    // The updates of frames 9 to 24 counted per actor (a multiple of every period, so each actor's own phase does
    // not count).
    std::vector<unsigned> updates[2] = {std::vector<unsigned>(6, 0u), std::vector<unsigned>(6, 0u)};
    for (unsigned frame = 1; frame <= 24; ++frame)
        for (unsigned l = 0; l < 2; ++l)
        {
            std::vector<unsigned> skippedBefore;
            for (const osg::ref_ptr<ActorNode>& actor : lines[l].actors)
                skippedBefore.push_back(actor->getNumUpdatesSkipped());
            runUpdate(*lines[l].group, frame);
            lines[l].probe.cull(frame);
            for (std::size_t a = 0; a < lines[l].actors.size(); ++a)
                if (frame >= 9 && lines[l].actors[a]->getNumUpdatesSkipped() == skippedBefore[a]) ++updates[l][a];
        }
    EXPECT_EQ(lines[0].group->getNumParallelCulls(), 24u);
    EXPECT_EQ(lines[1].group->getNumParallelCulls(), 0u);
    EXPECT_EQ(updates[0], updates[1]);
    // The test can fail: every rate is met (every frame, every second, every fourth, none).
    EXPECT_EQ(updates[1], (std::vector<unsigned>{16u, 16u, 16u, 8u, 4u, 0u}));
    // Those updated every frame, and the one never seen, hold the same poses in both.
    for (std::size_t a : {0u, 1u, 2u, 5u}) expectSamePose(*lines[0].actors[a], *lines[1].actors[a]);
}

TEST(UpdatePolicy, AnActorFileGivesTheActorItsCullModeAndUpdatePolicyAndTakesThemBack)
{
    std::istringstream text("osgactor 1\nactor arm {\n  cull node_by_node\n  update_policy {\n    only_when_seen\n"
                            "    max_distance 75.25\n    half_rate_below_pixels 30\n    quarter_rate_below_pixels 0.1\n"
                            "  }\n  joint base { dof rz }\n}\n");
    const ActorReadResult read = readActor(text, "arm.actor");
    ASSERT_TRUE(read) << read.error;
    const ActorNodeResult made = createActorNode(read.document, read.definition, "arm.actor", nullptr);
    ASSERT_TRUE(made.actor.valid()) << made.error;
    EXPECT_EQ(made.actor->getCullMode(), ActorNode::CULL_NODE_BY_NODE);
    const ActorNode::UpdatePolicy& policy = made.actor->getUpdatePolicy();
    EXPECT_TRUE(policy.onlyWhenSeen);
    EXPECT_EQ(policy.maxDistance, 75.25);
    EXPECT_EQ(policy.halfRateBelowPixels, 30.0f);
    EXPECT_EQ(policy.quarterRateBelowPixels, 0.1f);

    // What the actor holds is what it gives back, and an actor of the defaults writes neither statement.
    const ActorDocument back = extractActorDocument(*made.actor);
    EXPECT_TRUE(back.cullNodeByNode);
    EXPECT_EQ(back.updatePolicy, read.document.updatePolicy);
    made.actor->setCullMode(ActorNode::CULL_AS_ONE);
    made.actor->setUpdatePolicy(ActorNode::UpdatePolicy());
    std::ostringstream written;
    writeActor(written, extractActorDocument(*made.actor));
    EXPECT_EQ(written.str().find("cull"), std::string::npos) << written.str();
    EXPECT_EQ(written.str().find("update_policy"), std::string::npos) << written.str();
}
