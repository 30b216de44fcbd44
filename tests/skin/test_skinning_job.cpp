#include "SkinTestData"

#include <osgActor/core/detail/WorkerPool>
#include <osgActor/core/skin/SkinBinding>
#include <osgActor/core/skin/SkinningJob>

#include <glm/ext/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** A skin built from a source, bound to a definition and posed: everything a SkinningJob needs, and its outputs. */
struct PosedSkin
{
    SkinSource source;
    SkinPtr skin;
    std::vector<glm::mat4> matrices;
    std::vector<glm::mat4> normalMatrices;
    std::vector<SkinDualQuaternion> dualQuaternions;
    std::vector<glm::dmat4> reference; // model x inverseBind, multiplied by the test
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> tangents;

    PosedSkin(SkinSource skinSource, const ActorPose& pose, SkinningMethod method = SkinningMethod::LinearBlend)
        : source(std::move(skinSource))
    {
        const SkinBuildResult built = source.toBuilder("test", method).build();
        EXPECT_TRUE(built) << built.error;
        skin = built.skin;
        const SkinBinding binding = bindSkinToDefinition(*skin, *pose.getDefinition());
        EXPECT_TRUE(binding) << binding.error;
        const std::size_t numJoints = skin->getNumJoints();
        matrices.resize(numJoints);
        normalMatrices.resize(numJoints);
        dualQuaternions.resize(numJoints);
        SkinningMatricesJob matricesJob;
        matricesJob.modelMatrices = modelMatricesOf(pose);
        matricesJob.definitionJoints = binding.definitionJoints;
        matricesJob.inverseBindMatrices = skin->getInverseBindMatrices();
        matricesJob.bindScale = skin->getBindScale();
        matricesJob.matrices = matrices;
        matricesJob.normalMatrices = normalMatrices;
        matricesJob.dualQuaternions = dualQuaternions;
        EXPECT_TRUE(matricesJob.run());
        reference = referenceSkinningMatrices(pose, source);
        positions.assign(skin->getNumVertices(), glm::vec3(std::nanf("")));
        normals.assign(skin->getNumVertices(), glm::vec3(std::nanf("")));
        tangents.assign(skin->getNumVertices(), glm::vec4(std::nanf("")));
    }

    /** A job over every vertex, writing every output. */
    SkinningJob job(SkinningMethod method = SkinningMethod::LinearBlend)
    {
        SkinningJob job;
        job.method = method;
        job.vertices = skin->getVertices();
        job.matrices = matrices;
        job.dualQuaternions = dualQuaternions;
        job.bindScale = static_cast<float>(skin->getBindScale());
        job.positions = positions;
        job.normals = normals;
        job.tangents = tangents;
        return job;
    }
};

::testing::AssertionResult near(const glm::vec3& actual, const glm::dvec3& expected, double tolerance,
                                const char* what, std::size_t vertex)
{
    const glm::dvec3 error = glm::abs(glm::dvec3(actual) - expected);
    if (std::max({error.x, error.y, error.z}) <= tolerance) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << what << " of vertex " << vertex << " is (" << actual.x << ", "
                                         << actual.y << ", " << actual.z << "), the reference (" << expected.x << ", "
                                         << expected.y << ", " << expected.z << ")";
}

/** Every output of every vertex within tolerance of the reference (positions within positionTolerance, unit
  * vectors within vectorTolerance); outputs left empty are skipped. */
::testing::AssertionResult matchesReference(const PosedSkin& posed, const std::vector<ReferenceVertex>& reference,
                                            double positionTolerance, double vectorTolerance, bool checkNormals = true,
                                            bool checkTangents = true)
{
    for (std::size_t v = 0; v < reference.size(); ++v)
    {
        ::testing::AssertionResult result =
            near(posed.positions[v], reference[v].position, positionTolerance, "position", v);
        if (result && checkNormals) result = near(posed.normals[v], reference[v].normal, vectorTolerance, "normal", v);
        if (result && checkTangents)
        {
            result = near(glm::vec3(posed.tangents[v]), reference[v].tangent, vectorTolerance, "tangent", v);
            if (result && posed.tangents[v].w != posed.source.tangents[v].w)
                result = ::testing::AssertionFailure() << "tangent handedness of vertex " << v << " changed";
        }
        if (!result) return result;
    }
    return ::testing::AssertionSuccess();
}

