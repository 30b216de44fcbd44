#include "SkinTestData"

#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/skin/SkinBinding>
#include <osgActor/core/skin/SkinningJob>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kPi = 3.14159265358979323846;

/** Skins a source with the given method at the pose: positions, normals and tangents in file order. */
struct Skinned
{
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec4> tangents;
};

Skinned skin(const SkinSource& source, const ActorPose& pose, SkinningMethod method)
{
    const SkinBuildResult built = source.toBuilder("test", method).build();
    EXPECT_TRUE(built) << built.error;
    const Skin& skin = *built.skin;
    const SkinBinding binding = bindSkinToDefinition(skin, *pose.getDefinition());
    std::vector<glm::mat4> matrices(skin.getNumJoints());
    std::vector<SkinDualQuaternion> dualQuaternions(skin.getNumJoints());
    SkinningMatricesJob matricesJob;
    matricesJob.modelMatrices = modelMatricesOf(pose);
    matricesJob.definitionJoints = binding.definitionJoints;
    matricesJob.inverseBindMatrices = skin.getInverseBindMatrices();
    matricesJob.bindScale = skin.getBindScale();
    matricesJob.matrices = matrices;
    matricesJob.dualQuaternions = dualQuaternions;
    EXPECT_TRUE(matricesJob.run());

    Skinned out;
    out.positions.resize(skin.getNumVertices());
    out.normals.resize(skin.getNumVertices());
    out.tangents.resize(skin.getNumVertices());
    SkinningJob job;
    job.method = method;
    job.vertices = skin.getVertices();
    job.matrices = matrices;
    job.dualQuaternions = dualQuaternions;
    job.bindScale = static_cast<float>(skin.getBindScale());
    job.positions = out.positions;
    job.normals = out.normals;
    job.tangents = out.tangents;
    EXPECT_TRUE(job.run());
    return out;
}

::testing::AssertionResult matchesReference(const Skinned& skinned, const std::vector<ReferenceVertex>& reference,
                                            double positionTolerance, double vectorTolerance)
{
    for (std::size_t v = 0; v < reference.size(); ++v)
    {
        const double position = glm::length(glm::dvec3(skinned.positions[v]) - reference[v].position);
        const double normal = glm::length(glm::dvec3(skinned.normals[v]) - reference[v].normal);
        const double tangent = glm::length(glm::dvec3(skinned.tangents[v]) - reference[v].tangent);
        if (position > positionTolerance || normal > vectorTolerance || tangent > vectorTolerance)
            return ::testing::AssertionFailure() << "vertex " << v << " is off the reference by " << position
                                                 << " (position), " << normal << " (normal), " << tangent
                                                 << " (tangent)";
    }
    return ::testing::AssertionSuccess();
}

/** The area of the polygon the points make in the XY plane (shoelace formula). */
double areaInXY(const std::vector<glm::dvec3>& ring)
{
    double twiceArea = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i)
    {
        const glm::dvec3& a = ring[i];
        const glm::dvec3& b = ring[(i + 1) % ring.size()];
        twiceArea += a.x * b.y - b.x * a.y;
    }
    return 0.5 * std::abs(twiceArea);
}

} // namespace

class DualQuaternionInfluences : public ::testing::TestWithParam<unsigned>
{
};

TEST_P(DualQuaternionInfluences, MatchesTheReference)
{
    const unsigned influences = GetParam();
    const ActorDefinitionPtr definition = makeRandomDefinition(12, 7);
    const ActorPose pose = makeRandomPose(definition, 13);
    const SkinSource source = makeRandomSkin(*definition, 300, influences, 200 + influences);
    const Skinned skinned = skin(source, pose, SkinningMethod::DualQuaternion);
    const std::vector<ReferenceVertex> reference =
        referenceDualQuaternion(source, referenceSkinningMatrices(pose, source), 1.0);
    EXPECT_TRUE(matchesReference(skinned, reference, 1e-5 * source.diagonal(), 1e-5));
    for (std::size_t v = 0; v < source.tangents.size(); ++v)
        ASSERT_EQ(skinned.tangents[v].w, source.tangents[v].w) << "vertex " << v;
}

INSTANTIATE_TEST_SUITE_P(OneToEight, DualQuaternionInfluences, ::testing::Range(1u, kMaxSkinInfluences + 1));

