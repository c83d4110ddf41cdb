#pragma once
/// \file AtlasCantori.hpp
/// \brief The cantori between successive chains about the central island, as barriers of the atlas (issue 50): the
/// MacKay–Meiss–Percival flux through each (core/manifolds/MmpFlux.hpp: ΔW over the convergents of the noble rotation
/// number between the two chains) and the area it encloses, for the Markov tree's states.
///
/// Between two chains p₁/q₁ (outer) and p₂/q₂ (inner) about the centre that are Farey neighbours (|p₁q₂ − p₂q₁| = 1),
/// the noble number ω between them is the limit of the golden mediants r₀ = the one of smaller q, r₁ = the other,
/// r_{k+1} = r_k ⊕ r_{k−1} (at K = 0.1 between 5/31 and 1/6: 5/31, 6/37, 11/68, 17/105, 28/173, 45/278 — the
/// convergents of [0; 6, 5, 1, 1, …], docs/markov-tree.md).  Its flux is the limit of ΔW over r₁, r₂, … up to
/// period kMaxCantorusPeriod (convergentLimit: the last term with its tail bound).  The area it encloses is taken from
/// the last term's two Birkhoff orbits, which converge to the cantorus: each as a polygon of its points ordered by
/// the angle about the centre (shoelace); `zoneArea` is the minimax orbit's, `zoneSpread` the distance to the
/// minimizing orbit's — the polygons' disagreement, one part of the zone's uncertainty (the polygon's chords are
/// another: ~10⁻⁵ at q ≈ 280).  Its layer is that zone less the atlas's islands inside it (the inner chain's and
/// those nearer the centre), and it must lie between the layers of the barriers about it — else it is refused.
/// Chains that are not Farey neighbours hold a chain of lower period between them that the atlas did not keep: no
/// cantorus is sought there (the record says so).  Only about the centre: the Birkhoff orbits about a chain's
/// island (under Qⁿ) are not sought (MmpFlux finds them about (−√K, 0)).

#include <stop_token>
#include <string>
#include <utility>
#include <vector>

#include "core/atlas/Atlas.hpp"

namespace archipelago {

class PolygonRegion;

/// The atlas's islands inside `zone` (each counted by its centre, a member of its chain's elliptic orbit: an island
/// never crosses a separatrix): their summed area and number — every barrier's layer is its zone less these.
[[nodiscard]] std::pair<long double, int> atlasIslandsInside(const Atlas& atlas, const PolygonRegion& zone);

/// The largest period of a convergent used (ΔW's terms): 278 at K = 0.1 between 5/31 and 1/6 leaves a tail bound of
/// ~10⁻¹² relative; the finder's cost grows as q² (docs/markov-tree.md: q = 729 needs windows of 10⁻⁹).
inline constexpr int kMaxCantorusPeriod = 300;

/// The Farey-neighbour golden mediants between `outer` and `inner` (both in lowest terms, neighbours), from the one
/// of larger q up to period maxPeriod; empty when they are not neighbours.
[[nodiscard]] std::vector<Rational> nobleConvergents(const Rational& outer, const Rational& inner, int maxPeriod);

/// The cantori between each two successive chains about the centre that are barriers (flux found), outermost first,
/// with their layers settled against the atlas's islands.  A cantorus not found, or whose layer does not lie
/// between its neighbours', is kept with found = false and the reason.  Stops (returning what is done) on `stop`.
[[nodiscard]] std::vector<AtlasCantorus> centreCantori(const Atlas& atlas, std::stop_token stop = {});

}  // namespace archipelago
