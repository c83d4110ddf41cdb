// Island chains from rotation numbers (core/measures/ChainIdentification.hpp): the Stern–Brocot search against a
// brute-force one, and the paper's chain of order 138 = 6 × 23 (Karney 1983, §6) named from one orbit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/measures/ChainIdentification.hpp"

namespace archipelago {
namespace {

/// The smallest q ≤ maxQ with some p/q in [lo, hi], by trying every q (independent of the tree descent).
std::optional<Rational> bruteForce(double lo, double hi, std::int64_t maxQ) {
  for (std::int64_t q = 1; q <= maxQ; ++q) {
    const auto p = static_cast<std::int64_t>(std::ceil(static_cast<long double>(lo) * q));
    if (static_cast<long double>(p) <= static_cast<long double>(hi) * q) return Rational{p, q};
  }
  return std::nullopt;
}

TEST(ChainIdentification, ARotationNamesTheRationalOfSmallestDenominatorWithinEightTimesItsDifference) {
  // The one step from a measured rotation to p/q (issue 51: the chain identification, the rotation profile, the
  // atlas's classifier and its proof, and the box check call it): within 8 × the blocks' difference, at least 2^−50.
  EXPECT_EQ(rotationAccuracy(1e-12), 8e-12);
  EXPECT_EQ(rotationAccuracy(0), 0x1p-50);
  EXPECT_EQ(rationalOfRotation(1.0 / 6 + 7e-12, 1e-12, 2000), (Rational{1, 6}));
  EXPECT_EQ(rationalOfRotation(1.0 / 6 + 9e-12, 1e-12, 2000), std::nullopt);  // an invariant circle at that accuracy
  EXPECT_EQ(rationalOfRotation(-2.0 / 23, 0, 2000), (Rational{-2, 23}));
  EXPECT_EQ(rationalOfRotation(16.0 / 113, 1e-7, 1000), (Rational{16, 113}));
  EXPECT_EQ(rationalOfRotation(16.0 / 113, 1e-7, 112), std::nullopt);  // beyond the largest denominator
  EXPECT_EQ(rationalOfRotation(1e-4, 1e-4, 5), (Rational{0, 1}));  // not turning: 0 lies within 8e-4
}

TEST(ChainIdentification, SternBrocotFindsTheSmallestDenominator) {
  EXPECT_EQ(smallestDenominatorRational(0.33, 0.34, 100), (Rational{1, 3}));
  EXPECT_EQ(smallestDenominatorRational(1.0 / 6 - 1e-14, 1.0 / 6 + 1e-14, 10000), (Rational{1, 6}));
  EXPECT_EQ(smallestDenominatorRational(-2.0 / 23 - 1e-14, -2.0 / 23 + 1e-14, 10000), (Rational{-2, 23}));
  EXPECT_EQ(smallestDenominatorRational(-0.1, 0.1, 5), (Rational{0, 1}));
  EXPECT_EQ(smallestDenominatorRational(0.14159, 0.14160, 1000), (Rational{16, 113}));  // π − 3
  EXPECT_EQ(smallestDenominatorRational(0.14159, 0.14160, 112), std::nullopt);
  EXPECT_EQ(smallestDenominatorRational(1e-12, 2e-12, 1'000'000), std::nullopt);  // runs of 10¹¹ steps: at once
  EXPECT_EQ(smallestDenominatorRational(2.5, 2.5, 10), (Rational{5, 2}));
  EXPECT_THROW((void)smallestDenominatorRational(0.2, 0.1, 10), std::invalid_argument);
  EXPECT_THROW((void)smallestDenominatorRational(std::nan(""), 0.1, 10), std::invalid_argument);
  std::mt19937_64 rng(138);
  std::uniform_real_distribution<double> centre(-0.5, 0.5), width(-12, -2);
  for (int i = 0; i < 3000; ++i) {
    const double c = centre(rng), h = std::pow(10.0, width(rng));
    const auto a = smallestDenominatorRational(c - h, c + h, 3000);
    const auto b = bruteForce(c - h, c + h, 3000);
    ASSERT_EQ(a.has_value(), b.has_value()) << c << " ± " << h;
    if (a) {
      EXPECT_EQ(a->q, b->q) << c << " ± " << h;
    }
  }
}

TEST(ChainIdentification, NamesThe138ChainFromAnOrbitNextToItsEllipticOrbit) {
  // §6: an elliptic orbit of period 138 has a member near x + √K ≈ 0.352, y ≈ 0.034 (the CLI: `periodic --period
  // 138 --near 0.0358,0.034 --stable`); an orbit started 10⁻⁶ from it circles it.
  const MapParameters box{0.1, -0.8, 0.5};
  const FixedPointMap map(box);
  ChainRequest r;
  r.map = box;
  r.start = map.toUnit(0.0360286533088399L + 1e-6L, 0.0341809124510990L);
  const ChainIdentification c = identifyChain(r);
  EXPECT_EQ(c.period, 138u);
  EXPECT_EQ(c.factors, (std::vector<std::int64_t>{6, 23}));
  ASSERT_EQ(c.levels.size(), 3u);
  EXPECT_EQ(c.levels[0].rational, (Rational{1, 6}));
  EXPECT_EQ(c.levels[1].rational, (Rational{2, 23}));
  EXPECT_FALSE(c.levels[2].rational.has_value());  // an invariant curve about the period-138 orbit
  EXPECT_EQ(c.levels[1].orbit->period, 6);
  EXPECT_EQ(c.levels[2].orbit->period, 138);
  EXPECT_NEAR(static_cast<double>(c.levels[2].centre.x + std::sqrt(0.1L)), 0.352, 1e-3);
  EXPECT_NEAR(static_cast<double>(c.levels[2].centre.y), 0.034, 1e-3);
  EXPECT_EQ(c.summary.rfind("6 × 23 = 138, rotation 1/6 about the centre, 2/23 about its island; an invariant curve", 0),
            0u)
      << c.summary;
}

TEST(ChainIdentification, AnInvariantCurveAboutTheCentreHasNoChain) {
  const MapParameters box{0.1, -0.8, 0.5};
  ChainRequest r;
  r.map = box;
  r.start = FixedPointMap(box).toUnit(-0.3L, 0);
  const ChainIdentification c = identifyChain(r);
  EXPECT_EQ(c.period, 1u);
  EXPECT_TRUE(c.factors.empty());
  ASSERT_EQ(c.levels.size(), 1u);
  EXPECT_EQ(c.summary.rfind("an invariant curve of rotation 0.19002", 0), 0u) << c.summary;
  r.start = FixedPointMap(box).toUnit(0.3L, 0.3L);
  EXPECT_EQ(identifyChain(r).summary.rfind("escaping", 0), 0u);
}

TEST(ChainIdentification, RejectsInvalidRequests) {
  ChainRequest r;
  r.map = {0.0, -0.8, 0.5};  // K = 0: the fixed point is parabolic
  EXPECT_THROW((void)identifyChain(r), std::invalid_argument);
  r.map = {1.2, -1.5, 0.5};  // K > 1: hyperbolic
  EXPECT_THROW((void)identifyChain(r), std::invalid_argument);
  r.map = {0.1, -0.8, 0.5};
  r.maxPeriod = 0;
  EXPECT_THROW((void)identifyChain(r), std::invalid_argument);
  r.maxPeriod = 100;
  r.maxLevels = -1;
  EXPECT_THROW((void)identifyChain(r), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago
