#include "core/manifolds/HyperbolicOrbit.hpp"

#include "core/limits/Limits.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/map/MapParameters.hpp"  // shortestDecimal
#include "core/periodic/HyperbolicPartner.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {

namespace {

using smooth::Point;

/// λ with |λ| > 1 from the trace (det = 1): the root of λ² − trace·λ + 1 = 0 of larger modulus.
quad multiplierOf(quad trace) {
  const quad root = smooth::squareRoot(trace * trace - 4);
  return trace > 0 ? (trace + root) / 2 : (trace - root) / 2;
}

}  // namespace

long double HyperbolicOrbit::residue() const noexcept {
  return static_cast<long double>((2 - monodromy.trace()) / 4);
}

std::vector<PhysicalPoint> HyperbolicOrbit::physicalPoints() const {
  std::vector<PhysicalPoint> out;
  out.reserve(points.size());
  for (const Point<quad>& p : points) out.push_back({static_cast<long double>(p.x), static_cast<long double>(p.y)});
  return out;
}

std::optional<std::string> manifoldKError(long double K) {
  if (!std::isfinite(K) || !(K > kManifoldMinK) || K > kManifoldMaxK)
    return "K = " + shortestDecimal(static_cast<double>(K)) +
           " must be a number in (0, 1] (the hyperbolic fixed point (√K, 0) and the central island exist)";
  return std::nullopt;
}

HyperbolicOrbit hyperbolicFixedPoint(long double K) {
  if (auto e = manifoldKError(K)) throw std::invalid_argument(*e);
  HyperbolicOrbit orbit;
  orbit.K = K;
  orbit.period = 1;
  orbit.fixedPoint = true;
  const Point<quad> z{smooth::squareRoot(quad(K)), 0};
  orbit.points = {z};
  orbit.monodromy = smooth::jacobian(z);
  orbit.multiplier = multiplierOf(orbit.monodromy.trace());
  const Point<quad> image = smooth::step(quad(K), z);
  orbit.closure = smooth::absolute(image.x - z.x) + smooth::absolute(image.y - z.y);
  return orbit;
}

HyperbolicOrbit hyperbolicOrbitOf(const PeriodicOrbit& periodic) {
  if (auto e = manifoldKError(periodic.K)) throw std::invalid_argument(*e);
  if (periodic.points.empty() || periodic.period < 1)
    throw std::invalid_argument("the periodic orbit has no points");
  const int n = periodic.period;
  const std::optional<Point<quad>> z0 =
      polishPeriodicPoint(periodic.K, n, Point<quad>{periodic.points.front().x, periodic.points.front().y});
  if (!z0)
    throw std::invalid_argument("the periodic orbit of period " + std::to_string(n) +
                                " does not converge under Newton in quad precision");
  HyperbolicOrbit orbit;
  orbit.K = periodic.K;
  orbit.period = n;
  const quad K = periodic.K;
  Point<quad> z = *z0;
  smooth::Matrix2<quad> m;
  for (int j = 0; j < n; ++j) {
    orbit.points.push_back(z);
    m = smooth::jacobian(z) * m;
    z = smooth::step(K, z);
  }
  orbit.monodromy = m;
  orbit.closure = smooth::squareRoot((z.x - z0->x) * (z.x - z0->x) + (z.y - z0->y) * (z.y - z0->y));
  const quad trace = m.trace();
  if (!(smooth::absolute(trace) > quad(2) + quad(1e-12L)))
    throw std::invalid_argument("the periodic orbit of period " + std::to_string(n) + " is not hyperbolic (trace DQⁿ = " +
                                shortestDecimal(static_cast<double>(trace)) + ", |trace| must exceed 2)");
  orbit.multiplier = multiplierOf(trace);
  orbit.fixedPoint = n == 1;
  return orbit;
}

std::optional<std::string> manifoldPeriodError(long long period) {
  return rangeError("period", period, 1, kMaxManifoldPeriod);
}

std::optional<std::string> orbitPointError(long long point, long long period) {
  return rangeError("point", point, 0, period - 1, "a point of the orbit");
}

std::optional<PeriodicOrbit> hyperbolicOrbitNear(long double K, int period, std::optional<PhysicalPoint> near,
                                                 long double radius) {
  if (auto e = manifoldKError(K)) throw std::invalid_argument(*e);
  if (auto e = manifoldPeriodError(period)) throw std::invalid_argument(*e);
  if (!near) {
    if (period != 1)
      throw std::invalid_argument("a guess near a point of the orbit is needed for period " + std::to_string(period));
    return std::nullopt;
  }
  PeriodicOrbitSearch search;
  search.period = period;
  search.near = *near;
  search.searchRadius = radius;
  return findHyperbolicOrbit(K, search);
}

}  // namespace archipelago
