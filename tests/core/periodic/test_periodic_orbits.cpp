// Periodic orbits of Q (core/periodic): the map's reversibility, residues, rotation numbers, the chains of
// Karney (1983) §6 at K = 0.1 (6 islands; 6 × 23 = 138 around them).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"
#include "LongDoubleNear.hpp"

namespace archipelago {
namespace {

using P = smooth::Point<long double>;

TEST(SmoothQuadraticMap, InvolutionsComposeToQAndAreTheirOwnInverses) {
  // Q = I₂ ∘ I₁ with I₁(x, y) = (x, −y − g(x)), I₂(x, y) = (x − y, −y)   (SmoothQuadraticMap.hpp)
  const long double K = 0.1L;
  auto I1 = [&](P z) { return P{z.x, -z.y - smooth::kick(K, z.x)}; };
  auto I2 = [](P z) { return P{z.x - z.y, -z.y}; };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int i = 0; i < 1000; ++i) {
    const P z{u(rng), u(rng)};
    const P q = smooth::step(K, z), viaInvolutions = I2(I1(z));
    EXPECT_TRUE(Near(q.x, viaInvolutions.x, 1e-18L));
    EXPECT_TRUE(Near(q.y, viaInvolutions.y, 1e-18L));
    EXPECT_TRUE(Near(I1(I1(z)).y, z.y, 1e-18L));
    EXPECT_EQ(I2(I2(z)).y, z.y);
    EXPECT_TRUE(Near(I2(I2(z)).x, z.x, 1e-18L));
    const P back = smooth::inverseStep(K, q);
    EXPECT_TRUE(Near(back.x, z.x, 1e-18L));
    EXPECT_TRUE(Near(back.y, z.y, 1e-18L));
    const auto d = smooth::jacobian(z);
    EXPECT_TRUE(Near(d.xx * d.yy - d.xy * d.yx, 1.0L, 1e-18L));  // area-preserving
    // The lines are the fixed sets.
    const P s1 = smooth::onLine(smooth::SymmetryLine::S1, K, z.x), s2 = smooth::onLine(smooth::SymmetryLine::S2, K, z.x);
    EXPECT_TRUE(Near(I1(s1).y, s1.y, 1e-18L));
    EXPECT_EQ(I2(s2).x, s2.x);
  }
}

TEST(PeriodicOrbit, CentralFixedPointHasResidueRootK) {
  // trace DQ at (−√K, 0) is 2 + 4x = 2 − 4√K, so R = (2 − trace)/4 = √K; cos 2πω₀ = 1 − 2R.
  for (long double K : {0.01L, 0.1L, 0.25L, 0.5L}) {
    SCOPED_TRACE(static_cast<double>(K));
    PeriodicOrbitSearch search;
    search.period = 1;
    search.near = {-std::sqrt(K) + 0.01L, 0.005L};
    search.stableOnly = true;
    const PeriodicOrbit o = findPeriodicOrbit(K, search);
    ASSERT_EQ(o.points.size(), 1u);
    EXPECT_TRUE(Near(o.points[0].x, -std::sqrt(K), 1e-18L));
    EXPECT_TRUE(Near(o.points[0].y, 0.0L, 1e-18L));
    EXPECT_TRUE(Near(o.residue, std::sqrt(K), 1e-18L));
    EXPECT_TRUE(Near(o.trace, 2 - 4 * std::sqrt(K), 1e-18L));
    EXPECT_TRUE(o.stable());
    EXPECT_TRUE(Near(o.rotationNumber, std::acos(1 - 2 * std::sqrt(K)) / (2 * std::numbers::pi_v<long double>), 1e-15L));
  }
  // The other fixed point (√K, 0) is hyperbolic: R = −√K.
  PeriodicOrbitSearch search;
  search.period = 1;
  search.near = {0.3L, 0};
  const PeriodicOrbit h = findPeriodicOrbit(0.1L, search);
  EXPECT_TRUE(Near(h.points[0].x, std::sqrt(0.1L), 1e-18L));
  EXPECT_TRUE(Near(h.residue, -std::sqrt(0.1L), 1e-18L));
  EXPECT_FALSE(h.stable());
}

TEST(PeriodicOrbit, SixIslandChainAtKPointOne) {
  // The elliptic period-6 orbit at the centres of the six islands around the central island (§5, fig. 2).
  const long double K = 0.1L;
  PeriodicOrbitSearch search;
  search.period = 6;
  search.near = {0.05L, 0.1L};
  search.searchRadius = 0.1L;
  const std::vector<PeriodicOrbit> all = findSymmetricPeriodicOrbits(K, search);
  ASSERT_GE(all.size(), 2u);  // the elliptic orbit and the hyperbolic one between the islands
  search.stableOnly = true;
  search.searchRadius = 0.02L;
  const PeriodicOrbit e = findPeriodicOrbit(K, search);
  EXPECT_EQ(e.period, 6);
  EXPECT_GT(e.residue, 0);
  EXPECT_LT(e.residue, 1);
  EXPECT_TRUE(Near(e.residue, 0.1482764292L, 1e-9L));  // regression value of this code (quad precision)
  EXPECT_EQ(e.windingTurns, 1);
  EXPECT_TRUE(Near(e.rotationNumber, 1.0L / 6, 1e-18L));
  EXPECT_LT(e.closure, 1e-25L);
  EXPECT_EQ(e.symmetry, OrbitSymmetry::LineS1);
  EXPECT_TRUE(Near(e.points[0].x, 0.0509024128L, 1e-9L));
  EXPECT_TRUE(Near(e.points[0].y, 0.0974089444L, 1e-9L));
  EXPECT_TRUE(e.insideBox(MapParameters{}));
  for (int k = 0; k < 6; ++k) {  // consecutive points are images under Q
    const P next = smooth::step(K, P{e.points[k].x, e.points[k].y});
    EXPECT_TRUE(Near(next.x, e.points[(k + 1) % 6].x, 1e-17L));
    EXPECT_TRUE(Near(next.y, e.points[(k + 1) % 6].y, 1e-17L));
  }
  // The hyperbolic partner lies on S₂ (y = 0) at x ≈ 0.0157 and has R < 0.
  search.stableOnly = false;
  search.near = {0.0157L, 0};
  const PeriodicOrbit h = findPeriodicOrbit(K, search);
  EXPECT_LT(h.residue, 0);
  EXPECT_EQ(h.symmetry, OrbitSymmetry::LineS2);
  EXPECT_EQ(h.windingTurns, 1);
}

TEST(PeriodicOrbit, ResidueAgreesWithFiniteDifferencesOfQn) {
  // Independent of the Jacobian product: trace DQ⁶ by central differences of Q⁶ in quad precision.
  const long double K = 0.1L;
  PeriodicOrbitSearch search;
  search.period = 6;
  search.near = {0.05L, 0.1L};
  search.stableOnly = true;
  const PeriodicOrbit e = findPeriodicOrbit(K, search);
  const quad h = 1e-12L, k = K, x = e.points[0].x, y = e.points[0].y;
  auto Qn = [&](quad a, quad b) { return smooth::iterate(k, smooth::Point<quad>{a, b}, 6); };
  const quad dxdx = (Qn(x + h, y).x - Qn(x - h, y).x) / (2 * h);
  const quad dydy = (Qn(x, y + h).y - Qn(x, y - h).y) / (2 * h);
  EXPECT_TRUE(Near(static_cast<long double>((2 - dxdx - dydy) / 4), e.residue, 1e-9L));
}

TEST(PeriodicOrbit, Period138ChainAroundTheSixIslands) {
  // §6: the longest segment at K = 0.1 sticks to a chain of order 6 × 23 = 138, one member near
  // x + √K ≈ 0.352, y ≈ 0.034.
  const long double K = 0.1L;
  PeriodicOrbitSearch search;
  search.period = 138;
  search.near = {0.0358L, 0.034L};
  search.stableOnly = true;
  const PeriodicOrbit o = findPeriodicOrbit(K, search);
  EXPECT_EQ(o.period, 138);
  ASSERT_EQ(o.points.size(), 138u);
  // The paper's position of the member is a statement of the paper's table: tests/paper checks it.  These are
  // regression pins of this finder's own earlier result (not a reference), guarding its convergence.
  EXPECT_TRUE(Near(o.points[0].x, 0.036028653309L, 1e-11L));
  EXPECT_TRUE(Near(o.points[0].y, 0.034180912451L, 1e-11L));
  EXPECT_TRUE(o.stable());
  EXPECT_TRUE(Near(o.residue, 0.6890952616L, 1e-8L));
  EXPECT_EQ(o.windingTurns, 23);  // 23 turns about the centre in 138 steps: ω = 1/6, with the six islands
  EXPECT_TRUE(Near(o.rotationNumber, 1.0L / 6, 1e-18L));
  EXPECT_LT(o.closure, 1e-20L);
  EXPECT_TRUE(o.insideBox(MapParameters{}));
  // It follows the six islands: z_k is nearest to island (j₀ + k) mod 6 of the elliptic period-6 orbit.
  search.period = 6;
  search.near = {0.05L, 0.1L};
  const PeriodicOrbit six = findPeriodicOrbit(K, search);
  const std::size_t j0 = six.nearestIndex(o.points[0]);
  for (std::size_t k = 0; k < o.points.size(); ++k) EXPECT_EQ(six.nearestIndex(o.points[k]), (j0 + k) % 6) << k;

  // The general two-dimensional Newton method converges back to it from a perturbed guess.
  const std::optional<PeriodicOrbit> refined =
      refinePeriodicOrbit(K, 138, {o.points[0].x + 1e-7L, o.points[0].y - 1e-7L});
  ASSERT_TRUE(refined.has_value());
  EXPECT_TRUE(Near(refined->points[0].x, o.points[0].x, 1e-16L));
  EXPECT_TRUE(Near(refined->points[0].y, o.points[0].y, 1e-16L));
  EXPECT_TRUE(Near(refined->residue, o.residue, 1e-12L));
  EXPECT_EQ(refined->symmetry, OrbitSymmetry::None);
}

TEST(PeriodicOrbit, OddPeriodPairBetweenCentreAndSixChain) {
  // Odd periods shoot from S₂ to S₁ (SmoothQuadraticMap.hpp).  Period 11, W = 2 (ω = 2/11 between ω₀ ≈ 0.19
  // at the centre and 1/6 at the six islands): an elliptic and a hyperbolic orbit with R ≈ ±4e-4.
  PeriodicOrbitSearch search;
  search.period = 11;
  search.near = {-0.15L, 0};
  search.searchRadius = 0.1L;
  const std::vector<PeriodicOrbit> orbits = findSymmetricPeriodicOrbits(0.1L, search);
  ASSERT_GE(orbits.size(), 2u);
  int stable = 0, unstable = 0;
  for (const PeriodicOrbit& o : orbits) {
    EXPECT_EQ(o.windingTurns, 2);
    EXPECT_LT(std::fabs(o.residue), 1e-3L);
    (o.stable() ? stable : unstable) += 1;
  }
  EXPECT_GE(stable, 1);
  EXPECT_GE(unstable, 1);
}

TEST(PeriodicOrbit, GeneralNewtonFindsTheSixChainFromARoughGuess) {
  const std::optional<PeriodicOrbit> o = refinePeriodicOrbit(0.1L, 6, {0.052L, 0.096L});
  ASSERT_TRUE(o.has_value());
  EXPECT_TRUE(Near(o->residue, 0.1482764292L, 1e-9L));
  EXPECT_EQ(o->windingTurns, 1);
  // Converging to the fixed point would be a smaller period: refused.
  EXPECT_FALSE(refinePeriodicOrbit(0.1L, 6, {-0.3162L, 0.0L}).has_value());
}

TEST(PeriodicOrbit, BadInputAndNoOrbitGiveClearErrors) {
  PeriodicOrbitSearch search;
  search.period = 0;
  EXPECT_THROW(validate(0.1L, search), std::invalid_argument);
  search.period = 6;
  EXPECT_THROW(validate(std::nanl(""), search), std::invalid_argument);
  search.searchRadius = -1;
  EXPECT_THROW(validate(0.1L, search), std::invalid_argument);
  search.searchRadius = 0.001L;
  search.near = {5, 5};  // escapes to infinity: no orbit there
  try {
    (void)findPeriodicOrbit(0.1L, search);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no periodic orbit of period 6"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace archipelago
