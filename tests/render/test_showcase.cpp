// The showcase's drivers: the insect's leg inverse kinematics, the tripod gait's planted feet, the walker's path.
#include "InsectLeg.h"
#include "PathWalker.h"
#include "ShowcaseScene.h"
#include "TripodGait.h"

#include <osgActor/ActorNode>
#include <osgActor/core/ActorDefinitionBuilder>

#include <osg/FrameStamp>
#include <osg/Group>
#include <osgDB/ReadFile>
#include <osgUtil/UpdateVisitor>

#include <gtest/gtest.h>

#include <cmath>

using namespace osgActor;
using namespace osgActorShowcase;

namespace {

const double kReach = 0.57;

/** The insect of data/insect.actor, legs only (same offsets, DOFs, defaults and limits), built in code. */
ActorDefinitionPtr makeInsectDefinition()
{
    ActorDefinitionBuilder b("cockroach");
    b.addJoint("thorax").offset(0, 0, 0.25).dofs(kRotationDofs | Dof::TX | Dof::TY | Dof::TZ);
    const struct { const char* name; double y; double swing; double swingMin; double swingMax; } legs[] = {
        {"front", -0.12, -30.0, -70.0, 10.0}, {"middle", 0.0, 0.0, -40.0, 40.0}, {"hind", 0.12, 30.0, -10.0, 70.0}};
    for (const auto& leg : legs)
        for (double side : {1.0, -1.0})
        {
            const std::string name = std::string(side > 0 ? "l_" : "r_") + leg.name;
            const double swing = side * leg.swing;
            b.addJoint(name + "_coxa", "thorax").offset(side * 0.08, leg.y, -0.02).dofs(Dof::RZ | Dof::RY)
                .limits(Dof::RZ, osg::DegreesToRadians(side > 0 ? leg.swingMin : -leg.swingMax),
                        osg::DegreesToRadians(side > 0 ? leg.swingMax : -leg.swingMin))
                .defaultValue(Dof::RZ, osg::DegreesToRadians(swing))
                .limits(Dof::RY, osg::DegreesToRadians(-30.0), osg::DegreesToRadians(30.0));
            b.addJoint(name + "_femur", name + "_coxa").offset(side * 0.08, 0, 0).dofs(dofBit(Dof::RY))
                .limits(Dof::RY, osg::DegreesToRadians(side > 0 ? -80.0 : 0.0), osg::DegreesToRadians(side > 0 ? 0.0 : 80.0))
                .defaultValue(Dof::RY, osg::DegreesToRadians(side * -40.0));
            b.addJoint(name + "_tibia", name + "_femur").offset(side * 0.2, 0, 0).dofs(dofBit(Dof::RY))
                .limits(Dof::RY, osg::DegreesToRadians(side > 0 ? 0.0 : -150.0), osg::DegreesToRadians(side > 0 ? 150.0 : 0.0))
                .defaultValue(Dof::RY, osg::DegreesToRadians(side * 80.0));
        }
    const BuildResult result = b.build();
    EXPECT_TRUE(result) << result.error;
    return result.definition;
}

/** The tip of a leg's foot in world space, by the nodekit's own forward kinematics. */
osg::Vec3d footWorld(const ActorNode& actor, const InsectLeg& leg)
{
    const osg::Matrixd tibia = actor.getJointWorldMatrix(unsigned(actor.getJointIndex(leg.name + "_tibia")));
    return osg::Vec3d(leg.side * leg.tibiaLength, 0.0, 0.0) * tibia;
}

void runUpdate(osg::Node& root, double time, unsigned frame)
{
    osg::ref_ptr<osgUtil::UpdateVisitor> visitor = new osgUtil::UpdateVisitor;
    osg::ref_ptr<osg::FrameStamp> stamp = new osg::FrameStamp;
    stamp->setFrameNumber(frame);
    stamp->setSimulationTime(time);
    visitor->setFrameStamp(stamp.get());
    visitor->setTraversalNumber(frame);
    root.accept(*visitor);
}

osg::ref_ptr<osg::AnimationPath> straightPath(double speed)
{
    osg::ref_ptr<osg::AnimationPath> path = new osg::AnimationPath;
    path->setLoopMode(osg::AnimationPath::NO_LOOPING);
    // Heading +X: the insect's head (-Y) turned by +90 degrees about Z.
    for (int i = 0; i <= 100; ++i)
        path->insert(i * 0.1, osg::AnimationPath::ControlPoint(osg::Vec3d(speed * i * 0.1, 0, 0),
                                                               osg::Quat(osg::PI_2, osg::Vec3d(0, 0, 1))));
    return path;
}

} // namespace

TEST(InsectLeg, RefusesADefinitionWithoutTheLeg)
{
    ActorDefinitionBuilder b("stick");
    b.addJoint("thorax");
    InsectLeg leg;
    EXPECT_FALSE(leg.bind(*b.build().definition, "l_front", kReach));
}

