// Primary homoclinic points (core/manifolds/HomoclinicPoints.hpp), checked against computations that do not use the
// manifolds' parameterization: the escape side of orbits started on the symmetry lines, and actions summed along
// orbits iterated directly with Q and Q⁻¹.
#include <gtest/gtest.h>

#include <cmath>

#include "core/manifolds/GeneratingFunction.hpp"
#include "core/manifolds/HomoclinicPoints.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {
namespace {

using P = smooth::Point<quad>;
using smooth::SymmetryLine;

struct Manifolds {
  HyperbolicOrbit orbit;
  ManifoldParameterization unstable, stable;
  explicit Manifolds(HyperbolicOrbit o)
      : orbit(o), unstable(o, ManifoldKind::Unstable), stable(o, ManifoldKind::Stable) {}
};

/// Which way the orbit of the point of `line` at abscissa x leaves the hyperbolic point (√K, 0) after approaching it:
/// +1 to the right (x > √K: off to infinity), −1 to the left (back into the loop), 0 undecided.  A homoclinic point on
/// the line is where this flips (the orbit approaches along W^s and leaves along one branch of W^u or the other).
int escapeSide(quad K, SymmetryLine line, quad x) {
  const quad r = smooth::squareRoot(K);
  P z = smooth::onLine(line, K, x);
  bool approached = false;
  for (int step = 0; step < 400; ++step) {
    z = smooth::step(K, z);
    const quad d = z.x - r;
    if (!approached && smooth::absolute(d) + smooth::absolute(z.y) < quad(0.05L) * r) approached = true;
    if (approached && smooth::absolute(d) > quad(0.2L) * r) return d > 0 ? 1 : -1;
  }
  return 0;
}

/// The flip of escapeSide along `line` in [a, b], by bisection in quad: independent of the parameterization.
quad bisectEscape(quad K, SymmetryLine line, quad a, quad b) {
  const int sa = escapeSide(K, line, a);
  for (int i = 0; i < 200 && b - a > quad(1e-32L); ++i) {
    const quad m = (a + b) / 2;
    if (escapeSide(K, line, m) == sa) a = m;
    else b = m;
  }
  return (a + b) / 2;
}

TEST(HomoclinicPoints, FixedPointPrimaryPointsAreOnTheSymmetryLinesNearTheTip) {
  for (long double K : {0.05L, 0.1L, 0.2L}) {
    const Manifolds m(hyperbolicFixedPoint(K));
    const PrimaryIntersections p = primaryHeteroclinicPoints(m.unstable, m.stable, BranchSide::Inward);
    // h on S₁ first, then h' on S₂ (the classical pair; the tip of the continuum loop is (−2√K, 0), eq. hamb).
    EXPECT_EQ(p.first.line, SymmetryLine::S1);
    EXPECT_EQ(p.second.line, SymmetryLine::S2);
    EXPECT_EQ(p.first.target, 0);
    for (const HeteroclinicPoint* h : {&p.first, &p.second}) {
      EXPECT_LE(static_cast<long double>(smooth::absolute(smooth::offsetFromLine(h->line, quad(K), h->point))), 1e-30L);
      EXPECT_LE(static_cast<long double>(h->mismatch), 1e-30L);  // W^u and W^s meet there
      EXPECT_NEAR(static_cast<double>(h->point.x) / std::sqrt(static_cast<double>(K)), -2, 0.5);
    }
    // Consecutive along W^u: |σ_h| < |σ_h'| < λ|σ_h|.
    EXPECT_LT(smooth::absolute(p.first.sigma), smooth::absolute(p.second.sigma));
    EXPECT_LT(smooth::absolute(p.second.sigma), m.orbit.multiplier * smooth::absolute(p.first.sigma));
  }
}

// The escape side flips exactly at the homoclinic points: found by bisection with Q alone.  Tolerance: the bisection
// stops at 1e−32 and the escape is decided after ~40 steps, where quad's rounding (1e−34) has grown by λ^40 ≈ 1e18
// relative to the distance from W^s: the flip is located to ~1e−28.
TEST(HomoclinicPoints, AgreeWithTheEscapeSideBisection) {
  for (long double K : {0.05L, 0.1L, 0.2L}) {
    const Manifolds m(hyperbolicFixedPoint(K));
    const PrimaryIntersections p = primaryHeteroclinicPoints(m.unstable, m.stable, BranchSide::Inward);
    for (const HeteroclinicPoint* h : {&p.first, &p.second}) {
      const quad x = h->point.x, w = quad(1e-6L);
      ASSERT_NE(escapeSide(quad(K), h->line, x - w), escapeSide(quad(K), h->line, x + w));
      const quad flip = bisectEscape(quad(K), h->line, x - w, x + w);
      EXPECT_LE(static_cast<long double>(smooth::absolute(flip - x)), 1e-26L) << "K " << static_cast<double>(K);
    }
  }
}

/// ΔW(h) by iterating Q forward and Q⁻¹ backward from h in quad, `steps` each way (independent of the
/// parameterization: only h itself comes from it).
quad directAction(quad K, P h, int steps) {
  const quad r = smooth::squareRoot(K);
  const quad reference = generatingFunction(K, r, r);
  quad sum = 0;
  P z = h;
  for (int t = 0; t < steps; ++t) {
    const P next = smooth::step(K, z);
    sum += generatingFunction(K, z.x, next.x) - reference;
    z = next;
  }
  z = h;
  for (int t = 0; t < steps; ++t) {
    const P previous = smooth::inverseStep(K, z);
    sum += generatingFunction(K, previous.x, z.x) - reference;
    z = previous;
  }
  return sum;
}

// The summands are O(λ^{−2|t|}) while iterating amplifies h's distance from W^s (≤ 1e−33) like λ^{|t|}: with
// |t| ≤ T = 0.45 ln(1e33)/ln λ steps each way the orbit is still within 1e−18 of the true one at distance λ^{−T} ≈ 1e−15
// from (√K, 0), and the omitted tail is ~λ^{−2T} ≈ 1e−30.  The parameterized sum runs to 1e−40: they must agree
// to 1e−24.
TEST(HomoclinicPoints, ActionsAgreeWithDirectIteration) {
  for (long double K : {0.05L, 0.1L, 0.2L}) {
    const Manifolds m(hyperbolicFixedPoint(K));
    const PrimaryIntersections p = primaryHeteroclinicPoints(m.unstable, m.stable, BranchSide::Inward);
    const int steps = static_cast<int>(0.45L * std::log(1e33L) / std::log(static_cast<long double>(m.orbit.multiplier)));
    for (const HeteroclinicPoint* h : {&p.first, &p.second})
      EXPECT_LE(static_cast<long double>(smooth::absolute(h->action - directAction(quad(K), h->point, steps))), 1e-24L)
          << "K " << static_cast<double>(K);
  }
}

// The orbit of a homoclinic point converges to (√K, 0) both ways, like λ^{−|t|}.
TEST(HomoclinicPoints, OrbitIsHomoclinic) {
  const Manifolds m(hyperbolicFixedPoint(0.1L));
  const PrimaryIntersections p = primaryHeteroclinicPoints(m.unstable, m.stable, BranchSide::Inward);
  const std::vector<P> orbit = heteroclinicOrbit(m.unstable, m.stable, p.first, 40, 40);
  const P z = m.orbit.points[0];
  auto distance = [&](const P& a) {
    return static_cast<long double>(smooth::squareRoot((a.x - z.x) * (a.x - z.x) + (a.y - z.y) * (a.y - z.y)));
  };
  EXPECT_LE(distance(orbit.front()), 1e-15L);
  EXPECT_LE(distance(orbit.back()), 1e-15L);
  for (std::size_t t = 1; t < orbit.size(); ++t) {  // consecutive points are images under Q
    const P image = smooth::step(quad(0.1L), orbit[t - 1]);
    EXPECT_LE(static_cast<long double>(smooth::absolute(image.x - orbit[t].x) + smooth::absolute(image.y - orbit[t].y)), 1e-30L);
  }
}

// The period-6 chain's outer separatrix: two primary heteroclinic orbits from z_0 to the same neighbour z_b; every
// crossing lies on its line and both manifolds meet there.
TEST(HomoclinicPoints, PeriodSixChainHasTwoPrimaryHeteroclinicOrbits) {
  PeriodicOrbitSearch s;
  s.period = 6;
  s.near = {0.0157L, 0};
  const Manifolds m(hyperbolicOrbitOf(findPeriodicOrbit(0.1L, s)));
  for (BranchSide side : {BranchSide::Outward, BranchSide::Inward}) {
    const PrimaryIntersections p = primaryHeteroclinicPoints(m.unstable, m.stable, side);
    EXPECT_EQ(p.first.target, p.second.target);
    EXPECT_NE(p.first.target, 0);  // heteroclinic: to a neighbour
    for (const HeteroclinicPoint& h : p.crossings) EXPECT_LE(static_cast<long double>(h.mismatch), 1e-29L);
    // The carried points lie on the line after `symmetricIndex` steps.
    for (const HeteroclinicPoint* h : {&p.first, &p.second}) {
      P z = h->point;
      for (int i = 0; i < h->symmetricIndex; ++i) z = smooth::step(quad(0.1L), z);
      EXPECT_LE(static_cast<long double>(smooth::absolute(smooth::offsetFromLine(h->line, quad(0.1L), z))), 1e-28L);
    }
  }
}

TEST(HomoclinicPoints, RejectsNonSymmetricOrReflectingOrbits) {
  const Manifolds m(hyperbolicFixedPoint(0.1L));
  EXPECT_THROW((void)primaryHeteroclinicPoints(m.stable, m.unstable, BranchSide::Inward), std::invalid_argument);
  EXPECT_THROW((void)primaryHeteroclinicPoints(m.unstable, m.stable, BranchSide::Inward, -1), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago
