// The IK solvers' inline arctangent against the C library's: within 2 ulp everywhere, the same on the edge cases.
#include <osgActor/core/ik/Arctangent>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

using namespace osgActor;

namespace {

/** |a - b| in units in the last place of b (b != 0). */
double ulpsApart(double a, double b)
{
    const double ulp = std::nextafter(std::abs(b), std::numeric_limits<double>::infinity()) - std::abs(b);
    return std::abs(a - b) / ulp;
}

} // namespace

TEST(Arctangent, MatchesTheLibraryOnItsEdges)
{
    const double inf = std::numeric_limits<double>::infinity();
    const double zeros[] = {0.0, -0.0};
    for (double y : zeros)
        for (double x : zeros) EXPECT_EQ(arctangent2(y, x), std::atan2(y, x)) << y << " " << x;
    EXPECT_EQ(arctangent2(1.0, 0.0), std::atan2(1.0, 0.0));
    EXPECT_EQ(arctangent2(-1.0, 0.0), std::atan2(-1.0, 0.0));
    EXPECT_EQ(arctangent2(0.0, -1.0), std::atan2(0.0, -1.0)) << "pi";
    EXPECT_EQ(arctangent2(-0.0, -1.0), std::atan2(-0.0, -1.0)) << "-pi";
    EXPECT_EQ(arctangent2(-0.0, 1.0), std::atan2(-0.0, 1.0));
    EXPECT_EQ(arctangent2(inf, inf), std::atan2(inf, inf));
    EXPECT_EQ(arctangent2(1.0, -inf), std::atan2(1.0, -inf));
    EXPECT_TRUE(std::isnan(arctangent2(std::nan(""), 1.0)));
    // The seams of the argument reduction: a / b at 0.66 and at tan(3 pi / 8), and the diagonal.
    for (double ratio : {0.66, 2.41421356237309504880, 1.0})
        for (double scale : {1e-300, 1e-8, 1.0, 1e8, 1e300})
            for (int step = -3; step <= 3; ++step)
            {
                double y = ratio * scale;
                for (int i = 0; i < std::abs(step); ++i) y = std::nextafter(y, step > 0 ? inf : 0.0);
                for (double sy : {1.0, -1.0})
                    for (double sx : {1.0, -1.0})
                        EXPECT_LE(ulpsApart(arctangent2(sy * y, sx * scale), std::atan2(sy * y, sx * scale)), 2.0)
                            << sy * y << " " << sx * scale;
            }
}

TEST(Arctangent, IsWithinTwoUlpOfTheLibrary)
{
    std::mt19937_64 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), exponent(-30.0, 30.0);
    double worst = 0.0;
    for (int i = 0; i < 2000000; ++i)
    {
        const double x = unit(random) * std::exp2(exponent(random));
        double y = unit(random) * std::exp2(exponent(random));
        if (i % 5 == 0) y = x * (1.0 + 1e-3 * unit(random)); // near the diagonals, where the quadrant arithmetic bites
        if (i % 7 == 0) y = -x * (1.0 + 1e-9 * unit(random));
        const double expected = std::atan2(y, x);
        if (expected == 0.0) continue;
        worst = std::max(worst, ulpsApart(arctangent2(y, x), expected));
    }
    EXPECT_LE(worst, 2.0);
}
