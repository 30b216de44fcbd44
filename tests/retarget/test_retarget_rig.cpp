// The rig: what buildRetargetRig refuses (nothing half-built), and what it works out from two skeletons.
#include "RetargetTestUtil"

#include <osgActor/core/retarget/HAnimHumanoid>

#include <limits>

using namespace osgActor;
using namespace osgActor::test;

namespace {

std::string refusal(const RetargetSkeleton& source, const RetargetSkeleton& target)
{
    const RetargetRigBuildResult result = buildRetargetRig(source, target);
    EXPECT_FALSE(result);
    EXPECT_EQ(result.rig, nullptr) << "nothing half-built";
    return result.error;
}

::testing::AssertionResult mentions(const std::string& text, const std::string& part)
{
    if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "'" << text << "' does not mention '" << part << "'";
}

} // namespace

TEST(RetargetRigBuild, RefusesAMissingSkeletonAndARestPoseOfTheWrongSize)
{
    const ActorDefinitionPtr humanoid = readHumanoid();
    EXPECT_TRUE(mentions(refusal(skeleton(nullptr), skeleton(humanoid)), "the source has no skeleton"));
    EXPECT_TRUE(mentions(refusal(skeleton(humanoid), skeleton(humanoid, {0.0, 1.0})),
                         "the target rest pose has 2 values, but skeleton 'humanoid' has " +
                             std::to_string(humanoid->getNumDofs()) + " DOFs"));
}

TEST(RetargetRigBuild, RefusesARestPoseWithNaNNamingTheDof)
{
    const ActorDefinitionPtr humanoid = readHumanoid();
    std::vector<double> rest = humanoid->getDefaultDofs();
    rest[static_cast<unsigned>(humanoid->findDof("l_knee.rx"))] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_TRUE(mentions(refusal(skeleton(humanoid, rest), skeleton(humanoid)),
                         "the source rest pose gives DOF 'l_knee.rx' of skeleton 'humanoid' the value nan"));
    rest[static_cast<unsigned>(humanoid->findDof("l_knee.rx"))] = std::numeric_limits<double>::infinity();
    EXPECT_TRUE(mentions(refusal(skeleton(humanoid), skeleton(humanoid, rest)), "not a finite number"));
}

TEST(RetargetRigBuild, RefusesAMapThatDoesNotFitItsSkeletonNamingItsLine)
{
    const ActorDefinitionPtr humanoid = readHumanoid();
    RetargetSkeleton target = skeleton(humanoid);
    target.map.setName("humanoid.map");
    target.map.add("HumanoidRoot", "HumanoidRoot", "humanoid.map:1");
    target.map.add("l_thigh", "l_hip", "humanoid.map:2");
    EXPECT_TRUE(mentions(refusal(skeleton(humanoid), target),
                         "the target skeleton 'humanoid': humanoid.map:2: joint map 'humanoid.map' names joint "
                         "'l_thigh', which the skeleton 'humanoid' does not have"));
}

TEST(RetargetRigBuild, RefusesSkeletonsWithNoJointInCommon)
{
    const ActorDefinitionPtr humanoid = readHumanoid();
    ActorDefinitionBuilder b("crane");
    b.addJoint("base").dofs(kRotationDofs);
    b.addJoint("boom", "base").offset(0, 0, 3).dofs(dofBit(Dof::RX));
    RetargetSkeleton crane = skeleton(b.build().definition);
    crane.map.add("base", "base_joint"); // a map that names no H-Anim joint at all fails first
    EXPECT_TRUE(mentions(refusal(crane, skeleton(humanoid)), "neither an H-Anim joint name"));
    // Mapped, but to joints the other side lacks.
    RetargetSkeleton fingers = skeleton(crane.definition);
    fingers.map = JointMap();
    fingers.map.add("base", "l_thumb1");
    fingers.map.add("boom", "l_thumb2");
    EXPECT_TRUE(mentions(refusal(fingers, skeleton(humanoid)),
                         "the source skeleton 'crane' and the target skeleton 'humanoid' have no H-Anim joint in "
                         "common (2 and 18 joints mapped)"));
}

TEST(RetargetRigBuild, RefusesANegativeScale)
{
    const ActorDefinitionPtr humanoid = readHumanoid();
    RetargetOptions options;
    options.scale = -1.0;
    const RetargetRigBuildResult result = buildRetargetRig(skeleton(humanoid), skeleton(humanoid), options);
    EXPECT_FALSE(result);
    EXPECT_TRUE(mentions(result.error, "the scale must be a finite number >= 0"));
}

