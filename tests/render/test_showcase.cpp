// The showcase's rigs: the insect's feet planted by the library's leg IK on a stored path (TripodGait), the
// walker's stored path and walk (PathWalker: the procedural cycle, or Cesium Man's own clip), the Charleston
// retargeted onto a second Cesium Man at load (RetargetedDance), their paths and their osgDB wrappers; the scene's shadows and the camera that frames its actors.
#include "LightNumberShadowMap.h"
#include "LoopTrajectory.h"
#include "PathWalker.h"
#include "RetargetedDance.h"
#include "ShowcaseScene.h"
#include "TripodGait.h"
#include "TripodGaitController.h"
#include "WalkCycle.h"

#include <osgActor/ActorNode>
#include <osgActor/ActorRetarget>
#include <osgActor/ActorSceneIO>
#include <osgActor/SkinnedMesh>
#include <osgActor/GlmOsg>
#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>
#include <osgActor/core/SamplingJob>
#include <osgActor/mocap/MotionFile>

#include <osg/FrameStamp>
#include <osg/Group>
#include <osg/MatrixTransform>
#include <osgDB/ReadFile>
#include <osgDB/Registry>
#include <osg/LightSource>
#include <osgShadow/ShadowedScene>
#include <osgUtil/UpdateVisitor>

#include "CameraView.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <sstream>

using namespace osgActor;
using namespace osgActorShowcase;

