// IK through ActorNode and a real update traversal: world goals, goals that follow a node, on top of a clip, and the
// scene graph showing the solved pose after the same frame.
#include "IkTestUtil"
#include "TestMath"
#include "nodes/NodeTestUtil"

#include <osgActor/ActorNode>
#include <osgActor/GlmOsg>
#include <osgActor/IkNodeController>
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipPlayer>
#include <osgActor/core/ik/IkController>

#include <osg/MatrixTransform>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** The effector's world position as the scene graph shows it: the skeleton nodes' matrices as written. */
osg::Vec3d sceneGraphWorldPosition(ActorNode& actor, unsigned joint)
{
    SkeletonNode* node = actor.getSkeletonNode(joint);
    return osg::computeLocalToWorld(node->getParentalNodePaths().front()).getTrans();
}

/** A leg actor placed in a scene: root -> transform -> actor, with pre and post transforms. */
struct LegScene
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    osg::ref_ptr<osg::MatrixTransform> place = new osg::MatrixTransform;
    osg::ref_ptr<ActorNode> actor;
    IkChainPtr chain;

    explicit LegScene(IkSolverType solver)
    {
        const ActorDefinitionPtr leg = makeLegActor();
        actor = new ActorNode(leg);
        place->setMatrix(osg::Matrixd::rotate(0.7, osg::Vec3d(0, 1, 0)) * osg::Matrixd::translate(3, 0, -1));
        root->addChild(place);
        place->addChild(actor);
        actor->setPreTranslation(osg::Vec3d(0.5, 0, 0));
        actor->setPreRotation(osg::Quat(0.4, osg::Vec3d(0, 0, 1)));
        actor->setPostTranslation(osg::Vec3d(0, 0.1, 0));
        chain = makeChain(*leg, chainSpec("leg", "hip", "ankle", solver));
    }

    /** The world position of the ankle for a DOF vector, from a second actor posed there in the same place. */
    osg::Vec3d worldAnkleFor(const std::vector<double>& dofs)
    {
        osg::ref_ptr<ActorNode> twin = osg::clone(actor.get(), osg::CopyOp::SHALLOW_COPY);
        place->addChild(twin);
        twin->setDofs(dofs);
        const osg::Vec3d position = twin->getJointWorldPosition(chain->getEffectorJoint());
        place->removeChild(twin);
        return position;
    }
};

} // namespace

TEST(IkNodes, AWorldGoalIsReachedAndShownInTheSameFrame)
{
    for (IkSolverType solver : {IkSolverType::TwoBone, IkSolverType::Ccd, IkSolverType::Dls})
    {
        LegScene scene(solver);
        std::mt19937 random(13);
        std::vector<double> target = randomPose(*scene.actor->getDefinition(), random);
        for (unsigned d = 0; d < 3; ++d) target[d] = 0.0; // the pelvis at rest, as the actor has it
        const osg::Vec3d worldGoal = scene.worldAnkleFor(target);

        auto ik = std::make_shared<IkController>(scene.chain);
        IkGoal goal;
        goal.position = toGlm(worldGoal);
        ik->setGoal(goal, IkGoalSpace::World);
        scene.actor->addController(ik);
        runUpdate(*scene.root, 1);

        const double tolerance = 1e-4 * scene.chain->getLength();
        EXPECT_TRUE(vec3Near(scene.actor->getJointWorldPosition(scene.chain->getEffectorJoint()), worldGoal, tolerance))
            << ikSolverName(solver);
        EXPECT_TRUE(
            vec3Near(sceneGraphWorldPosition(*scene.actor, scene.chain->getEffectorJoint()), worldGoal, tolerance))
            << ikSolverName(solver) << ": the skeleton nodes were written after the solve, in the same update";
    }
}

