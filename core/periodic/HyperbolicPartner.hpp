#pragma once
/// \file HyperbolicPartner.hpp
/// \brief The hyperbolic partner of an island chain: the unstable periodic orbit of the same period and
/// rotation number whose points lie between the islands (Karney 1983, §6; Poincaré–Birkhoff).
///
/// An island chain of order n is centred on an elliptic orbit of period n; by the Poincaré–Birkhoff theorem a
/// hyperbolic orbit of the same period and rotation number p/n lies between its islands, and its stable and
/// unstable manifolds form the chain's separatrices (core/manifolds draws them and measures the flux through
/// them).  For the central fixed point (−√K, 0) the partner is the hyperbolic fixed point (√K, 0).
///
/// Method: the partner's points lie between neighbouring islands.  The symmetric-orbit search of
/// PeriodicOrbitFinder.hpp runs from z_0 with search radius the chain's widest gap between neighbouring points (both
/// symmetry lines, windows around the iterates); a candidate is an unstable orbit of minimal period n with the
/// chain's clockwise winding about (−√K, 0) whose every point p lies within 4 local spacings s(p) (the distance
/// between the two chain points nearest to p) of the chain (measured: ≤ 0.5 for the six islands of §6, ≤ 1.9 for the
/// 138-chain) — another orbit of the same period and winding elsewhere in
/// the sea (there are many near a sub-chain such as the 138-chain) has points far from it.  The candidate whose points
/// sit most nearly between islands wins.  When none is symmetric, damped Newton (refinePeriodicOrbit) from the
/// midpoints of z_0 and its two nearest neighbours is tried.

#include <optional>

#include "core/periodic/PeriodicOrbit.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {

/// The hyperbolic partner of the elliptic orbit `chain` (classification elliptic, 0 < R < 1), relabelled so that
/// its z_0 is the partner point nearest to chain.points[0]; nothing when none was found.
/// Throws std::invalid_argument when `chain` is not elliptic, has no points, or its K is not finite.
[[nodiscard]] std::optional<PeriodicOrbit> findHyperbolicPartner(const PeriodicOrbit& chain);

/// The hyperbolic periodic orbit of period `search.period` near `search.near` (stableOnly is ignored): the nearest orbit
/// the symmetric search finds from the guess decides — unstable, it is returned; elliptic (the guess is inside one of
/// its islands), its hyperbolic partner is; else damped Newton from the guess.  Relabelled
/// so that z_0 is the point nearest to the guess.  Throws std::invalid_argument for invalid input (validate()) and
/// NotFound "no hyperbolic periodic orbit of period n found near (x, y) …" when none is found.
[[nodiscard]] PeriodicOrbit findHyperbolicOrbit(long double K, const PeriodicOrbitSearch& search);

}  // namespace archipelago