namespace {

// Needs OSG_LIBRARY_PATH on the build's lib (set by ctest): osgdb_actor, the serializers, libosgActorShowcase.
std::string dataFile(const std::string& name) { return std::string(OSGACTOR_TEST_DATA_DIR) + "/" + name; }

osg::ref_ptr<ActorNode> readActor(const std::string& name)
{
    osg::ref_ptr<ActorNode> actor = dynamic_cast<ActorNode*>(osgDB::readRefNodeFile(dataFile(name)).get());
    EXPECT_TRUE(actor.valid()) << "cannot read " << dataFile(name) << " as an actor";
    return actor;
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

/** A straight path along +X at speed (model units per second), 100 s long, the insect's head (-Y) turned to +X. */
TrajectoryPtr straightPath(double speed)
{
    std::vector<TrajectoryKey> keys(2);
    keys[1].time = 100.0;
    keys[1].position = glm::dvec3(speed * 100.0, 0.0, 0.0);
    keys[0].heading = keys[1].heading = osg::PI_2;
    return TrajectoryBuilder::build("straight", keys).trajectory;
}

/** A group holding the actor, with the rig as its update callback, as the showcase scene hangs its rigs. */
osg::ref_ptr<osg::Group> groupWithRig(ActorNode* actor, ControllerRig* rig)
{
    osg::ref_ptr<osg::Group> group = new osg::Group;
    group->addChild(actor);
    group->setUpdateCallback(rig);
    return group;
}

std::shared_ptr<TripodGaitController> findGait(const ActorNode& actor)
{
    return std::dynamic_pointer_cast<TripodGaitController>(actor.findController(TripodGaitController::kControllerName));
}

/** The tip of a leg's foot in world space, by the nodekit's own forward kinematics of the actor's pose. */
/** How high the end of an insect leg's chain stands when the foot rests on the floor: the radius of the round tip
  * around it (data/insect.actor, the cap of the tibia's capsule). */
const double kFootTipRadius = 0.012;

osg::Vec3d footWorld(const ActorNode& actor, const IkChain& leg)
{
    return toOsg(leg.getEffectorOffset()) * actor.getJointWorldMatrix(leg.getEffectorJoint());
}

/** What happened to one leg's foot over a run, in world space. */
struct LegTrack
{
    unsigned stancesSeen = 0;       // stances watched from touch-down to lift-off
    double worstStanceSlip = 0.0;   // the largest distance from where a foot touched down, during its stance
    double lowestStance = 1e9;      // the lowest and highest foot heights during stances
    double highestStance = -1e9;
    double lowestSwingPeak = 1e9;   // the lowest of the swings' highest points
    std::vector<osg::Vec3d> touchDowns; // where each watched stance began
};

/** Runs the scene's update at fps from time 0 to seconds and watches the actor's feet, stance by stance (the
  * gait's own stance phases; positions from the nodekit's FK). A stance under way at time 0 is not counted. */
std::vector<LegTrack> trackFeet(osg::Node& scene, const ActorNode& actor, double seconds, double fps)
{
    std::vector<LegTrack> tracks(TripodGaitController::kNumLegs);
    std::vector<bool> wasInStance(TripodGaitController::kNumLegs, true);
    std::vector<bool> watching(TripodGaitController::kNumLegs, false);
    std::vector<double> swingPeak(TripodGaitController::kNumLegs, -1e9);
    std::vector<osg::Vec3d> touchDown(TripodGaitController::kNumLegs);
    const unsigned frames = unsigned(seconds * fps);
    for (unsigned frame = 0; frame <= frames; ++frame)
    {
        runUpdate(scene, frame / fps, frame + 1);
        const std::shared_ptr<TripodGaitController> gait = findGait(actor);
        if (!gait) continue;
        const double time = gait->getBodyPlayer().getPlayTime();
        for (unsigned leg = 0; leg < TripodGaitController::kNumLegs; ++leg)
        {
            LegTrack& track = tracks[leg];
            const osg::Vec3d foot = footWorld(actor, *gait->getLegController(leg).getChain());
            const bool inStance = gait->isInStance(leg, time);
            if (inStance && !wasInStance[leg])
            {
                if (watching[leg]) track.lowestSwingPeak = std::min(track.lowestSwingPeak, swingPeak[leg]);
                watching[leg] = true; // a stance seen from its start
                touchDown[leg] = foot;
                track.touchDowns.push_back(foot);
            }
            if (!inStance && wasInStance[leg] && watching[leg]) ++track.stancesSeen;
            if (inStance && watching[leg])
            {
                track.worstStanceSlip = std::max(track.worstStanceSlip, (foot - touchDown[leg]).length());
                track.lowestStance = std::min(track.lowestStance, foot.z());
                track.highestStance = std::max(track.highestStance, foot.z());
            }
            if (!inStance)
                swingPeak[leg] = inStance != wasInStance[leg] ? foot.z() : std::max(swingPeak[leg], foot.z());
            wasInStance[leg] = inStance;
        }
    }
    return tracks;
}

} // namespace

TEST(LoopTrajectory, RefusesWhatCannotBeWalked)
{
    const auto circle = [](double s) {
        return osg::Vec3d(std::cos(2.0 * osg::PI * s), std::sin(2.0 * osg::PI * s), 0);
    };
    EXPECT_NE(makeLoopTrajectory("p", circle, 0.0).error.find("speed"), std::string::npos);
    EXPECT_NE(makeLoopTrajectory("p", circle, 1.0, -0.1).error.find("time between keys"), std::string::npos);
    EXPECT_NE(makeLoopTrajectory("p", [](double) { return osg::Vec3d(1, 2, 3); }, 1.0).error.find("no length"),
              std::string::npos);
}

TEST(LoopTrajectory, LoopsAtConstantSpeedFacingTheWayOfTravel)
{
    const TrajectoryBuildResult built = makeLoopTrajectory(
        "circle",
        [](double s) { return osg::Vec3d(2.0 * std::cos(2.0 * osg::PI * s), 2.0 * std::sin(2.0 * osg::PI * s), 0.0); },
        0.5);
    ASSERT_TRUE(built) << built.error;
    const Trajectory& path = *built.trajectory;
    EXPECT_EQ(path.getStartTime(), 0.0);
    EXPECT_NEAR(path.getEndTime(), 2.0 * osg::PI * 2.0 / 0.5, 1e-3) << "once round a circle of radius 2 at 0.5/s";
    EXPECT_LT(glm::length(path.getKeys().back().position - path.getKeys().front().position), 1e-9) << "closed";
    std::size_t cursor = 0;
    const TrajectoryKey a = path.sample(3.0, cursor);
    const TrajectoryKey b = path.sample(3.2, cursor);
    EXPECT_NEAR(glm::length(b.position - a.position), 0.1, 1e-3);
    // An actor facing -Y, turned by the heading about +Z, faces the direction of travel.
    const osg::Vec3d facing = osg::Quat(a.heading, osg::Vec3d(0, 0, 1)) * osg::Vec3d(0, -1, 0);
    osg::Vec3d travel = toOsg(b.position - a.position);
    travel.normalize();
    EXPECT_GT(facing * travel, 0.99);
}

TEST(WalkCycle, RefusesAnActorWithoutLegs)
{
    ActorDefinitionBuilder b("stick");
    b.addJoint("thorax").dofs(dofBit(Dof::RZ));
    const ClipBuildResult walk = makeWalkCycleClip(*b.build().definition, 1.1);
    EXPECT_FALSE(walk);
    EXPECT_NE(walk.error.find("'stick' has none of the DOFs"), std::string::npos) << walk.error;
}

TEST(WalkCycle, ClipHoldsOneSeamlessCycleOfTheActorsDofs)
{
    ActorDefinitionBuilder b("legs");
    b.addJoint("HumanoidRoot").dofs(dofBit(Dof::TZ));
    b.addJoint("l_hip", "HumanoidRoot").dofs(dofBit(Dof::RX));
    b.addJoint("l_knee", "l_hip").offset(0, 0, -0.45).dofs(dofBit(Dof::RX));
    const ClipBuildResult walk = makeWalkCycleClip(*b.build().definition, 1.1, 40);
    ASSERT_TRUE(walk) << walk.error;
    const Clip& clip = *walk.clip;
    EXPECT_EQ(clip.getNumChannels(), 3u) << "only the DOFs the actor has";
    EXPECT_NEAR(clip.getDuration(), 1.1, 1e-12);
    ASSERT_EQ(clip.getNumFrames(), 41u);
    for (unsigned c = 0; c < clip.getNumChannels(); ++c)
        EXPECT_DOUBLE_EQ(clip.getFrame(40)[c], clip.getFrame(0)[c]) << "the last frame is the first: it loops";
    // A quarter cycle in (frame 10): the left hip at its most forward, -0.35 rad, its knee straight but for 0.08.
    EXPECT_NEAR(clip.getFrame(10)[clip.findChannel("l_hip.rx")], -0.35, 1e-12);
    EXPECT_NEAR(clip.getFrame(10)[clip.findChannel("l_knee.rx")], 0.08, 1e-12);
}

TEST(TripodGait, RefusesAnActorWithoutLegChains)
{
    osg::ref_ptr<ActorNode> humanoid = readActor("humanoid.actor");
    ASSERT_TRUE(humanoid.valid());
    osg::ref_ptr<TripodGait> gait = new TripodGait;
    gait->setPath(straightPath(0.3));
    osg::ref_ptr<osg::Group> group = groupWithRig(humanoid.get(), gait.get());
    runUpdate(*group, 0.0, 1);
    runUpdate(*group, 0.1, 2);
    EXPECT_TRUE(humanoid->getControllers().empty()) << "no leg chains, no gait";
}

TEST(TripodGait, InsectFileHasALegChainPerLeg)
{
    osg::ref_ptr<ActorNode> insect = readActor("insect.actor");
    ASSERT_TRUE(insect.valid());
    for (unsigned leg = 0; leg < TripodGaitController::kNumLegs; ++leg)
    {
        const IkChainPtr chain = insect->findIkChain(TripodGaitController::legChainName(leg));
        ASSERT_TRUE(chain) << TripodGaitController::legChainName(leg);
        EXPECT_EQ(chain->getNumJoints(), 3u) << "coxa, femur, tibia";
        EXPECT_EQ(chain->getNumDofs(), 3u) << "swing, lift, knee: the coxa's tilt is held";
        // In the rest pose the foot's round tip (centred 0.37 along the tibia) touches the floor, z = 0.
        const osg::Vec3d foot = footWorld(*insect, *chain);
        EXPECT_NEAR(foot.z(), kFootTipRadius, 0.0005) << chain->getName();
    }
}

TEST(TripodGait, FeetOnTheGroundStayPlantedByTheLegIkWhileTheBodyMoves)
{
    osg::ref_ptr<ActorNode> insect = readActor("insect.actor");
    ASSERT_TRUE(insect.valid());
    // In a frame scaled like the showcase's: the gait works in the path's frame, the IK goals in world space.
    osg::ref_ptr<osg::MatrixTransform> group = new osg::MatrixTransform(osg::Matrixd::scale(0.8, 0.8, 0.8));
    group->addChild(insect.get());
    osg::ref_ptr<TripodGait> gait = new TripodGait;
    const double speed = 0.3;   // path units per second
    const double cycle = 0.8;   // seconds
    gait->setPath(straightPath(speed));
    gait->setCycleDuration(cycle);
    gait->setStepHeight(0.08);
    group->setUpdateCallback(gait.get());

    const std::vector<LegTrack> tracks = trackFeet(*group, *insect, 4.0, 50.0);
    const std::shared_ptr<TripodGaitController> controller = findGait(*insect);
    ASSERT_TRUE(controller) << "the rig gave the insect its gait";
    EXPECT_NEAR(insect->getPreTranslation().x(), speed * 4.0, 1e-9) << "the body follows the stored path";
    for (unsigned leg = 0; leg < TripodGaitController::kNumLegs; ++leg)
    {
        const LegTrack& track = tracks[leg];
        const char* name = TripodGaitController::kLegNames[leg];
        EXPECT_GE(track.stancesSeen, 4u) << name;
        EXPECT_LT(track.worstStanceSlip, 1e-4) << name << ": a planted foot slid (world units)";
        EXPECT_LT(track.highestStance - track.lowestStance, 1e-4) << name << ": feet stand on one ground";
        EXPECT_NEAR(track.lowestStance, kFootTipRadius * 0.8, 0.0005) << name << ": on the floor";
        // Swings lift the foot by the step height (0.08 in the path's frame, scaled by 0.8) ...
        EXPECT_NEAR(track.lowestSwingPeak - track.lowestStance, 0.08 * 0.8, 0.005) << name;
        // ... and put it down one stride ahead: the body's travel in one cycle along +X.
        for (std::size_t k = 1; k < track.touchDowns.size(); ++k)
        {
            const osg::Vec3d stride = track.touchDowns[k] - track.touchDowns[k - 1];
            EXPECT_NEAR(stride.x(), speed * cycle * 0.8, 1e-4) << name;
            EXPECT_NEAR(stride.y(), 0.0, 1e-4) << name;
        }
        EXPECT_TRUE(controller->getLegController(leg).getLastResult().reached) << name;
    }
}

TEST(PathWalker, GivesTheActorThePathAndTheWalkAsLibraryPlayers)
{
    osg::ref_ptr<ActorNode> humanoid = readActor("humanoid.actor");
    ASSERT_TRUE(humanoid.valid());
    osg::ref_ptr<PathWalker> walker = new PathWalker;
    walker->setPath(straightPath(1.1));
    walker->setCycleDuration(1.1);
    osg::ref_ptr<osg::Group> group = groupWithRig(humanoid.get(), walker.get());
    for (unsigned frame = 0; frame <= 11; ++frame) runUpdate(*group, frame * 0.05, frame + 1);
    ASSERT_TRUE(std::dynamic_pointer_cast<TrajectoryPlayer>(humanoid->findController(PathWalker::kPathControllerName)));
    ASSERT_TRUE(std::dynamic_pointer_cast<ClipPlayer>(humanoid->findController(PathWalker::kWalkControllerName)));
    EXPECT_NEAR(humanoid->getPreTranslation().x(), 1.1 * 0.55, 1e-9);
    // 0.55 s is half a cycle: the left hip is back where it started, swinging the other way (-0.35 sin(pi)).
    double hip = 1.0;
    ASSERT_TRUE(humanoid->getDof("l_hip.rx", hip));
    EXPECT_NEAR(hip, 0.0, 1e-9);
    EXPECT_EQ(humanoid->getControllers().size(), 2u) << "rigged once";
}

TEST(PathWalker, TakesThePathPlayerAnActorReadBackKeeps)
{
    // Rigged, written to .osgt and read back, the humanoid keeps the path's player and the walk cycle, under the
    // rig's names: it counts as rigged, and walks the kept path and cycle once, not twice.
    osg::ref_ptr<ActorNode> humanoid = readActor("humanoid.actor");
    ASSERT_TRUE(humanoid.valid());
    osg::ref_ptr<PathWalker> walker = new PathWalker;
    walker->setPath(straightPath(1.1));
    osg::ref_ptr<osg::Group> group = groupWithRig(humanoid.get(), walker.get());
    for (unsigned frame = 0; frame <= 3; ++frame) runUpdate(*group, frame * 0.05, frame + 1);
    ASSERT_EQ(humanoid->getControllers().size(), 2u);

    osgDB::ReaderWriter* osgt = osgDB::Registry::instance()->getReaderWriterForExtension("osgt");
    ASSERT_NE(osgt, nullptr);
    osg::ref_ptr<osgDB::Options> ascii = new osgDB::Options;
    ascii->setPluginStringData("fileType", "Ascii");
    std::stringstream text;
    ASSERT_TRUE(osgt->writeNode(*humanoid, text, ascii.get()).success());
    osg::ref_ptr<ActorNode> back = dynamic_cast<ActorNode*>(osgt->readNode(text, ascii.get()).getNode());
    ASSERT_TRUE(back.valid());
    ASSERT_EQ(back->getControllers().size(), 2u) << "the path's player and the walk cycle, kept";
    const ControllerPtr kept = back->getControllers()[0];
    EXPECT_EQ(kept->getName(), PathWalker::kPathControllerName);
    const ControllerPtr keptCycle = back->findController(PathWalker::kWalkControllerName);
    EXPECT_TRUE(std::dynamic_pointer_cast<ClipPlayer>(keptCycle));

    osg::ref_ptr<osg::Group> reloaded = groupWithRig(back.get(), walker.get());
    for (unsigned frame = 0; frame <= 11; ++frame) runUpdate(*reloaded, frame * 0.05, frame + 1);
    ASSERT_EQ(back->getControllers().size(), 2u) << "the kept path and walk cycle, no second of either";
    EXPECT_EQ(back->findController(PathWalker::kPathControllerName), kept);
    EXPECT_EQ(back->findController(PathWalker::kWalkControllerName), keptCycle);
    EXPECT_GT(back->getPreTranslation().x(), humanoid->getPreTranslation().x()) << "it walks on along the path";
}

TEST(PathWalker, TakesThePathPlayerAFileOfTheTrajectoryShorthandMade)
{
    // A file that plays the path with the trajectory section's own "play" (as files did before players kept their
    // names) gives a player named after the trajectory: the rig takes it rather than walking the path twice.
    osg::ref_ptr<ActorNode> humanoid = readActor("humanoid.actor");
    ASSERT_TRUE(humanoid.valid());
    ActorDocument document = extractActorDocument(*humanoid);
    TrajectoryDocument path;
    path.trajectory = straightPath(1.1);
    path.play = true;
    path.playMode = PlayMode::Loop;
    document.trajectories.push_back(path);
    std::stringstream text;
    writeActor(text, document);
    const ActorReadResult read = readActor(text, "shorthand.actor");
    ASSERT_TRUE(read) << read.error;
    const ActorNodeResult made = createActorNode(read.document, read.definition, "shorthand.actor", nullptr);
    ASSERT_TRUE(made.actor.valid()) << made.error;
    ASSERT_EQ(made.actor->getControllers().size(), 1u);
    const ControllerPtr shorthand = made.actor->getControllers()[0];
    EXPECT_EQ(shorthand->getName(), "straight");

    osg::ref_ptr<PathWalker> walker = new PathWalker;
    walker->setPath(straightPath(1.1));
    osg::ref_ptr<osg::Group> group = groupWithRig(made.actor.get(), walker.get());
    runUpdate(*group, 0.0, 1);
    ASSERT_EQ(made.actor->getControllers().size(), 2u) << "the file's path player and the walk cycle";
    EXPECT_EQ(made.actor->findController(PathWalker::kPathControllerName), shorthand);
}

TEST(PathWalker, LetsAnActorThatPlaysAClipOfItsOwnWalkWithIt)
{
    // A rigged model's actor plays its own walk (readRiggedModelActor's "clip"): the rig adds the path alone.
    osg::ref_ptr<ActorNode> humanoid = readActor("humanoid.actor");
    ASSERT_TRUE(humanoid.valid());
    const ClipBuildResult ownWalk = makeWalkCycleClip(*humanoid->getDefinition(), 0.9);
    ASSERT_TRUE(ownWalk) << ownWalk.error;
    auto own = std::make_shared<ClipPlayer>(ownWalk.clip);
    own->setName("clip");
    humanoid->addController(own);
    osg::ref_ptr<PathWalker> walker = new PathWalker;
    walker->setPath(straightPath(0.9));
    osg::ref_ptr<osg::Group> group = groupWithRig(humanoid.get(), walker.get());
    for (unsigned frame = 0; frame <= 3; ++frame) runUpdate(*group, frame * 0.05, frame + 1);
    ASSERT_EQ(humanoid->getControllers().size(), 2u) << "its own clip and the path";
    EXPECT_EQ(humanoid->getControllers()[0], own);
    EXPECT_TRUE(std::dynamic_pointer_cast<TrajectoryPlayer>(humanoid->findController(PathWalker::kPathControllerName)));
    EXPECT_FALSE(humanoid->findController(PathWalker::kWalkControllerName)) << "no procedural cycle on top";
    EXPECT_NEAR(humanoid->getPreTranslation().x(), 0.9 * 0.15, 1e-9) << "it follows the path";
}

TEST(ShowcaseScene, CastsTheShadowsOfEverythingButTheFloorOnTheFloor)
{
    ShowcaseSources sources;
    sources.dancer.clear();
    const osg::ref_ptr<osg::Group> scene = makeShowcaseScene(sources);
    const osgShadow::ShadowedScene* shadowed = dynamic_cast<const osgShadow::ShadowedScene*>(scene.get());
    ASSERT_NE(shadowed, nullptr) << "the root is a shadowed scene";
    const LightNumberShadowMap* shadowMap = dynamic_cast<const LightNumberShadowMap*>(shadowed->getShadowTechnique());
    ASSERT_NE(shadowMap, nullptr);
    const unsigned casts = shadowed->getCastsShadowTraversalMask();
    const unsigned receives = shadowed->getReceivesShadowTraversalMask();
    EXPECT_EQ(casts & receives, 0u) << "one bit each, so that a node can receive without casting";
    unsigned floors = 0;
    unsigned suns = 0;
    for (unsigned i = 0; i < scene->getNumChildren(); ++i)
    {
        const osg::Node& child = *scene->getChild(i);
        if (const osg::LightSource* sun = dynamic_cast<const osg::LightSource*>(&child))
        {
            ++suns;
            EXPECT_EQ(sun->getLight()->getLightNum(), shadowMap->getLightNumber()) << "the sun casts the shadows";
            EXPECT_EQ(sun->getLight()->getPosition().w(), 0.0f) << "a directional light";
        }
        EXPECT_NE(child.getNodeMask() & receives, 0u) << child.getName() << " receives";
        if (child.getName() == "floor")
        {
            ++floors;
            EXPECT_EQ(child.getNodeMask() & casts, 0u) << "the floor casts nothing";
        }
        else EXPECT_NE(child.getNodeMask() & casts, 0u) << child.getName() << " casts";
    }
    EXPECT_EQ(floors, 1u);
    EXPECT_EQ(suns, 1u);
}

TEST(ShowcaseScene, HasItsPartsAndRigsEvenWithoutADancer)
{
    ShowcaseSources sources;
    sources.dancer.clear();
    const osg::ref_ptr<osg::Group> scene = makeShowcaseScene(sources);
    unsigned walkers = 0, gaits = 0;
    for (unsigned i = 0; i < scene->getNumChildren(); ++i)
    {
        if (const PathWalker* walker = dynamic_cast<PathWalker*>(scene->getChild(i)->getUpdateCallback()))
        {
            ++walkers;
            EXPECT_TRUE(walker->getPath());
        }
        if (const TripodGait* gait = dynamic_cast<TripodGait*>(scene->getChild(i)->getUpdateCallback()))
        {
            ++gaits;
            EXPECT_TRUE(gait->getPath());
        }
        EXPECT_NE(scene->getChild(i)->getName(), "dancer");
    }
    EXPECT_EQ(walkers, 1u);
    EXPECT_EQ(gaits, 1u);
}

TEST(ShowcaseWrappers, PathsGoThroughOsgtAndBadOnesAreRefused)
{
    osgDB::ReaderWriter* osgt = osgDB::Registry::instance()->getReaderWriterForExtension("osgt");
    ASSERT_NE(osgt, nullptr);
    osg::ref_ptr<TripodGait> gait = new TripodGait;
    gait->setPath(straightPath(0.25));
    gait->setStepHeight(0.05);
    osg::ref_ptr<osgDB::Options> ascii = new osgDB::Options;
    ascii->setPluginStringData("fileType", "Ascii"); // what the .osgt extension sets for a file
    std::stringstream text;
    ASSERT_TRUE(osgt->writeObject(*gait, text, ascii.get()).success());

    osgDB::ReaderWriter::ReadResult read = osgt->readObject(text, ascii.get());
    const TripodGait* back = dynamic_cast<const TripodGait*>(read.getObject());
    ASSERT_NE(back, nullptr) << "libosgActorShowcase on OSG_LIBRARY_PATH?";
    // Every number exactly (OSG's own double serializer would write the stream's 6 digits).
    EXPECT_EQ(back->getStepHeight(), 0.05);
    EXPECT_EQ(back->getCycleDuration(), gait->getCycleDuration());
    ASSERT_TRUE(back->getPath());
    EXPECT_EQ(back->getPath()->getName(), "straight");
    ASSERT_EQ(back->getPath()->getKeys().size(), 2u);
    for (std::size_t k = 0; k < 2; ++k)
    {
        const osgActor::TrajectoryKey& key = back->getPath()->getKeys()[k];
        const osgActor::TrajectoryKey& written = gait->getPath()->getKeys()[k];
        EXPECT_EQ(key.time, written.time) << k;
        EXPECT_EQ(key.position, written.position) << k;
        EXPECT_EQ(key.heading, written.heading) << k;
    }
    EXPECT_EQ(back->getPath()->getKeys()[1].position.x, 25.0);

    // The same file with the second key's time before the first: refused as a whole.
    std::string broken = text.str();
    const std::size_t at = broken.find("100 25");
    ASSERT_NE(at, std::string::npos) << broken;
    broken.replace(at, 3, "-1 ");
    std::stringstream brokenText(broken);
    EXPECT_EQ(osgt->readObject(brokenText, ascii.get()).getObject(), nullptr);

    // A key's word that is not a number: refused with the word, not read as 0 or as the number it starts with.
    std::string notANumber = text.str();
    notANumber.replace(at, 6, "100 25x");
    std::stringstream notANumberText(notANumber);
    osgDB::ReaderWriter::ReadResult refused = osgt->readObject(notANumberText, ascii.get());
    EXPECT_EQ(refused.getObject(), nullptr);
    EXPECT_NE(refused.message().find("path 'straight': '25x' is not a number"), std::string::npos)
        << refused.message();
}

TEST(ShowcaseFile, LoadsAndItsInsectKeepsItsFeetPlantedAllRoundItsPath)
{
    const std::string file = dataFile("showcase.osgt");
    const osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(file);
    ASSERT_TRUE(scene.valid()) << "cannot read " << file;
    struct Counter : public osg::NodeVisitor
    {
        Counter() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Node& node) override
        {
            walkers += dynamic_cast<PathWalker*>(node.getUpdateCallback()) != nullptr;
            gaits += dynamic_cast<TripodGait*>(node.getUpdateCallback()) != nullptr;
            if (ActorNode* actor = dynamic_cast<ActorNode*>(&node)) actors.push_back(actor);
            traverse(node);
        }
        unsigned walkers = 0, gaits = 0;
        std::vector<ActorNode*> actors;
    } counter;
    scene->accept(counter);
    EXPECT_EQ(counter.walkers, 1u);
    EXPECT_EQ(counter.gaits, 1u);
    ASSERT_EQ(counter.actors.size(), 4u)
        << "Cesium Man, the insect, the motion-capture dancer and Cesium Man dancing its motion";
    ActorNode& humanoid = *counter.actors[0];
    ActorNode& insect = *counter.actors[1];
    EXPECT_GE(humanoid.getJointIndex("leg_joint_L_5"), 0) << "the walker is Cesium Man";
    EXPECT_EQ(insect.getDefinition()->getName(), "cockroach");