TEST(IkNodes, AGoalFollowsAnotherNode)
{
    LegScene scene(IkSolverType::TwoBone);
    osg::ref_ptr<osg::MatrixTransform> cup = new osg::MatrixTransform;
    osg::ref_ptr<osg::MatrixTransform> knee = new osg::MatrixTransform; // where the knee should point
    scene.root->addChild(cup);
    scene.root->addChild(knee);
    std::mt19937 random(14);
    auto follow = std::make_shared<IkNodeController>(scene.chain, cup.get());
    follow->setFollowOrientation(true);
    follow->setPoleNode(knee.get());
    scene.actor->addController(follow);
    const unsigned ankle = scene.chain->getEffectorJoint();
    for (unsigned frame = 1; frame <= 3; ++frame)
    {
        // The node goes where the ankle of a random pose would be, turned as that ankle would be.
        std::vector<double> target = randomPose(*scene.actor->getDefinition(), random);
        for (unsigned d = 0; d < 3; ++d) target[d] = 0.0;
        osg::ref_ptr<ActorNode> twin = osg::clone(scene.actor.get(), osg::CopyOp::SHALLOW_COPY);
        scene.place->addChild(twin);
        twin->setDofs(target);
        const osg::Matrixd goalWorld = twin->getJointWorldMatrix(ankle);
        knee->setMatrix(osg::Matrixd::translate(twin->getJointWorldPosition(scene.chain->getJoint(1))));
        scene.place->removeChild(twin);
        cup->setMatrix(goalWorld);

        runUpdate(*scene.root, frame);
        const osg::Matrixd reached = scene.actor->getJointWorldMatrix(ankle);
        EXPECT_TRUE(vec3Near(reached.getTrans(), goalWorld.getTrans(), 1e-4 * scene.chain->getLength())) << frame;
        EXPECT_LE(angleBetween(toGlm(reached.getRotate()), toGlm(goalWorld.getRotate())), 1e-4) << frame;
    }

    // The node goes away: the controller stops solving, and nothing breaks.
    const std::vector<double> before = scene.actor->getDofs();
    scene.root->removeChild(cup);
    cup = nullptr;
    runUpdate(*scene.root, 4);
    EXPECT_FALSE(follow->hasGoal());
    EXPECT_EQ(scene.actor->getDofs(), before);
}

TEST(IkNodes, IkWritesOnTopOfAClipAndClonesSolveOnTheirOwn)
{
    LegScene scene(IkSolverType::Dls);
    const ActorDefinitionPtr leg = scene.actor->getDefinition();
    // A clip stand-in that bends the pelvis and swings the leg each frame.
    class Swing : public Controller
    {
    public:
        void update(const ControllerContext& context, ControllerTarget& target) override
        {
            for (unsigned d = 0; d < target.pose.getNumDofs(); ++d)
                writeDof(target.pose, d, 0.1 * std::sin(context.time + d));
        }
        std::shared_ptr<Controller> cloneController() const override { return std::make_shared<Swing>(*this); }
    };
    scene.actor->addController(std::make_shared<Swing>());
    auto ik = std::make_shared<IkController>(scene.chain);
    ik->setSelection(DofSelection::joints(*leg, {"hip", "knee"}, false));
    IkGoal goal;
    goal.position = glm::dvec3(0.1, 0.35, 0.25); // model space
    ik->setGoal(goal);
    scene.actor->addController(ik);

    osg::ref_ptr<ActorNode> clone = osg::clone(scene.actor.get(), osg::CopyOp::SHALLOW_COPY);
    scene.place->addChild(clone);
    auto cloneIk = std::dynamic_pointer_cast<IkController>(clone->findController("leg"));
    ASSERT_TRUE(cloneIk);
    ASSERT_NE(cloneIk, ik);
    IkGoal cloneGoal = goal;
    cloneGoal.position.z = -0.1;
    cloneIk->setGoal(cloneGoal);

    runUpdate(*scene.root, 30);
    const double time = 30 / 60.0;
    for (unsigned d = 0; d < 3; ++d)
        EXPECT_NEAR(scene.actor->getDof(d), 0.1 * std::sin(time + d), 1e-15) << "pelvis from the clip";
    for (const char* name : {"ankle.rx", "ankle.ry", "ankle.rz"})
    {
        const unsigned d = static_cast<unsigned>(leg->findDof(name));
        EXPECT_NEAR(scene.actor->getDof(d), 0.1 * std::sin(time + d), 1e-15)
            << name << " is outside the IK's selection";
    }
    const unsigned ankle = scene.chain->getEffectorJoint();
    const double tolerance = 1e-4 * scene.chain->getLength();
    EXPECT_TRUE(vectorsNear(glm::dvec3(toGlm(scene.actor->getJointModelMatrix(ankle))[3]), goal.position, tolerance));
    EXPECT_TRUE(vectorsNear(glm::dvec3(toGlm(clone->getJointModelMatrix(ankle))[3]), cloneGoal.position, tolerance));
}

