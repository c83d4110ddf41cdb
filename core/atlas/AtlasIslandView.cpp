#include "core/atlas/AtlasIslandView.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "core/limits/Limits.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/portrait/MapOverlays.hpp"

namespace archipelago {

std::uint64_t atlasBoundarySteps(std::uint64_t period) {
  return std::clamp<std::uint64_t>(period * kAtlasPointsPerIsland, kAtlasMinBoundaryPoints,
                                   std::min(kAtlasMaxBoundaryPoints, limits::kOrbitLength));
}

std::vector<PhysicalPoint> islandCircle(std::span<const PhysicalPoint> orbit, std::uint64_t period,
                                        PhysicalPoint centre) {
  const std::size_t n = std::max<std::size_t>(period, 1);
  std::size_t phase = 0;
  long double nearest = std::numeric_limits<long double>::infinity();
  for (std::size_t k = 0; k < std::min(n, orbit.size()); ++k) {
    const long double d = std::hypot(orbit[k].x - centre.x, orbit[k].y - centre.y);
    if (d < nearest) nearest = d, phase = k;
  }
  std::vector<PhysicalPoint> own;
  for (std::size_t k = phase; k < orbit.size(); k += n) own.push_back(orbit[k]);
  return own;
}

std::optional<PeriodicOrbit> wholeOrbit(long double K, const PeriodicOrbit& orbit) {
  if (static_cast<int>(orbit.points.size()) == orbit.period && orbit.period > 0) return orbit;
  if (orbit.points.empty()) return std::nullopt;
  return refinePeriodicOrbit(K, orbit.period, orbit.points.front());
}

namespace {

/// The boundary orbit and the frame of the island's own circle; the reason when they cannot be drawn.
void traceBoundary(const MapParameters& map, const AtlasNode& node, AtlasIslandView& view,
                   std::vector<std::string>& missing) {
  if (!node.boundaryFound) return;
  try {
    view.boundary = traceOrbit(map, node.boundaryPoint.x, node.boundaryPoint.y, atlasBoundarySteps(node.period), false);
    const std::vector<PhysicalPoint> own = islandCircle(view.boundary, node.period, node.centre);
    if (!own.empty()) view.island = dwellRegion(own, 1.0, 64, kAtlasViewMargin);  // framed whole, elongated or not
  } catch (const std::exception& e) {
    missing.push_back("the boundary circle (" + std::string(e.what()) + ")");
  }
}

}  // namespace

AtlasIslandView atlasIslandView(const MapParameters& map, const AtlasNode& node) {
  AtlasIslandView view;
  std::vector<std::string> missing;
  traceBoundary(map, node, view, missing);
  const long double K = static_cast<long double>(map.K);
  view.chain = wholeOrbit(K, node.orbit);
  if (!view.chain)
    missing.push_back("the chain's orbit of period " + std::to_string(static_cast<int>(node.period)) +
                      " (not found again)");
  if (node.flux.partner) {
    view.partner = wholeOrbit(K, *node.flux.partner);
    if (!view.partner) missing.push_back("the hyperbolic partner (not found again)");
  }
  for (const std::string& phrase : missing) view.missing += (view.missing.empty() ? "" : ", ") + phrase;
  return view;
}

}  // namespace archipelago
