// PolygonRegion (core/manifolds/PolygonRegion.hpp): the grid-accelerated point-in-polygon test against plain ray
// casting, and the shoelace area of shapes of known area.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/manifolds/PolygonRegion.hpp"
#include "core/random/CounterRng.hpp"

namespace archipelago {
namespace {

/// Plain even–odd ray casting, O(n) per point.
bool rayCast(const std::vector<PhysicalPoint>& v, long double x, long double y) {
  bool inside = false;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    if ((v[i].y > y) != (v[j].y > y) && x < v[j].x + (y - v[j].y) * (v[i].x - v[j].x) / (v[i].y - v[j].y)) inside = !inside;
  return inside;
}

/// A wiggly star: non-convex, many vertices, with thin spikes like a lobe's.
std::vector<PhysicalPoint> star(int n) {
  std::vector<PhysicalPoint> v;
  for (int i = 0; i < n; ++i) {
    const long double a = 2 * std::numbers::pi_v<long double> * i / n;
    const long double r = 1 + 0.4L * std::sin(7 * a) + 0.3L * std::sin(53 * a);
    v.push_back({r * std::cos(a), 0.5L * r * std::sin(a)});
  }
  return v;
}

TEST(PolygonRegion, AgreesWithRayCasting) {
  const std::vector<PhysicalPoint> v = star(3000);
  const PolygonRegion region(v);
  int inside = 0;
  for (std::uint64_t i = 1; i <= 200000; ++i) {
    const long double x = -2 + 4 * std::ldexp(static_cast<long double>(orbitDraw(7, 2 * i)), -52);
    const long double y = -1 + 2 * std::ldexp(static_cast<long double>(orbitDraw(7, 2 * i + 1)), -52);
    const bool expected = rayCast(v, x, y);
    ASSERT_EQ(region.contains(x, y), expected) << x << ", " << y;
    inside += expected ? 1 : 0;
  }
  EXPECT_GT(inside, 10000);
}

TEST(PolygonRegion, ShoelaceAreas) {
  // A square of side 2 traversed counter-clockwise: +4; clockwise: −4.
  const std::vector<PhysicalPoint> square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_EQ(signedShoelaceArea(square), 4);
  EXPECT_EQ(signedShoelaceArea({{0, 0}, {0, 2}, {2, 2}, {2, 0}}), -4);
  EXPECT_EQ(PolygonRegion(square).area(), 4);
  // A regular n-gon inscribed in the unit circle: (n/2) sin(2π/n), exactly up to rounding.
  const int n = 1000;
  std::vector<PhysicalPoint> polygon;
  for (int i = 0; i < n; ++i) {
    const long double a = 2 * std::numbers::pi_v<long double> * i / n;
    polygon.push_back({3 + std::cos(a), -5 + std::sin(a)});  // far from the origin: the sum is taken about a vertex
  }
  EXPECT_NEAR(static_cast<double>(signedShoelaceArea(polygon)),
              static_cast<double>(n / 2.0L * std::sin(2 * std::numbers::pi_v<long double> / n)), 1e-15);
}

TEST(PolygonRegion, RejectsDegeneratePolygons) {
  EXPECT_THROW(PolygonRegion({{0, 0}, {1, 1}}), std::invalid_argument);
  EXPECT_THROW(PolygonRegion({{0, 0}, {1, 1}, {std::nanl(""), 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago
