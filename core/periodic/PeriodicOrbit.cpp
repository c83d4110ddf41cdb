#include "core/periodic/PeriodicOrbit.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <numbers>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

const char* toString(OrbitSymmetry s) noexcept {
  switch (s) {
    case OrbitSymmetry::LineS1: return "S1 (y = K - x^2)";
    case OrbitSymmetry::LineS2: return "S2 (y = 0)";
    case OrbitSymmetry::None: break;
  }
  return "none";
}

std::size_t PeriodicOrbit::nearestIndex(PhysicalPoint p) const noexcept {
  std::size_t best = 0;
  long double bestDistance = std::numeric_limits<long double>::infinity();
  for (std::size_t k = 0; k < points.size(); ++k) {
    const long double d = std::hypot(points[k].x - p.x, points[k].y - p.y);
    if (d < bestDistance) {
      bestDistance = d;
      best = k;
    }
  }
  return best;
}

long double PeriodicOrbit::distanceTo(PhysicalPoint p) const noexcept {
  if (points.empty()) return std::numeric_limits<long double>::infinity();
  const PhysicalPoint& q = points[nearestIndex(p)];
  return std::hypot(q.x - p.x, q.y - p.y);
}

bool PeriodicOrbit::stable() const noexcept { return !std::isnan(residue) && classifyOrbit(residue).stable(); }

std::string rotationNumberText(const PeriodicOrbit& orbit, int digits) {
  std::string text;
  if (orbit.linearRotation) {
    if (std::isnan(orbit.rotationNumber)) return "none (hyperbolic fixed point: nearby orbits do not turn about it)";
    const char* exact = orbit.rotationNumber == 0 ? " = 0/1" : (orbit.rotationNumber == 0.5L ? " = 1/2" : "");
    text = io::formatC("%.*Lg%s (linear, at the central fixed point)", digits, orbit.rotationNumber,
                       exact);
    return text;
  }
  const long turns = orbit.windingTurns;
  const long period = orbit.period;
  const long divisor = std::gcd(turns, period);
  text = io::formatC("%.*Lg = %ld/%ld = %ld/%ld (clockwise turns about (−√K, 0) per step)", digits,
                     orbit.rotationNumber, turns, period, divisor != 0 ? turns / divisor : turns,
                     divisor != 0 ? period / divisor : period);
  return text;
}

bool PeriodicOrbit::insideBox(const MapParameters& box) const noexcept {
  const long double L = box.width();
  for (const PhysicalPoint& p : points)
    if (!(p.x >= box.xmin && p.x < box.xmax && p.y >= -L / 2 && p.y < L / 2)) return false;
  return !points.empty();
}

PeriodicOrbit PeriodicOrbit::rotatedToStart(std::size_t first) const {
  PeriodicOrbit r = *this;
  if (points.empty()) return r;
  for (std::size_t k = 0; k < points.size(); ++k) r.points[k] = points[(first + k) % points.size()];
  return r;
}

long clockwiseTurns(std::span<const PhysicalPoint> points, long double cx, long double cy) noexcept {
  const long double pi = std::numbers::pi_v<long double>;
  long double total = 0;
  const std::size_t n = points.size();
  for (std::size_t k = 0; k < n; ++k) {
    const PhysicalPoint& a = points[k];
    const PhysicalPoint& b = points[(k + 1) % n];
    long double d = std::atan2(b.y - cy, b.x - cx) - std::atan2(a.y - cy, a.x - cx);
    if (d > pi) d -= 2 * pi;
    if (d <= -pi) d += 2 * pi;
    total += d;
  }
  return std::lround(-total / (2 * pi));
}

PeriodicOrbit analysePeriodicOrbit(long double K, int period, quad x0, quad y0, OrbitSymmetry symmetry) {
  if (auto e = lowerBoundError("period", period, 1)) throw std::invalid_argument(*e);
  using Point = smooth::Point<quad>;
  const quad k = K;
  PeriodicOrbit orbit;
  orbit.K = K;
  orbit.period = period;
  orbit.symmetry = symmetry;
  orbit.points.reserve(static_cast<std::size_t>(period));
  smooth::Matrix2<quad> product;
  Point z{x0, y0};
  for (int i = 0; i < period; ++i) {
    orbit.points.push_back({static_cast<long double>(z.x), static_cast<long double>(z.y)});
    product = smooth::jacobian(z) * product;
    z = smooth::step(k, z);
  }
  const quad dx = z.x - x0, dy = z.y - y0;
  orbit.closure = static_cast<long double>(smooth::squareRoot(dx * dx + dy * dy));
  orbit.trace = static_cast<long double>(product.trace());
  orbit.residue = static_cast<long double>((2 - product.trace()) / 4);

  const quad rootK = smooth::squareRoot(k);
  const long double cx = static_cast<long double>(-rootK);
  const bool atCentre = period == 1 && smooth::absolute(x0 + rootK) < quad(1e-15L) * (1 + smooth::absolute(rootK)) &&
                        smooth::absolute(y0) < quad(1e-15L);
  if (atCentre) {
    // No angle to follow: the linear rotation number, cos 2πω₀ = trace/2 = 1 − 2R (elliptic when 0 < R < 1).
    orbit.windingTurns = 0;
    orbit.linearRotation = true;
    orbit.rotationNumber = std::numeric_limits<long double>::quiet_NaN();
    if (!std::isnan(orbit.residue))
      orbit.rotationNumber = orbit.classification().rotationNumber.value_or(orbit.rotationNumber);
  } else {
    orbit.windingTurns = clockwiseTurns(orbit.points, cx, 0);
    orbit.rotationNumber = static_cast<long double>(orbit.windingTurns) / period;
  }
  return orbit;
}

}  // namespace archipelago
