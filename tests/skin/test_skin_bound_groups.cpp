// SkinBoundsJob's grouped path: pieces with at most four joints laid out eight at a time (groupSkinBlendSets()) and
// moved at once give the box the one-by-one path gives, within float rounding, on every frame.
#include "SkinTestData"

#include <osgActor/core/Clip>
#include <osgActor/core/SamplingJob>
#include <osgActor/core/skin/SkinBinding>
#include <osgActor/core/skin/SkinBoundsJob>
#include <osgActor/core/skin/SkinningJob>
#include <osgActor/import/GltfReader>
#include <osgActor/import/RiggedActorBuilder>
#include <osgActor/mocap/BvhReader>

#include <glm/ext/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** The float skinning matrices of a skin bound to the pose's definition, the pose's matrices up to date. */
std::vector<glm::mat4> skinningMatricesOf(const ActorPose& pose, const Skin& skin, const SkinBinding& binding)
{
    std::vector<glm::mat4> matrices(skin.getNumJoints());
    SkinningMatricesJob job;
    job.modelMatrices = modelMatricesOf(pose);
    job.definitionJoints = binding.definitionJoints;
    job.inverseBindMatrices = skin.getInverseBindMatrices();
    job.matrices = matrices;
    EXPECT_TRUE(job.run());
    return matrices;
}

/** The skin's bound from its groups (and its other pieces one by one), and from every piece one by one. */
struct BothBounds
{
    SkinBox grouped;
    SkinBox oneByOne;
};

BothBounds boundsOf(const Skin& skin, const std::vector<glm::mat4>& matrices)
{
    BothBounds both;
    SkinBoundsJob job = makeSkinBoundsJob(skin);
    job.matrices = matrices;
    job.bound = &both.grouped;
    EXPECT_TRUE(job.run());
    job.blendSetGroups = Span<const SkinBlendSetGroup>();
    job.bound = &both.oneByOne;
    EXPECT_TRUE(job.run());
    return both;
}

/** The largest difference between the two boxes' sides, over float rounding's scale: a few units of the last place of
  * the box's largest coordinate, which the bound's margin (many times that) covers. */
double differenceInUlps(const BothBounds& both)
{
    const SkinBox& a = both.grouped;
    const SkinBox& b = both.oneByOne;
    double largest = 0.0, difference = 0.0;
    for (int r = 0; r < 3; ++r)
    {
        largest = std::max({largest, std::abs(double(b.min[r])), std::abs(double(b.max[r]))});
        difference = std::max({difference, std::abs(double(a.min[r]) - b.min[r]), std::abs(double(a.max[r]) - b.max[r])});
    }
    return difference / (largest * std::numeric_limits<float>::epsilon());
}

/** How many of the skin's pieces the groups should hold: those with at most kSkinBlendSetGroupJoints joints. */
std::size_t groupablePieces(const Skin& skin)
{
    return std::size_t(std::count_if(skin.getBlendSets().begin(), skin.getBlendSets().end(),
                                     [](const SkinBlendSet& set) { return set.numJoints <= kSkinBlendSetGroupJoints; }));
}

bool contains(const SkinBox& box, const glm::vec3& p)
{
    return p.x >= box.min.x && p.y >= box.min.y && p.z >= box.min.z && p.x <= box.max.x && p.y <= box.max.y &&
           p.z <= box.max.z;
}

constexpr double kUlps = 16.0;

} // namespace

// --- invalid jobs first ---

TEST(SkinBoundGroups, AJobWhoseGroupNamesAJointBeyondTheMatricesIsRefused)
{
    const SkinBuildResult built = makeRandomSkin(*makeRandomDefinition(6, 3u), 200, 3, 5u).toBuilder("random").build();
    ASSERT_TRUE(built) << built.error;
    ASSERT_FALSE(built.skin->getBlendSetGroups().empty());
    std::vector<glm::mat4> matrices(built.skin->getNumJoints());
    std::vector<SkinBlendSetGroup> groups(built.skin->getBlendSetGroups().begin(), built.skin->getBlendSetGroups().end());
    SkinBox bound;
    SkinBoundsJob job = makeSkinBoundsJob(*built.skin);
    job.matrices = matrices;
    job.bound = &bound;
    job.blendSetGroups = groups;
    EXPECT_TRUE(job.validate());
    groups.back().joints[2][7] = static_cast<std::uint32_t>(matrices.size()); // one past the last joint
    EXPECT_FALSE(job.validate());
    EXPECT_FALSE(job.run());
}

// --- the layout ---

