#pragma once
/// \file AtlasCantori.hpp
/// \brief The cantori about each island, as barriers of the atlas (issue 50): the
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
/// cantorus is sought there (the record says so).  The same about an island of a chain of period n, under Qⁿ
/// (MmpRequest::stride: Q-orbits of period n·q), and between each island's innermost barrier chain and its boundary
/// circle the island's boundary cantorus (atlasCantori).

#include <stop_token>
#include <string>
#include <optional>
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

/// The largest period n·q of a term about an island of a chain of period n, and of a boundary cantorus's term (n = 1
/// at the centre): the Birkhoff orbits about an island are Q-orbits of period n·q (at K = 0.1 about the six, between
/// 1/12 and 2/23: 138, 210, 348, 558, 906, 1464); the centre's boundary cantorus at K = 0.1 has terms 15/89 … 328/1947
/// (to 742 its tail bound was 2.2·10⁻¹⁰, 15 % of the flux; to 1947, 7.8·10⁻¹⁴).  Each term after the first is sought
/// first in windows of ±2·10⁻⁶ about the previous term's points on the lines (cantorusFlux: 4000 samples each).
inline constexpr int kMaxIslandCantorusPeriod = 2000;

/// The most nobles tried for an island's boundary cantorus (atlasCantori): at K = 0.1 about the centre, the second.
inline constexpr int kMaxBoundaryCandidates = 8;

/// The Farey neighbour of `chain` (|p·chain.q − chain.p·q| = 1) of least q ≤ maxQ strictly between it and the
/// boundary rotation, or nothing: the other end of the noble interval of the island's boundary cantorus (at K = 0.1,
/// depth 2, the centre's boundary turns 0.16878 and its innermost barrier chain is 1/6: 14/83).
[[nodiscard]] std::optional<Rational> boundaryNeighbour(const Rational& chain, double boundaryRotation, int maxQ);

/// The cantorus's name for people: "cantorus 5/31-1/6", "cantorus 1/12-2/23 about 6", "boundary cantorus 1/6-15/89"
/// (of the centre), "boundary cantorus 4/43-11/118 of 6".
[[nodiscard]] std::string atlasCantorusName(const Atlas& atlas, const AtlasCantorus& cantorus);

/// The cantori about every measured island with a boundary circle, parents first: between each two successive chains
/// about it that are barriers (flux found), outermost first, and its boundary cantorus — the noble number between its
/// innermost barrier chain p₁/q₁ and its boundary circle's rotation (the golden mediants from p₁/q₁ and
/// boundaryNeighbour), which lies outside the boundary circle and inside that chain — or, where ΔW over that noble's
/// convergents falls to zero within its tail bound (an invariant circle may be there), the noble of the next Farey
/// neighbour nearer p₁/q₁, up to kMaxBoundaryCandidates (at K = 0.1 about the centre: 1/6 and 14/83 falls to
/// 1.5·10⁻¹² ± 2.0·10⁻¹² over 14/83 … 307/1821, 1/6 and 15/89 gives 1.42526·10⁻⁹ ± 7.8·10⁻¹⁴).  About an island of a chain of
/// period n the Birkhoff orbits are sought under Qⁿ (MmpRequest::stride) on the symmetry lines through the chain's
/// members, and the zone is n times the polygon about the island's member.  A cantorus not found, whose layer does
/// not lie between its neighbours' (for the boundary cantorus: above 0, outside the island), or with fewer than three
/// terms is kept with found = false and the reason.  Stops (returning what is done) on `stop`.
[[nodiscard]] std::vector<AtlasCantorus> atlasCantori(const Atlas& atlas, std::stop_token stop = {});

}  // namespace archipelago