struct RandomCase
{
    ActorDefinitionPtr definition = makeRandomDefinition(12, 7);
    ActorPose pose = makeRandomPose(definition, 11);
};

} // namespace

// --- invalid jobs first ---

TEST(SkinningJob, RefusesAJobWithoutPositionOutput)
{
    RandomCase c;
    PosedSkin posed(makeRandomSkin(*c.definition, 20, 2, 1), c.pose);
    SkinningJob job = posed.job();
    job.positions = Span<glm::vec3>();
    EXPECT_FALSE(job.validate());
    EXPECT_FALSE(job.run());
}

TEST(SkinningJob, RefusesInconsistentVertexSpans)
{
    RandomCase c;
    PosedSkin posed(makeRandomSkin(*c.definition, 20, 2, 1), c.pose);
    SkinningJob countsOff = posed.job();
    countsOff.vertices.counts[1] -= 1;
    EXPECT_FALSE(countsOff.validate());

    SkinningJob shortJoints = posed.job();
    shortJoints.vertices.joints = shortJoints.vertices.joints.subspan(0, shortJoints.vertices.joints.size() - 1);
    EXPECT_FALSE(shortJoints.validate());

    SkinningJob shortNormals = posed.job();
    shortNormals.vertices.normals = shortNormals.vertices.normals.subspan(0, 19);
    EXPECT_FALSE(shortNormals.validate());
}

TEST(SkinningJob, RefusesAJointIndexBeyondTheMatrices)
{
    RandomCase c;
    PosedSkin posed(makeRandomSkin(*c.definition, 20, 3, 1), c.pose);
    SkinningJob job = posed.job();
    // Fewer matrices than the skin's joints: some vertex names a joint with no matrix.
    job.matrices = Span<const glm::mat4>(posed.matrices.data(), 2);
    EXPECT_FALSE(job.validate());
    EXPECT_FALSE(job.run());
    EXPECT_TRUE(std::isnan(posed.positions[0].x)) << "a refused job wrote its outputs";
}

TEST(SkinningJob, RefusesOutputsSmallerThanTheOutputIndices)
{
    RandomCase c;
    PosedSkin posed(makeRandomSkin(*c.definition, 20, 2, 1), c.pose);
    SkinningJob job = posed.job();
    job.normals = job.normals.subspan(0, 19);
    EXPECT_FALSE(job.validate());
}

TEST(SkinningJob, RefusesAnOutputWithoutItsInput)
{
    RandomCase c;
    SkinSource bare = makeRandomSkin(*c.definition, 20, 2, 1);
    bare.normals.clear();
    bare.tangents.clear();
    PosedSkin posed(bare, c.pose);
    SkinningJob normals = posed.job();
    normals.tangents = Span<glm::vec4>();
    EXPECT_FALSE(normals.validate()); // normals asked for, none in the skin
    normals.normals = Span<glm::vec3>();
    EXPECT_TRUE(normals.validate());

    PosedSkin full(makeRandomSkin(*c.definition, 20, 2, 1), c.pose);
    SkinningJob tangentsAlone = full.job();
    tangentsAlone.normals = Span<glm::vec3>();
    EXPECT_FALSE(tangentsAlone.validate()); // tangents need normals
}

TEST(SkinningJob, RefusesNormalMatricesOfAnotherSize)
{
    RandomCase c;
    PosedSkin posed(makeRandomSkin(*c.definition, 20, 2, 1), c.pose);
    SkinningJob job = posed.job();
    job.normalMatrices = Span<const glm::mat4>(posed.normalMatrices.data(), 3);
    EXPECT_FALSE(job.validate());
}