TEST(SkinBoundGroups, LayPiecesOfAtMostFourJointsEightToAGroupWithWeightlessFillers)
{
    // Eleven pieces: ten with one to four joints, one with five (left to the one-by-one path) and, between them,
    // one with an empty box (nothing to bound). Piece i's box: [0, 2] x [0, 4] x [0, 6] in a frame at (i, 2i, 0),
    // turned 90 degrees about Z for piece 1: the centre (1, 2, 3) and half sizes (1, 2, 3) in the frame.
    std::vector<SkinBlendSet> sets;
    std::vector<std::uint32_t> setJoints;
    std::vector<float> setWeights;
    for (unsigned i = 0; i < 12; ++i)
    {
        SkinBlendSet set;
        set.box.boxToBind = glm::translate(glm::mat4(1.0f), glm::vec3(float(i), 2.0f * i, 0.0f));
        if (i == 1) set.box.boxToBind = glm::rotate(set.box.boxToBind, glm::radians(90.0f), glm::vec3(0, 0, 1));
        set.box.box.min = glm::vec3(0.0f);
        set.box.box.max = i == 3 ? glm::vec3(-1.0f) : glm::vec3(2.0f, 4.0f, 6.0f);
        set.firstJoint = static_cast<std::uint32_t>(setJoints.size());
        set.numJoints = i == 5 ? 5u : 1u + i % 4u;
        for (unsigned j = 0; j < set.numJoints; ++j)
        {
            setJoints.push_back(10 * i + j);
            setWeights.push_back(j == 0 ? 0.5f : 0.1f * float(j));
        }
        sets.push_back(set);
    }
    const std::vector<SkinBlendSetGroup> groups = groupSkinBlendSets(sets, setJoints, setWeights);
    ASSERT_EQ(groups.size(), 2u); // ten pieces: eight, then two and six fillers
    const std::vector<unsigned> lanePieces{0, 1, 2, 4, 6, 7, 8, 9, 10, 11};
    for (unsigned at = 0; at < 16; ++at)
    {
        const SkinBlendSetGroup& group = groups[at / 8];
        const unsigned lane = at % 8;
        const unsigned i = lanePieces[at < 10 ? at : 8]; // the last group's fillers: copies of its first piece
        SCOPED_TRACE("lane " + std::to_string(lane) + " of group " + std::to_string(at / 8) + ", piece " + std::to_string(i));
        const glm::vec3 centre = i == 1 ? glm::vec3(1.0f - 2.0f, 2.0f + 1.0f, 3.0f) : glm::vec3(i + 1.0f, 2.0f * i + 2.0f, 3.0f);
        const glm::vec3 halfAxes[3] = {i == 1 ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0),
                                       i == 1 ? glm::vec3(-2, 0, 0) : glm::vec3(0, 2, 0), glm::vec3(0, 0, 3)};
        for (int r = 0; r < 3; ++r)
        {
            EXPECT_NEAR(group.centre[r][lane], centre[r], 1e-6f);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(group.halfAxes[c][r][lane], halfAxes[c][r], 1e-6f);
        }
        const unsigned numJoints = 1u + i % 4u;
        EXPECT_FLOAT_EQ(group.budget[lane], 0.5f + 4.0f * std::numeric_limits<float>::epsilon());
        EXPECT_EQ(group.joints[0][lane], 10 * i);
        for (unsigned slot = 1; slot < 4; ++slot)
        {
            EXPECT_EQ(group.joints[slot][lane], slot < numJoints ? 10 * i + slot : 10 * i);
            EXPECT_FLOAT_EQ(group.caps[slot - 1][lane], slot < numJoints ? 0.1f * float(slot) : 0.0f);
        }
    }
    // The farthest coordinate: the largest centre coordinate plus the half sizes (1 + 2 + 3).
    EXPECT_NEAR(groups[0].bindReach, 2.0f * 9.0f + 2.0f + 6.0f, 1e-5f);
    EXPECT_NEAR(groups[1].bindReach, 2.0f * 11.0f + 2.0f + 6.0f, 1e-5f);
}

// --- the same box ---

TEST(SkinBoundGroups, GiveTheOneByOneBoxOnEveryFrameOfAWalkOnTubes)
{
    const MocapImport motion = readBvhFile(std::string(OSGACTOR_TEST_MOCAP_DIR) + "/bvh/12_03.bvh");
    ASSERT_TRUE(motion) << motion.error;
    const ActorDefinition& definition = *motion.definition;
    double longest = 0.0; // tubes around the bones longer than a tenth of the longest
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
        longest = std::max(longest, glm::length(definition.getOffsetTranslation(j)));
    const SkinBuildResult built = makeTubeSkin(definition, 8, 12, 0.15, 0.1 * longest).toBuilder("tubes").build();
    ASSERT_TRUE(built) << built.error;
    const Skin& skin = *built.skin;
    ASSERT_EQ(skin.getBlendSetGroups().size(), (groupablePieces(skin) + 7) / 8);
    const SkinBinding binding = bindSkinToDefinition(skin, definition);
    ASSERT_TRUE(binding) << binding.error;
    ActorPose pose(motion.definition);
    double worst = 0.0;
    for (unsigned frame = 0; frame < motion.clip->getNumFrames(); ++frame)
    {
        ASSERT_TRUE(succeeded(pose.setDofs(motion.clip->getFrame(frame), definition.getNumDofs())));
        pose.updateMatrices();
        worst = std::max(worst, differenceInUlps(boundsOf(skin, skinningMatricesOf(pose, skin, binding))));
    }
    std::cout << "grouped against one by one: largest difference " << worst << " units of the last place\n";
    EXPECT_LE(worst, kUlps);
}

