#include "SkinTestData"
#include "TestMath"

#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/skin/SkinBinding>
#include <osgActor/core/skin/SkinningMatricesJob>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace osgActor;
using osgActor::test::fromRows;
using osgActor::test::matricesNear;

namespace {

const double kPi = 3.14159265358979323846;

/** hip at the origin turning about Z, knee 0.5 below it turning about X: a leg whose matrices are easy by hand. */
ActorDefinitionPtr makeLeg()
{
    ActorDefinitionBuilder builder("leg");
    builder.addJoint("hip").dofs(dofBit(Dof::RZ));
    builder.addJoint("knee", "hip").offset(0, 0, -0.5).dofs(dofBit(Dof::RX));
    return builder.build().definition;
}

struct Fixture
{
    std::vector<glm::dmat4> model{glm::dmat4(1.0), glm::dmat4(1.0)};
    std::vector<std::uint32_t> definitionJoints{0, 1};
    std::vector<glm::dmat4> inverseBinds{glm::dmat4(1.0), glm::dmat4(1.0)};
    std::vector<glm::dmat4> doubles = std::vector<glm::dmat4>(2);
    std::vector<glm::mat4> floats = std::vector<glm::mat4>(2);

    SkinningMatricesJob job()
    {
        SkinningMatricesJob job;
        job.modelMatrices = model;
        job.definitionJoints = definitionJoints;
        job.inverseBindMatrices = inverseBinds;
        job.matricesDouble = doubles;
        job.matrices = floats;
        return job;
    }
};

} // namespace

// --- invalid jobs first ---

TEST(SkinningMatricesJob, RefusesADefinitionJointOutOfRange)
{
    Fixture f;
    f.definitionJoints[1] = 2;
    EXPECT_FALSE(f.job().validate());
    EXPECT_FALSE(f.job().run());
}

TEST(SkinningMatricesJob, RefusesSpansOfDifferentSizes)
{
    Fixture f;
    SkinningMatricesJob fewerInverseBinds = f.job();
    fewerInverseBinds.inverseBindMatrices = Span<const glm::dmat4>(f.inverseBinds.data(), 1);
    EXPECT_FALSE(fewerInverseBinds.validate());

    SkinningMatricesJob shortOutput = f.job();
    shortOutput.matrices = Span<glm::mat4>(f.floats.data(), 1);
    EXPECT_FALSE(shortOutput.validate());
}

TEST(SkinningMatricesJob, RefusesAJobWithNoOutput)
{
    Fixture f;
    SkinningMatricesJob job = f.job();
    job.matrices = Span<glm::mat4>();
    job.matricesDouble = Span<glm::dmat4>();
    EXPECT_FALSE(job.validate());
}

TEST(SkinningMatricesJob, RefusesANonPositiveBindScaleForDualQuaternions)
{
    Fixture f;
    std::vector<SkinDualQuaternion> dualQuaternions(2);
    SkinningMatricesJob job = f.job();
    job.dualQuaternions = dualQuaternions;
    job.bindScale = 0.0;
    EXPECT_FALSE(job.validate());
    job.bindScale = 1.0;
    EXPECT_TRUE(job.validate());
}

// --- what it computes ---

TEST(SkinningMatricesJob, GivesModelTimesInverseBindAsDerivedByHand)
{
    const ActorDefinitionPtr leg = makeLeg();
    ActorPose pose(leg);
    pose.setDof(static_cast<unsigned>(leg->getDofIndex(0, Dof::RZ)), kPi / 2);
    pose.setDof(static_cast<unsigned>(leg->getDofIndex(1, Dof::RX)), kPi / 2);
    pose.updateMatrices();

    // Bind pose: the rest pose, so the inverse bind matrices are the rest model matrices' inverses: identity for
    // the hip, T(0, 0, 0.5) for the knee.
    SkinBuilder builder("leg skin");
    builder.addJoint("knee", glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 0.5)));
    builder.addJoint("hip");
    builder.addVertex(glm::vec3(0.0f));
    builder.addInfluence(0, 0, 1.0f);
    const SkinPtr skin = builder.build().skin;
    const SkinBinding binding = bindSkinToDefinition(*skin, *leg);
    ASSERT_TRUE(binding) << binding.error;

    std::vector<glm::dmat4> doubles(2);
    std::vector<glm::mat4> floats(2);
    SkinningMatricesJob job;
    job.modelMatrices = modelMatricesOf(pose);
    job.definitionJoints = binding.definitionJoints;
    job.inverseBindMatrices = skin->getInverseBindMatrices();
    job.matricesDouble = doubles;
    job.matrices = floats;
    ASSERT_TRUE(job.run());

    // hip: Rz(90): x -> y, y -> -x.
    EXPECT_TRUE(matricesNear(doubles[1], fromRows(0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0)));
    // knee: Rz(90) T(0,0,-0.5) Rx(90) T(0,0,0.5). Rx(90): y -> z, z -> -y, so Rx(90) T(0,0,0.5) maps p to
    // (x, -z - 0.5, y); then T(0,0,-0.5) gives (x, -z - 0.5, y - 0.5); then Rz(90) gives (z + 0.5, x, y - 0.5).
    EXPECT_TRUE(matricesNear(doubles[0], fromRows(0, 0, 1, 0.5, 1, 0, 0, 0, 0, 1, 0, -0.5)));
    for (int j = 0; j < 2; ++j)
        EXPECT_TRUE(matricesNear(glm::dmat4(floats[j]), doubles[j], 1e-7));
}

