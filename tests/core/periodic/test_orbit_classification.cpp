// The one classification of periodic orbits by Greene's residue (core/periodic/OrbitClassification.hpp):
// each class at and around its boundaries R = 0 and R = 1, the linear rotation number cos 2πω = 1 − 2R, and
// the K = 0 fixed point that the CLI once called "hyperbolic with reflection" with rotation number "nan".

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/periodic/OrbitClassification.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "LongDoubleNear.hpp"

namespace archipelago {
namespace {

constexpr long double kEps = std::numeric_limits<long double>::epsilon();
constexpr long double kInf = std::numeric_limits<long double>::infinity();
constexpr long double kTiny = std::numeric_limits<long double>::denorm_min();

TEST(OrbitClassification, EachClassAtAndAroundTheBoundaries) {
  struct Case {
    long double R;
    OrbitStability stability;
    const char* description;
  };
  const Case table[] = {
      {-kInf, OrbitStability::Hyperbolic, "hyperbolic, R < 0"},
      {-1, OrbitStability::Hyperbolic, "hyperbolic, R < 0"},
      {-kTiny, OrbitStability::Hyperbolic, "hyperbolic, R < 0"},
      {0, OrbitStability::Parabolic, "parabolic, R = 0"},
      {-0.0L, OrbitStability::Parabolic, "parabolic, R = 0"},
      {kTiny, OrbitStability::Elliptic, "elliptic, 0 < R < 1"},
      {0.5L, OrbitStability::Elliptic, "elliptic, 0 < R < 1"},
      {1 - kEps / 2, OrbitStability::Elliptic, "elliptic, 0 < R < 1"},
      {1, OrbitStability::Parabolic, "parabolic, R = 1"},
      {1 + kEps, OrbitStability::HyperbolicReflection, "hyperbolic with reflection, R > 1"},
      {2, OrbitStability::HyperbolicReflection, "hyperbolic with reflection, R > 1"},
      {kInf, OrbitStability::HyperbolicReflection, "hyperbolic with reflection, R > 1"},
  };
  for (const Case& c : table) {
    const OrbitClassification k = classifyOrbit(c.R);
    EXPECT_EQ(k.stability, c.stability) << "R = " << static_cast<double>(c.R);
    EXPECT_STREQ(k.description(), c.description) << "R = " << static_cast<double>(c.R);
    EXPECT_EQ(k.stable(), c.stability == OrbitStability::Elliptic);
    // The rotation number exists exactly on 0 ≤ R ≤ 1.
    EXPECT_EQ(k.rotationNumber.has_value(), c.stability != OrbitStability::Hyperbolic &&
                                                c.stability != OrbitStability::HyperbolicReflection)
        << "R = " << static_cast<double>(c.R);
  }
  EXPECT_STREQ(toString(OrbitStability::Hyperbolic), "hyperbolic");
  EXPECT_STREQ(toString(OrbitStability::Parabolic), "parabolic");
  EXPECT_STREQ(toString(OrbitStability::Elliptic), "elliptic");
  EXPECT_STREQ(toString(OrbitStability::HyperbolicReflection), "hyperbolic with reflection");
}

TEST(OrbitClassification, RotationNumberFromTheResidue) {
  // cos 2πω = 1 − 2R: exact at the parabolic ends, the simple fractions in between, and R = sin²(πω).
  EXPECT_EQ(*classifyOrbit(0).rotationNumber, 0);
  EXPECT_EQ(*classifyOrbit(1).rotationNumber, 0.5L);
  const long double tolerance = 64 * kEps;
  EXPECT_TRUE(Near(*classifyOrbit(0.25L).rotationNumber, 1.0L / 6, tolerance));
  EXPECT_TRUE(Near(*classifyOrbit(0.5L).rotationNumber, 0.25L, tolerance));
  EXPECT_TRUE(Near(*classifyOrbit(0.75L).rotationNumber, 1.0L / 3, tolerance));
  for (long double R : {1e-30L, 1e-6L, 0.1L, 0.3162L, 0.9L, 1 - 1e-9L}) {
    const long double w = *classifyOrbit(R).rotationNumber;
    EXPECT_GT(w, 0);
    EXPECT_LT(w, 0.5L);
    const long double s = std::sin(std::numbers::pi_v<long double> * w);
    EXPECT_TRUE(Near(s * s, R, 64 * kEps)) << "R = " << static_cast<double>(R);
  }
  // Small R: ω ≈ √R/π, continuous down to the parabolic end.
  EXPECT_TRUE(Near(*classifyOrbit(1e-30L).rotationNumber, std::sqrt(1e-30L) / std::numbers::pi_v<long double>, 1e-30L));
}

TEST(OrbitClassification, NanHasNoClass) { EXPECT_THROW((void)classifyOrbit(std::nanl("")), std::invalid_argument); }

// Regression (issue #11 item 9): `archipelago-cli periodic --K 0 --period 1 --near=0,0` reported the fixed point
// x = y = 0 (R = 0, the tangent bifurcation of §2) as "hyperbolic with reflection, R >= 1" with rotation number
// "nan = 0/1".  It is parabolic, and its rotation number is 0 = 0/1.
TEST(OrbitClassification, KZeroFixedPointIsParabolicNotHyperbolicWithReflection) {
  PeriodicOrbitSearch search;
  search.period = 1;
  search.near = {0, 0};
  const PeriodicOrbit orbit = findPeriodicOrbit(0, search);
  EXPECT_EQ(orbit.residue, 0);
  EXPECT_EQ(orbit.classification().stability, OrbitStability::Parabolic);
  EXPECT_FALSE(orbit.stable());
  const std::string text = rotationNumberText(orbit);
  EXPECT_EQ(text, "0 = 0/1 (linear, at the central fixed point)");
  EXPECT_EQ(text.find("nan"), std::string::npos);
}

TEST(OrbitClassification, CentralFixedPointRotationText) {
  // K = 0.1: R = √K, elliptic, ω₀ = arccos(1 − 2√K)/2π.
  const long double K = 0.1L, rootK = std::sqrt(K);
  const PeriodicOrbit elliptic = analysePeriodicOrbit(K, 1, -rootK, 0, OrbitSymmetry::LineS2);
  EXPECT_EQ(elliptic.classification().stability, OrbitStability::Elliptic);
  EXPECT_TRUE(Near(elliptic.rotationNumber, std::acos(1 - 2 * rootK) / (2 * std::numbers::pi_v<long double>), 1e-15L));
  EXPECT_NE(rotationNumberText(elliptic).find("(linear, at the central fixed point)"), std::string::npos);
  // K = 1.44: the "centre" (−1.2, 0) has R = 1.2 > 1: hyperbolic with reflection, and no rotation number.
  const PeriodicOrbit reflected = analysePeriodicOrbit(1.44L, 1, -1.2L, 0, OrbitSymmetry::LineS2);
  EXPECT_EQ(reflected.classification().stability, OrbitStability::HyperbolicReflection);
  EXPECT_EQ(rotationNumberText(reflected), "none (hyperbolic fixed point: nearby orbits do not turn about it)");
  // Away from the centre: the winding fraction (the six-island chain turns once in six steps).
  PeriodicOrbitSearch six;
  six.period = 6;
  six.near = {0.0509L, 0.0974L};
  six.stableOnly = true;
  const std::string sixText = rotationNumberText(findPeriodicOrbit(K, six), 6);
  EXPECT_EQ(sixText, "0.166667 = 1/6 = 1/6 (clockwise turns about (−√K, 0) per step)");
}

}  // namespace
}  // namespace archipelago
