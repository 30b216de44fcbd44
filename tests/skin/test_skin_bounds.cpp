#include "SkinTestData"

#include <osgActor/core/skin/SkinBinding>
#include <osgActor/core/skin/SkinBoundsJob>
#include <osgActor/core/skin/SkinningJob>
#include <osgActor/mocap/AmcReader>
#include <osgActor/mocap/BvhReader>

#include <glm/ext/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <tuple>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

double volumeOf(const SkinBox& box)
{
    const glm::dvec3 size = glm::dvec3(box.max) - glm::dvec3(box.min);
    return size.x * size.y * size.z;
}

bool contains(const SkinBox& box, const glm::vec3& p)
{
    return p.x >= box.min.x && p.y >= box.min.y && p.z >= box.min.z && p.x <= box.max.x && p.y <= box.max.y &&
           p.z <= box.max.z;
}

/** A motion-capture clip with its skeleton. */
MocapImport loadClip(const std::string& name)
{
    const std::string mocap = OSGACTOR_TEST_MOCAP_DIR;
    if (name == "12_03.bvh") return readBvhFile(mocap + "/bvh/12_03.bvh");
    const AsfImport skeleton = readAsfFile(mocap + "/asfamc/charleston.asf");
    return readAmcFile(mocap + "/asfamc/charleston1.amc", skeleton);
}

} // namespace

// --- invalid jobs first ---

TEST(SkinBoundsJob, RefusesAMissingBoundAndGivesAnEmptyBoxForNoPiece)
{
    std::vector<glm::mat4> matrices(2);
    SkinBox bound;
    SkinBoundsJob job;
    job.matrices = matrices;
    EXPECT_FALSE(job.validate());
    EXPECT_FALSE(job.run());
    job.bound = &bound;
    EXPECT_TRUE(job.run());
    EXPECT_TRUE(bound.isEmpty()); // no piece, no vertex
}

TEST(SkinBoundsJob, RefusesPiecesNamingJointsOrWeightsOutOfRangeOrTooManyJoints)
{
    std::vector<glm::mat4> matrices(3);
    std::vector<SkinBlendSet> sets(1);
    std::vector<std::uint32_t> setJoints{0, 2};
    std::vector<float> setWeights{0.6f, 0.4f};
    SkinBox bound;
    SkinBoundsJob job;
    job.method = SkinningMethod::DualQuaternion;
    job.matrices = matrices;
    job.blendSets = sets;
    job.blendSetJoints = setJoints;
    job.blendSetWeights = setWeights;
    job.bound = &bound;
    sets[0].numJoints = 2;
    EXPECT_TRUE(job.validate());
    setJoints[1] = 3; // no such joint
    EXPECT_FALSE(job.validate());
    setJoints[1] = 2;
    sets[0].numJoints = 3; // past the end of the joint list
    EXPECT_FALSE(job.validate());
    sets[0].numJoints = 2;
    job.blendSetWeights = Span<const float>(setWeights.data(), 1); // a weight short
    EXPECT_FALSE(job.validate());
    job.blendSetWeights = setWeights;
    std::vector<std::uint32_t> nineJoints(9, 0);
    std::vector<float> nineWeights(9, 1.0f / 9.0f);
    job.blendSetJoints = nineJoints;
    job.blendSetWeights = nineWeights;
    sets[0].numJoints = 9; // more joints than a vertex may follow
    EXPECT_FALSE(job.validate());
    sets[0].numJoints = 8;
    EXPECT_TRUE(job.validate());
}

// --- what it computes ---

