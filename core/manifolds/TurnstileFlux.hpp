#pragma once
/// \file TurnstileFlux.hpp
/// \brief The flux through the separatrix of a hyperbolic orbit (the turnstile's lobe area) by two methods that share
/// the manifolds and the homoclinic points (not independent: see "The two methods"), and the area of the resonance
/// zone it bounds.
///
/// MacKay, Meiss & Percival, "Transport in Hamiltonian systems", Physica D 13 (1984) 55; Meiss, "Thirty years of
/// turnstiles and transport", Chaos 25 (2015) 097602.  The resonance zone of a hyperbolic orbit z_0 … z_{n−1} is
/// bounded by n pieces W^u(z_c)[z_c → h_c] ∪ W^s(z_{c+b})[h_c → z_{c+b}] (h_c = Q^c(h), h the primary
/// heteroclinic point nearest to z_0, HomoclinicPoints.hpp), joined at the points c → c + b → c + 2b → …: one closed
/// curve when gcd(b, n) = 1 (the six islands of §6), else gcd(b, n) of them (the 138-chain: b = −6, one curve of 23
/// pieces around each of the six islands it surrounds); for the fixed point (√K, 0) it is the loop around the central
/// island (n = 1, b = 0).  The pieces are images of each other (piece c = Q^c(piece 0)), so Q⁻¹ maps the
/// zone onto itself except on the last piece, where W^u(z_{n−1}) now ends at Q⁻ⁿ(h_{n−1}) instead of h_{n−1}: the
/// zone and its preimage differ by the two lobes between those points (the turnstile), the exit lobe inside the zone
/// (its points leave in one step) and the entry lobe outside (they come in).  Each lobe has the area of the lobe
/// between h and h' (Q is area-preserving and maps lobes onto lobes), so the flux per step is one lobe's area for
/// every n (over n steps each of the n turnstiles acts once).
///
/// The two methods:
///   1. action: lobe area = |ΔW(h) − ΔW(h')|, the difference of the actions of the two primary orbits
///      (GeneratingFunction.hpp), summed in __float128; zone area = |Σ_c ΔW(h_c)|.
///   2. polygon: the shoelace area of the closed polygon whose vertices lie on the arcs, N + 1 vertices per arc
///      uniform in the analytic parameter (σ on W^u, μ on W^s; ManifoldParameterization.hpp), in long double, for
///      N = N₀, 2N₀, 4N₀, …; the area between a chord and its arc is an odd function of the chord's parameter length,
///      so the polygon's error is a series in even powers 1/N², 1/N⁴, … (Euler–Maclaurin) and Richardson
///      extrapolation (Romberg's table) removes them.  The result is the extrapolated value, its error the larger of
///      the table's last diagonal difference and a bound on the shoelace sum's rounding, `raw` the plain shoelace area
///      of the finest polygon.
/// The two share the parameterizations of the manifolds (checked separately, to 1e−30 relative, by their
/// invariance) and the primary homoclinic/heteroclinic points h, h' (found on those parameterizations,
/// HomoclinicPoints.hpp), not the formula: one sums L along two orbits, the other integrates around a curve through
/// the same points.  Their agreement checks the area computation; an error in the manifolds or in the points would
/// move both alike, and is what the invariance checks and independent computations (issue 39: own manifolds and
/// homoclinic points in mpmath, 22–31 digits at K = 0.15, 0.3 and for the period-6 lobe) are for.
///
/// Arithmetic, step by step, and why:
///   - Taylor coefficients, homoclinic points (bisection + Newton), the action sums: __float128.  The lobe is the
///     difference of two actions of size ≈ 9.6 K^{5/4} and is exponentially smaller (7e−4 of them at K = 0.05,
///     ~1e−16 at K = 0.001): quad's 34 digits leave ≥ 17 after the cancellation; long double's 19 would leave 3 at
///     K = 0.001.  The sums are stationary in the orbit (errors in h enter squared), so h to ~1e−32 suffices.  Their
///     rounding is bounded (HeteroclinicPoint::actionError) and a lobe not resolved to 1e−9 by it is refused.
///   - polygon vertices: long double.  Rounding moves a vertex by ~1e−19 of the coordinates, almost all of it along
///     the curve; the area moves by ~1e−19 × perimeter ≈ 1e−20, i.e. 1e−16 of the lobe at K = 0.05.  In double
///     (1e−16 × perimeter ≈ 3e−17) it would be 2e−13 of that lobe: enough for 9 digits at K ≥ 0.05, not below
///     K ≈ 0.01.  The shoelace sum is taken about a vertex of the polygon and accumulated in __float128.
///   - Where the lobe is so small that long double cannot resolve it (below ~1e−13 of the zone, K ≲ 0.01) the
///     polygon's `error` says so, and the action (method 1) remains valid.
/// Measured (docs/manifolds.md): at K = 0.05, 0.1, 0.2 the two agree to 17–18 significant digits.

#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/manifolds/HomoclinicPoints.hpp"
#include "core/manifolds/PolygonRegion.hpp"
#include "core/periodic/PeriodicOrbit.hpp"