TEST(IkNodes, AFootStaysPlantedWhileAClipPlays)
{
    // A clip sways the pelvis and swings the leg; IK, added after it, keeps the ankle on one point of the ground.
    LegScene scene(IkSolverType::TwoBone);
    const ActorDefinitionPtr leg = scene.actor->getDefinition();
    ClipBuilder sway("sway");
    for (const char* dof : {"pelvis.rx", "pelvis.rz", "hip.rx", "knee.rx"})
    {
        const unsigned channel = sway.addChannel(dof, Interpolation::Cubic);
        sway.addKey(channel, 0.0, 0.1);
        sway.addKey(channel, 0.5, std::string(dof) == "knee.rx" ? 0.6 : -0.15);
        sway.addKey(channel, 1.0, 0.1);
    }
    const ClipBuildResult clip = sway.build();
    ASSERT_TRUE(clip) << clip.error;
    auto player = std::make_shared<ClipPlayer>(clip.clip);
    player->setPlayMode(PlayMode::Loop);
    scene.actor->addController(player);
    // The same clip alone on a twin, to see what the clip wrote.
    osg::ref_ptr<ActorNode> clipOnly = osg::clone(scene.actor.get(), osg::CopyOp::SHALLOW_COPY);
    scene.place->addChild(clipOnly);

    std::vector<double> planted = leg->getDefaultDofs();
    planted[static_cast<unsigned>(leg->findDof("knee.rx"))] = 0.5;
    planted[static_cast<unsigned>(leg->findDof("hip.rx"))] = -0.25;
    const osg::Vec3d ground = scene.worldAnkleFor(planted);
    auto foot = std::make_shared<IkController>(scene.chain);
    IkGoal goal;
    goal.position = toGlm(ground);
    foot->setGoal(goal, IkGoalSpace::World);
    scene.actor->addController(foot);

    const unsigned ankle = scene.chain->getEffectorJoint();
    for (unsigned frame = 1; frame <= 60; frame += 7)
    {
        runUpdate(*scene.root, frame);
        EXPECT_TRUE(vec3Near(sceneGraphWorldPosition(*scene.actor, ankle), ground, 1e-4 * scene.chain->getLength()))
            << "frame " << frame;
        EXPECT_TRUE(foot->getLastResult().reached) << "frame " << frame;
        for (const char* dof : {"pelvis.rx", "pelvis.rz"})
        {
            const unsigned d = static_cast<unsigned>(leg->findDof(dof));
            EXPECT_EQ(scene.actor->getDof(d), clipOnly->getDof(d)) << dof << " is the clip's, frame " << frame;
        }
        EXPECT_NE(scene.actor->getDof(static_cast<unsigned>(leg->findDof("knee.rx"))),
                  clipOnly->getDof(static_cast<unsigned>(leg->findDof("knee.rx"))))
            << "IK overrides the clip's knee, frame " << frame;
    }
}