TEST(InsectLeg, SolvedAnglesPutTheFootOnTheTarget)
{
    const ActorDefinitionPtr definition = makeInsectDefinition();
    for (const char* name : TripodGait::kLegNames)
    {
        InsectLeg leg;
        ASSERT_TRUE(leg.bind(*definition, name, kReach)) << name;
        const osg::Vec3d rest = leg.footPosition(definition->getDofDefault(unsigned(leg.coxaSwingDof)),
                                                 definition->getDofDefault(unsigned(leg.femurDof)),
                                                 definition->getDofDefault(unsigned(leg.tibiaDof)));
        EXPECT_NEAR(rest.z(), -0.25, 0.02) << name << ": the rest pose stands on the floor";
        for (const osg::Vec3d& shift : {osg::Vec3d(0, 0, 0), osg::Vec3d(0, 0.1, 0), osg::Vec3d(0, -0.1, 0.08),
                                        osg::Vec3d(leg.side * 0.05, 0.05, 0)})
        {
            double swing = 0, femur = 0, tibia = 0;
            leg.solve(rest + shift, swing, femur, tibia);
            EXPECT_LT((leg.footPosition(swing, femur, tibia) - (rest + shift)).length(), 1e-9) << name;
            EXPECT_GT(leg.side * tibia, 0.0) << name << ": the knee bends downwards";
        }
    }
}

TEST(InsectLeg, SolutionAgreesWithTheNodekitsForwardKinematics)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makeInsectDefinition());
    for (const char* name : TripodGait::kLegNames)
    {
        InsectLeg leg;
        ASSERT_TRUE(leg.bind(*actor->getDefinition(), name, kReach));
        // A target near the rest foot, so that no angle reaches a limit (thorax frame).
        const ActorDefinition& definition = *actor->getDefinition();
        const osg::Vec3d target = leg.footPosition(definition.getDofDefault(unsigned(leg.coxaSwingDof)),
                                                   definition.getDofDefault(unsigned(leg.femurDof)),
                                                   definition.getDofDefault(unsigned(leg.tibiaDof))) +
                                  osg::Vec3d(0.03, -0.06, 0.05);
        double swing = 0, femur = 0, tibia = 0;
        leg.solve(target, swing, femur, tibia);
        actor->setDof(unsigned(leg.coxaSwingDof), swing);
        actor->setDof(unsigned(leg.femurDof), femur);
        actor->setDof(unsigned(leg.tibiaDof), tibia);
        const osg::Vec3d expected = target * actor->getJointWorldMatrix(unsigned(actor->getJointIndex("thorax")));
        EXPECT_LT((footWorld(*actor, leg) - expected).length(), 1e-9) << name;
    }
}

TEST(TripodGait, FeetOnTheGroundStayPlantedWhileTheBodyMoves)
{
    osg::ref_ptr<ActorNode> actor = new ActorNode(makeInsectDefinition());
    osg::ref_ptr<osg::Group> group = new osg::Group;
    group->addChild(actor.get());
    osg::ref_ptr<TripodGait> gait = new TripodGait;
    gait->setPath(straightPath(0.3));
    gait->setCycleDuration(0.8);
    group->setUpdateCallback(gait.get());

    InsectLeg front;
    ASSERT_TRUE(front.bind(*actor->getDefinition(), "l_front", kReach)); // tripod A: stance for u in [k, k + 0.5)
    // Stance of step 1: times 0.8 .. 1.2 s. The body moves 0.12 m; the foot must not.
    std::vector<osg::Vec3d> feet;
    std::vector<osg::Vec3d> bodies;
    unsigned frame = 1;
    for (double t = 0.82; t < 1.18; t += 0.06)
    {
        runUpdate(*group, t, frame++);
        feet.push_back(footWorld(*actor, front));
        bodies.push_back(actor->getPreTranslation());
    }
    EXPECT_NEAR((bodies.back() - bodies.front()).length(), 0.3 * 0.3, 1e-6);
    for (const osg::Vec3d& foot : feet)
    {
        EXPECT_LT((foot - feet.front()).length(), 1e-6) << "the planted foot slid";
        EXPECT_NEAR(foot.z(), feet.front().z(), 1e-9);
    }
    // In the swing that follows (1.2 .. 1.6 s) the foot leaves the ground and lands ahead.
    runUpdate(*group, 1.4, frame++);
    EXPECT_GT(footWorld(*actor, front).z(), feet.front().z() + 0.05);
    runUpdate(*group, 1.62, frame++);
    const osg::Vec3d landed = footWorld(*actor, front);
    EXPECT_NEAR(landed.z(), feet.front().z(), 1e-6);
    EXPECT_NEAR(landed.x() - feet.front().x(), 0.3 * 0.8, 1e-6) << "one step is the distance of one cycle";
}