TEST(SkinningJob, RefusesDualQuaternionSkinningWithoutDualQuaternionsOrScale)
{
    RandomCase c;
    PosedSkin posed(makeRandomSkin(*c.definition, 20, 2, 1), c.pose, SkinningMethod::DualQuaternion);
    SkinningJob missing = posed.job(SkinningMethod::DualQuaternion);
    missing.dualQuaternions = Span<const SkinDualQuaternion>();
    EXPECT_FALSE(missing.validate());
    SkinningJob zeroScale = posed.job(SkinningMethod::DualQuaternion);
    zeroScale.bindScale = 0.0f;
    EXPECT_FALSE(zeroScale.validate());
    SkinningJob nanScale = posed.job(SkinningMethod::DualQuaternion);
    nanScale.bindScale = std::nanf("");
    EXPECT_FALSE(nanScale.validate());
}

// --- linear blend skinning against the double-precision reference ---

class SkinningJobInfluences : public ::testing::TestWithParam<unsigned>
{
};

TEST_P(SkinningJobInfluences, MatchesTheReferenceForPositionsNormalsAndTangents)
{
    const unsigned influences = GetParam();
    RandomCase c;
    PosedSkin posed(makeRandomSkin(*c.definition, 300, influences, 100 + influences), c.pose);
    ASSERT_EQ(posed.skin->getVertices().counts[influences - 1], 300u);
    const double tolerance = 1e-5 * posed.source.diagonal();
    const std::vector<ReferenceVertex> reference = referenceLinearBlend(posed.source, posed.reference);

    ASSERT_TRUE(posed.job().run());
    EXPECT_TRUE(matchesReference(posed, reference, tolerance, 1e-5));

    // The positions-only and positions-and-normals loops too.
    std::fill(posed.positions.begin(), posed.positions.end(), glm::vec3(std::nanf("")));
    std::fill(posed.normals.begin(), posed.normals.end(), glm::vec3(std::nanf("")));
    SkinningJob withNormals = posed.job();
    withNormals.tangents = Span<glm::vec4>();
    ASSERT_TRUE(withNormals.run());
    EXPECT_TRUE(matchesReference(posed, reference, tolerance, 1e-5, true, false));

    std::fill(posed.positions.begin(), posed.positions.end(), glm::vec3(std::nanf("")));
    SkinningJob positionsOnly = posed.job();
    positionsOnly.normals = Span<glm::vec3>();
    positionsOnly.tangents = Span<glm::vec4>();
    ASSERT_TRUE(positionsOnly.run());
    EXPECT_TRUE(matchesReference(posed, reference, tolerance, 1e-5, false, false));
}

INSTANTIATE_TEST_SUITE_P(OneToEight, SkinningJobInfluences, ::testing::Range(1u, kMaxSkinInfluences + 1));

TEST(SkinningJob, MatchesTheReferenceOnASkinWithEveryInfluenceCount)
{
    RandomCase c;
    // Vertices with 1 to 8 influences mixed in file order: outputs must land at their file index.
    SkinSource source = makeRandomSkin(*c.definition, 40, 8, 5);
    for (std::size_t v = 0; v < source.influences.size(); ++v)
    {
        auto& influences = source.influences[v];
        influences.resize(1 + v % kMaxSkinInfluences);
        double sum = 0.0;
        for (const auto& influence : influences) sum += influence.second;
        for (auto& influence : influences) influence.second /= sum;
    }
    PosedSkin posed(source, c.pose);
    for (unsigned k = 0; k < kMaxSkinInfluences; ++k) EXPECT_EQ(posed.skin->getVertices().counts[k], 5u);
    ASSERT_TRUE(posed.job().run());
    EXPECT_TRUE(matchesReference(posed, referenceLinearBlend(posed.source, posed.reference),
                                 1e-5 * posed.source.diagonal(), 1e-5));
}

TEST(SkinningJob, MovesNormalsByTheInverseTransposeWhenGivenNormalMatrices)
{
    RandomCase c;
    SkinSource source = makeRandomSkin(*c.definition, 200, 3, 9);
    // The mesh was modelled stretched: each joint's inverse bind matrix scales non-uniformly first.
    for (glm::dmat4& inverseBind : source.inverseBindMatrices)
        inverseBind = inverseBind * glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 2.5, 0.4));
    PosedSkin posed(source, c.pose);
    ASSERT_EQ(posed.skin->getNormalTransform(), NormalTransform::InverseTranspose);
    SkinningJob job = posed.job();
    job.normalMatrices = posed.normalMatrices;
    ASSERT_TRUE(job.run());
    const std::vector<ReferenceVertex> reference = referenceLinearBlend(posed.source, posed.reference, true);
    // The normal matrices' entries reach 1 / 0.4: a tolerance of that many times 1e-5.
    EXPECT_TRUE(matchesReference(posed, reference, 1e-5 * posed.source.diagonal(), 2.5e-5));
}