    // Once round the figure of eight (about 36 s) at 30 frames per second, turns and all.
    runUpdate(*scene, 0.0, 1);
    const std::shared_ptr<TripodGaitController> gait = findGait(insect);
    ASSERT_TRUE(gait);
    const double loop = gait->getBodyPlayer().getTrajectory()->getEndTime();
    EXPECT_GT(loop, 30.0);
    const osg::Vec3d humanoidStart = humanoid.getPreTranslation();
    const std::vector<LegTrack> tracks = trackFeet(*scene, insect, loop, 30.0);
    for (unsigned leg = 0; leg < TripodGaitController::kNumLegs; ++leg)
    {
        const char* name = TripodGaitController::kLegNames[leg];
        EXPECT_GT(tracks[leg].stancesSeen, 50u) << name;
        EXPECT_LT(tracks[leg].worstStanceSlip, 1e-4) << name << ": a planted foot slid (metres)";
        // On the floor, in the showcase's frame scaled by 0.8.
        EXPECT_NEAR(tracks[leg].lowestStance, kFootTipRadius * 0.8, 0.0005) << name;
        EXPECT_LT(tracks[leg].highestStance, kFootTipRadius * 0.8 + 0.0005) << name;
        EXPECT_GT(tracks[leg].lowestSwingPeak, 0.05) << name << ": every swing lifts the foot";
    }
    // Cesium Man walked his stored path too: once round his ellipse takes about 10 s: after `loop` seconds he is
    // elsewhere.
    EXPECT_GT((humanoid.getPreTranslation() - humanoidStart).length(), 0.5);
}

