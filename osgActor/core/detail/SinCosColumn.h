// Internal to the library (not installed): the sine and cosine of four angles at once, the kernel of sinCos() and of
// forward kinematics. Branch-free but for angles beyond 1e6 radians, which take the library's functions.
#ifndef OSGACTOR_CORE_DETAIL_SINCOSCOLUMN_H
#define OSGACTOR_CORE_DETAIL_SINCOSCOLUMN_H 1

#include "Column.h"

#include <cmath>

namespace osgActor {

namespace sincos_detail {

// pi/2 split into three parts: the first two have 30 significant bits, so j * part is exact for |j| < 2^23 and the
// reduction x - j pi/2 loses nothing (Cody and Waite). kLargestFastAngle keeps j far inside that range; larger
// angles take the library's functions.
constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
constexpr double kHalfPi1 = 0x1.921fb54800000p+0;
constexpr double kHalfPi2 = -0x1.de973dc800000p-31;
constexpr double kHalfPi3 = -0x1.9d9cceba3f91fp-62;
constexpr double kLargestFastAngle = 1.0e6;
// Adding 1.5 * 2^52 to a double below 2^51 in magnitude rounds it to an integer, held in the low mantissa bits
// (two's complement for negative values, so the low two bits are the integer mod 4).
constexpr double kRoundingShift = 0x1.8p52;

// Taylor coefficients: on the reduced range |r| <= pi/4 the first omitted terms (r^17 / 17!, r^18 / 18!) are below
// 1e-16, a fraction of an ulp of the results.
constexpr double kSin[] = {-1.0 / 6, 1.0 / 120, -1.0 / 5040, 1.0 / 362880, -1.0 / 39916800, 1.0 / 6227020800,
                           -1.0 / 1307674368000};
constexpr double kCos[] = {-1.0 / 2,        1.0 / 24,          -1.0 / 720,            1.0 / 40320,
                           -1.0 / 3628800,  1.0 / 479001600,   -1.0 / 87178291200,    1.0 / 20922789888000};

/** The lanes beyond the fast range, through std::sin and std::cos; out of line, as it almost never runs. */
__attribute__((noinline, cold)) inline void sinCosOfLargeLanes(const double (&x)[4], double (&sine)[4],
                                                                double (&cosine)[4])
{
    for (unsigned lane = 0; lane < 4; ++lane)
        if (std::fabs(x[lane]) > kLargestFastAngle)
        {
            sine[lane] = std::sin(x[lane]);
            cosine[lane] = std::cos(x[lane]);
        }
}

} // namespace sincos_detail

/** sine = sin(x), cosine = cos(x), lane by lane, to about an ulp, for |x| <= kLargestFastAngle (see
  * withinFastSinCosRange; sinCosColumn takes any finite angle). */
OSGACTOR_INLINE void sinCosColumnInFastRange(Column x, Column& sine, Column& cosine)
{
    using namespace sincos_detail;
    const Column shifted = x * kTwoOverPi + kRoundingShift;
    const Column j = shifted - kRoundingShift; // the nearest multiple of pi/2
    const Column r = ((x - j * kHalfPi1) - j * kHalfPi2) - j * kHalfPi3;
    const Column r2 = r * r;
    // Estrin's scheme: pairs of terms first, then pairs of pairs, so the chain of dependent multiply-adds is three
    // deep instead of seven and three columns of angles overlap in the pipeline.
    const Column r4 = r2 * r2, r8 = r4 * r4;
    const Column ps = ((kSin[0] + kSin[1] * r2) + (kSin[2] + kSin[3] * r2) * r4) +
                      ((kSin[4] + kSin[5] * r2) + kSin[6] * r4) * r8;
    const Column pc = ((kCos[0] + kCos[1] * r2) + (kCos[2] + kCos[3] * r2) * r4) +
                      ((kCos[4] + kCos[5] * r2) + (kCos[6] + kCos[7] * r2) * r4) * r8;
    const Column s = r + r * r2 * ps; // sin r
    const Column c = 1.0 + r2 * pc;   // cos r
    // x = r + q pi/2 with q = j mod 4, the low two bits of shifted: (sin, cos) of x is (s, c), (c, -s), (-s, -c),
    // (-c, s). Shifted left by 62, q's bit 1 is the sign bit (sine negated for q = 2, 3) and bit 0 the one below it.
    const ColumnBits q62 = reinterpret_cast<ColumnBits>(shifted) << 62;
    const ColumnBits signBit = ColumnBits{} + (1ull << 63);
    const auto odd = reinterpret_cast<ColumnSignedBits>(q62 << 1) < 0;
    const Column sinMagnitude = odd ? c : s;
    const Column cosMagnitude = odd ? s : c;
    sine = reinterpret_cast<Column>(reinterpret_cast<ColumnBits>(sinMagnitude) ^ (q62 & signBit));
    cosine = reinterpret_cast<Column>(reinterpret_cast<ColumnBits>(cosMagnitude) ^ ((q62 ^ (q62 << 1)) & signBit));
}

/** Whether every one of the count values is within the range of sinCosColumnInFastRange; false if any is NaN. */
OSGACTOR_INLINE bool withinFastSinCosRange(const double* values, unsigned count)
{
    // Four at a time: whether any magnitude is out of range (or NaN), as the bits of a comparison.
    ColumnBits outside = ColumnBits{};
    unsigned i = 0;
    for (; i + 4 <= count; i += 4)
    {
        const auto inside = absColumn(loadColumn(values + i)) <= sincos_detail::kLargestFastAngle;
        outside |= reinterpret_cast<ColumnBits>(!inside);
    }
    bool within = (outside[0] | outside[1] | outside[2] | outside[3]) == 0;
    for (; i < count; ++i) within = within && std::fabs(values[i]) <= sincos_detail::kLargestFastAngle;
    return within;
}

/** Collects, column by column, whether any angle is beyond sinCosColumnInFastRange's range (or NaN): a caller that
  * takes the fast path first and checks once after, redoing the rare large-angle case, skips a pass over the
  * angles. */
class FastSinCosRangeGuard
{
public:
    OSGACTOR_INLINE void check(Column x)
    {
        _outside |= reinterpret_cast<ColumnBits>(!(absColumn(x) <= sincos_detail::kLargestFastAngle));
    }
    OSGACTOR_INLINE bool passed() const { return (_outside[0] | _outside[1] | _outside[2] | _outside[3]) == 0; }

private:
    ColumnBits _outside = ColumnBits{};
};

/** sine = sin(x), cosine = cos(x), lane by lane, to about an ulp; x must be finite. */
OSGACTOR_INLINE void sinCosColumn(Column x, Column& sine, Column& cosine)
{
    using namespace sincos_detail;
    sinCosColumnInFastRange(x, sine, cosine);
    const auto large = absColumn(x) > kLargestFastAngle;
    if (__builtin_expect((large[0] | large[1] | large[2] | large[3]) != 0, 0))
    {
        double xs[4], ss[4], cs[4];
        storeColumn(xs, x);
        storeColumn(ss, sine);
        storeColumn(cs, cosine);
        sinCosOfLargeLanes(xs, ss, cs);
        sine = loadColumn(ss);
        cosine = loadColumn(cs);
    }
}

} // namespace osgActor

#endif
