// The IK pass: contacts found by hand-derived trajectories, what the jobs refuse, the root lowered for a leg out of
// reach, and on CMU's walks the measures of issue 27: planted feet that stay put, ends where the source puts them.
#include "RetargetTestUtil"

#include <osgActor/core/ClipBuilder>
#include <osgActor/core/retarget/FootContacts>
#include <osgActor/core/retarget/HAnimHumanoid>
#include <osgActor/core/retarget/RetargetMeasures>

#include <glm/geometric.hpp>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A foot sliding in at 1 m/s for 50 frames, still for 50, then lifting at 1 m/s, at 100 frames per second. */
std::vector<glm::dvec3> stepTrajectory()
{
    std::vector<glm::dvec3> positions;
    for (unsigned f = 0; f < 150; ++f)
    {
        if (f < 50) positions.emplace_back(-0.5 + 0.01 * f, 0.0, 0.0);
        else if (f < 100) positions.emplace_back(0.0, 0.0, 0.0);
        else positions.emplace_back(0.0, 0.0, 0.01 * (f - 99));
    }
    return positions;
}

std::string clipError(const RetargetRig& rig, const Clip& clip, const RetargetClipOptions& options)
{
    const RetargetClipResult result = retargetClip(rig, clip, options);
    EXPECT_FALSE(result);
    EXPECT_EQ(result.clip, nullptr);
    return result.error;
}

} // namespace

TEST(FootContacts, AFootThatStopsIsInContactWhileItStaysStillAndLow)
{
    const std::vector<glm::dvec3> step = stepTrajectory();
    // Hip height 0.9: the defaults allow 5.4 cm above the lowest point and 9 cm/s (central differences: the frames
    // either side of the stop see it move).
    const std::vector<FootContact> contacts = findFootContacts(step, 100.0, 0.9);
    ASSERT_EQ(contacts.size(), 1u);
    EXPECT_EQ(contacts[0].first, 51u);
    EXPECT_EQ(contacts[0].last, 98u);
    // Overridden: up to 60 cm/s counts as still, and 3 cm up as low: the edges of the stop join in.
    FootContactOptions lenient;
    lenient.speed = 0.6;
    lenient.height = 0.03;
    const std::vector<FootContact> wider = findFootContacts(step, 100.0, 0.9, lenient);
    ASSERT_EQ(wider.size(), 1u);
    EXPECT_EQ(wider[0].first, 50u);
    EXPECT_EQ(wider[0].last, 99u);
    // A stop shorter than the minimum duration is a foot passing low, not a step.
    FootContactOptions longer;
    longer.minDuration = 0.6;
    EXPECT_TRUE(findFootContacts(step, 100.0, 0.9, longer).empty());
    EXPECT_TRUE(findFootContacts(Span<const glm::dvec3>(), 100.0, 0.9).empty());
}

TEST(FootContacts, APlantsHoldEasesInAndOut)
{
    const FootContact contact{20, 30};
    EXPECT_EQ(footHoldWeight(25, contact, 10.0), 1.0);
    EXPECT_EQ(footHoldWeight(20, contact, 10.0), 1.0);
    EXPECT_DOUBLE_EQ(footHoldWeight(15, contact, 10.0), 0.5); // smoothstep half way
    EXPECT_DOUBLE_EQ(footHoldWeight(35, contact, 10.0), 0.5);
    EXPECT_EQ(footHoldWeight(10, contact, 10.0), 0.0);
    EXPECT_EQ(footHoldWeight(31, contact, 0.0), 0.0);
}

TEST(RetargetClip, RefusesAClipOfAnotherSkeletonAndBadOptions)
{
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(humanoid), skeleton(humanoid));
    ClipBuilder other("other");
    other.addKey(other.addChannel("tail.rx"), 0.0, 1.0);
    const ClipPtr tail = other.build().clip;
    EXPECT_EQ(clipError(*rig, *tail, RetargetClipOptions()),
              "clip 'other' drives no DOF of the skeleton 'humanoid'");
    ClipBuilder wave("wave");
    const unsigned elbow = wave.addChannel("r_elbow.rx");
    wave.addKey(elbow, 0.0, 0.0);
    wave.addKey(elbow, 1.0, -1.0);
    const ClipPtr keyed = wave.build().clip;
    RetargetClipOptions noRate;
    noRate.frameRate = 0.0;
    EXPECT_EQ(clipError(*rig, *keyed, noRate), "sampling clip 'wave': the frame rate must be positive");
    RetargetClipOptions backwards;
    backwards.blendTime = -0.1;
    EXPECT_EQ(clipError(*rig, *keyed, backwards), "retargeting clip 'wave': the blend time must be 0 or more");
    // A keyed clip is sampled at the frame rate asked for: 1 s at 30 frames per second is 31 frames.
    const RetargetClipResult sampled = retargetClip(*rig, *keyed);
    ASSERT_TRUE(sampled) << sampled.error;
    EXPECT_EQ(sampled.numFrames, 31u);
    EXPECT_NEAR(sampled.clip->getFrame(30)[humanoid->findDof("r_elbow.rx")], -1.0, 1e-9);
}

