#pragma once
/// \file PeriodicOrbitAt.hpp
/// \brief The periodic orbit at a point of the portrait (issue 37, finding 16): a click names its island chain as
/// the rotation instrument does (identifyChain: "6 × 23 = 138, rotation 1/6 about the centre, 2/23 about its
/// island"), and the elliptic orbit of that chain's period is found by core's finder from the chain's deepest centre
/// — the call `archipelago-cli periodic --period n --near X,Y --stable` makes, so the CLI prints the same orbit.
/// A point on an invariant curve about the centre gives the elliptic fixed point (period 1); a chaotic or escaping
/// orbit has no chain to find an orbit of (NotFound, with the chain's words).

#include <stop_token>

#include "core/measures/ChainIdentification.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {

struct PeriodicOrbitAt {
  ChainIdentification chain;   ///< the clicked point's identification (its summary names the chain)
  PeriodicOrbitSearch search;  ///< the finder's request: the chain's period, near its deepest centre, elliptic only
  PeriodicOrbit orbit;         ///< findPeriodicOrbit(K, search)
};

/// The orbit at `request`'s start (a request of chainRequestAt).  Throws std::invalid_argument for invalid input,
/// NotFound when the orbit from there is chaotic or escapes (no chain) or the finder finds nothing, and
/// OperationStopped when `stop` is requested.
[[nodiscard]] PeriodicOrbitAt periodicOrbitAt(const ChainRequest& request, std::stop_token stop = {});

/// The point of `orbit` nearest `p` (Euclidean, physical): the island centre a rotation profile across that
/// island is measured about (RotationProfileRequest::about; issue 37, finding 17).  Throws std::invalid_argument
/// for an orbit without points.
[[nodiscard]] PhysicalPoint nearestMember(const PeriodicOrbit& orbit, PhysicalPoint p);

}  // namespace archipelago