TEST(SkinBoundsJob, MovesAJointsBoxByItsMatrixAsDerivedByHand)
{
    // One joint over the box [0, 2] x [0, 1] x [0, 0.5] (its eight corners as vertices); the joint turns 90 degrees
    // about Z and moves by (10, 0, 0): (x, y, z) -> (10 - y, x, z), so the box becomes [9, 10] x [0, 2] x [0, 0.5].
    SkinBuilder builder("brick");
    builder.addJoint("only");
    for (int corner = 0; corner < 8; ++corner)
    {
        builder.addVertex(glm::vec3(corner & 1 ? 2.0f : 0.0f, corner & 2 ? 1.0f : 0.0f, corner & 4 ? 0.5f : 0.0f));
        builder.addInfluence(corner, 0, 1.0f);
    }
    const SkinBuildResult built = builder.build();
    ASSERT_TRUE(built) << built.error;
    const std::vector<glm::mat4> matrices{glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)) *
                                          glm::rotate(glm::mat4(1.0f), glm::radians(90.0f), glm::vec3(0, 0, 1))};
    SkinBox bound;
    SkinBoundsJob job = makeSkinBoundsJob(*built.skin);
    job.matrices = matrices;
    job.bound = &bound;
    ASSERT_TRUE(job.run());
    const float margin = 1e-3f;
    EXPECT_NEAR(bound.min.x, 9.0f, margin);
    EXPECT_NEAR(bound.max.x, 10.0f, margin);
    EXPECT_NEAR(bound.min.y, 0.0f, margin);
    EXPECT_NEAR(bound.max.y, 2.0f, margin);
    EXPECT_NEAR(bound.min.z, 0.0f, margin);
    EXPECT_NEAR(bound.max.z, 0.5f, margin);
    EXPECT_LE(bound.min.x, 9.0f);
    EXPECT_GE(bound.max.y, 2.0f);
}

TEST(SkinBoundsJob, BoxesEachJointInTheFrameWhereItsVerticesFitTightest)
{
    // A thin rod along the diagonal (1, 1, 1): its bind-space box is a cube, its principal-axes box a thin prism.
    SkinBuilder builder("rod");
    builder.addJoint("only");
    for (int i = 0; i <= 20; ++i)
        for (int side = 0; side < 4; ++side)
        {
            const float t = i / 20.0f;
            const glm::vec3 offset = 0.01f * (side & 1 ? glm::vec3(1, -1, 0) : glm::vec3(1, 1, -2)) * (side & 2 ? 1.0f : -1.0f);
            builder.addVertex(glm::vec3(t) + offset);
            builder.addInfluence(static_cast<unsigned>(i * 4 + side), 0, 1.0f);
        }
    const SkinBuildResult built = builder.build();
    ASSERT_TRUE(built) << built.error;
    const SkinJointBox& joint = built.skin->getJointBoxes()[0];
    const glm::vec3 size = joint.box.max - joint.box.min;
    const SkinBox& bindBox = built.skin->getBindBox();
    const glm::vec3 bindSize = bindBox.max - bindBox.min;
    EXPECT_LT(size.x * size.y * size.z, 0.01f * bindSize.x * bindSize.y * bindSize.z);
}

TEST(SkinBoundsJob, CutsASkinIntoAtMostEightPiecesPerJointWhateverItsVertexCount)
{
    // Scattered vertices with random weights on three joints: the worst case for pieces (every split would help).
    for (const unsigned numVertices : {300u, 30000u})
    {
        SkinBuilder builder("scattered");
        for (const char* name : {"a", "b", "c"}) builder.addJoint(name);
        std::uint32_t state = 12345u;
        const auto next = [&state]() { return (state = state * 1664525u + 1013904223u) / 4294967296.0f; };
        for (unsigned v = 0; v < numVertices; ++v)
        {
            builder.addVertex(glm::vec3(next(), next(), next()));
            for (unsigned j = 0; j < 3; ++j) builder.addInfluence(v, j, 0.05f + next());
        }
        const SkinBuildResult built = builder.build();
        ASSERT_TRUE(built) << built.error;
        const std::size_t pieces = built.skin->getBlendSets().size();
        EXPECT_GE(pieces, 3u) << numVertices << " vertices"; // a set per joint that is some vertex's largest
        EXPECT_LE(pieces, 24u) << numVertices << " vertices";
    }
}

class SkinBoundsOnAClip : public ::testing::TestWithParam<std::tuple<std::string, SkinningMethod>>
{
};

