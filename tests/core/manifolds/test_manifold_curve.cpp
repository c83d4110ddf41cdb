// Branches drawn by fundamental-domain iteration with adaptive refinement (core/manifolds/ManifoldCurve.hpp): the
// polylines are invariant (the image of a drawn point lies on the drawn curve), meet their refinement bounds, agree
// between the two constructions of the stable manifold, and honour the view, the box and the stop token.
#include <gtest/gtest.h>

#include <cmath>
#include <stop_token>

#include "core/manifolds/ManifoldCurve.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {
namespace {

/// Distance from p to the polyline pieces of `curve`, only over points whose parameter is in [tLow, tHigh].
long double distanceToCurve(const ManifoldCurve& curve, PhysicalPoint p, long double tLow = -1e30L, long double tHigh = 1e30L) {
  long double best = INFINITY;
  for (const ManifoldPiece& piece : curve.pieces)
    for (std::size_t i = 1; i < piece.points.size(); ++i) {
      if (piece.parameter[i] < tLow || piece.parameter[i - 1] > tHigh) continue;
      const PhysicalPoint a = piece.points[i - 1], b = piece.points[i];
      const long double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
      const long double u = l2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / l2, 0.0L, 1.0L) : 0;
      best = std::min(best, std::hypot(p.x - a.x - u * dx, p.y - a.y - u * dy));
    }
  return best;
}

/// The largest distance from a refined polyline to its curve: chords of at most `spacing` kept with their midpoint
/// after a turn of at most `angle` there miss the arc by about (c/2)(α/4) ≤ spacing·angle/8; asserted with a factor 2.
long double chordTolerance(const ManifoldCurveRequest& r) { return r.maxSpacing * r.maxAngle / 4; }

// Invariance: the image under Q of every drawn point of the fixed point's inner unstable branch lies on the drawn
// branch (one domain further out), within the chord tolerance.
TEST(ManifoldCurve, ImagesOfDrawnPointsLieOnTheDrawnCurve) {
  ManifoldCurveRequest r;
  r.K = 0.1L;
  r.length = 8;
  const ManifoldCurve c = computeManifoldCurve(r);
  ASSERT_EQ(c.stoppedBy, "length");
  const long double tMax = c.pieces.back().parameter.back();
  long double worst = 0;
  int checked = 0;
  for (const ManifoldPiece& piece : c.pieces)
    for (std::size_t i = 0; i < piece.points.size(); i += 7) {
      const long double t = piece.parameter[i];
      if (t < 0 || t + 1 > tMax) continue;  // Q maps domain t to t + 1 (period 1, λ > 0)
      const smooth::Point<long double> image = smooth::step(r.K, smooth::Point<long double>{piece.points[i].x, piece.points[i].y});
      worst = std::max(worst, distanceToCurve(c, {image.x, image.y}, t + 0.5L, t + 1.5L));
      ++checked;
    }
  EXPECT_GT(checked, 300);
  EXPECT_LE(worst, chordTolerance(r));
}

TEST(ManifoldCurve, MeetsItsRefinementBounds) {
  ManifoldCurveRequest r;
  r.K = 0.1L;
  r.length = 8;
  const ManifoldCurve c = computeManifoldCurve(r);
  // The parameter's resolution is reached only where the branch runs off to infinity (|dz/dt| unbounded near the
  // escape radius): a few cuts there, none elsewhere on this branch.
  EXPECT_LE(c.unresolved, 3u);
  EXPECT_GE(c.length, r.length);
  EXPECT_NEAR(static_cast<double>(c.pieces.front().points.front().x), std::sqrt(0.1), 1e-18);  // starts at (√K, 0)
  long double longest = 0, sharpest = 0;
  for (const ManifoldPiece& p : c.pieces) {
    for (std::size_t i = 1; i < p.points.size(); ++i) {
      longest = std::max(longest, std::hypot(p.points[i].x - p.points[i - 1].x, p.points[i].y - p.points[i - 1].y));
      EXPECT_GT(p.arcLength[i], p.arcLength[i - 1]);
      EXPECT_GT(p.parameter[i], p.parameter[i - 1]);
    }
    for (std::size_t i = 2; i < p.points.size(); ++i) {
      const long double ux = p.points[i - 1].x - p.points[i - 2].x, uy = p.points[i - 1].y - p.points[i - 2].y;
      const long double vx = p.points[i].x - p.points[i - 1].x, vy = p.points[i].y - p.points[i - 1].y;
      sharpest = std::max(sharpest, std::fabs(std::atan2(ux * vy - uy * vx, ux * vx + uy * vy)));
    }
  }
  EXPECT_LE(longest, r.maxSpacing);
  // The turn is bounded at each interval's midpoint; at the junction of two intervals it is at most their sum.
  EXPECT_LE(sharpest, 2 * r.maxAngle);
}

// The stable branch from Q⁻¹ and from the reversing symmetry are the same curve: each point of one lies on the other's
// polyline within the chord tolerance.
TEST(ManifoldCurve, StableFromInverseMapAndFromSymmetryAgree) {
  for (long double K : {0.05L, 0.1L, 0.2L}) {
    ManifoldCurveRequest r;
    r.K = K;
    r.kind = ManifoldKind::Stable;
    r.length = 3;
    const ManifoldCurve inverse = computeManifoldCurve(r);
    r.stableFrom = StableConstruction::ReversingSymmetry;
    const ManifoldCurve symmetric = computeManifoldCurve(r);
    long double worst = 0;
    const long double common = std::min(inverse.length, symmetric.length) - 0.05L;
    for (const ManifoldPiece& p : symmetric.pieces)
      for (std::size_t i = 0; i < p.points.size(); i += 5)
        if (p.arcLength[i] < common) worst = std::max(worst, distanceToCurve(inverse, p.points[i]));
    EXPECT_LE(worst, chordTolerance(r)) << "K " << static_cast<double>(K);
  }
}

