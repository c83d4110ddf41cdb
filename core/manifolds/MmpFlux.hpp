#pragma once
/// \file MmpFlux.hpp
/// \brief The MacKay–Meiss–Percival flux: the action difference ΔW_{p/q} of the two Birkhoff periodic orbits of type
/// p/q about the central island, and its limit over the convergents of a cantorus's rotation number.
///
/// MacKay, Meiss & Percival, "Transport in Hamiltonian systems", Physica D 13 (1984) 55; Meiss, Rev. Mod. Phys. 64
/// (1992) 795.  For every p/q in the twist interval an area-preserving twist map has (at least) two Birkhoff
/// periodic orbits of type p/q — orbits that keep the cyclic order of their points, each point going p places on
/// in the order of q — the minimizing one (Greene's residue R < 0) and the minimax one (R > 0; MacKay & Meiss,
/// Phys. Lett. A 98 (1983) 92: the residue criterion).  A curve C through the points of both, alternately, and its
/// image Q(C) meet at those points and bound 2q lobes; the area that crosses C per step (one way, the same the other
/// way) is
///     ΔW_{p/q} = W(minimax) − W(minimizing),       W = Σ_{k=0}^{q−1} L(x_k, x_{k+1}),  x_q = x_0,
/// with L the generating function of Q (GeneratingFunction.hpp: the one definition).  For an irrational ω whose
/// invariant circle is broken, the circle's remnant is a cantorus, and ΔW_{p_k/q_k} over the convergents p_k/q_k of ω
/// tends to the flux through it (MMP 1984: the minimax orbit tends to the minimax orbit homoclinic to the
/// cantorus).  Here the map is not a twist map of a cylinder but turns points about the elliptic centre (−√K, 0):
/// the "cyclic order" is the order of the angles about the centre (clockwise, as PeriodicOrbit.hpp measures the
/// rotation number), and the p/q orbits are the symmetric orbits of the finder (PeriodicOrbitFinder.hpp) with p
/// clockwise turns in q steps.
///
/// Sign.  ΔW is an area and does not depend on the coordinates, but its sign depends on the orientation: in the
/// plane's (x, y) with this L, about the central island at K = 0.1 (orbits turning clockwise, ω falling outward), the
/// orbit with R < 0 has the *larger* W (measured for 1/6 … 118/729, docs/markov-tree.md).  `planeDifference` is
/// W(R > 0) − W(R < 0) as the formula reads with the residue's labels, and `flux` = |planeDifference|.
///
/// Method.
///   1. Candidates: findSymmetricPeriodicOrbitsIn() — the finder's scan of the four half-lines of S₁ and S₂ from the
///      centre, between the distances innerRadius and outerRadius from it (an annulus that holds the p/q orbits, e.g.
///      between the chains of the neighbouring rotation numbers), at the given spacing.  Kept: minimal period q, p
///      clockwise turns, well ordered
///      (wellOrdered()).  Exactly two distinct orbits must remain, one with R < 0 and one with R > 0; anything else
///      is refused (NotFound, with what was found), since which orbits to difference would then be a guess.
///   2. Each orbit in __float128: its point on its symmetry line S is polished again along the line
///      (polishSymmetricPoint), ⌈q/2⌉ steps are taken forward, and the other half is the reversor's image
///      (I Q I = Q⁻¹, so z_{−k} = I(z_k) for z_0 on the fixed line of I): rounding grows as √|λ| along a half orbit,
///      not as |λ| along the whole one (at q = 729 about the central island at K = 0.1, |λ| ≈ 10¹⁵).  The two halves
///      meet at z_{⌈q/2⌉}: their distance is `mismatch`.
///   3. W = Σ L(x_k, x_{k+1}) in __float128.  W is stationary on an orbit, so an error δ of the points enters as δ²;
///      the rounding of the sum is bounded by 4 ε_quad Σ |L| (`actionError`).  ΔW ≈ 10⁻⁵ against W ≈ 10 at q ≈ 700:
///      quad's 34 digits leave ≥ 27.