namespace {

/** The showcase file's actors, in the scene's order: Cesium Man, the insect, the dancer, Cesium Man dancing. */
std::vector<ActorNode*> showcaseActors(osg::Node& scene)
{
    struct Finder : public osg::NodeVisitor
    {
        Finder() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Transform& transform) override
        {
            if (ActorNode* actor = dynamic_cast<ActorNode*>(&transform)) actors.push_back(actor);
            else traverse(transform);
        }
        std::vector<ActorNode*> actors;
    } finder;
    scene.accept(finder);
    return finder.actors;
}

} // namespace

TEST(ShowcaseFile, CesiumManIsSkinnedOnTheGpuAndPlaysHisWalkAlongHisPathUnderTheSunsShadows)
{
    const osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(dataFile("showcase.osgt"));
    ASSERT_TRUE(scene.valid());
    const std::vector<ActorNode*> actors = showcaseActors(*scene);
    ASSERT_EQ(actors.size(), 4u);
    ActorNode& man = *actors[0];
    struct MeshFinder : public osg::NodeVisitor
    {
        MeshFinder() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Drawable& drawable) override
        {
            if (SkinnedMesh* mesh = dynamic_cast<SkinnedMesh*>(&drawable)) meshes.push_back(mesh);
        }
        std::vector<SkinnedMesh*> meshes;
    } meshes;
    man.accept(meshes);
    ASSERT_EQ(meshes.meshes.size(), 1u) << "one skinned primitive, one material";
    EXPECT_EQ(meshes.meshes[0]->getSkinningPath(), SkinnedMesh::GPU_SKINNING);
    EXPECT_TRUE(meshes.meshes[0]->getSetupError().empty()) << meshes.meshes[0]->getSetupError();

    // The shadow map's light number went through the file.
    const osgShadow::ShadowedScene* shadowed = dynamic_cast<const osgShadow::ShadowedScene*>(scene.get());
    ASSERT_NE(shadowed, nullptr);
    const LightNumberShadowMap* shadowMap = dynamic_cast<const LightNumberShadowMap*>(shadowed->getShadowTechnique());
    ASSERT_NE(shadowMap, nullptr) << "libosgActorShowcase on OSG_LIBRARY_PATH?";
    EXPECT_EQ(shadowMap->getLightNumber(), 1);

    runUpdate(*scene, 0.0, 1);
    EXPECT_TRUE(std::dynamic_pointer_cast<TrajectoryPlayer>(man.findController(PathWalker::kPathControllerName)));
    EXPECT_TRUE(std::dynamic_pointer_cast<ClipPlayer>(man.findController("clip"))) << "his own walk";
    EXPECT_FALSE(man.findController(PathWalker::kWalkControllerName)) << "not the procedural cycle";
}