TEST(DualQuaternionSkinning, AppliesTheSkinsUniformBindScale)
{
    const double scale = 0.01; // the mesh in centimetres, the skeleton in metres
    const ActorDefinitionPtr definition = makeRandomDefinition(10, 4);
    const ActorPose pose = makeRandomPose(definition, 5);
    SkinSource source = makeRandomSkin(*definition, 200, 3, 6, scale);
    for (glm::vec3& p : source.positions) p /= static_cast<float>(scale);
    const Skinned skinned = skin(source, pose, SkinningMethod::DualQuaternion);
    const std::vector<ReferenceVertex> reference =
        referenceDualQuaternion(source, referenceSkinningMatrices(pose, source), scale);
    EXPECT_TRUE(matchesReference(skinned, reference, 1e-5 * scale * source.diagonal(), 1e-5));
}

TEST(DualQuaternionSkinning, EqualsLinearBlendForVerticesThatFollowOneJoint)
{
    const ActorDefinitionPtr definition = makeRandomDefinition(12, 8);
    const ActorPose pose = makeRandomPose(definition, 9);
    const SkinSource source = makeRandomSkin(*definition, 200, 1, 10);
    const Skinned dual = skin(source, pose, SkinningMethod::DualQuaternion);
    const Skinned linear = skin(source, pose, SkinningMethod::LinearBlend);
    const double tolerance = 1e-5 * source.diagonal();
    for (std::size_t v = 0; v < source.positions.size(); ++v)
        ASSERT_LE(glm::length(dual.positions[v] - linear.positions[v]), tolerance) << "vertex " << v;
}

TEST(DualQuaternionSkinning, KeepsACylinderTwistedNinetyDegreesFromCollapsingWhereLinearBlendDoesNot)
{
    // A cylinder of radius 0.1 along +Z from 0 to 1, on two joints: base at the origin and twist at z = 0.5, both
    // turning about Z. A vertex at height z follows twist with weight z and base with weight 1 - z, so the middle
    // ring (z = 0.5) follows each half.
    ActorDefinitionBuilder builder("twister");
    builder.addJoint("base").dofs(dofBit(Dof::RZ));
    builder.addJoint("twist", "base").offset(0, 0, 0.5).dofs(dofBit(Dof::RZ));
    const ActorDefinitionPtr definition = builder.build().definition;

    const unsigned rings = 11, sides = 32, middle = 5;
    const double radius = 0.1;
    SkinSource source;
    source.jointNames = {"base", "twist"};
    source.inverseBindMatrices = {glm::dmat4(1.0), glm::dmat4(1.0)};
    source.inverseBindMatrices[1][3][2] = -0.5; // the inverse of twist's rest matrix T(0, 0, 0.5)
    std::vector<glm::dvec3> bindRing;
    for (unsigned ring = 0; ring < rings; ++ring)
    {
        const double z = (ring + 0.5) / rings;
        for (unsigned k = 0; k < sides; ++k)
        {
            const double theta = 2.0 * kPi * k / sides;
            const glm::dvec3 outward(std::cos(theta), std::sin(theta), 0.0);
            source.positions.push_back(glm::vec3(radius * outward + glm::dvec3(0, 0, z)));
            source.normals.push_back(glm::vec3(outward));
            source.tangents.push_back(glm::vec4(0, 0, 1, 1));
            source.influences.push_back({{0u, 1.0 - z}, {1u, z}});
            if (ring == middle) bindRing.push_back(glm::dvec3(source.positions.back()));
        }
    }
    ASSERT_DOUBLE_EQ((middle + 0.5) / rings, 0.5);

    ActorPose pose(definition);
    pose.setDof(static_cast<unsigned>(definition->getDofIndex(1, Dof::RZ)), kPi / 2);
    pose.updateMatrices();
    const double bindArea = areaInXY(bindRing);
    double area[2];
    const SkinningMethod methods[2] = {SkinningMethod::DualQuaternion, SkinningMethod::LinearBlend};
    for (int m = 0; m < 2; ++m)
    {
        const Skinned skinned = skin(source, pose, methods[m]);
        std::vector<glm::dvec3> ring;
        for (unsigned k = 0; k < sides; ++k) ring.push_back(glm::dvec3(skinned.positions[middle * sides + k]));
        area[m] = areaInXY(ring) / bindArea;
    }
    RecordProperty("dual_quaternion_area_ratio", std::to_string(area[0]));
    RecordProperty("linear_blend_area_ratio", std::to_string(area[1]));
    EXPECT_GE(area[0], 0.95);
    // Linear blend averages the ring with itself turned 90 degrees: radius times cos 45 degrees, half the area.
    EXPECT_NEAR(area[1], 0.5, 1e-3);
    EXPECT_LT(area[1], area[0]);
}
