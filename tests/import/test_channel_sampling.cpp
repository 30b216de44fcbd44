// Exact sampling of animation channels and the Euler angles of rotations, against hand-derived values.
#include "TestMath"

#include <osgActor/import/ChannelSampling>
#include <osgActor/import/EulerFit>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/gtc/constants.hpp>

using namespace osgActor;
using namespace osgActor::test;

namespace {

AnimationChannel vectorChannel(KeyInterpolation interpolation)
{
    AnimationChannel channel;
    channel.path = AnimationPath::Translation;
    channel.interpolation = interpolation;
    channel.times = {1.0, 3.0};
    channel.values = {glm::dvec4(0, 0, 0, 0), glm::dvec4(2, 4, -2, 0)};
    return channel;
}

glm::dvec4 xyzw(const glm::dquat& q) { return glm::dvec4(q.x, q.y, q.z, q.w); }

} // namespace

TEST(ChannelSampling, HoldsTheEndValuesOutsideTheKeys)
{
    const AnimationChannel channel = vectorChannel(KeyInterpolation::Linear);
    EXPECT_TRUE(vectorsNear(sampleVectorChannel(channel, 0.0), glm::dvec3(0, 0, 0)));
    EXPECT_TRUE(vectorsNear(sampleVectorChannel(channel, 5.0), glm::dvec3(2, 4, -2)));
}

TEST(ChannelSampling, StepHoldsAKeyUntilTheNext)
{
    const AnimationChannel channel = vectorChannel(KeyInterpolation::Step);
    EXPECT_TRUE(vectorsNear(sampleVectorChannel(channel, 2.999), glm::dvec3(0, 0, 0)));
    EXPECT_TRUE(vectorsNear(sampleVectorChannel(channel, 3.0), glm::dvec3(2, 4, -2)));
}

TEST(ChannelSampling, LinearVectorsInterpolateLinearly)
{
    EXPECT_TRUE(vectorsNear(sampleVectorChannel(vectorChannel(KeyInterpolation::Linear), 1.5), glm::dvec3(0.5, 1, -0.5)));
}

TEST(ChannelSampling, CubicSplineIsTheHermiteCurveWithTangentsScaledByTheInterval)
{
    // p0 = 0, m0 = 1 per second, p1 = 0, m1 = 0, over 2 seconds: at u = 1/2, (u^3 - 2u^2 + u) * 2 * 1 = 0.25.
    AnimationChannel channel = vectorChannel(KeyInterpolation::CubicSpline);
    channel.values = {glm::dvec4(0.0), glm::dvec4(0.0)};
    channel.inTangents = {glm::dvec4(0.0), glm::dvec4(0.0)};
    channel.outTangents = {glm::dvec4(1, 0, 0, 0), glm::dvec4(0.0)};
    EXPECT_TRUE(vectorsNear(sampleVectorChannel(channel, 2.0), glm::dvec3(0.25, 0, 0), 1e-15));
}

TEST(ChannelSampling, LinearRotationsSlerpTheShorterWay)
{
    AnimationChannel channel;
    channel.interpolation = KeyInterpolation::Linear;
    channel.times = {0.0, 1.0};
    // 0 and 120 degrees about Z, the second given as its negative (the same rotation, the long way round).
    channel.values = {xyzw(glm::dquat(1, 0, 0, 0)), -xyzw(glm::angleAxis(glm::radians(120.0), glm::dvec3(0, 0, 1)))};
    const glm::dquat middle = sampleRotationChannel(channel, 0.5);
    EXPECT_NEAR(std::abs(glm::dot(middle, glm::angleAxis(glm::radians(60.0), glm::dvec3(0, 0, 1)))), 1.0, 1e-14);
}

TEST(ChannelSampling, AnimationTimeRangeSpansEveryChannel)
{
    RiggedAnimation animation;
    animation.channels = {vectorChannel(KeyInterpolation::Linear), vectorChannel(KeyInterpolation::Linear)};
    animation.channels[1].times = {0.5, 2.0};
    double first, last;
    animationTimeRange(animation, first, last);
    EXPECT_EQ(first, 0.5);
    EXPECT_EQ(last, 3.0);
}

TEST(EulerFit, AnglesRebuildTheRotationInEveryOrder)
{
    const glm::dquat q = glm::angleAxis(1.1, glm::normalize(glm::dvec3(0.3, -0.5, 0.8)));
    for (EulerOrder order : {EulerOrder::XYZ, EulerOrder::XZY, EulerOrder::YXZ, EulerOrder::YZX, EulerOrder::ZXY, EulerOrder::ZYX})
    {
        double angles[3];
        eulerAngles(q, order, nullptr, angles);
        EXPECT_NEAR(std::abs(glm::dot(eulerRotation(order, angles), q)), 1.0, 1e-14) << eulerOrderName(order);
    }
}

TEST(EulerFit, ZxyIsRzTimesRxTimesRy)
{
    // Hand-derived: ZXY with angles (rz, rx, ry) = (0.3, 0.2, 0.1) is Rz(0.3) Rx(0.2) Ry(0.1).
    const double angles[3] = {0.3, 0.2, 0.1};
    const glm::dquat expected = glm::angleAxis(0.3, glm::dvec3(0, 0, 1)) * glm::angleAxis(0.2, glm::dvec3(1, 0, 0)) *
                                glm::angleAxis(0.1, glm::dvec3(0, 1, 0));
    EXPECT_NEAR(std::abs(glm::dot(eulerRotation(EulerOrder::ZXY, angles), expected)), 1.0, 1e-15);
}

TEST(EulerFit, AnglesStayContinuousPastAHalfTurn)
{
    // A turn about Z from 170 to 190 degrees: the second angle continues past pi instead of jumping to -170.
    const double previous[3] = {0.0, 0.0, glm::radians(170.0)};
    double angles[3];
    eulerAngles(glm::angleAxis(glm::radians(190.0), glm::dvec3(0, 0, 1)), EulerOrder::XYZ, previous, angles);
    EXPECT_NEAR(angles[0], 0.0, 1e-12);
    EXPECT_NEAR(angles[1], 0.0, 1e-12);
    EXPECT_NEAR(angles[2], glm::radians(190.0), 1e-12);
}

TEST(EulerFit, ChoosesTheOrderAwayFromGimbalLock)
{
    // Rotations about Y up to 90 degrees lock XYZ and ZYX (Y in the middle); an order with Y first or last does not.
    std::vector<glm::dquat> rotations;
    for (int degrees = 0; degrees <= 90; degrees += 10)
        rotations.push_back(glm::angleAxis(glm::radians(double(degrees)), glm::dvec3(0, 1, 0)));
    double margin = 0.0;
    const EulerOrder order = chooseEulerOrder(rotations, &margin);
    unsigned axes[3];
    eulerOrderAxes(order, axes);
    EXPECT_NE(axes[1], 1u);
    EXPECT_NEAR(margin, 1.0, 1e-12);
    EXPECT_NEAR(gimbalMargin(rotations.back(), EulerOrder::XYZ), 0.0, 1e-7);
}