namespace {

/** Cesium Man's feet (the ends of his legs' chains, his toes) and how far the planted one (the lower) slides. */
struct FootSlide
{
    double slid = 0.0;   // the planted foot's horizontal travel over the floor, summed over the frames
    double walked = 0.0; // the reference point's, the same
};

/** Adds one frame's step to the sums: the feet before and after (world space), and the reference point's step.
  * Frames where the other foot becomes the lower one are left out (the weight passes from foot to foot). */
void addStep(FootSlide& slide, const osg::Vec3d before[2], const osg::Vec3d after[2], const osg::Vec3d& walked)
{
    const int plantedBefore = before[0].z() <= before[1].z() ? 0 : 1;
    const int plantedAfter = after[0].z() <= after[1].z() ? 0 : 1;
    if (plantedBefore != plantedAfter) return;
    const osg::Vec3d step = after[plantedAfter] - before[plantedBefore];
    slide.slid += osg::Vec2d(step.x(), step.y()).length();
    slide.walked += osg::Vec2d(walked.x(), walked.y()).length();
}

const char* const kCesiumManFeet[2] = {"leg_joint_L_5", "leg_joint_R_5"};

} // namespace

TEST(ShowcaseFile, CesiumMansPlantedFootSlidesLeastAtHisPathsSpeed)
{
    // His clip walks on the spot with a stride of its own, not quite even (the planted foot moves back at 0.2 to
    // 1.3 m/s in the clip): the path's speed is the one at which the planted foot slides least over the floor.
    // Measured at 60 frames per second over two cycles of the clip, in model space (his forward is -Y) ...
    osg::ref_ptr<ActorNode> man = readActor("models/CesiumMan/CesiumMan.gltf.actor");
    ASSERT_TRUE(man.valid());
    const int feet[2] = {man->getJointIndex(kCesiumManFeet[0]), man->getJointIndex(kCesiumManFeet[1])};
    ASSERT_GE(feet[0], 0);
    ASSERT_GE(feet[1], 0);
    osg::ref_ptr<osg::Group> stage = new osg::Group;
    stage->addChild(man.get());
    const double fps = 60.0;
    std::vector<std::array<osg::Vec3d, 2>> track;
    for (unsigned frame = 0; frame <= unsigned(4.0 * fps); ++frame)
    {
        runUpdate(*stage, frame / fps, frame + 1);
        track.push_back({man->getJointWorldPosition(unsigned(feet[0])), man->getJointWorldPosition(unsigned(feet[1]))});
    }
    const auto slideAt = [&](double speed) {
        FootSlide slide;
        const osg::Vec3d step(0.0, -speed / fps, 0.0);
        for (std::size_t k = 1; k < track.size(); ++k)
        {
            // On the floor, his feet move with his reference point: frame k's feet are k steps further on.
            const osg::Vec3d travelBefore = step * double(k - 1);
            const osg::Vec3d travelAfter = step * double(k);
            const osg::Vec3d before[2] = {track[k - 1][0] + travelBefore, track[k - 1][1] + travelBefore};
            const osg::Vec3d after[2] = {track[k][0] + travelAfter, track[k][1] + travelAfter};
            addStep(slide, before, after, step);
        }
        return slide.slid / slide.walked;
    };
    const double speed = ShowcaseSources().walkerSpeed;
    const double atSpeed = slideAt(speed);
    EXPECT_LT(atSpeed, slideAt(speed * 0.8)) << "slower slides more";
    EXPECT_LT(atSpeed, slideAt(speed * 1.2)) << "faster slides more";
    EXPECT_LT(atSpeed, 0.6) << "the clip's own slide, at its best";

    // ... and in the showcase, where he walks his ellipse: the path adds no slide of its own.
    const osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(dataFile("showcase.osgt"));
    ASSERT_TRUE(scene.valid());
    const std::vector<ActorNode*> actors = showcaseActors(*scene);
    ASSERT_EQ(actors.size(), 4u);
    ActorNode& walker = *actors[0];
    FootSlide slide;
    osg::Vec3d before[2];
    osg::Vec3d reference;
    double lowest = 1e9;
    for (unsigned frame = 0; frame <= unsigned(4.0 * fps); ++frame)
    {
        runUpdate(*scene, frame / fps, frame + 1);
        const osg::Vec3d after[2] = {walker.getJointWorldPosition(unsigned(feet[0])),
                                     walker.getJointWorldPosition(unsigned(feet[1]))};
        lowest = std::min({lowest, after[0].z(), after[1].z()});
        if (frame > 0) addStep(slide, before, after, walker.getPreTranslation() - reference);
        before[0] = after[0];
        before[1] = after[1];
        reference = walker.getPreTranslation();
    }
    EXPECT_NEAR(slide.walked, speed * 4.0 * 0.9, speed * 4.0 * 0.1) << "he walked (but for the changes of foot)";
    EXPECT_NEAR(slide.slid / slide.walked, atSpeed, 0.05) << "slid " << slide.slid << " m in " << slide.walked << " m";
    EXPECT_NEAR(lowest, 0.0, 0.03) << "his feet reach the floor, z = 0";
}