TEST(SkinningMatricesJob, GivesNormalMatricesThatKeepNormalsPerpendicularUnderStretch)
{
    Fixture f;
    f.model[1] = glm::rotate(glm::dmat4(1.0), 0.7, glm::normalize(glm::dvec3(1, 2, 3)));
    f.inverseBinds[1] = glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 3.0, 0.5));
    std::vector<glm::mat4> normalMatrices(2);
    SkinningMatricesJob job = f.job();
    job.normalMatrices = normalMatrices;
    ASSERT_TRUE(job.run());
    // A surface tangent t and its normal n: the moved tangent (linear part) stays perpendicular to the moved normal.
    const glm::dvec3 t = glm::normalize(glm::dvec3(1, 1, 0));
    const glm::dvec3 n = glm::normalize(glm::dvec3(1, -1, 0.5));
    ASSERT_NEAR(glm::dot(t, n), 0.0, 1e-12);
    const glm::dvec3 movedT = glm::dmat3(f.doubles[1]) * t;
    const glm::dvec3 movedN = glm::dmat3(glm::dmat4(normalMatrices[1])) * n;
    EXPECT_NEAR(glm::dot(movedT, movedN), 0.0, 1e-6);
    EXPECT_GT(std::abs(glm::dot(movedT, glm::dmat3(f.doubles[1]) * n)), 0.1); // the linear part alone would not
    EXPECT_EQ(normalMatrices[1][3], glm::vec4(0, 0, 0, 1));
}

TEST(SkinningMatricesJob, GivesDualQuaternionsThatMoveBindPointsAsTheMatrixDoes)
{
    Fixture f;
    const double scale = 0.01; // the mesh modelled in centimetres
    f.model[0] = glm::translate(glm::dmat4(1.0), glm::dvec3(0.3, -0.2, 1.0)) *
                 glm::rotate(glm::dmat4(1.0), 2.5, glm::normalize(glm::dvec3(-1, 2, 0.5)));
    f.inverseBinds[0] = glm::rotate(glm::dmat4(1.0), -0.4, glm::dvec3(0, 0, 1)) *
                        glm::scale(glm::dmat4(1.0), glm::dvec3(scale));
    std::vector<SkinDualQuaternion> dualQuaternions(2);
    SkinningMatricesJob job = f.job();
    job.dualQuaternions = dualQuaternions;
    job.bindScale = scale;
    ASSERT_TRUE(job.run());
    const glm::dquat real(dualQuaternions[0].real);
    const glm::dquat dual(dualQuaternions[0].dual);
    EXPECT_NEAR(glm::length(real), 1.0, 1e-6);
    EXPECT_GE(real.w, 0.0);
    const glm::dquat translation = 2.0 * dual * glm::conjugate(real);
    for (const glm::dvec3 p : {glm::dvec3(0.0), glm::dvec3(10, -20, 30), glm::dvec3(-50, 5, 0)})
    {
        const glm::dvec3 byMatrix(f.doubles[0] * glm::dvec4(p, 1.0));
        const glm::dvec3 byDualQuaternion =
            real * (scale * p) + glm::dvec3(translation.x, translation.y, translation.z);
        EXPECT_TRUE(osgActor::test::vectorsNear(byDualQuaternion, byMatrix, 1e-6));
    }
}
