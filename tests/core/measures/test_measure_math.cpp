// The portable arithmetic of the orbit measures (core/measures/MeasureMath.inl): its atan2 and log against long
// double libm (an independent computation, 64-bit mantissa), TwoSum's exactness, and the special values.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

#include "core/map/FixedPointMap.hpp"  // int128

namespace archipelago::measures {
namespace {
#include "core/measures/MeasureMath.inl"

constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(MeasureMath, Atan2MatchesLongDoubleWithinItsRoundingBound) {
  // Angles all round the circle, at magnitudes from the grid unit to the box (grid units 1 … 2^52), the octant
  // boundaries (|s| = |c|, |s| = tan(π/8)|c|) included.
  std::mt19937_64 rng(27);
  std::uniform_real_distribution<double> angle(-3.2, 3.2), scale(0, 52);
  double worst = 0;
  for (int i = 0; i < 200000; ++i) {
    const double r = std::exp2(scale(rng)), a = angle(rng);
    double s = r * std::sin(a), c = r * std::cos(a);
    if (i % 4 == 1) s = std::copysign(std::fabs(c), s);                    // on an octant boundary
    if (i % 4 == 2) s = std::copysign(std::fabs(c) * kTanPi8, s);           // on the reduction's boundary
    const long double reference = std::atan2(static_cast<long double>(s), static_cast<long double>(c));
    worst = std::max(worst, static_cast<double>(std::fabs(atan2Portable(s, c) - reference)));
  }
  // The bound, with ε = 2^−53: the reduced argument u = (min − max·tan α)/(max + min·tan α), |u| ≤ tan(π/16),
  // carries three roundings, 3ε|u| ≤ 0.66·10⁻¹⁶ in atan, and for tan α = τ the product max·τ 0.21ε = 0.23·10⁻¹⁶;
  // the polynomial ~0.5·10⁻¹⁶; then K_lo ± a, below π/16 + 2^−52 < 1/4, half an ulp 2^−56 = 0.14·10⁻¹⁶, and the
  // final sum with K_hi, half an ulp of a value up to π: 2^−52 = 2.22·10⁻¹⁶.  In all 3.75·10⁻¹⁶ (5.75·10⁻¹⁶ before
  // issue 41, when α, π/2 and π were added one after another, each rounding).
  EXPECT_LT(worst, 3.75e-16) << worst;
}

TEST(MeasureMath, Atan2SpecialValuesAndRange) {
  constexpr double pi = 3.14159265358979323846;
  EXPECT_EQ(atan2Portable(0.0, 0.0), 0.0);
  EXPECT_EQ(atan2Portable(0.0, 1.0), 0.0);
  EXPECT_EQ(atan2Portable(0.0, -1.0), pi);   // (−π, π]: the negative axis is +π …
  EXPECT_EQ(atan2Portable(-0.0, -1.0), pi);  // … from either side of zero
  EXPECT_EQ(atan2Portable(0.0, -0.0), 0.0);
  EXPECT_EQ(atan2Portable(1.0, -0.0), pi / 2);
  EXPECT_EQ(atan2Portable(-1.0, -0.0), -pi / 2);
  EXPECT_EQ(atan2Portable(0.0, -1e-300), pi);
  EXPECT_EQ(atan2Portable(-1e-300, -1.0), -pi);
  EXPECT_EQ(atan2Portable(1.0, 0.0), pi / 2);
  EXPECT_EQ(atan2Portable(-1.0, 0.0), -pi / 2);
  EXPECT_NEAR(atan2Portable(1.0, 1.0), pi / 4, 2e-16);
  EXPECT_NEAR(atan2Portable(-1.0, -1.0), -3 * pi / 4, 4e-16);
  // Clockwise angle: Q turns (1, 0) about the centre to (1 − 4√K, −4√K), a clockwise turn, so positive.
  EXPECT_GT(clockwiseAngle(1.0, 0.0, 0.5, -0.5), 0);
  EXPECT_NEAR(clockwiseAngle(1.0, 0.0, 0.0, -1.0), pi / 2, 2e-16);
  EXPECT_NEAR(clockwiseAngle(0.0, 1.0, 1.0, 0.0), pi / 2, 2e-16);
  EXPECT_NEAR(clockwiseAngle(1.0, 0.0, 0.0, 1.0), -pi / 2, 2e-16);
}

TEST(MeasureMath, LogMatchesLongDoubleWithinTwoAndAHalfUlps) {
  std::mt19937_64 rng(72);
  std::uniform_real_distribution<double> exponent(-300, 300), mantissa(1, 2);
  double worstUlps = 0;
  for (int i = 0; i < 200000; ++i) {
    double r = std::ldexp(mantissa(rng), static_cast<int>(exponent(rng)));
    if (i % 3 == 0) r = std::nextafter(1.0, 2.0) + i * kEps;  // near 1, where ln r is small
    if (i % 7 == 0) r = std::ldexp(kSqrt2, static_cast<int>(exponent(rng)));  // the reduction's boundary
    const long double reference = std::log(static_cast<long double>(r));
    const double ulp = std::fabs(std::nextafter(static_cast<double>(reference), 0.0) - static_cast<double>(reference));
    worstUlps = std::max(worstUlps, static_cast<double>(std::fabs(lnPositive(r) - reference)) / ulp);
  }
  // s = (m − 1)/(m + 1) and 2s·P(s²) carry about four relative roundings (2 ulps), the sum e·ln 2 + ln m one
  // more half ulp: 2.5 ulps.
  EXPECT_LT(worstUlps, 2.5) << worstUlps;
  EXPECT_EQ(lnPositive(1.0), 0.0);
  EXPECT_EQ(lnPositive(2.0), kLn2Hi + kLn2Lo);
}

TEST(MeasureMath, SplitExponentIsExact) {
  for (double r : {1.0, 1.5, 0.75, 3.0, 0x1p200, 0x1.fffffffffffffp-3, 1e-300}) {
    double m = 0;
    const double e = splitExponent(r, m);
    EXPECT_EQ(std::ldexp(m, static_cast<int>(e)), r);
    EXPECT_GE(m, 1.0);
    EXPECT_LT(m, 2.0);
  }
  double m = 0;
  EXPECT_EQ(absValue(-0.0), 0.0);
  EXPECT_FALSE(std::signbit(absValue(-0.0)));  // the sign bit cleared, as vandpd does
  EXPECT_EQ(splitExponent(0x1p-1000, m), -1000.0);
}

TEST(MeasureMath, TwoSumKeepsTheExactSum) {
  // Sums of integers times powers of two are exact in 128-bit integers: hi + lo must equal them exactly.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 100; ++trial) {
    double hi = 0, lo = 0;
    int128 exact = 0;  // in units of 2^-60
    for (int i = 0; i < 1000; ++i) {
      const std::int64_t k = static_cast<std::int64_t>(rng() >> 11) - (std::int64_t{1} << 52);
      const int shift = static_cast<int>(rng() % 40);
      twoSumAdd(hi, lo, std::ldexp(static_cast<double>(k), shift - 60));
      exact += static_cast<int128>(k) << shift;
    }
    // hi + lo rounded once equals the exact sum rounded once.
    const long double sum = static_cast<long double>(hi) + static_cast<long double>(lo);
    const auto exactD = std::ldexp(static_cast<long double>(exact), -60);
    EXPECT_LE(std::fabs(sum - exactD), std::fabs(exactD) * 1e-18L);
    EXPECT_EQ(hi + lo, static_cast<double>(exactD));
  }
}

}  // namespace
}  // namespace archipelago::measures