TEST(ShowcaseFile, CameraFramingTheActorsSeesThemWhereverTheyWalk)
{
    // The box the viewer's home and osgactorrender --frame-actors frame: every actor's path and what they draw,
    // much smaller than the floor (16 m x 10 m), larger than their paths' spans.
    const osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(dataFile("showcase.osgt"));
    ASSERT_TRUE(scene.valid());
    runUpdate(*scene, 0.0, 1); // the rigs give the actors the players of their paths
    const osg::BoundingBox box = osgActorApps::actorsBox(*scene);
    ASSERT_TRUE(box.valid());
    // Cesium Man's ellipse round the dancer at (0, 1.3): x in [-2, 2], y in [0.1, 2.5]; the insect's figure of
    // eight round (4.4, 1.3): x in [2.6, 6.2], y in [0.4, 2.2]; each grown by the actor's reach (under a metre).
    EXPECT_LT(box.xMin(), -2.0);
    EXPECT_GT(box.xMin(), -3.0);
    EXPECT_GT(box.xMax(), 6.2);
    EXPECT_LT(box.xMax(), 7.2);
    EXPECT_LT(box.yMin(), 0.1);
    EXPECT_GT(box.yMin(), -0.9);
    EXPECT_GT(box.yMax(), 2.5);
    EXPECT_LT(box.yMax(), 3.5);
    EXPECT_LT(box.zMax(), 2.5) << "no taller than the dancer's reach";
}

