// The numbers of Karney (1983) §2 and §4 (core/theory/PaperNumbers.hpp, and the ones that live in
// SmallKTheory.hpp): each against the paper's text and against an independent computation done here — the
// Jacobian of Q by finite differences, quadrature of the trapping-time integral, the period-2 orbit in closed
// form, the periodic-orbit finder's rotation number, and the scaling argument of §4.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/theory/PaperNumbers.hpp"
#include "core/theory/SmallKTheory.hpp"

namespace archipelago::paper {
namespace {

struct Point {
  long double x, y;
};

// Q of eq. (qu), written out here: y' = y + 2(x² − K), x' = x + y'.
Point stepQ(long double K, Point z) {
  const long double y = z.y + 2 * (z.x * z.x - K);
  return {z.x + y, y};
}

// DQ at z by central differences (Q is quadratic, so they are exact up to rounding): {trace, determinant}.
struct Linearisation {
  long double trace, determinant;
};
Linearisation linearise(long double K, Point z) {
  const long double h = 1e-6L;
  const Point xp = stepQ(K, {z.x + h, z.y}), xm = stepQ(K, {z.x - h, z.y});
  const Point yp = stepQ(K, {z.x, z.y + h}), ym = stepQ(K, {z.x, z.y - h});
  const long double a = (xp.x - xm.x) / (2 * h), b = (yp.x - ym.x) / (2 * h);
  const long double c = (xp.y - xm.y) / (2 * h), d = (yp.y - ym.y) / (2 * h);
  return {a + d, a * d - b * c};
}

// ---------------------------------------------------------------------------------------------------------
// §2: the elliptic fixed point

TEST(PaperNumbers, RotationAtTheEllipticFixedPointIsTheLinearisations) {
  // §2: cos α = 1 − 2√K (Hénon's parameter); the eigenvalues of DQ at (−√K, 0) are e^(±iα), so trace = 2 cos α.
  for (double K : {1e-4, 0.01, 0.1, 0.3, 0.5, 0.9, 1.0}) {
    const Point centre{-std::sqrt(static_cast<long double>(K)), 0};
    const Point image = stepQ(K, centre);
    EXPECT_NEAR(static_cast<double>(image.x - centre.x), 0, 1e-18) << K;
    EXPECT_NEAR(static_cast<double>(image.y - centre.y), 0, 1e-18) << K;
    const Linearisation L = linearise(K, centre);
    EXPECT_NEAR(static_cast<double>(L.determinant), 1, 1e-9) << K;
    EXPECT_NEAR(ellipticRotationCosine(K), static_cast<double>(L.trace / 2), 1e-9) << K;
    EXPECT_NEAR(ellipticFixedPointResidue(K), static_cast<double>((2 - L.trace) / 4), 1e-9) << K;
  }
  EXPECT_EQ(ellipticRotationCosine(0.25), 0.0);  // α = 90° at K = 1/4
  EXPECT_EQ(ellipticRotationCosine(1.0), -1.0);  // α = 180°: the period doubling
  EXPECT_TRUE(std::isnan(ellipticRotationCosine(-0.1)));
  EXPECT_TRUE(std::isnan(ellipticRotationCosine(1.1)));
}

TEST(PaperNumbers, PeriodOneOrbitRotationNumberGivesCosAlpha) {
  // The periodic-orbit finder's period-1 orbit at (−√K, 0) and its rotation number ω: cos 2πω = 1 − 2√K.
  for (long double K : {0.1L, 0.3L, 0.5L}) {
    PeriodicOrbitSearch search;
    search.period = 1;
    search.near = {-std::sqrt(K) + 1e-3L, 1e-3L};
    const PeriodicOrbit orbit = findPeriodicOrbit(K, search);
    ASSERT_EQ(orbit.period, 1);
    EXPECT_NEAR(static_cast<double>(orbit.points.front().x), -std::sqrt(static_cast<double>(K)), 1e-15);
    const double omega = static_cast<double>(orbit.rotationNumber);
    EXPECT_NEAR(std::cos(2 * std::numbers::pi * omega), ellipticRotationCosine(static_cast<double>(K)), 1e-14)
        << static_cast<double>(K);
    EXPECT_NEAR(static_cast<double>(orbit.residue), ellipticFixedPointResidue(static_cast<double>(K)), 1e-15);
  }
}

// ---------------------------------------------------------------------------------------------------------
// §4: the hyperbolic fixed point and the decay rates

TEST(PaperNumbers, LyapunovNumberIsTheJacobiansEigenvalueAtTheHyperbolicPoint) {
  // §4: λ = 1 + 2√K + 2√(√K + K) at (√K, 0) (the paper prints "(0, √K)"): the larger root of
  // λ² − trace λ + 1 = 0 with the finite-difference trace.
  for (double K : {1e-6, 1e-4, 1e-3, 1e-2, 0.1, 0.5}) {
    const Point saddle{std::sqrt(static_cast<long double>(K)), 0};
    const Linearisation L = linearise(K, saddle);
    const long double eigenvalue = (L.trace + std::sqrt(L.trace * L.trace - 4 * L.determinant)) / 2;
    EXPECT_NEAR(smallk::positiveKLyapunovNumber(K), static_cast<double>(eigenvalue), 1e-9) << K;
    EXPECT_NEAR(hyperbolicFixedPointResidue(K), static_cast<double>((2 - L.trace) / 4), 1e-9) << K;
  }
  // The small-K limit λ ≈ 1 + 2K^(1/4): λ − 1 − 2K^(1/4) = 2√K + K^(3/4) + O(K^(5/4)) ≤ 3√K.
  for (double K : {1e-16, 1e-12, 1e-8, 1e-4, 1e-2}) {
    const double exact = smallk::positiveKLyapunovNumber(K), limit = smallKLyapunovNumber(K);
    EXPECT_GT(exact, limit) << K;
    EXPECT_LE(exact - limit, 3 * std::sqrt(K)) << K;
  }
  EXPECT_EQ(smallKLyapunovNumber(1e-4), 1.2);
}

TEST(PaperNumbers, DecayRatesAtKOneThousandthAndOneHundredth) {
  // Issue 14 quotes the theory as 0.177 (K = 1e-3) and 0.311 (K = 1e-2).  These are ½ log λ with the exact λ;
  // the small-K form K^(1/4) gives 0.1778 and 0.3162, which do not round to them.
  EXPECT_NEAR(smallk::positiveKDecayRate(1e-3), 0.177, 5e-4);
  EXPECT_NEAR(smallk::positiveKDecayRate(1e-2), 0.311, 5e-4);
  EXPECT_GT(std::fabs(std::pow(1e-3, 0.25) - 0.177), 5e-4);
  EXPECT_GT(std::fabs(std::pow(1e-2, 0.25) - 0.311), 5e-4);
  // And §4: "for K = 10⁻⁴ the decay rate should be about 0.1".
  EXPECT_NEAR(smallk::positiveKDecayRate(1e-4), 0.1, 1e-3);
}

TEST(PaperNumbers, SegmentDecayExponentFollowsTheScalingArgument) {
  // §4 with g(x) = x^m: dY/dT = X^m, dX/dT = Y, so Y ~ X^((m+1)/2), the trapping time T ~ X0^(−(m−1)/2), the
  // area A ~ X0·Y ~ X0^((m+3)/2) ~ T^(−(m+3)/(m−1)); f_t ~ (1/T) dA/dT ~ T^(−(m+3)/(m−1) − 2).
  for (int m = 2; m <= 12; ++m) {
    const double scaling = static_cast<double>(m + 3) / (m - 1) + 2;
    EXPECT_NEAR(segmentDecayExponent(m), scaling, 1e-14) << m;
  }
  EXPECT_EQ(segmentDecayExponent(2), 7.0);  // §4: f_t ~ t⁻⁷ at K = 0
  EXPECT_EQ(segmentDecayExponent(3), 5.0);
  EXPECT_NEAR(segmentDecayExponent(1e9), 3, 1e-8);
  EXPECT_TRUE(std::isnan(segmentDecayExponent(1)));
}

// T(X0) = 2∫_{X0}^∞ dX / √(4(X³ − X0³)/3) by quadrature: X = X0 + u² (X³ − X0³ = u²(X² + X X0 + X0²)), then
// u = tan θ and the midpoint rule on θ ∈ (0, π/2), whose integrand is smooth up to both ends.
double zeroKTrappingTimeByQuadrature(double X0) {
  const long double x0 = X0;
  const int points = 20000;
  const long double h = std::numbers::pi_v<long double> / 2 / points;
  long double sum = 0;
  for (int i = 0; i < points; ++i) {
    const long double theta = (i + 0.5L) * h, u = std::tan(theta), c = std::cos(theta);
    const long double X = x0 + u * u;
    sum += 4 / std::sqrt(4 * (X * X + X * x0 + x0 * x0) / 3) / (c * c);
  }
  return static_cast<double>(sum * h);
}

TEST(PaperNumbers, ZeroKTrappingTimeBranches) {
  // §4 prints T(X0) = {1 over √3} × 4.207 |X0|^(−1/2) for X ≷ 0.  Quadrature decides the branches: the factor
  // 1 belongs to X0 > 0 and √3 to X0 < 0 (by X = |X0|v: √3 ∫₁^∞ dv/√(v³ − 1) against √3 ∫₋₁^∞ dv/√(v³ + 1)).
  EXPECT_NEAR(zeroKTrappingTimeByQuadrature(1), 4.207, 5e-4);
  EXPECT_NEAR(zeroKTrappingTimeByQuadrature(-1), std::sqrt(3.0) * 4.207, 5e-4 * std::sqrt(3.0));
  for (double X0 : {0.25, 1.0, 4.0, 30.0}) {
    const double positive = zeroKTrappingTimeByQuadrature(X0), negative = zeroKTrappingTimeByQuadrature(-X0);
    EXPECT_NEAR(smallk::zeroKTrappingTime(X0), positive, 1e-10 * positive) << X0;
    EXPECT_NEAR(smallk::zeroKTrappingTime(-X0), negative, 1e-10 * negative) << X0;
    EXPECT_NEAR(negative / positive, std::sqrt(3.0), 1e-10) << X0;
  }
}

// ---------------------------------------------------------------------------------------------------------
// §2: the period doublings

TEST(PaperNumbers, FirstTwoPeriodDoublingsInClosedForm) {
  // K₀ = 1: the fixed point's residue √K reaches 1.
  EXPECT_EQ(ellipticFixedPointResidue(kFirstPeriodDoubling), 1.0);
  // K₁ = 5/4: the period-2 orbit x₁,₂ = −1 ∓ √(K − 1), y = ±(x₁ − x₂); its trace of DQ² from the
  // finite-difference Jacobians, and the finder's orbit and residue at the same K.
  for (long double K : {1.05L, 1.1L, 1.2L, 1.25L, 1.3L}) {
    const long double s = std::sqrt(K - 1);
    const Point z1{-1 - s, -2 * s}, z2{-1 + s, 2 * s};
    const Point image = stepQ(K, z1), back = stepQ(K, image);
    EXPECT_NEAR(static_cast<double>(image.x - z2.x) + static_cast<double>(image.y - z2.y), 0, 1e-17);
    EXPECT_NEAR(static_cast<double>(back.x - z1.x) + static_cast<double>(back.y - z1.y), 0, 1e-17);
    // DQ(z) = [[1 + 4x, 1], [4x, 1]] at both points: trace(DQ(z2) DQ(z1)).
    const long double a1 = 1 + 4 * z1.x, c1 = 4 * z1.x, a2 = 1 + 4 * z2.x, c2 = 4 * z2.x;
    const long double trace = a2 * a1 + c1 + c2 + 1;
    const double residue = static_cast<double>((2 - trace) / 4);
    EXPECT_NEAR(residue, 4 * static_cast<double>(K - 1), 1e-15);
    PeriodicOrbitSearch search;
    search.period = 2;
    search.near = {static_cast<long double>(z1.x), static_cast<long double>(z1.y)};
    const PeriodicOrbit orbit = findPeriodicOrbit(K, search);
    EXPECT_NEAR(static_cast<double>(orbit.residue), residue, 1e-14) << static_cast<double>(K);
  }
  EXPECT_EQ(4 * (kSecondPeriodDoubling - 1), 1.0);
}

TEST(PaperNumbers, PeriodDoublingCascadeAccumulatesAtThePapersK) {
  // §2: "At K = 1.2840 the period-doubling sequence accumulates".  K_n for periods 1 … 64 and the geometric
  // extrapolation K_∞ = K_n + (K_n − K_{n−1})/(δ_n − 1).  Tolerances: the paper's 4 decimals (±5e-5), plus
  // 10× the change of the extrapolation from its previous level (3e-8 at n = 5, 6e-10 at n = 6, so the
  // extrapolation error is far below the paper's rounding).  The ratios δ_n approach the area-preserving
  // Feigenbaum constant 8.7210972 (Greene, MacKay, Vivaldi & Stark 1981; Bountis 1981): their errors fall by
  // ~6–10× per level (−0.42, −0.063, −0.0055, −0.0008 at n = 2 … 5), so δ₆ is within 2e-4.
  const PeriodDoublingCascade c = periodDoublingCascade(7);
  ASSERT_EQ(c.bifurcations.size(), 7u);
  EXPECT_EQ(c.bifurcations[0], 1.0);
  EXPECT_EQ(c.bifurcations[1], 1.25);
  for (std::size_t n = 1; n < c.bifurcations.size(); ++n) EXPECT_GT(c.bifurcations[n], c.bifurcations[n - 1]);
  ASSERT_EQ(c.ratios.size(), 5u);
  EXPECT_NEAR(c.ratios.back(), 8.7210972, 2e-4);
  for (std::size_t i = 1; i < c.ratios.size(); ++i)
    EXPECT_LT(std::fabs(c.ratios[i] - 8.7210972), std::fabs(c.ratios[i - 1] - 8.7210972));
  EXPECT_LT(c.accumulationChange, 1e-8);
  EXPECT_NEAR(c.accumulation, 1.2840, 5e-5 + 10 * c.accumulationChange);
  // At each K_n the period-2ⁿ orbit's residue crosses 1: check K_2 with the finder on both sides.
  for (double dK : {-1e-9, 1e-9}) {
    PeriodicOrbitSearch search;
    search.period = 4;
    search.near = {-1.5L, -1.0L};
    search.searchRadius = 0.2L;
    search.stableOnly = dK < 0;
    const auto orbits = findSymmetricPeriodicOrbits(c.bifurcations[2] + dK, search);
    bool crossing = false;
    for (const PeriodicOrbit& o : orbits) crossing = crossing || std::fabs(static_cast<double>(o.residue) - 1) < 1e-6;
    EXPECT_TRUE(crossing) << dK;
  }
  EXPECT_THROW((void)periodDoublingCascade(2), std::invalid_argument);
  EXPECT_THROW((void)periodDoublingCascade(8), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago::paper