TEST(RetargetRig, ScalesByHipHeightsAndTurnsTheFacingAbout)
{
    // CMU's ASF (metres) onto the humanoid: both face -Y once in Z up; the hip heights are HumanoidRoot's height
    // above the hips plus the thigh and shank lengths.
    const MocapImport cmu = readCmuAmc("11.asf", "11_01.amc");
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(cmu.definition), skeleton(humanoid));
    ASSERT_TRUE(rig);
    EXPECT_NEAR(rig->getTargetHipHeight(), 0.05 + 0.42 + 0.41, 1e-12);
    EXPECT_NEAR(rig->getScale(), rig->getTargetHipHeight() / rig->getSourceHipHeight(), 1e-15);
    // Both face -Y; CMU's hips are not quite level front to back, so A turns a little about +Z, and only about +Z.
    const glm::dmat3& a = rig->getAlignment();
    EXPECT_NEAR(a[2][2], 1.0, 1e-15);
    EXPECT_LE(angleBetween(a, glm::dmat3(1.0)), degrees(5));
    // Points scale about the floor (z = 0 on both sides by default) and turn with A.
    const glm::dvec3 mapped = rig->mapPosition(glm::dvec3(1.0, 2.0, 0.5));
    const glm::dvec3 expected = a * (rig->getScale() * glm::dvec3(1.0, 2.0, 0.5));
    EXPECT_NEAR(glm::length(mapped - expected), 0.0, 1e-15);
    EXPECT_NEAR(mapped.z, rig->getScale() * 0.5, 1e-15);
    RetargetOptions floors;
    floors.sourceFloor = 0.1;
    floors.targetFloor = -0.2;
    floors.scale = 2.0;
    const RetargetRigPtr raised = buildRig(skeleton(cmu.definition), skeleton(humanoid), floors);
    EXPECT_NEAR(raised->mapPosition(glm::dvec3(0.0, 0.0, 0.5)).z, 2.0 * (0.5 - 0.1) - 0.2, 1e-15);

    // A humanoid turned to face +X: A is the quarter turn about +Z taking -Y to +X.
    ActorDefinitionBuilder turned = toBuilder(*humanoid);
    turned.joint(0).rotation(glm::half_pi<double>(), 0, 0, 1);
    const ActorDefinitionPtr facingX = turned.build().definition;
    const RetargetRigPtr turnedRig = buildRig(skeleton(humanoid), skeleton(facingX));
    ASSERT_TRUE(turnedRig);
    const glm::dvec3 forward = turnedRig->getAlignment() * glm::dvec3(0, -1, 0);
    EXPECT_NEAR(forward.x, 1.0, 1e-12);
    EXPECT_NEAR(forward.y, 0.0, 1e-12);
    EXPECT_NEAR(forward.z, 0.0, 1e-12);
}

TEST(RetargetRig, TheHumanoidsOneJointTorsoFollowsTheSourcesWholeBack)
{
    const MocapImport cmu = readBvhScaled(repositoryMocap("bvh/12_03.bvh"));
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(cmu.definition), skeleton(humanoid));
    ASSERT_TRUE(rig);
    auto sourceName = [&](const char* target) {
        const RetargetJointPlan& plan = rig->getPlan(static_cast<unsigned>(humanoid->findJoint(target)));
        return plan.sourceB >= 0 ? cmu.definition->getJointName(static_cast<unsigned>(plan.sourceB)) : std::string("-");
    };
    EXPECT_EQ(sourceName("vl5"), "Spine1");          // where the source's arms and neck part, not LowerBack
    EXPECT_EQ(sourceName("l_wrist"), "LeftFingerBase"); // the wrist's flexion, below the twist of LeftHand
    EXPECT_EQ(sourceName("l_hip"), "LeftUpLeg");
    EXPECT_EQ(sourceName("HumanoidRoot"), "Hips");
    EXPECT_EQ(rig->getPlan(static_cast<unsigned>(humanoid->findJoint("l_midtarsal"))).kind, RetargetJointKind::Rest);
    bool notedRest = false;
    for (const std::string& note : rig->getNotes())
        notedRest = notedRest || note.find("kept at rest): l_midtarsal, r_midtarsal") != std::string::npos;
    EXPECT_TRUE(notedRest);
}
