// ActorTransforms, the one form of an actor's reference-point transforms: what it refuses, then pretr_m, posttr_m
// and actor_m against products worked out by hand (column-vector notation).
#include <osgActor/core/ActorTransforms>
#include <osgActor/core/Dof>

#include "TestMath"

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>

#include <limits>

using namespace osgActor;
using osgActor::test::fromRows;
using osgActor::test::matricesNear;

namespace {

const double kQuarter = glm::pi<double>() / 2.0;
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInfinity = std::numeric_limits<double>::infinity();

} // namespace

TEST(ActorTransforms, RefusesTranslationsBeyondTheLargestMagnitudeOrNotFinite)
{
    EXPECT_FALSE(isValidTransformTranslation(glm::dvec3(kNaN, 0, 0)));
    EXPECT_FALSE(isValidTransformTranslation(glm::dvec3(0, kInfinity, 0)));
    EXPECT_FALSE(isValidTransformTranslation(glm::dvec3(0, 0, -2 * kMaxDofMagnitude)));
    EXPECT_TRUE(isValidTransformTranslation(glm::dvec3(kMaxDofMagnitude, -kMaxDofMagnitude, 0)));
}

TEST(ActorTransforms, RefusesZeroOrNonFiniteRotations)
{
    EXPECT_FALSE(isValidTransformRotation(glm::dquat(0, 0, 0, 0)));
    EXPECT_FALSE(isValidTransformRotation(glm::dquat(1, kNaN, 0, 0)));
    EXPECT_FALSE(isValidTransformRotation(glm::dquat(kInfinity, 0, 0, 0)));
    EXPECT_FALSE(isValidTransformRotation(glm::dquat(1e200, 1e200, 0, 0))) << "its squared length overflows";
    EXPECT_TRUE(isValidTransformRotation(glm::dquat(3, 0, 0, 0))) << "not unit: normalized when used";
}

TEST(ActorTransforms, TheDefaultIsTheIdentity)
{
    const ActorTransforms identity;
    EXPECT_EQ(computeActorMatrix(identity), glm::dmat4(1.0));
}

TEST(ActorTransforms, EachTransformTurnsThenPlaces)
{
    // pretr_m = T(1, 2, 3) * Rz(90); posttr_m = T(0, 0, 5) * Rx(90), its quaternion given at twice unit length.
    ActorTransforms t;
    t.preTranslation = glm::dvec3(1, 2, 3);
    t.preRotation = glm::angleAxis(kQuarter, glm::dvec3(0, 0, 1));
    t.postTranslation = glm::dvec3(0, 0, 5);
    t.postRotation = 2.0 * glm::angleAxis(kQuarter, glm::dvec3(1, 0, 0));
    EXPECT_TRUE(matricesNear(computePreTransformMatrix(t), fromRows(0, -1, 0, 1, 1, 0, 0, 2, 0, 0, 1, 3), 1e-15));
    EXPECT_TRUE(matricesNear(computePostTransformMatrix(t), fromRows(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 5), 1e-15));
    // actor_m = pretr_m * posttr_m: the rotation Rz(90) Rx(90) = [[0,0,1],[1,0,0],[0,1,0]], the translation
    // Rz(90) (0, 0, 5) + (1, 2, 3) = (1, 2, 8).
    EXPECT_TRUE(matricesNear(computeActorMatrix(t), fromRows(0, 0, 1, 1, 1, 0, 0, 2, 0, 1, 0, 8), 1e-15));
}
