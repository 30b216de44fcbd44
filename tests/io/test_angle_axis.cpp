#include <osgActor/io/AngleAxis>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace osgActor;

namespace {

bool sameQuaternion(const glm::dquat& a, const glm::dquat& b)
{
    return (a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z) ||
           (a.w == -b.w && a.x == -b.x && a.y == -b.y && a.z == -b.z);
}

} // namespace

TEST(AngleAxis, AZeroOrNonFiniteAxisIsNoRotation)
{
    glm::dquat q;
    AngleAxis zero;
    zero.axis[2] = 0.0;
    EXPECT_FALSE(toQuaternion(zero, q));
    AngleAxis huge;
    huge.axis[0] = huge.axis[1] = 1e300;
    EXPECT_FALSE(toQuaternion(huge, q)) << "its length overflows";
    const double zeros[4] = {0.0, 0.0, 0.0, 0.0};
    EXPECT_FALSE(quaternionAsWritten(zeros, q));
    const double infinite[4] = {1.0, std::numeric_limits<double>::infinity(), 0.0, 0.0};
    EXPECT_FALSE(quaternionAsWritten(infinite, q));
}

TEST(AngleAxis, RotationsReadAsAnAngleAboutAnAxisScaledToItsLargestComponent)
{
    glm::dquat q;
    AngleAxis turn;
    turn.degrees = 90.0;
    turn.axis[2] = 2.0; // any length
    ASSERT_TRUE(toQuaternion(turn, q));
    EXPECT_NEAR(q.w, std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(q.z, std::sqrt(0.5), 1e-15);
    const AngleAxis back = toAngleAxis(-q); // the same rotation with w < 0
    EXPECT_NEAR(back.degrees, 90.0, 1e-12);
    EXPECT_EQ(back.axis[2], 1.0);
    EXPECT_EQ(back.axis[0], 0.0);
    EXPECT_TRUE(isIdentityRotation(glm::dquat(1.0, 0.0, 0.0, 0.0)));
    EXPECT_TRUE(isIdentityRotation(glm::dquat(-1.0, 0.0, 0.0, 0.0)));
    EXPECT_FALSE(isIdentityRotation(glm::dquat(1.0, 1e-300, 0.0, 0.0))) << "exactly, not nearly";
    EXPECT_FALSE(isIdentityRotation(q));
}

TEST(AngleAxis, TheAngleAndAxisAFileWroteAreFoundAgainExactly)
{
    const double written[][4] = {{90, 0, 0, 1}, {33.3, 1, -0.25, 0.7}, {180, 1, 0, 0}, {0.001, 0, 1, 0},
                                 {-45, 0, 0, 1}, {120, 1, 1, 1}, {1e-300, 1, 0, 0}, {179.999, 0.3, -1, 0.2}};
    for (const auto& w : written)
    {
        AngleAxis read;
        read.degrees = w[0];
        for (int i = 0; i < 3; ++i) read.axis[i] = w[i + 1];
        glm::dquat q;
        ASSERT_TRUE(toQuaternion(read, q));
        AngleAxis found;
        ASSERT_TRUE(toExactAngleAxis(q, found)) << w[0];
        glm::dquat again;
        ASSERT_TRUE(toQuaternion(found, again));
        EXPECT_TRUE(sameQuaternion(again, q)) << w[0];
    }
}

TEST(AngleAxis, ExactAngleAndAxisGiveTheRotationBackWhenFound)
{
    // Rotations computed elsewhere (an import's axis change) need not have one; when one is found it is exact.
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> component(-1.0, 1.0);
    int found = 0;
    for (int i = 0; i < 2000; ++i)
    {
        const glm::dquat q = glm::normalize(
            glm::dquat(component(random), component(random), component(random), component(random)));
        AngleAxis angleAxis;
        if (!toExactAngleAxis(q, angleAxis)) continue;
        ++found;
        glm::dquat again;
        ASSERT_TRUE(toQuaternion(angleAxis, again));
        EXPECT_TRUE(sameQuaternion(again, q));
    }
    EXPECT_GT(found, 0);
}

TEST(AngleAxis, AWrittenQuaternionIsKeptWhenUnitAndNormalizedOtherwise)
{
    const double unit[4] = {0.7071067811865476, 0.0, 0.0, 0.7071067811865475};
    glm::dquat q;
    ASSERT_TRUE(quaternionAsWritten(unit, q));
    EXPECT_EQ(q, glm::dquat(unit[0], unit[1], unit[2], unit[3])) << "kept bit for bit";
    const double typed[4] = {0.7071, 0.0, 0.0, 0.7071};
    ASSERT_TRUE(quaternionAsWritten(typed, q));
    EXPECT_NEAR(q.w, std::sqrt(0.5), 1e-15);
    // Normalized once, it is kept the next time: reading what was written is a fixed point.
    const double normalized[4] = {q.w, q.x, q.y, q.z};
    glm::dquat again;
    ASSERT_TRUE(quaternionAsWritten(normalized, again));
    EXPECT_EQ(again, q);
}
