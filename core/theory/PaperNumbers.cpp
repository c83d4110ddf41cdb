#include "core/theory/PaperNumbers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago::paper {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

double ellipticRotationCosine(double K) noexcept { return K >= 0 && K <= 1 ? 1 - 2 * std::sqrt(K) : kNaN; }

double ellipticFixedPointResidue(double K) noexcept { return K >= 0 ? std::sqrt(K) : kNaN; }

double hyperbolicFixedPointResidue(double K) noexcept { return K >= 0 ? -std::sqrt(K) : kNaN; }

double smallKLyapunovNumber(double K) noexcept { return K >= 0 ? 1 + 2 * std::sqrt(std::sqrt(K)) : kNaN; }

double segmentDecayExponent(double m) noexcept { return m > 1 ? (3 * m + 1) / (m - 1) : kNaN; }

namespace {

// The period-2ⁿ orbit of the cascade, followed in K from just after its birth at K_{n−1} (parent: a point of
// the period-2ⁿ⁻¹ orbit there) to K_n, where R = 1.  Returns K_n and, through *atBifurcation, the orbit there.
double nextBifurcation(int period, double bornAt, double previousGap, const PhysicalPoint& parent,
                       PeriodicOrbit* atBifurcation) {
  // Just after birth the new orbit is ~√(K − K_{n−1}) from its parent: search there for the elliptic one.
  const long double start = bornAt + 1e-3 * previousGap;
  PeriodicOrbitSearch search;
  search.period = period;
  search.near = parent;
  search.searchRadius = 20 * std::sqrt(1e-3L * previousGap);
  search.stableOnly = true;
  std::vector<PeriodicOrbit> found = findSymmetricPeriodicOrbits(start, search);
  if (found.empty())
    throw std::runtime_error("period-doubling cascade: no period-" + std::to_string(period) + " orbit near its birth");
  PeriodicOrbit low = found.front();
  long double kLow = start;
  // Follow it in K: the symmetric finder near its last position (Newton alone from there can fall onto the
  // parent, which solves Qⁿ(z) = z too), with a radius of its distance from the parent (steps of 25% in K − K_{n−1} move it by ~12% of that); Newton from
  // the last position only if the finder finds nothing.
  auto follow = [&](long double K, const PeriodicOrbit& from) {
    const PhysicalPoint z = from.points.front();
    PeriodicOrbitSearch near = search;
    near.near = z;
    near.stableOnly = false;
    near.searchRadius = std::max(std::hypot(z.x - parent.x, z.y - parent.y), 1e-9L);
    std::vector<PeriodicOrbit> candidates = findSymmetricPeriodicOrbits(K, near);
    if (!candidates.empty()) return candidates.front();
    std::optional<PeriodicOrbit> o = refinePeriodicOrbit(K, period, z);
    if (!o) throw std::runtime_error("period-doubling cascade: lost the period-" + std::to_string(period) + " orbit");
    return *o;
  };
  long double step = 0.25e-3L * previousGap;  // ¼ of the distance from the birth, then growing by 25%
  std::optional<PeriodicOrbit> high;
  long double kHigh = 0;
  for (int i = 0; i < 200 && !high; ++i) {
    const long double K = kLow + step;
    PeriodicOrbit o = follow(K, low);
    if (o.residue >= 1) {
      high = o;
      kHigh = K;
    } else {
      low = o;
      kLow = K;
      step *= 1.25L;
    }
  }
  if (!high) throw std::runtime_error("period-doubling cascade: R never reached 1");
  // Bisection on R(K) − 1, each orbit refined from the nearest lower one.
  while (kHigh - kLow > 1e-16L) {
    const long double K = (kLow + kHigh) / 2;
    PeriodicOrbit o = follow(K, low);
    if (o.residue >= 1) {
      kHigh = K;
    } else {
      low = o;
      kLow = K;
    }
    if (K == kLow && K == kHigh) break;
  }
  *atBifurcation = low;
  return static_cast<double>((kLow + kHigh) / 2);
}

}  // namespace

PeriodDoublingCascade periodDoublingCascade(int levels) {
  if (auto e = rangeError("levels", levels, 3, 7)) throw std::invalid_argument(*e);
  PeriodDoublingCascade c;
  c.bifurcations = {kFirstPeriodDoubling, kSecondPeriodDoubling};
  // The period-2 orbit at K₁ = 5/4: x = −1 ∓ √(K − 1) = −1 ∓ ½ (PaperNumbers.hpp).
  PeriodicOrbit parent;
  parent.points = {PhysicalPoint{-1.5L, -1.0L}, PhysicalPoint{-0.5L, 1.0L}};
  for (int n = 2; n < levels; ++n) {
    const double gap = c.bifurcations[n - 1] - c.bifurcations[n - 2];
    PeriodicOrbit orbit;
    c.bifurcations.push_back(nextBifurcation(1 << n, c.bifurcations[n - 1], gap, parent.points.front(), &orbit));
    parent = orbit;
  }
  for (std::size_t n = 2; n < c.bifurcations.size(); ++n)
    c.ratios.push_back((c.bifurcations[n - 1] - c.bifurcations[n - 2]) / (c.bifurcations[n] - c.bifurcations[n - 1]));
  auto extrapolate = [&](std::size_t n) {  // from K_n, K_{n−1} and δ_n
    const double delta = c.ratios[n - 2];
    return c.bifurcations[n] + (c.bifurcations[n] - c.bifurcations[n - 1]) / (delta - 1);
  };
  const std::size_t last = c.bifurcations.size() - 1;
  c.accumulation = extrapolate(last);
  c.accumulationChange = std::fabs(extrapolate(last - 1 >= 2 ? last - 1 : last) - c.accumulation);
  return c;
}

}  // namespace archipelago::paper
