#include "core/measures/PeriodicOrbitAt.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace archipelago {

PeriodicOrbitAt periodicOrbitAt(const ChainRequest& request, std::stop_token stop) {
  PeriodicOrbitAt r;
  r.chain = identifyChain(request, stop);
  if (r.chain.cancelled) throw OperationStopped();
  if (r.chain.levels.empty() || r.chain.levels.front().rotation.verdict != OrbitVerdict::Regular)
    throw NotFound("no island chain there to find a periodic orbit of: the orbit is " + r.chain.summary);
  r.search.period = static_cast<int>(r.chain.period);
  // The deepest level measured about a member of the period-n orbit (level 0: the fixed point (−√K, 0)).
  r.search.near = r.chain.levels.front().centre;
  for (const ChainLevel& level : r.chain.levels)
    if (level.power == r.chain.period) r.search.near = level.centre;
  r.search.stableOnly = true;
  r.orbit = findPeriodicOrbit(request.map.K, r.search, stop);
  return r;
}

PhysicalPoint nearestMember(const PeriodicOrbit& orbit, PhysicalPoint p) {
  if (orbit.points.empty()) throw std::invalid_argument("the periodic orbit has no points");
  const auto distance = [p](const PhysicalPoint& z) { return std::hypot(z.x - p.x, z.y - p.y); };
  return *std::min_element(orbit.points.begin(), orbit.points.end(),
                           [&](const PhysicalPoint& a, const PhysicalPoint& b) { return distance(a) < distance(b); });
}

}  // namespace archipelago