// A period-6 orbit: Q⁶ maps the outward unstable branch of z_0 into itself.
TEST(ManifoldCurve, PeriodSixBranchIsInvariantUnderQ6) {
  PeriodicOrbitSearch s;
  s.period = 6;
  s.near = {0.0157L, 0};
  ManifoldCurveRequest r;
  r.K = 0.1L;
  r.orbit = findPeriodicOrbit(0.1L, s);
  r.side = BranchSide::Outward;
  r.length = 1.5L;
  const ManifoldCurve c = computeManifoldCurve(r);
  const long double tMax = c.pieces.back().parameter.back();
  long double worst = 0;
  for (const ManifoldPiece& piece : c.pieces)
    for (std::size_t i = 0; i < piece.points.size(); i += 3) {
      if (piece.parameter[i] < 0 || piece.parameter[i] + 1 > tMax) continue;
      smooth::Point<long double> z{piece.points[i].x, piece.points[i].y};
      for (int k = 0; k < 6; ++k) z = smooth::step(r.K, z);
      worst = std::max(worst, distanceToCurve(c, {z.x, z.y}));
    }
  EXPECT_LE(worst, chordTolerance(r));
}

// A view: fine inside, coarse outside, so fewer points for the same length; inside it the spacing bound holds.
TEST(ManifoldCurve, RefinesFinelyOnlyInTheView) {
  ManifoldCurveRequest r;
  r.K = 0.1L;
  r.length = 8;
  r.maxSpacing = 2e-4L;
  const ManifoldCurve full = computeManifoldCurve(r);
  r.view = PhysicalRect{-0.75L, -0.55L, -0.45L, -0.25L};  // the lower left of the loop, near the tip
  const ManifoldCurve zoomed = computeManifoldCurve(r);
  EXPECT_LT(zoomed.points, full.points / 2);
  int inside = 0;
  for (const ManifoldPiece& p : zoomed.pieces)
    for (std::size_t i = 1; i < p.points.size(); ++i) {
      const PhysicalPoint a = p.points[i - 1], b = p.points[i];
      const bool seen = a.x > r.view->x0 && a.x < r.view->x1 && a.y > r.view->y0 && a.y < r.view->y1 &&
                        b.x > r.view->x0 && b.x < r.view->x1 && b.y > r.view->y0 && b.y < r.view->y1;
      if (!seen) continue;
      ++inside;
      EXPECT_LE(std::hypot(b.x - a.x, b.y - a.y), r.maxSpacing);
    }
  EXPECT_GT(inside, 100);
}

// Q* in the box: every point inside the box, the curve cut where it wraps, each piece a real polyline.
TEST(ManifoldCurve, TorusMapStaysInTheBoxAndIsCutAtTheWraps) {
  ManifoldCurveRequest r;
  r.K = 0.1L;
  r.length = 20;
  r.box = MapParameters{0.1, -0.8, 0.5};
  const ManifoldCurve c = computeManifoldCurve(r);
  EXPECT_GT(c.breaks, 0u);
  EXPECT_GT(c.pieces.size(), 1u);
  EXPECT_LE(c.pieces.size(), c.breaks + 1);  // a cut may leave a single point, which is no piece
  const long double x0 = r.box->xmin, x1 = r.box->xmax, half = static_cast<long double>(r.box->width()) / 2;
  for (const ManifoldPiece& p : c.pieces) {
    EXPECT_GE(p.points.size(), 2u);
    for (const PhysicalPoint& z : p.points) {
      EXPECT_GE(z.x, x0);
      EXPECT_LT(z.x, x1);
      EXPECT_GE(z.y, -half);
      EXPECT_LT(z.y, half);
    }
  }
}

// The plane: the branch escapes to infinity beyond the escape radius and is cut there.
TEST(ManifoldCurve, PlaneBranchIsCutWhereItEscapes) {
  ManifoldCurveRequest r;
  r.K = 0.1L;
  r.length = 30;
  const ManifoldCurve c = computeManifoldCurve(r);
  EXPECT_GT(c.breaks, 0u);
  for (const ManifoldPiece& p : c.pieces)
    for (const PhysicalPoint& z : p.points) EXPECT_LE(std::hypot(z.x, z.y), r.escapeRadius);
}

TEST(ManifoldCurve, ValidatesAndStops) {
  ManifoldCurveRequest r;
  for (auto bad : {0.0L, -1.0L, 2e6L, static_cast<long double>(NAN)}) {
    r.length = bad;
    EXPECT_TRUE(validationError(r).has_value());
  }
  r.length = 1;
  r.point = 1;  // the fixed point has one point
  EXPECT_TRUE(validationError(r).has_value());
  r.point = 0;
  r.view = PhysicalRect{1, 0, 0, 1};
  EXPECT_TRUE(validationError(r).has_value());
  r.view.reset();
  r.box = MapParameters{0.1, -0.2, 0.5};  // xmin > −√K: not a valid box
  EXPECT_TRUE(validationError(r).has_value());
  r.box = MapParameters{0.1, -0.8, 0.2};  // valid, but (√K, 0) lies outside it
  EXPECT_THROW((void)computeManifoldCurve(r), std::invalid_argument);
  r.box.reset();
  std::stop_source stop;
  stop.request_stop();
  EXPECT_THROW((void)computeManifoldCurve(r, {}, stop.get_token()), std::runtime_error);
}

}  // namespace
}  // namespace archipelago