TEST(TripodGait, AnyFrameCanBeComputedAlone)
{
    osg::ref_ptr<ActorNode> first = new ActorNode(makeInsectDefinition());
    osg::ref_ptr<ActorNode> second = new ActorNode(makeInsectDefinition());
    osg::ref_ptr<TripodGait> gait = new TripodGait;
    gait->setPath(straightPath(0.3));
    for (int i = 0; i <= 20; ++i) gait->drive(*first, 0.1 * i);
    gait->drive(*second, 2.0);
    for (unsigned i = 0; i < first->getNumDofs(); ++i) EXPECT_DOUBLE_EQ(first->getDof(i), second->getDof(i)) << i;
}

TEST(ShowcasePaths, LoopAtConstantSpeedFacingTheWayOfTravel)
{
    const osg::ref_ptr<osg::AnimationPath> path =
        makeLoopPath([](double s) { return osg::Vec3d(2.0 * std::cos(2.0 * osg::PI * s), 2.0 * std::sin(2.0 * osg::PI * s), 0.0); }, 0.5);
    EXPECT_NEAR(path->getPeriod(), 2.0 * osg::PI * 2.0 / 0.5, 1e-3);
    osg::AnimationPath::ControlPoint a, b;
    ASSERT_TRUE(path->getInterpolatedControlPoint(3.0, a));
    ASSERT_TRUE(path->getInterpolatedControlPoint(3.2, b));
    EXPECT_NEAR((b.getPosition() - a.getPosition()).length(), 0.1, 1e-3);
    // An actor facing -Y, turned by the path, faces the direction of travel.
    const osg::Vec3d facing = a.getRotation() * osg::Vec3d(0, -1, 0);
    osg::Vec3d travel = b.getPosition() - a.getPosition();
    travel.normalize();
    EXPECT_GT(facing * travel, 0.99);
}

TEST(ShowcaseScene, HasItsPartsAndDriversEvenWithoutADancer)
{
    ShowcaseSources sources;
    sources.dancer.clear();
    const osg::ref_ptr<osg::Group> scene = makeShowcaseScene(sources);
    unsigned walkers = 0, gaits = 0;
    for (unsigned i = 0; i < scene->getNumChildren(); ++i)
    {
        walkers += dynamic_cast<PathWalker*>(scene->getChild(i)->getUpdateCallback()) != nullptr;
        gaits += dynamic_cast<TripodGait*>(scene->getChild(i)->getUpdateCallback()) != nullptr;
        EXPECT_NE(scene->getChild(i)->getName(), "dancer");
    }
    EXPECT_EQ(walkers, 1u);
    EXPECT_EQ(gaits, 1u);
}

TEST(ShowcaseFile, LoadsWithItsActorsAndDrivers)
{
    // Needs OSG_LIBRARY_PATH on the build's lib (set by ctest): osgdb_actor, the serializers, libosgActorShowcase.
    const std::string file = std::string(OSGACTOR_TEST_DATA_DIR) + "/showcase.osgt";
    const osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(scene.valid()) << "cannot read " << file;
    struct Counter : public osg::NodeVisitor
    {
        Counter() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Node& node) override
        {
            walkers += dynamic_cast<PathWalker*>(node.getUpdateCallback()) != nullptr;
            gaits += dynamic_cast<TripodGait*>(node.getUpdateCallback()) != nullptr;
            if (ActorNode* actor = dynamic_cast<ActorNode*>(&node)) names.push_back(actor->getDefinition()->getName());
            traverse(node);
        }
        unsigned walkers = 0, gaits = 0;
        std::vector<std::string> names;
    } counter;
    scene->accept(counter);
    EXPECT_EQ(counter.walkers, 1u);
    EXPECT_EQ(counter.gaits, 1u);
    ASSERT_EQ(counter.names.size(), 3u) << "the humanoid, the insect and the motion-capture dancer";
    EXPECT_EQ(counter.names[0], "humanoid");
    EXPECT_EQ(counter.names[1], "cockroach");

    // Driven: after an update at t = 2 s the humanoid has walked away from where it was at t = 0.
    ActorNode* humanoid = nullptr;
    struct FirstActor : public osg::NodeVisitor
    {
        FirstActor() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Transform& node) override
        {
            if (!actor) actor = dynamic_cast<ActorNode*>(&node);
            traverse(node);
        }
        ActorNode* actor = nullptr;
    } first;
    scene->accept(first);
    humanoid = first.actor;
    ASSERT_NE(humanoid, nullptr);
    runUpdate(*scene, 0.0, 1);
    const osg::Vec3d start = humanoid->getPreTranslation();
    runUpdate(*scene, 2.0, 2);
    EXPECT_NEAR((humanoid->getPreTranslation() - start).length(), 2.0, 0.3) << "1.1 m/s on a gentle curve";
}