namespace {

const char* const kCharlestonSkeleton = "mocap/asfamc/charleston.asf";
const char* const kCharlestonMotion = "mocap/asfamc/charleston1.amc";

/** Collects the messages OSG_WARN sends while it lives (and puts the previous handler back). */
class CapturedWarnings : public osg::NotifyHandler
{
public:
    void notify(osg::NotifySeverity severity, const char* message) override
    {
        if (severity <= osg::WARN) text += message;
    }
    std::string text;
};

struct WarningCapture
{
    WarningCapture() : previous(osg::getNotifyHandler()), captured(new CapturedWarnings)
    {
        osg::setNotifyHandler(captured.get());
    }
    ~WarningCapture() { osg::setNotifyHandler(previous.get()); }
    unsigned count(const std::string& what) const
    {
        unsigned n = 0;
        for (std::size_t at = captured->text.find(what); at != std::string::npos;
             at = captured->text.find(what, at + what.size()))
            ++n;
        return n;
    }
    osg::ref_ptr<osg::NotifyHandler> previous;
    osg::ref_ptr<CapturedWarnings> captured;
};

/** The Charleston retargeted onto a Cesium Man of his own, by the library's call, independently of the rig. */
ClipPtr charlestonOnFreshCesiumMan()
{
    const osg::ref_ptr<ActorNode> man = readActor("models/CesiumMan/CesiumMan.gltf.actor");
    if (!man) return nullptr;
    MotionFileOptions options;
    options.skeletonFile = dataFile(kCharlestonSkeleton);
    const MocapImport imported = readMotionFile(dataFile(kCharlestonMotion), options);
    EXPECT_TRUE(imported && imported.clip) << imported.error;
    if (!imported || !imported.clip) return nullptr;
    RetargetSkeleton source;
    source.definition = imported.definition;
    const RetargetClipResult result =
        retargetClipOntoActor(*man, source, *imported.clip, RetargetedDance::retargetOptions());
    EXPECT_TRUE(result) << result.error;
    return result.clip;
}

} // namespace

TEST(RetargetedDance, RefusesAMissingMotionFileOnceWithAWarningAndLeavesTheActorAsItWas)
{
    const osg::ref_ptr<ActorNode> man = readActor("models/CesiumMan/CesiumMan.gltf.actor");
    ASSERT_TRUE(man);
    const std::vector<ControllerPtr> controllers = man->getControllers();
    const ClipLibraryPtr library = man->getClipLibrary();
    const std::vector<std::string> clipNames = library ? library->getClipNames() : std::vector<std::string>();
    osg::ref_ptr<RetargetedDance> dance = new RetargetedDance;
    dance->setDatabasePath(OSGACTOR_TEST_DATA_DIR);
    dance->setSkeletonFile(kCharlestonSkeleton);
    dance->setMotionFile("mocap/asfamc/no such dance.amc");
    const osg::ref_ptr<osg::Group> group = groupWithRig(man.get(), dance.get());

    WarningCapture warnings;
    for (unsigned frame = 0; frame < 3; ++frame) runUpdate(*group, frame / 30.0, frame + 1);
    EXPECT_EQ(warnings.count("no such dance.amc"), 1u) << "once, naming the file: " << warnings.captured->text;
    EXPECT_EQ(man->getControllers(), controllers) << "his own players, untouched";
    EXPECT_FALSE(man->findController(RetargetedDance::kControllerName));
    ASSERT_EQ(man->getClipLibrary(), library);
    if (library)
    {
        EXPECT_EQ(library->getClipNames(), clipNames) << "no clip added";
    }
}

