// The parameterization method (core/manifolds/ManifoldParameterization.hpp): invariance of the computed manifolds
// under the map, and the stable manifold from the inverse map against the one from the reversing symmetries.
#include <gtest/gtest.h>

#include <cmath>

#include "core/manifolds/ManifoldParameterization.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {
namespace {

using P = smooth::Point<quad>;

long double distance(P a, P b) { return static_cast<long double>(smooth::squareRoot((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y))); }

/// |a − b| / (1 + |b|): rounding is relative to the size of the points.
long double relative(P a, P b) { return distance(a, b) / (1 + distance(b, P{0, 0})); }

/// The hyperbolic period-6 orbit between the six islands at K = 0.1 (Karney 1983, §6), from its point on y = 0.
PeriodicOrbit periodSix() {
  PeriodicOrbitSearch s;
  s.period = 6;
  s.near = {0.0157L, 0};
  return findPeriodicOrbit(0.1L, s);
}

// Invariance at every order: Q(Φ_j(σ)) = Φ_{j+1}(μ_j σ) and Q⁻¹(Ψ_j(σ)) = Ψ_{j−1}(ν_j σ), evaluated in quad, for σ
// across several fundamental domains on both branches.  Tolerance: the series is truncated at 1e−32 of its linear
// term and quad rounds at 1e−34 per operation, relative to the point's size (the outward branches run off to
// infinity, where |z| is large), so 1e−30 (1 + |z|) leaves a factor 100 for the few dozen operations of the Horner sum
// and the steps of the map.
void expectInvariant(const HyperbolicOrbit& orbit) {
  const ManifoldParameterization u(orbit, ManifoldKind::Unstable), s(orbit, ManifoldKind::Stable);
  const quad K = orbit.K;
  long double worst = 0;
  for (int j = 0; j < orbit.period; ++j) {
    for (int sign : {-1, 1}) {
      for (int i = 1; i <= 40; ++i) {
        // σ from 1/8 of the series radius to ~3 domains beyond it.
        const quad sigma = sign * u.radius(j) * quad(std::pow(2.0L, -3.0L + 0.15L * i));
        worst = std::max(worst, relative(smooth::step(K, u.point(j, sigma)), u.point(j + 1, u.stretch(j) * sigma)));
        const quad mu = sign * s.radius(j) * quad(std::pow(2.0L, -3.0L + 0.15L * i));
        worst = std::max(worst, relative(smooth::inverseStep(K, s.point(j, mu)), s.point(j - 1, s.stretch(j) * mu)));
      }
    }
  }
  EXPECT_LE(worst, 1e-30L) << "period " << orbit.period;
}

TEST(ManifoldParameterization, InvariantToQuadPrecisionAtTheFixedPoint) {
  for (long double K : {0.05L, 0.1L, 0.2L, 0.001L, 1.0L}) expectInvariant(hyperbolicFixedPoint(K));
}

TEST(ManifoldParameterization, InvariantToQuadPrecisionForThePeriodSixOrbit) {
  const HyperbolicOrbit orbit = hyperbolicOrbitOf(periodSix());
  EXPECT_EQ(orbit.period, 6);
  EXPECT_LT(orbit.residue(), 0);  // hyperbolic
  EXPECT_LE(static_cast<long double>(orbit.closure), 1e-30L);
  expectInvariant(orbit);
}

// The fixed point's multiplier: λ = 1 + 2√K + 2√(√K + K) (Karney 1983, §5), and the linear terms are unit
// eigenvectors of DQ (unstable: λ, stable: 1/λ).
TEST(ManifoldParameterization, LinearTermsAreTheEigenvectors) {
  for (long double K : {0.05L, 0.1L, 0.2L}) {
    const HyperbolicOrbit orbit = hyperbolicFixedPoint(K);
    const long double r = std::sqrt(K);
    EXPECT_NEAR(static_cast<double>(orbit.multiplier), static_cast<double>(1 + 2 * r + 2 * std::sqrt(r + K)), 1e-15);
    const ManifoldParameterization u(orbit, ManifoldKind::Unstable), s(orbit, ManifoldKind::Stable);
    const smooth::Matrix2<quad> m = smooth::jacobian(orbit.points[0]);
    for (const auto& [param, e] : {std::pair{&u, orbit.multiplier}, std::pair{&s, 1 / orbit.multiplier}}) {
      const P v = param->coefficient(0, 1);
      const P mv{m.xx * v.x + m.xy * v.y, m.yx * v.x + m.yy * v.y};
      EXPECT_LE(distance(mv, P{e * v.x, e * v.y}), 1e-32L);
      EXPECT_NEAR(static_cast<double>(v.x * v.x + v.y * v.y), 1.0, 1e-30);
    }
    // Outward means away from (−√K, 0): +x at (√K, 0).
    EXPECT_GT(u.coefficient(0, 1).x, 0);
    EXPECT_GT(s.coefficient(0, 1).x, 0);
  }
}

// The stable manifold from Q⁻¹ is the image of the unstable one under either involution: Ψ_j(c σ) = I(Φ_i(σ))
// pointwise, with the constant c of the linear terms (ManifoldParameterization.hpp).  Same (relative) tolerance as
// invariance.
void expectReversalAgrees(const HyperbolicOrbit& orbit) {
  const ManifoldParameterization u(orbit, ManifoldKind::Unstable), s(orbit, ManifoldKind::Stable);
  long double worst = 0;
  for (Reversor r : {Reversor::I1, Reversor::I2}) {
    for (int j = 0; j < orbit.period; ++j) {
      const quad c = reversalScale(u, s, r, j);
      const int i = *reversedIndex(orbit, r, j);
      for (int sign : {-1, 1})
        for (int k = 1; k <= 30; ++k) {
          const quad sigma = sign * u.radius(i) * quad(std::pow(2.0L, -3.0L + 0.2L * k));
          worst = std::max(worst, relative(reversedUnstable(u, r, j, sigma), s.point(j, c * sigma)));
        }
    }
  }
  EXPECT_LE(worst, 1e-30L) << "period " << orbit.period;
}

TEST(ManifoldParameterization, StableFromTheInverseMapEqualsTheReversedUnstable) {
  for (long double K : {0.05L, 0.1L, 0.2L}) expectReversalAgrees(hyperbolicFixedPoint(K));
  expectReversalAgrees(hyperbolicOrbitOf(periodSix()));
}

// In long double (how curves are drawn), a far point is off the manifold only by rounding: the image of Φ(σ) lies
// on the curve, up to an offset along it.  Transverse distance bound: ~100 ε_ld |z| ≈ 1e−17 for O(1) points, the
// rounding of one step and of the series; asserted ≤ 1e−16.
TEST(ManifoldParameterization, LongDoublePointsStayOnTheCurve) {
  const HyperbolicOrbit orbit = hyperbolicFixedPoint(0.1L);
  const ManifoldParameterization u(orbit, ManifoldKind::Unstable);
  const long double K = orbit.K;
  for (int k = 0; k < 40; ++k) {
    const long double sigma = -0.5L * std::pow(1.3L, k);  // inner branch, up to ~15 domains out
    smooth::Point<long double> tangent;
    const smooth::Point<long double> image = smooth::step(K, u.point(0, sigma));
    const smooth::Point<long double> target = u.point(0, static_cast<long double>(u.stretch(0)) * sigma, &tangent);
    if (!std::isfinite(target.x)) break;  // escaped to infinity
    const long double t = std::hypot(tangent.x, tangent.y);
    const long double transverse = std::fabs((image.x - target.x) * tangent.y - (image.y - target.y) * tangent.x) / t;
    EXPECT_LE(transverse, 1e-16L * (1 + std::hypot(target.x, target.y))) << "sigma " << static_cast<double>(sigma);
  }
}

TEST(ManifoldParameterization, RejectsWhatIsNotAHyperbolicOrbit) {
  EXPECT_THROW((void)hyperbolicFixedPoint(0), std::invalid_argument);
  EXPECT_THROW((void)hyperbolicFixedPoint(-0.1L), std::invalid_argument);
  EXPECT_THROW((void)hyperbolicFixedPoint(1.5L), std::invalid_argument);
  EXPECT_THROW((void)hyperbolicFixedPoint(std::nanl("")), std::invalid_argument);
  PeriodicOrbitSearch s;
  s.period = 1;
  s.near = {-0.32L, 0};
  const PeriodicOrbit elliptic = findPeriodicOrbit(0.1L, s);  // the central fixed point (−√K, 0)
  EXPECT_THROW((void)hyperbolicOrbitOf(elliptic), std::invalid_argument);
  EXPECT_THROW(ManifoldParameterization(hyperbolicFixedPoint(0.1L), ManifoldKind::Unstable, 1), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago
