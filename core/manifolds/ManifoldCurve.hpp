#pragma once
/// \file ManifoldCurve.hpp
/// \brief A branch of a stable or unstable manifold drawn as polylines: fundamental-domain iteration with adaptive
/// refinement, to a requested arc length, in the plane (Q) or in the box of the torus map (Q*), optionally refined
/// only inside a view rectangle (a zoomed portrait).
///
/// Parameter.  Points are images of the local manifold (ManifoldParameterization.hpp) under the map: with σ₀ = ρ/Λ
/// (ρ the series radius at the chosen point, Λ the domain factor), the branch is z(t) = Φ(s·σ(t)), s = ±1 the side,
///     σ(t) = σ₀ (1 + t)      for −1 ≤ t ≤ 0  (the local arc from the orbit point, straight up to ~1e−32),
///     σ(t) = σ₀ Λᵗ           for t ≥ 0       (t ∈ [d, d+1] is the d-th fundamental domain's image),
/// and a point at t ∈ [d, d+1] is the local point σ₀Λ^{t−d} iterated d·stepsPerDomain steps: "fundamental-domain
/// iteration".  Every point is computed from the local series directly, never interpolated from its neighbours, so
/// a refined point lies on the manifold to the working precision (long double) however far out (Hobson, J. Comput.
/// Phys. 104 (1993) 14; Krauskopf & Osinga, J. Comput. Phys. 146 (1998) 404, whose accuracy conditions on the
/// spacing and the turning angle are used here).
///
/// Refinement.  Each domain starts with `initialPoints` points uniform in t; an interval [a, b] of neighbours is
/// accepted when its chord is at most maxSpacing and the polyline a → m → b through its parameter midpoint m turns
/// by at most maxAngle (then m is kept too); otherwise both halves are refined, down to the parameter resolution
/// (64 ε|t|; an interval still too coarse there is counted as `unresolved` and the polyline is cut there rather than
/// drawn with a chord that is not the curve: it happens where the branch runs off to infinity, whose speed |dz/dt|
/// grows without bound, or where rounding of long double dominates after many domains).  With a view rectangle, intervals whose
/// three points lie away from the view (farther than maxSpacing) use coarse bounds instead (spacing at most the
/// view's larger side, angle 0.5 rad): the curve is resolved where it is seen.
///
/// Breaks.  In the plane, a branch of Q runs off to infinity wherever it leaves the resonance zone: points beyond
/// `escapeRadius` are dropped and the polyline is broken there (after refining toward the escape to the resolution).
/// In the box, Q* wraps x and y into [xmin, xmax) × [−L/2, L/2) after each step, and g is periodic (eq. gstar), so
/// the branch is cut wherever two neighbours took different wraps: each point carries a hash of its wraps, and
/// neighbours with different hashes are refined toward the cut, then the polyline is broken.  A new piece starts
/// after every break; arc length is counted along the pieces only.
///
/// Stable branches come from Q⁻¹ (the default) or, for an orbit its involution maps onto itself, by the reversing
/// symmetry from the unstable branch of the reflected point (`stableFrom`); the two agree to the working precision
/// (tests/core/manifolds).

#include <cstddef>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/manifolds/ManifoldParameterization.hpp"
#include "core/manifolds/TurnstileFlux.hpp"  // ManifoldProgressCallback
#include "core/map/MapParameters.hpp"
#include "core/view/Viewport.hpp"        // PhysicalRect