TEST(SkinBoundGroups, GiveTheOneByOneBoxOnEveryFrameOfCesiumMansWalk)
{
    const RiggedModelRead read = readGltfFile(std::string(OSGACTOR_TEST_DATA_DIR) + "/models/CesiumMan/CesiumMan.gltf");
    ASSERT_TRUE(read) << read.error;
    const RiggedActor actor = buildRiggedActor(read.model);
    ASSERT_TRUE(actor) << actor.error;
    ASSERT_EQ(actor.skins.size(), 1u);
    ASSERT_FALSE(actor.clips.empty());
    const Skin& skin = *actor.skins[0].skin;
    ASSERT_GT(groupablePieces(skin), 100u);
    ASSERT_EQ(skin.getBlendSetGroups().size(), (groupablePieces(skin) + 7) / 8);
    const SkinBinding binding = bindSkinToDefinition(skin, *actor.definition);
    ASSERT_TRUE(binding) << binding.error;

    const Clip& clip = *actor.clips[0];
    std::vector<std::uint32_t> dofs;
    for (unsigned c = 0; c < clip.getNumChannels(); ++c)
    {
        const int dof = actor.definition->findDof(clip.getChannel(c).target);
        ASSERT_GE(dof, 0) << clip.getChannel(c).target;
        dofs.push_back(static_cast<std::uint32_t>(dof));
    }
    ClipCursor cursor;
    clip.initCursor(cursor);
    std::vector<double> values(clip.getNumChannels());
    ActorPose pose(actor.definition);
    double worst = 0.0;
    unsigned frames = 0;
    for (double t = 0.0; t <= clip.getDuration() + 1e-9; t += 1.0 / 60.0, ++frames)
    {
        ASSERT_TRUE(sampleEveryChannel(clip, t, cursor, values));
        pose.setDofs(dofs.data(), values.data(), clip.getNumChannels());
        pose.updateMatrices();
        worst = std::max(worst, differenceInUlps(boundsOf(skin, skinningMatricesOf(pose, skin, binding))));
    }
    EXPECT_GE(frames, 60u);
    std::cout << "grouped against one by one: largest difference " << worst << " units of the last place\n";
    EXPECT_LE(worst, kUlps);
}

TEST(SkinBoundGroups, GiveTheOneByOneBoxBesidePiecesOfMoreJointsAndHoldEveryVertex)
{
    // Random vertices following one to eight random joints (vertex v the first 1 + v % 8 of eight, renormalised by
    // the builder): pieces of every size, the larger ones left to the one-by-one path; random poses.
    const ActorDefinitionPtr definition = makeRandomDefinition(12, 7u);
    SkinSource source = makeRandomSkin(*definition, 2000, 8, 11u);
    for (std::size_t v = 0; v < source.influences.size(); ++v) source.influences[v].resize(1 + v % 8);
    const SkinBuildResult built = source.toBuilder("mixed").build();
    ASSERT_TRUE(built) << built.error;
    const Skin& skin = *built.skin;
    ASSERT_GT(groupablePieces(skin), 0u);
    ASSERT_LT(groupablePieces(skin), skin.getBlendSets().size());
    ASSERT_EQ(skin.getBlendSetGroups().size(), (groupablePieces(skin) + 7) / 8);
    const SkinBinding binding = bindSkinToDefinition(skin, *definition);
    ASSERT_TRUE(binding) << binding.error;
    std::vector<glm::vec3> positions(skin.getNumVertices());
    double worst = 0.0;
    unsigned outside = 0;
    for (std::uint32_t seed = 1; seed <= 50; ++seed)
    {
        const ActorPose pose = makeRandomPose(definition, seed);
        const std::vector<glm::mat4> matrices = skinningMatricesOf(pose, skin, binding);
        const BothBounds both = boundsOf(skin, matrices);
        worst = std::max(worst, differenceInUlps(both));
        SkinningJob skinning;
        skinning.vertices = skin.getVertices();
        skinning.matrices = matrices;
        skinning.positions = positions;
        ASSERT_TRUE(skinning.run());
        for (const glm::vec3& p : positions) outside += contains(both.grouped, p) ? 0 : 1;
    }
    EXPECT_EQ(outside, 0u);
    std::cout << "grouped against one by one: largest difference " << worst << " units of the last place\n";
    EXPECT_LE(worst, kUlps);
}
