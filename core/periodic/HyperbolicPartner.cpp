#include "core/periodic/HyperbolicPartner.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

namespace archipelago {

namespace {

/// The smallest distance between two points of the orbit (∞ for a fixed point).
long double smallestSpacing(const PeriodicOrbit& orbit) {
  long double d = std::numeric_limits<long double>::infinity();
  for (std::size_t i = 0; i < orbit.points.size(); ++i)
    for (std::size_t j = i + 1; j < orbit.points.size(); ++j)
      d = std::min(d, std::hypot(orbit.points[i].x - orbit.points[j].x, orbit.points[i].y - orbit.points[j].y));
  return d;
}

/// The largest distance from a point of `candidate` to the nearest point of `chain`: small for a partner.
long double separation(const PeriodicOrbit& candidate, const PeriodicOrbit& chain) {
  long double worst = 0;
  for (const PhysicalPoint& p : candidate.points) worst = std::max(worst, chain.distanceTo(p));
  return worst;
}

bool partnerOf(const PeriodicOrbit& candidate, const PeriodicOrbit& chain) {
  return candidate.period == chain.period && !std::isnan(candidate.residue) && !candidate.stable() &&
         candidate.residue != 0 && candidate.windingTurns == chain.windingTurns;
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
  const long double spacing = smallestSpacing(chain);
  PeriodicOrbitSearch search;
  search.period = chain.period;
  search.near = start;
  search.searchRadius = spacing;
  std::optional<PeriodicOrbit> best;
  long double bestSeparation = std::numeric_limits<long double>::infinity();
  for (PeriodicOrbit& candidate : findSymmetricPeriodicOrbits(chain.K, search)) {
    if (!partnerOf(candidate, chain)) continue;
    const long double s = separation(candidate, chain);
    if (s < bestSeparation) {
      bestSeparation = s;
      best = std::move(candidate);
    }
  }
  if (!best) {
    const std::size_t neighbour = [&] {
      std::size_t index = 1;
      long double d = std::numeric_limits<long double>::infinity();
      for (std::size_t i = 1; i < chain.points.size(); ++i) {
        const long double di = std::hypot(chain.points[i].x - start.x, chain.points[i].y - start.y);
        if (di < d) {
          d = di;
          index = i;
        }
      }
      return index;
    }();
    const PhysicalPoint middle{(start.x + chain.points[neighbour].x) / 2, (start.y + chain.points[neighbour].y) / 2};
    if (std::optional<PeriodicOrbit> general = refinePeriodicOrbit(chain.K, chain.period, middle))
      if (partnerOf(*general, chain)) best = std::move(general);
  }
  if (best) *best = best->rotatedToStart(best->nearestIndex(start));
  return best;
}

PeriodicOrbit findHyperbolicOrbit(long double K, const PeriodicOrbitSearch& request) {
  PeriodicOrbitSearch search = request;
  search.stableOnly = false;
  validate(K, search);
  const std::vector<PeriodicOrbit> found = findSymmetricPeriodicOrbits(K, search);  // nearest first
  for (const PeriodicOrbit& orbit : found)
    if (!std::isnan(orbit.residue) && !orbit.stable() && orbit.residue != 0) return orbit;
  for (const PeriodicOrbit& orbit : found) {
    if (!orbit.stable()) continue;
    if (std::optional<PeriodicOrbit> partner = findHyperbolicPartner(orbit))
      return partner->rotatedToStart(partner->nearestIndex(search.near));
  }
  if (std::optional<PeriodicOrbit> general = refinePeriodicOrbit(K, search.period, search.near))
    if (!std::isnan(general->residue) && !general->stable() && general->residue != 0)
      return general->rotatedToStart(general->nearestIndex(search.near));
  char where[96];
  std::snprintf(where, sizeof where, "(%.10Lg, %.10Lg)", search.near.x, search.near.y);
  throw std::runtime_error("no hyperbolic periodic orbit of period " + std::to_string(search.period) + " found near " +
                           where + " within search radius " + std::to_string(static_cast<double>(search.searchRadius)));
}

}  // namespace archipelago
