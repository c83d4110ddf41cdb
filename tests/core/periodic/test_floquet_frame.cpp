// The normal-form (Floquet) frame of an elliptic periodic orbit (core/periodic/FloquetFrame.hpp, issue 50): in it
// DQⁿ is a rotation by ν, and the largest step of the physical angle under DQⁿ lies foldMargin below half a turn —
// both checked with DQⁿ built here from the map's Jacobian, and the angles' steps counted over a circle of directions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/periodic/FloquetFrame.hpp"

namespace archipelago {
namespace {

smooth::Matrix2<long double> monodromy(long double K, PhysicalPoint c, int n) {
  smooth::Matrix2<long double> m;
  smooth::Point<long double> z{c.x, c.y};
  for (int i = 0; i < n; ++i) {
    m = smooth::Matrix2<long double>{1 + 4 * z.x, 1, 4 * z.x, 1} * m;
    z = smooth::step(K, z);
  }
  return m;
}

PhysicalPoint apply(const smooth::Matrix2<long double>& m, PhysicalPoint v) {
  return {m.xx * v.x + m.xy * v.y, m.yx * v.x + m.yy * v.y};
}

// At K = 0.1 the 2/13 chain's member on S₂ (x = −0.540361006765074, the atlas's): DQ¹³ there is conjugate to the
// rotation by ν = 0.4025 (R = 0.909), its eigen-ellipses 4.9 times longer than wide.
TEST(FloquetFrame, TurnsEveryDirectionByNuInNormalFormAndFoldsThePhysicalAngleByTheMargin) {
  const long double K = 0.1L;
  const PhysicalPoint c{-0.540361006765074L, 0};
  const auto f = floquetFrame(K, c, 13);
  ASSERT_TRUE(f.has_value());
  const smooth::Matrix2<long double> m = monodromy(K, c, 13);
  EXPECT_NEAR(static_cast<double>(std::cos(2 * std::numbers::pi_v<long double> * f->rotation)),
              static_cast<double>(m.trace() / 2), 1e-12);
  EXPECT_NEAR(static_cast<double>(f->rotation), 0.4025, 1e-3);
  EXPECT_NEAR(static_cast<double>(f->axisRatio), 4.9, 0.05);
  const long double twoPi = 2 * std::numbers::pi_v<long double>;
  long double largest = 0;
  for (int k = 0; k < 100000; ++k) {
    const long double phi = twoPi * k / 100000;
    const PhysicalPoint u{std::cos(phi), std::sin(phi)};
    // In normal form: a rotation (length kept, the angle moved by ν in one sense or the other).
    const PhysicalPoint w = f->normal(apply(m, f->physical(u)));
    ASSERT_NEAR(static_cast<double>(std::hypot(w.x, w.y)), 1.0, 1e-9);
    const long double step = std::remainder(std::atan2(w.y, w.x) - phi, twoPi) / twoPi;
    ASSERT_NEAR(static_cast<double>(std::fabs(step)), static_cast<double>(f->rotation), 1e-9);
    // Physically: the step of the direction's angle, largest where it crosses the ellipses' short axis.
    const PhysicalPoint v = f->physical(u), mv = apply(m, v);
    largest = std::max(largest, std::fabs(std::remainder(std::atan2(mv.y, mv.x) - std::atan2(v.y, v.x), twoPi)) / twoPi);
  }
  EXPECT_NEAR(static_cast<double>(largest), static_cast<double>(0.5L - f->foldMargin), 1e-6);
  EXPECT_LT(f->foldMargin, 0.05L);  // thin: the atlas scans it in this frame
}

TEST(FloquetFrame, TheCentreAtK01TurnsByItsLinearRotationAndAHyperbolicPointHasNone) {
  const long double K = 0.1L;
  const auto f = floquetFrame(K, {-std::sqrt(K), 0}, 1);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(static_cast<double>(std::cos(2 * std::numbers::pi_v<long double> * f->rotation)),
              static_cast<double>(1 - 2 * std::sqrt(K)), 1e-15);  // cos α = 1 − 2√K (§2)
  EXPECT_NEAR(static_cast<double>(f->axisRatio), 1.9125, 1e-4);
  EXPECT_NEAR(static_cast<double>(f->foldMargin), 0.2086, 1e-4);  // its angles never fold
  EXPECT_FALSE(floquetFrame(K, {std::sqrt(K), 0}, 1).has_value());  // (√K, 0): trace 2 + 4√K
}

}  // namespace
}  // namespace archipelago