TEST(RetargetIkJob, RefusesWrongSizesAndInvalidGoals)
{
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(humanoid), skeleton(humanoid));
    const RetargetLimbs limbs = buildRetargetLimbs(*rig);
    ASSERT_EQ(limbs.limbs.size(), 4u);
    RetargetWorkspace workspace;
    workspace.resize(*rig);
    std::vector<IkWorkspace> ikWorkspaces;
    std::vector<IkGoal> goals(4);
    std::vector<double> dofs = humanoid->getDefaultDofs();
    RetargetIkJob job = ikJob(*rig, limbs, goals, dofs, workspace, ikWorkspaces);
    EXPECT_TRUE(job.validate());
    job.goals = Span<const IkGoal>(goals.data(), 3);
    EXPECT_FALSE(job.run());
    job.goals = goals;
    goals[2].position.x = std::numeric_limits<double>::quiet_NaN();
    EXPECT_FALSE(job.run());
    goals[2].position.x = 0.0;
    const std::vector<std::uint8_t> someEnabled = {1, 0};
    job.enabled = someEnabled;
    EXPECT_FALSE(job.validate());
}

TEST(RetargetIkJob, LowersTheRootForALegOutOfReach)
{
    // The humanoid standing at rest, its left foot's goal 10 cm below where its straight leg ends: the root comes
    // down, the foot reaches, and the hands' goals, relative to the body, come down with it.
    const ActorDefinitionPtr humanoid = readHumanoid();
    const RetargetRigPtr rig = buildRig(skeleton(humanoid), skeleton(humanoid));
    const RetargetLimbs limbs = buildRetargetLimbs(*rig);
    RetargetWorkspace workspace;
    std::vector<double> dofs = humanoid->getDefaultDofs();
    ASSERT_TRUE(retargetJob(*rig, humanoid->getDefaultDofs(), dofs, workspace).run());
    std::vector<IkGoal> goals(limbs.limbs.size());
    for (std::size_t i = 0; i < limbs.limbs.size(); ++i)
        goals[i].position = workspace.targetPosition(limbs.limbs[i].chain->getEffectorJoint());
    goals[0].position.z -= 0.1; // l_leg
    std::vector<IkWorkspace> ikWorkspaces;
    RetargetIkJob job = ikJob(*rig, limbs, goals, dofs, workspace, ikWorkspaces);
    ASSERT_TRUE(job.run());
    EXPECT_NEAR(job.rootDrop, 0.1 + 0.001 * limbs.limbs[0].chain->getLength(), 1e-9);
    EXPECT_LE(job.largestError, 1e-9);
    ActorPose pose(humanoid);
    pose.setDofs(dofs.data(), dofs.size());
    pose.updateMatrices();
    for (std::size_t i = 0; i < limbs.limbs.size(); ++i)
    {
        const glm::dvec3 end(pose.getModelMatrix(limbs.limbs[i].chain->getEffectorJoint())[3]);
        const glm::dvec3 expected = goals[i].position - (limbs.limbs[i].isLeg ? glm::dvec3(0.0) :
                                                                                glm::dvec3(0.0, 0.0, job.rootDrop));
        EXPECT_LE(glm::length(end - expected), 1e-9) << limbs.limbs[i].name;
    }
    EXPECT_NEAR(pose.getModelMatrix(0)[3].z, 0.95 - job.rootDrop, 1e-12);
}

TEST(RetargetIk, PlantedFeetStayPutAndEndsFollowOnCmuWalks)
{
    // CMU walks (Debian's assimp-testmodels BVH files, CMU's ASF/AMC in data/mocap) onto the project's humanoid and
    // onto Boxing_Toes.bvh's skeleton in metres, both about 1.75 m tall. With the IK pass: during each of the source's
    // foot contacts the target's ankle moves at most 1 cm (on a 1.75 m body), and ankles and wrists stay within 1% of
    // the body's height of where the source puts them. Without it the feet slide.
    const ActorDefinitionPtr humanoid = readHumanoid();
    const ActorDefinitionPtr boxing = readBvhScaled(assimpBvh("Boxing_Toes.bvh"), 0.01).definition;
    struct Case
    {
        MocapImport source;
        ActorDefinitionPtr target;
    };
    const MocapImport walk0101 = readBvhScaled(assimpBvh("01_01.bvh"));
    const MocapImport walk1101 = readCmuAmc("11.asf", "11_01.amc");
    const std::vector<Case> cases = {{walk0101, humanoid},
                                     {walk0101, boxing},
                                     {readBvhScaled(assimpBvh("01_03.bvh")), humanoid},
                                     {walk1101, humanoid},
                                     {walk1101, boxing}};
    for (const Case& c : cases)
    {
        SCOPED_TRACE(c.source.definition->getName() + " onto " + c.target->getName());
        const RetargetRigPtr rig = buildRig(skeleton(c.source.definition), skeleton(c.target));
        ASSERT_TRUE(rig);
        RetargetClipOptions options;
        options.ik = true;
        const RetargetClipResult planted = retargetClip(*rig, *c.source.clip, options);
        ASSERT_TRUE(planted) << planted.error;
        const RetargetMeasures measures = measureRetargetedClip(*rig, *c.source.clip, planted);
        const double toHeight = 1.75 / measures.targetHeight; // target units to metres of a 1.75 m body
        ASSERT_GE(measures.contacts.size(), 4u);
        for (const RetargetMeasures::Contact& contact : measures.contacts)
            EXPECT_LE(contact.slip * toHeight, 0.01) << contact.limb << " " << contact.frames.first;
        ASSERT_EQ(measures.ends.size(), 4u);
        for (const RetargetMeasures::End& end : measures.ends)
            EXPECT_LE(end.largestError, 0.01 * measures.targetHeight) << end.limb;

        // The same without the IK pass, measured over the same contacts: the feet slide more than 1 cm.
        RetargetClipResult free = retargetClip(*rig, *c.source.clip);
        ASSERT_TRUE(free) << free.error;
        free.feet = planted.feet;
        EXPECT_GT(measureRetargetedClip(*rig, *c.source.clip, free).largestSlip * toHeight, 0.01);
    }
}