TEST(RetargetedDance, RefusesAnActorWithNoJointsInCommonWithTheMotionAndLeavesItAsItWas)
{
    // A crane: one turning joint that no humanoid map knows.
    ActorDefinitionBuilder builder("crane");
    builder.addJoint("base").dofs(kRotationDofs);
    const BuildResult built = builder.build();
    ASSERT_TRUE(built) << built.error;
    const osg::ref_ptr<ActorNode> crane = new ActorNode(built.definition);
    const std::vector<double> dofs = crane->getDofs();
    osg::ref_ptr<RetargetedDance> dance = new RetargetedDance;
    dance->setDatabasePath(OSGACTOR_TEST_DATA_DIR);
    dance->setSkeletonFile(kCharlestonSkeleton);
    dance->setMotionFile(kCharlestonMotion);
    const osg::ref_ptr<osg::Group> group = groupWithRig(crane.get(), dance.get());

    WarningCapture warnings;
    for (unsigned frame = 0; frame < 3; ++frame) runUpdate(*group, frame / 30.0, frame + 1);
    EXPECT_EQ(warnings.count("charleston1.amc"), 1u) << warnings.captured->text;
    EXPECT_TRUE(crane->getControllers().empty());
    EXPECT_FALSE(crane->getClipLibrary() && crane->getClipLibrary()->getNumClips()) << "no clip added";
    EXPECT_EQ(crane->getDofs(), dofs);
}

TEST(ShowcaseWrappers, RetargetedDanceGoesThroughOsgtWithItsFiles)
{
    osgDB::ReaderWriter* osgt = osgDB::Registry::instance()->getReaderWriterForExtension("osgt");
    ASSERT_NE(osgt, nullptr);
    osg::ref_ptr<RetargetedDance> dance = new RetargetedDance;
    dance->setSkeletonFile("mocap/asfamc/charleston.asf");
    dance->setMotionFile("mocap/asfamc/charleston1.amc");
    dance->setDatabasePath("/not/written");
    osg::ref_ptr<osgDB::Options> ascii = new osgDB::Options;
    ascii->setPluginStringData("fileType", "Ascii");
    std::stringstream text;
    ASSERT_TRUE(osgt->writeObject(*dance, text, ascii.get()).success());
    EXPECT_EQ(text.str().find("/not/written"), std::string::npos) << "the folder comes from the reader, not the file";

    ascii->getDatabasePathList().push_back("/where/it/was/read");
    osgDB::ReaderWriter::ReadResult read = osgt->readObject(text, ascii.get());
    const RetargetedDance* back = dynamic_cast<const RetargetedDance*>(read.getObject());
    ASSERT_NE(back, nullptr) << "libosgActorShowcase on OSG_LIBRARY_PATH?";
    EXPECT_EQ(back->getSkeletonFile(), "mocap/asfamc/charleston.asf");
    EXPECT_EQ(back->getMotionFile(), "mocap/asfamc/charleston1.amc");
    EXPECT_EQ(back->getDatabasePath(), "/where/it/was/read");
}

TEST(ShowcaseFile, SecondCesiumManDancesTheCharlestonAsRetargetOntoAFreshCesiumManGivesIt)
{
    const osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(dataFile("showcase.osgt"));
    ASSERT_TRUE(scene.valid());
    const std::vector<ActorNode*> actors = showcaseActors(*scene);
    ASSERT_EQ(actors.size(), 4u);
    ActorNode& walker = *actors[0];
    ActorNode& dancer = *actors[3];
    ASSERT_NE(&walker, &dancer) << "two Cesium Men, not one loaded twice";
    EXPECT_GE(dancer.getJointIndex("leg_joint_L_5"), 0) << "the second dancer is Cesium Man";
    // Beside the stick-figure dancer, within two metres of it.
    const osg::Vec3d stickFigure = actors[2]->getBound().center();
    const osg::Vec3d man = dancer.getBound().center();
    EXPECT_LT((osg::Vec2d(man.x(), man.y()) - osg::Vec2d(stickFigure.x(), stickFigure.y())).length(), 2.0);

    const ClipPtr expected = charlestonOnFreshCesiumMan();
    ASSERT_TRUE(expected);
    const double fps = 30.0;
    std::vector<double> firstDance;
    for (unsigned frame = 0; frame <= unsigned(3.0 * fps); ++frame)
    {
        runUpdate(*scene, frame / fps, frame + 1);
        if (frame == 1) firstDance = dancer.getDofs();
    }
    const auto player = std::dynamic_pointer_cast<ClipPlayer>(dancer.findController(RetargetedDance::kControllerName));
    ASSERT_TRUE(player);
    EXPECT_FALSE(dancer.findController("clip")) << "his own walk gave way";
    EXPECT_TRUE(walker.findController("clip")) << "the walker still walks";
    EXPECT_FALSE(walker.findController(RetargetedDance::kControllerName));
    EXPECT_NEAR(player->getClipTime(), 3.0, 1.0 / fps + 1e-9) << "it played since the scene loaded";

    ClipCursor cursor;
    expected->initCursor(cursor);
    std::vector<double> values(expected->getNumChannels());
    ASSERT_TRUE(sampleEveryChannel(*expected, player->getClipTime(), cursor, values));
    const std::vector<double>& dofs = dancer.getDofs();
    ASSERT_EQ(dofs.size(), values.size()) << "one channel per DOF";
    double moved = 0.0;
    for (std::size_t d = 0; d < dofs.size(); ++d)
    {
        EXPECT_NEAR(dofs[d], values[d], 1e-9) << dancer.getDefinition()->getDofName(unsigned(d));
        moved = std::max(moved, std::abs(dofs[d] - firstDance[d]));
    }
    EXPECT_GT(moved, 0.1) << "he dances (radians or metres changed)";
}