#include <optional>
#include <span>
#include <stop_token>
#include <string>
#include <utility>
#include <vector>

#include "core/periodic/PeriodicOrbit.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"

namespace archipelago {

/// The largest outer radius (physical; the central island's chains lie within 0.5 of the centre, orbits much farther
/// out escape) and the most samples a window may take (each costs q/2 steps).
inline constexpr long double kMaxMmpRadius = 10;
inline constexpr long double kMaxMmpSamples = 1e9L;

/// What to compute.  Plain values; validationError() checks them.
struct MmpRequest {
  long double K = 0.1L;               ///< (0, 1]
  long p = 1;                         ///< clockwise turns about (−√K, 0), 1 ≤ p < q, gcd(p, q) = 1
  int q = 6;                          ///< the period, [2, PeriodicOrbitSearch::kMaxPeriod]
  long double innerRadius = 0.19L;    ///< the annulus scanned: distances from (−√K, 0) along the four half-lines of
  long double outerRadius = 0.44L;    ///< S₁ and S₂ from it, 0 < inner < outer (the defaults: 1/6 … 5/31 at K = 0.1)
  long double spacing = 1e-6L;        ///< the finder's sample spacing along x, > 0
  /// Instead of the annulus, these windows of the lines (when not empty): for large q, where the Birkhoff orbits'
  /// roots lie closer than any affordable spacing over the whole annulus (≈ |λ|^(−1/2): 3·10⁻⁸ at q = 729 about the
  /// central island at K = 0.1), narrow windows about the previous convergents' points on the lines.
  std::vector<LineWindow> windows;
  /// About an island of a chain of period n = `stride` instead of the centre (issue 50): the p/q orbits are then
  /// Q-orbits of period n·q whose every n-th point, from the one nearest `about` (a member of the chain's elliptic
  /// orbit), turns p times about it in q steps of Qⁿ (either sense: an island may turn either way) and is well ordered
  /// about it; W sums the n·q steps, so ΔW is the area crossing the n curves (one about each island) per step of Q, as
  /// the turnstile flux of a chain about an island is.  `windows` are then required (annulusWindows are the centre's).
  int stride = 1;
  PhysicalPoint about{};
  /// The chain's elliptic orbit m_0 … m_{n−1} (m_{k+1} = Q m_k), when known: an orbit is then kept only if it shadows
  /// the chain — its point nearest to m_a is followed by one nearest to m_{a+1}, all round (shadowsChain).  At K = 0.1
  /// about the six, the windows of 2/23 held 8 well-ordered orbits, 6 of them with residues 10⁶–10⁷ that wander
  /// between the islands; the pair (R = −0.717, 0.689) shadows the chain.
  std::vector<PhysicalPoint> members;
};

/// The first invalid field, named, or nothing.
[[nodiscard]] std::optional<std::string> validationError(const MmpRequest& request);

/// Whether the orbit z_0 … z_{N−1} (N a multiple of n = members.size()) shadows the chain m_0 … m_{n−1}: the member
/// nearest z_{k+1} follows the member nearest z_k in the chain's order, for every k (cyclically).  True for n ≤ 1.
[[nodiscard]] bool shadowsChain(std::span<const PhysicalPoint> points, std::span<const PhysicalPoint> members);

/// The points z_j, z_{j+n}, …, z_{j+(q−1)n} of an orbit of period n·q (n = stride), j in [0, n) the index of the point
/// nearest `about`: the orbit as it turns about that island under Qⁿ.  The whole orbit for stride 1.
[[nodiscard]] std::vector<PhysicalPoint> stridedAbout(std::span<const PhysicalPoint> points, int stride, PhysicalPoint about);

/// One Birkhoff orbit of type p/q, in __float128.
struct BirkhoffOrbit {
  PeriodicOrbit orbit;                          ///< the finder's orbit, relabelled so that z_0 lies on `line`
  smooth::SymmetryLine line = smooth::SymmetryLine::S2;  ///< the symmetry line of z_0
  std::vector<smooth::Point<quad>> points;      ///< z_0 … z_{q−1}: ⌈q/2⌉ steps forward, the rest by the reversor
  quad mismatch = 0;                            ///< |forward z_c − reversed z_c|, c = ⌈q/2⌉ (Euclidean)
  quad action = 0;                              ///< W = Σ_k L(x_k, x_{k+1}), x_q = x_0
  quad actionError = 0;                         ///< 4 ε_quad Σ_k |L(x_k, x_{k+1})|
};

struct MmpActionDifference {
  long double K = 0;
  long p = 0;
  int q = 0;
  int stride = 1;                ///< the chain's period about whose island (1: the centre); the orbits' period stride·q
  BirkhoffOrbit minimizing;      ///< R < 0
  BirkhoffOrbit minimax;         ///< R > 0
  quad planeDifference = 0;      ///< W(minimax) − W(minimizing) in the plane's orientation (see the file comment)
  quad flux = 0;                 ///< |planeDifference|: the area crossing a curve through both orbits per step
  quad fluxError = 0;            ///< the two actions' actionError
  int symmetricOrbits = 0;       ///< distinct symmetric orbits of minimal period q with p turns the finder found
  int birkhoffOrbits = 0;        ///< of those, the well-ordered ones (2 when computed)
};

/// The windows of the two symmetry lines between the distances `inner` and `outer` from (−√K, 0): two on each line,
/// one each side of the centre.  Throws std::invalid_argument unless 0 < inner < outer and K is valid.
[[nodiscard]] std::vector<LineWindow> annulusWindows(long double K, long double inner, long double outer);

/// The windows of the symmetry lines S₁ and S₂ where they pass within [inner, outer] of `member` (a point of an island
/// chain's elliptic orbit), for the Birkhoff orbits about its islands: a symmetric orbit has its points on the lines at
/// one of the chain's islands, not always one whose member lies on a line (at K = 0.1 the hyperbolic 3/34 orbit about
/// the six crosses S₁ only at the island about (−0.602, −0.262)).  Each line is sampled (4096 points) over the
/// member's x ± outer (a line's distance from a point is at least its offset in x) and each run of samples within the
/// radii kept, a sample wider on each side.  Throws std::invalid_argument unless 0 ≤ inner < outer, both finite.
[[nodiscard]] std::vector<LineWindow> lineWindowsAbout(long double K, PhysicalPoint member, long double inner,
                                                       long double outer);

/// Computes ΔW_{p/q}.  Throws std::invalid_argument for an invalid request (validationError), NotFound when the
/// finder's scan does not give exactly one well-ordered orbit with R < 0 and one with R > 0 (the message says what it
/// found), and OperationStopped when `stop` is requested.
[[nodiscard]] MmpActionDifference mmpActionDifference(const MmpRequest& request, std::stop_token stop = {});

/// Whether the orbit z_0 … z_{q−1} (z_{k+1} = Q z_k) is well ordered about `centre`: ordered by their clockwise angle
/// about it, Q moves every point the same number of places on (cyclically), as a rotation by p/q does.  False for
/// fewer than 1 point, a point at the centre or two points at the same angle.
[[nodiscard]] bool wellOrdered(std::span<const PhysicalPoint> points, PhysicalPoint centre);

/// The limit of a converging sequence a_0 … a_n (ΔW over convergents), as its last term with a bound on the tail:
/// with d_k = a_k − a_{k−1} and r the largest of the last three ratios |d_k / d_{k−1}| (k ≥ 2), r < 1, the rest of the
/// sum is at most |d_n| r/(1 − r) if the differences go on shrinking at least that fast (about the central island at
/// K = 0.1 they shrink faster between chains: the ratio fell from 0.2 to 2·10⁻⁴ over 5/31 … 118/729,
/// docs/markov-tree.md).  The largest of three, not the last alone (until 2026-12-07): near an island's boundary the
/// ratios wander — between 1/6 and 14/83 they were 0.082, 0.41, 0.17 and ΔW fell towards 0 (as through a circle),
/// while the last ratio alone gave 3.5·10⁻¹¹ ± 2.1·10⁻¹¹ at six terms and 7.8·10⁻¹⁰ ± 1.4·10⁻¹⁰ at four, which the next
/// terms left.  A bound under that assumption, not a proof.  Not an extrapolation: Aitken's Δ², which assumes a
/// constant ratio, overshoots such a sequence by more than its last difference.
struct ConvergentLimit {
  long double value = 0;        ///< a_n
  long double uncertainty = 0;  ///< |d_n| r / (1 − r)
  long double ratio = 0;        ///< r: the largest of the last three |d_k / d_{k−1}|
  int terms = 0;
};

/// Throws std::invalid_argument for fewer than three terms, a term that is not finite, a zero difference d_{n−1}, or
/// r ≥ 1 (not converging).
[[nodiscard]] ConvergentLimit convergentLimit(std::span<const long double> sequence);

/// The flux through a cantorus: ΔW over a list of its convergents (the caller names them: for a noble ω between two
/// chains p₁/q₁ and p₂/q₂, the Farey mediants (p₁ + p₂)/(q₁ + q₂), …).  Each term after the first is sought
/// first in windows of ±narrowHalfWidth about the previous term's points on the lines (both orbits) at narrowSpacing
/// — the convergents' orbits converge to the cantorus's, so their points on the lines do; cheap, and where the
/// windows hold no pair the annulus follows.  At large q the annulus misses the pair (its Birkhoff roots lie closer
/// than the annulus's spacing to others: q = 729, 150 s for nothing).  The first term scans the annulus.
struct CantorusRequest {
  long double K = 0.1L;
  std::vector<std::pair<long, int>> convergents;   ///< p/q, at least one; each as MmpRequest's p and q
  long double innerRadius = 0.19L;
  long double outerRadius = 0.44L;
  long double spacing = 1e-6L;
  long double narrowHalfWidth = 2e-6L;             ///< > 0
  long double narrowSpacing = 1e-9L;               ///< > 0
  int stride = 1;                                  ///< about an island: as MmpRequest's stride, about and
  PhysicalPoint about{};                           ///< members, with `windows` for the first term (the annulus is
  std::vector<PhysicalPoint> members;              ///< the centre's)
  std::vector<LineWindow> windows;
};

[[nodiscard]] std::optional<std::string> validationError(const CantorusRequest& request);

struct CantorusFlux {
  std::vector<MmpActionDifference> terms;   ///< one per convergent, in the request's order
  std::vector<bool> narrowed;               ///< the term came from the narrow windows
  std::optional<ConvergentLimit> limit;     ///< convergentLimit of the fluxes, with three or more terms
  std::string limitProblem;                 ///< why there is no limit (fewer than three terms, not converging)
};

/// Throws std::invalid_argument for an invalid request, NotFound (the term's p/q and both scans' messages) when a term
/// is not found either way, OperationStopped when stopped.
[[nodiscard]] CantorusFlux cantorusFlux(const CantorusRequest& request, std::stop_token stop = {});

/// The request and result as JSON (indent 2): K, radii, spacings; per term p, q, flux (double and 30-digit text),
/// its rounding bound, the plane's signed difference, both orbits (residue, line, z_0, action text, mismatch), the
/// finder's counts and whether the narrow windows were used; the limit (value, uncertainty, ratio) or why there is none.
[[nodiscard]] std::string cantorusFluxJson(const CantorusRequest& request, const CantorusFlux& result, double seconds = -1);

}  // namespace archipelago