namespace archipelago {

/// What to compute.  Plain values; validationError() checks them.
struct TurnstileRequest {
  long double K = 0.1L;                   ///< (0, 1]
  std::optional<PeriodicOrbit> orbit;     ///< a hyperbolic symmetric periodic orbit; none: the fixed point (√K, 0)
  BranchSide side = BranchSide::Inward;   ///< the unstable branch at z_0 (inward: the fixed point's loop)
  int maxDomains = 0;                     ///< fundamental domains scanned for the primary points, [0, 1000]
                                          ///< (0: automatic, HomoclinicPoints.hpp)
  int firstVertices = 32;                 ///< N₀ ≥ 4: vertices per arc at the first Romberg level
  int maxVertices = 1 << 14;              ///< ≥ N₀, ≤ 2^20: vertices per arc at the finest level
  int boundaryVertices = 2048;            ///< ≥ 8: vertices per arc of the returned boundaries (drawing, regions)
};

/// The first invalid field, named, or nothing.
[[nodiscard]] std::optional<std::string> validationError(const TurnstileRequest& r);

/// A polygon area extrapolated to infinitely many vertices.
struct PolygonArea {
  long double area = 0;       ///< signed: −(counter-clockwise area) along the path of the action's loop, i.e. the
                              ///< same sign as the action ΔW it is compared with
  long double error = 0;      ///< the larger of |T(i,i) − T(i−1,i−1)| (the last two diagonal entries of Romberg's
                              ///< table) and a worst-case bound on the shoelace sum's rounding, ε_ld Σ(|x_i y_{i+1}| +
                              ///< |x_{i+1} y_i|) about the first vertex (one rounding per product; typically the sum
                              ///< is 100 times more accurate)
  long double raw = 0;        ///< the plain (signed) shoelace area of the finest polygon
  int verticesPerArc = 0;     ///< N of the finest polygon
  int levels = 0;             ///< rows of Romberg's table computed
};

/// Progress of the longer computations of core/manifolds: a fraction in [0, 1] and the stage's name.
struct ManifoldProgress {
  double fraction = 0;
  std::string stage;
};
using ManifoldProgressCallback = std::function<void(const ManifoldProgress&)>;

struct TurnstileFlux {
  HyperbolicOrbit orbit;
  BranchSide side = BranchSide::Inward;
  PrimaryIntersections intersections;   ///< first = h, second = h'
  int target = 0;                       ///< b: the arcs go from z_0 to z_b

  quad lobeAction = 0;                  ///< ΔW(h) − ΔW(h') (signed, __float128)
  quad lobeActionError = 0;             ///< bound on its rounding (the two actions' actionError)
  long double lobeArea = 0;             ///< |lobeAction|: the flux per step
  PolygonArea lobePolygon;              ///< the same lobe by method 2 (signed like lobeAction)
  quad zoneAction = 0;                  ///< Σ_c ΔW(h_c) (signed)
  long double zoneArea = 0;             ///< |zoneAction|
  PolygonArea zonePolygon;              ///< the zone by method 2 (signed like zoneAction)

  /// Boundaries for drawing and for region tests (boundaryVertices per arc), physical coordinates:
  std::vector<std::vector<PhysicalPoint>> zoneBoundary;  ///< the zone: its closed curves (one through all n points,
                                                         ///< or gcd(b, n) of them, e.g. one around each of the six
                                                         ///< islands a 138-chain surrounds)
  std::vector<PhysicalPoint> lobeBoundary;   ///< the lobe between h and h' (the one whose area is reported)
  std::vector<PhysicalPoint> exitLobe;       ///< the turnstile's lobe inside the zone: its points leave in one step
  std::vector<PhysicalPoint> entryLobe;      ///< the turnstile's lobe outside the zone: its points come in

  /// −log₁₀ of the relative difference of the two methods for the lobe (∞ when equal): the agreeing digits.
  [[nodiscard]] long double lobeDigits() const noexcept;
  [[nodiscard]] long double zoneDigits() const noexcept;
};

/// Computes everything above.  Throws std::invalid_argument for an invalid request (validationError), an orbit that is
/// not hyperbolic or not symmetric; NotFound (PeriodicOrbitFinder.hpp) when the primary points are not found, when
/// the lobe is not resolved by __float128 (its action error above 1e−9 of it: K below ≈ 3e−4 for the fixed point, where the lobe is
/// below 1e−25 of the zone), or when stopped.
/// progress (if set) is called between stages on the calling thread; `stop` is checked between stages and levels.
[[nodiscard]] TurnstileFlux computeTurnstileFlux(const TurnstileRequest& request,
                                                 const ManifoldProgressCallback& progress = {},
                                                 std::stop_token stop = {});

/// One arc of a closed curve made of manifold arcs: the points of `manifold` at orbit point `point` with parameters
/// from `from` to `to`.
struct ManifoldArc {
  const ManifoldParameterization* manifold = nullptr;
  int point = 0;
  quad from = 0;
  quad to = 0;
};

/// A closed curve made of manifold arcs, each starting where the previous one ends.
using ArcRing = std::vector<ManifoldArc>;

/// The closed polygon with `perArc` vertices on each arc (uniform in its parameter, its end left to the next arc).
[[nodiscard]] std::vector<PhysicalPoint> arcPolygon(const ArcRing& arcs, int perArc);

/// The Romberg-extrapolated signed area −(counter-clockwise area), summed over the closed curves (see PolygonArea).
[[nodiscard]] PolygonArea extrapolatedArea(const std::vector<ArcRing>& rings, int firstVertices, int maxVertices,
                                           std::stop_token stop = {});

}  // namespace archipelago