// --- poses with known results ---

TEST(SkinningJob, ReproducesTheBindPoseAtTheRestPose)
{
    const ActorDefinitionPtr definition = makeRandomDefinition(16, 3);
    ActorPose rest(definition);
    rest.updateMatrices();
    PosedSkin posed(makeTubeSkin(*definition, 6, 8, 0.2, 0.01), rest);
    ASSERT_GT(posed.skin->getNumVertices(), 100u);
    ASSERT_TRUE(posed.job().run());
    const double tolerance = 1e-6 * posed.source.diagonal();
    for (std::size_t v = 0; v < posed.positions.size(); ++v)
    {
        ASSERT_TRUE(near(posed.positions[v], glm::dvec3(posed.source.positions[v]), tolerance, "position", v));
        ASSERT_TRUE(near(posed.normals[v], glm::dvec3(posed.source.normals[v]), 1e-6, "normal", v));
        ASSERT_TRUE(near(glm::vec3(posed.tangents[v]), glm::dvec3(posed.source.tangents[v]), 1e-6, "tangent", v));
    }
}

// --- splitting a skin between threads ---

TEST(SkinningJob, GivesTheSameOutputsSplitIntoRangesAsInOneRun)
{
    RandomCase c;
    SkinSource source = makeRandomSkin(*c.definition, 257, 8, 21);
    for (std::size_t v = 0; v < source.influences.size(); ++v) source.influences[v].resize(1 + v % 4);
    PosedSkin whole(source, c.pose);
    ASSERT_TRUE(whole.job().run());

    PosedSkin pieces(source, c.pose);
    const SkinVertices all = pieces.skin->getVertices();
    for (std::size_t first = 0; first < all.size(); first += 37)
    {
        SkinningJob piece = pieces.job();
        piece.vertices = all.subrange(first, std::min<std::size_t>(37, all.size() - first));
        ASSERT_TRUE(piece.run());
    }
    for (std::size_t v = 0; v < all.size(); ++v)
    {
        ASSERT_EQ(pieces.positions[v], whole.positions[v]) << "vertex " << v;
        ASSERT_EQ(pieces.normals[v], whole.normals[v]) << "vertex " << v;
        ASSERT_EQ(pieces.tangents[v], whole.tangents[v]) << "vertex " << v;
    }
}

TEST(SkinningJob, GivesTheSameOutputsRunOnAWorkerPool)
{
    RandomCase c;
    SkinSource source = makeRandomSkin(*c.definition, 5000, 8, 22);
    for (std::size_t v = 0; v < source.influences.size(); ++v) source.influences[v].resize(1 + (v * 7) % 8);
    PosedSkin single(source, c.pose);
    ASSERT_TRUE(single.job().run());

    PosedSkin threaded(source, c.pose);
    WorkerPool pool(4);
    const SkinVertices all = threaded.skin->getVertices();
    const unsigned chunk = 256;
    const unsigned numChunks = static_cast<unsigned>((all.size() + chunk - 1) / chunk);
    std::vector<char> succeeded(numChunks, 0);
    pool.parallelFor(numChunks, [&](unsigned i) {
        SkinningJob piece = threaded.job();
        const std::size_t first = std::size_t(i) * chunk;
        piece.vertices = all.subrange(first, std::min<std::size_t>(chunk, all.size() - first));
        succeeded[i] = piece.run() ? 1 : 0;
    }, 1);
    EXPECT_EQ(std::count(succeeded.begin(), succeeded.end(), 1), static_cast<long>(numChunks));
    for (std::size_t v = 0; v < all.size(); ++v)
    {
        ASSERT_EQ(threaded.positions[v], single.positions[v]) << "vertex " << v;
        ASSERT_EQ(threaded.normals[v], single.normals[v]) << "vertex " << v;
        ASSERT_EQ(threaded.tangents[v], single.tangents[v]) << "vertex " << v;
    }
}
