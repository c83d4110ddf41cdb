#pragma once
/// \file AtlasIslandView.hpp
/// \brief What a portrait draws of an island of the atlas, and the view it frames (docs/design.md, "Front ends fill,
/// call and format": a plan is core's, as the manifolds' is in core/manifolds/ManifoldViewPlan.hpp).  The GUI's Atlas
/// page calls atlasIslandView() off its thread and only draws the answer.
///
/// The plan: the orbit of the node's boundary point under Q, about kAtlasPointsPerIsland points per island of the
/// chain (atlasBoundarySteps); the island's own circle cut out of it (every n-th point from the first n's point
/// nearest the node's centre: the boundary point may lie on another island of the chain, 6 > 138's at K = 0.1); the
/// frame about that circle (dwellRegion of all its points with a margin of kAtlasViewMargin of its size on every
/// side); the chain's elliptic orbit and its hyperbolic partner whole, an orbit the atlas keeps as one point (an
/// atlas read from JSON) found again by core's Newton.  (In core/atlas, not beside the manifold plan in
/// core/manifolds: it reads an AtlasNode, and atlas depends on manifolds.)

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/atlas/Atlas.hpp"
#include "core/periodic/SegmentAnalysis.hpp"

namespace archipelago {

/// Points traced of an island's boundary circle, per island of its chain.
inline constexpr std::uint64_t kAtlasPointsPerIsland = 4000;
/// At least (as many as a launched orbit of the portrait, kSessionOrbitSteps) and at most this many in all.
inline constexpr std::uint64_t kAtlasMinBoundaryPoints = 20'000;
inline constexpr std::uint64_t kAtlasMaxBoundaryPoints = 2'000'000;
/// The margin about an island's boundary circle in its view, in parts of its size on each side.
inline constexpr double kAtlasViewMargin = 0.25;

/// What the portrait draws of one island of an atlas.
struct AtlasIslandView {
  std::vector<PhysicalPoint> boundary;    ///< the boundary point's orbit (every island of the chain); empty: none
  std::optional<SegmentRegion> island;    ///< the frame about the island's own circle (none without a boundary)
  std::optional<PeriodicOrbit> chain;     ///< the chain's elliptic orbit whole (the fixed point at the centre)
  std::optional<PeriodicOrbit> partner;   ///< its hyperbolic partner whole (none at the centre, or when none)
  std::string missing;                    ///< what could not be drawn, phrases joined by ", " (empty: everything)
};

/// Steps of the boundary orbit for a chain of `period` islands: period · kAtlasPointsPerIsland within
/// [kAtlasMinBoundaryPoints, min(kAtlasMaxBoundaryPoints, limits::kOrbitLength)].  Pure.
[[nodiscard]] std::uint64_t atlasBoundarySteps(std::uint64_t period);

/// The points of `orbit` (an orbit under Q of a chain of `period` islands) on the island about `centre`: every
/// period-th point, from the one of the first `period` nearest `centre`.  Pure.
[[nodiscard]] std::vector<PhysicalPoint> islandCircle(std::span<const PhysicalPoint> orbit, std::uint64_t period,
                                                      PhysicalPoint centre);

/// `orbit` whole: as it is when it holds its `period` points, found again from its first point by Newton
/// (refinePeriodicOrbit) when the atlas kept one point, none when it has none or Newton fails.
[[nodiscard]] std::optional<PeriodicOrbit> wholeOrbit(long double K, const PeriodicOrbit& orbit);

/// The plan above for `node` of an atlas of `map`: traces, cuts, frames and restores (seconds at most).  Never
/// throws for a node of an atlas of this map: what fails is named in `missing` ("the boundary circle (…)", "the
/// chain's orbit of period n (not found again)", "the hyperbolic partner (not found again)").
[[nodiscard]] AtlasIslandView atlasIslandView(const MapParameters& map, const AtlasNode& node);

}  // namespace archipelago