TEST_P(SkinBoundsOnAClip, HoldEveryVertexOnEveryFrameAndStayClose)
{
    const std::string clipName = std::get<0>(GetParam());
    const SkinningMethod method = std::get<1>(GetParam());
    const bool dualQuaternions = method == SkinningMethod::DualQuaternion;
    const MocapImport motion = loadClip(clipName);
    ASSERT_TRUE(motion) << motion.error;
    ASSERT_TRUE(motion.clip && motion.clip->isUniform());
    const ActorDefinition& definition = *motion.definition;
    ASSERT_EQ(motion.clip->getNumChannels(), definition.getNumDofs());

    // Tubes around the bones longer than a tenth of the longest one.
    ActorPose pose(motion.definition);
    pose.updateMatrices();
    double longest = 0.0;
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
        longest = std::max(longest, glm::length(definition.getOffsetTranslation(j)));
    const SkinSource source = makeTubeSkin(definition, 8, 12, 0.15, 0.1 * longest);
    const SkinBuildResult built = source.toBuilder("tubes", method).build();
    ASSERT_TRUE(built) << built.error;
    const Skin& skin = *built.skin;
    ASSERT_GT(skin.getNumVertices(), 1000u);
    const SkinBinding binding = bindSkinToDefinition(skin, definition);
    ASSERT_TRUE(binding) << binding.error;

    std::vector<glm::mat4> matrices(skin.getNumJoints());
    std::vector<SkinDualQuaternion> dualQuaternionsOfJoints(skin.getNumJoints());
    std::vector<glm::vec3> positions(skin.getNumVertices());
    std::vector<double> ratios;
    unsigned outside = 0;
    for (unsigned frame = 0; frame < motion.clip->getNumFrames(); ++frame)
    {
        ASSERT_TRUE(succeeded(pose.setDofs(motion.clip->getFrame(frame), definition.getNumDofs())));
        pose.updateMatrices();
        SkinningMatricesJob matricesJob;
        matricesJob.modelMatrices = modelMatricesOf(pose);
        matricesJob.definitionJoints = binding.definitionJoints;
        matricesJob.inverseBindMatrices = skin.getInverseBindMatrices();
        matricesJob.matrices = matrices;
        if (dualQuaternions) matricesJob.dualQuaternions = dualQuaternionsOfJoints;
        ASSERT_TRUE(matricesJob.run());
        SkinningJob skinning;
        skinning.method = method;
        skinning.vertices = skin.getVertices();
        skinning.matrices = matrices;
        skinning.dualQuaternions = dualQuaternionsOfJoints;
        skinning.positions = positions;
        ASSERT_TRUE(skinning.run());
        SkinBox bound;
        SkinBoundsJob bounds = makeSkinBoundsJob(skin);
        bounds.matrices = matrices;
        bounds.bound = &bound;
        ASSERT_TRUE(bounds.run());

        SkinBox exact;
        exact.min = exact.max = positions[0];
        for (const glm::vec3& p : positions)
        {
            exact.min = glm::min(exact.min, p);
            exact.max = glm::max(exact.max, p);
            if (!contains(bound, p)) ++outside;
        }
        ratios.push_back(volumeOf(bound) / volumeOf(exact));
    }
    EXPECT_EQ(outside, 0u) << "skinned vertices outside the bound, over all frames";

    std::vector<double> sorted(ratios);
    std::sort(sorted.begin(), sorted.end());
    const auto at = [&](double fraction) { return sorted[static_cast<std::size_t>(fraction * (sorted.size() - 1))]; };
    const double within = static_cast<double>(std::count_if(ratios.begin(), ratios.end(), [](double r) { return r <= 1.5; })) /
                          ratios.size();
    std::ostringstream distribution;
    distribution << clipName << (dualQuaternions ? ", dual quaternions" : ", linear blend") << ": " << ratios.size() << " frames, " << skin.getNumVertices()
                 << " vertices; bound volume / exact box volume: min " << sorted.front() << ", median " << at(0.5)
                 << ", 95th percentile " << at(0.95) << ", max " << sorted.back() << "; " << 100.0 * within
                 << "% of frames <= 1.5";
    std::cout << distribution.str() << "\n";
    RecordProperty("bound_volume_ratio", distribution.str());
    EXPECT_GE(sorted.front(), 1.0 - 1e-6); // a bound never smaller than the mesh
    EXPECT_GE(within, 0.95);
}

INSTANTIATE_TEST_SUITE_P(
    MotionCapture, SkinBoundsOnAClip,
    ::testing::Combine(::testing::Values("12_03.bvh", "charleston1.amc"),
                       ::testing::Values(SkinningMethod::LinearBlend, SkinningMethod::DualQuaternion)),
    [](const ::testing::TestParamInfo<std::tuple<std::string, SkinningMethod>>& info) {
        return std::string(std::get<0>(info.param) == "12_03.bvh" ? "Cmu12_03Bvh" : "CharlestonAmc") +
               (std::get<1>(info.param) == SkinningMethod::DualQuaternion ? "DualQuaternions" : "LinearBlend");
    });