namespace archipelago {

/// How a stable branch is computed.
enum class StableConstruction { InverseMap, ReversingSymmetry };

/// The finest chord bound: 10⁵ units in the last place of a long double coordinate of order 1.  Below it the chord
/// bound asks for more than the points' own precision, and the refinement runs down to the parameter resolution
/// everywhere: `--spacing 1e-17` recursed for hours (issue 36).  A zoomed portrait's spacing is clamped to it.
inline constexpr long double kMinManifoldSpacing = 1e-14L;
/// The memory a point of the branch may take while it is built: x, y, s and t in long double (64 bytes), twice for
/// the vectors' growth.  maxPoints of them must fit the machine before work starts (io::checkMemory).
inline constexpr std::size_t kManifoldBytesPerPoint = 2 * (sizeof(PhysicalPoint) + 2 * sizeof(long double));

struct ManifoldCurveRequest {
  long double K = 0.1L;                        ///< (0, 1]
  std::optional<PeriodicOrbit> orbit;          ///< a hyperbolic periodic orbit; none: the fixed point (√K, 0)
  int point = 0;                               ///< the orbit point whose branch is drawn, [0, period)
  ManifoldKind kind = ManifoldKind::Unstable;
  BranchSide side = BranchSide::Inward;        ///< inward: the fixed point's loop around the central island
  StableConstruction stableFrom = StableConstruction::InverseMap;
  long double length = 4;                      ///< arc length to draw (physical units), (0, 10⁶]
  int maxDomains = 40;                         ///< fundamental domains at most, [1, 10⁴]
  long double maxSpacing = 2e-3L;              ///< chord bound (physical units), [kMinManifoldSpacing, 1]
  long double maxAngle = 0.1L;                 ///< turning-angle bound (radians), (0, 1]
  int initialPoints = 32;                      ///< points per domain before refinement, [2, 10⁶]
  std::optional<PhysicalRect> view;            ///< refine finely only here (x0 < x1, y0 < y1)
  std::optional<MapParameters> box;            ///< draw the manifold of Q* in this box; none: Q in the plane
  long double escapeRadius = 3;                ///< plane only: points farther from the origin are dropped, [0.1, 10⁶]
  std::size_t maxPoints = 4'000'000;           ///< [16, 10⁸], and maxPoints·kManifoldBytesPerPoint available
};

/// The first invalid field, named, or nothing.  (The memory for maxPoints is checked by computeManifoldCurve().)
[[nodiscard]] std::optional<std::string> validationError(const ManifoldCurveRequest& r);

/// Throws io::NotEnoughMemory ("… needs about N MiB of memory but only M MiB are available") when the request's
/// maxPoints may not fit the memory available: computeManifoldCurve() checks it first; front ends that search for
/// the orbit before call it with their other checks, before that work.
void checkManifoldMemory(const ManifoldCurveRequest& r);

/// One unbroken polyline of the branch.
struct ManifoldPiece {
  std::vector<PhysicalPoint> points;
  std::vector<long double> arcLength;  ///< s at each point, counted from the orbit point along the pieces
  std::vector<long double> parameter;  ///< t at each point (see the file comment)
};

struct ManifoldCurve {
  std::vector<ManifoldPiece> pieces;
  PhysicalPoint origin;                ///< the orbit point the branch leaves (or approaches)
  long double length = 0;              ///< arc length drawn
  int domains = 0;                     ///< fundamental domains computed
  std::size_t points = 0;
  std::size_t unresolved = 0;          ///< intervals still coarser than the bounds at the parameter resolution (cut);
                                       ///< they count against maxPoints, so that the work is bounded
  std::size_t breaks = 0;              ///< cuts (escapes to infinity, wraps of the torus)
  std::string stoppedBy;               ///< "length", "domains", "points" or "escaped"
};

/// "inverse" (InverseMap) or "symmetry" (ReversingSymmetry): the names every front end gives the construction.
[[nodiscard]] const char* toString(StableConstruction c) noexcept;
/// The inverse of toString(); throws std::invalid_argument "<option> '<text>' must be inverse or symmetry".
[[nodiscard]] StableConstruction parseStableConstruction(const std::string& text,
                                                         const std::string& option = "stable_from");

/// Computes the branch.  Throws std::invalid_argument for an invalid request (or an orbit that is not hyperbolic, a
/// point out of range, a box that does not contain the orbit point, a reversing symmetry that does not map the
/// orbit onto itself); io::NotEnoughMemory when maxPoints·kManifoldBytesPerPoint exceeds the memory available,
/// before any work; std::runtime_error("stopped") when stopped.  progress is called after each domain.
[[nodiscard]] ManifoldCurve computeManifoldCurve(const ManifoldCurveRequest& request,
                                                 const ManifoldProgressCallback& progress = {},
                                                 std::stop_token stop = {});

}  // namespace archipelago
