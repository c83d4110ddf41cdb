#include "core/periodic/HyperbolicPartner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace archipelago {

namespace {

long double distance(const PhysicalPoint& a, const PhysicalPoint& b) { return std::hypot(a.x - b.x, a.y - b.y); }

/// The largest distance from a point of the orbit to its nearest other point: the widest gap between neighbours.
long double widestGap(const PeriodicOrbit& orbit) {
  long double widest = 0;
  for (std::size_t i = 0; i < orbit.points.size(); ++i) {
    long double nearest = std::numeric_limits<long double>::infinity();
    for (std::size_t j = 0; j < orbit.points.size(); ++j)
      if (j != i) nearest = std::min(nearest, distance(orbit.points[i], orbit.points[j]));
    widest = std::max(widest, nearest);
  }
  return widest;
}

/// How far `candidate` lies from between the chain's islands: the largest, over its points p, of d₁(p) / s(p), with
/// d₁ the distance to the nearest point of the chain and s the distance between the two chain points nearest to p
/// (the local spacing).  A partner point sits between two neighbouring islands (≈ ½ for the six islands of §6; up to
/// 1.9 at the elongated tips of the 138-chain, where neighbouring islands bunch up); a point of another orbit of the
/// same period and winding, elsewhere in the sea, gives tens (44 for those near the 138-chain at K = 0.1).
constexpr long double kMaxBetweenness = 4;
long double betweenness(const PeriodicOrbit& candidate, const PeriodicOrbit& chain) {
  long double worst = 0;
  for (const PhysicalPoint& p : candidate.points) {
    std::size_t a = 0, b = 1;
    if (distance(p, chain.points[b]) < distance(p, chain.points[a])) std::swap(a, b);
    for (std::size_t i = 2; i < chain.points.size(); ++i) {
      const long double d = distance(p, chain.points[i]);
      if (d < distance(p, chain.points[a])) {
        b = a;
        a = i;
      } else if (d < distance(p, chain.points[b])) {
        b = i;
      }
    }
    worst = std::max(worst, distance(p, chain.points[a]) / distance(chain.points[a], chain.points[b]));
  }
  return worst;
}

bool partnerOf(const PeriodicOrbit& candidate, const PeriodicOrbit& chain) {
  return candidate.period == chain.period && !std::isnan(candidate.residue) && !candidate.stable() &&
         candidate.residue != 0 && candidate.windingTurns == chain.windingTurns &&
         betweenness(candidate, chain) <= kMaxBetweenness;
}

}  // namespace

std::optional<PeriodicOrbit> findHyperbolicPartner(const PeriodicOrbit& chain) {
  if (!std::isfinite(chain.K)) throw std::invalid_argument("the chain's K must be finite");
  if (chain.points.empty() || chain.period < 1 || chain.points.size() != static_cast<std::size_t>(chain.period))
    throw std::invalid_argument("the chain's orbit has no points");
  if (!chain.stable())
    throw std::invalid_argument("the hyperbolic partner is asked of an elliptic orbit (0 < R < 1); this one has R = " +
                                std::to_string(static_cast<double>(chain.residue)));
  const PhysicalPoint start = chain.points.front();
  if (chain.period == 1) {
    // The central fixed point (−√K, 0): its partner is the other fixed point (√K, 0).
    if (!(chain.K > 0)) return std::nullopt;
    const quad root = smooth::squareRoot(quad(chain.K));
    return analysePeriodicOrbit(chain.K, 1, root, 0, OrbitSymmetry::LineS2);
  }
  if (chain.period == 2) return std::nullopt;  // two points: no "between" to speak of
  PeriodicOrbitSearch search;
  search.period = chain.period;
  search.near = start;
  search.searchRadius = widestGap(chain);
  std::optional<PeriodicOrbit> best;
  long double bestBetweenness = std::numeric_limits<long double>::infinity();
  for (PeriodicOrbit& candidate : findSymmetricPeriodicOrbits(chain.K, search)) {
    if (!partnerOf(candidate, chain)) continue;
    const long double b = betweenness(candidate, chain);
    if (b < bestBetweenness) {
      bestBetweenness = b;
      best = std::move(candidate);
    }
  }
  if (!best) {
    // Not symmetric (or missed): damped Newton from the midpoints of z_0 and its nearest neighbours.
    std::vector<std::size_t> order(chain.points.size() - 1);
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i + 1;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return distance(start, chain.points[a]) < distance(start, chain.points[b]);
    });
    for (std::size_t k = 0; k < std::min<std::size_t>(2, order.size()) && !best; ++k) {
      const PhysicalPoint& other = chain.points[order[k]];
      const PhysicalPoint middle{(start.x + other.x) / 2, (start.y + other.y) / 2};
      if (std::optional<PeriodicOrbit> general = refinePeriodicOrbit(chain.K, chain.period, middle))
        if (partnerOf(*general, chain)) best = std::move(general);
    }
  }
  if (best) *best = best->rotatedToStart(best->nearestIndex(start));
  return best;
}

PeriodicOrbit findHyperbolicOrbit(long double K, const PeriodicOrbitSearch& request) {
  PeriodicOrbitSearch search = request;
  search.stableOnly = false;
  validate(K, search);
  // The nearest orbit found decides: unstable, it is the one; elliptic, the guess is in one of its islands and the
  // orbit wanted is that chain's partner.
  for (const PeriodicOrbit& orbit : findSymmetricPeriodicOrbits(K, search)) {  // nearest first
    if (std::isnan(orbit.residue) || orbit.residue == 0) continue;
    if (!orbit.stable()) return orbit;
    if (std::optional<PeriodicOrbit> partner = findHyperbolicPartner(orbit))
      return partner->rotatedToStart(partner->nearestIndex(search.near));
  }
  if (std::optional<PeriodicOrbit> general = refinePeriodicOrbit(K, search.period, search.near))
    if (!std::isnan(general->residue) && !general->stable() && general->residue != 0)
      return general->rotatedToStart(general->nearestIndex(search.near));
  char where[96];
  std::snprintf(where, sizeof where, "(%.10Lg, %.10Lg)", search.near.x, search.near.y);
  throw NotFound("no hyperbolic periodic orbit of period " + std::to_string(search.period) + " found near " +
                           where + " within search radius " + std::to_string(static_cast<double>(search.searchRadius)));
}

}  // namespace archipelago
