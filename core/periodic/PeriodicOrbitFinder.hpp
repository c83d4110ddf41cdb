#pragma once
/// \file PeriodicOrbitFinder.hpp
/// \brief Finding periodic orbits of Q: symmetric ones by shooting between symmetry lines, any one by Newton.
///
/// Karney (1983), §6 (the chains of islands around islands); the method is the classical one for reversible
/// maps (Greene 1979; for this map, Hénon 1969): write Q = I₂ ∘ I₁ with involutions whose fixed sets are the
/// symmetry lines S₁: y = K − x² and S₂: y = 0 (SmoothQuadraticMap.hpp).  A symmetric orbit of period n has
/// a point z = (s, y_line(s)) on one line whose image after m = ⌊n/2⌋ or ⌈n/2⌉ steps lies on a line again, so
/// it is a root of the one-dimensional function F(s) = offset of Qᵐ(z(s)) from the target line.  Roots are
/// bracketed by scanning F over short windows of the line, refined by bisection in long double, and polished
/// by Newton's method along the line in __float128 (113 bits), so that even period 138 at K = 0.1 closes to
/// ~1e-25.  Roots whose minimal period is a proper divisor of n (e.g. the period-6 orbit solves the
/// period-138 problem) are discarded.
///
/// Where to scan: the guess `near` is iterated n times with Q; wherever an iterate passes within
/// `searchRadius` of a symmetry line, the window |x − x_iterate| ≤ searchRadius·(1 + |slope|) of that line is
/// scanned.  A guess inside an island of the chain, or anywhere within about searchRadius of an orbit point,
/// finds the chain's symmetric orbits (both its elliptic and its hyperbolic one, usually).
///
/// The general method (refinePeriodicOrbit) is damped Newton on Qⁿ(z) − z in __float128 with the exact
/// Jacobian DQⁿ − I; it needs a guess within the basin of the orbit (which shrinks as |DQⁿ| grows).

#include <functional>
#include <optional>
#include <span>
#include <vector>

#include <stdexcept>
#include <stop_token>

#include "core/map/FixedPointMap.hpp"  // PhysicalPoint
#include "core/periodic/PeriodicOrbit.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"

namespace archipelago {

/// What to look for.  Plain values; findSymmetricPeriodicOrbits() validates them.
struct PeriodicOrbitSearch {
  int period = 1;                    ///< n ≥ 1, at most kMaxPeriod
  PhysicalPoint near;                ///< a guess for a point of the orbit (physical x, y)
  long double searchRadius = 0.01L;  ///< > 0: how far (physical units) from the guess's iterates to scan
  int samplesPerWindow = 400;        ///< ≥ 8: scan points per window of width 2·searchRadius
  bool stableOnly = false;           ///< keep only elliptic orbits (0 < R < 1)

  static constexpr int kMaxPeriod = 100000;
};

/// Throws std::invalid_argument naming the first invalid field (K must be finite too).
void validate(long double K, const PeriodicOrbitSearch& search);

/// All distinct symmetric orbits of minimal period `search.period` found from the guess, nearest first
/// (distance from `near` to the orbit's nearest point); each is relabelled so that z_0 is that nearest point.
/// Empty when none was found.  Accepted orbits close to |Qⁿ(z_0) − z_0| ≤ 1e-12.
/// A search of period n costs about 2 · samples · n steps of Q: at the largest periods that is tens of seconds,
/// so `stop` is checked at every sample, and a stopped search throws OperationStopped.
[[nodiscard]] std::vector<PeriodicOrbit> findSymmetricPeriodicOrbits(long double K, const PeriodicOrbitSearch& search,
                                                                     std::stop_token stop = {});

/// A window lo ≤ x ≤ hi of a symmetry line (both lines are graphs over x).
struct LineWindow {
  smooth::SymmetryLine line = smooth::SymmetryLine::S2;
  long double lo = 0;
  long double hi = 0;
};

/// The same scan over given windows of the lines instead of those near a guess's iterates: every symmetric orbit of
/// minimal period `period` with a point in a window whose shooting function changes sign between two samples
/// `spacing` apart (found in the order of the windows, duplicates dropped; z_0 is the point on the line).  For
/// callers that know where on the lines the orbits lie, e.g. between two radii about the centre (MmpFlux.hpp).
/// `accept`, when set, sees each bracketed root (long double, on its line) before it is polished in quad and kept: a
/// cheap test (e.g. the winding of its q steps in long double) that spares the quad work on roots the caller would
/// drop (in a chaotic layer most of them: thousands at q ≈ 300).
/// Throws std::invalid_argument for an invalid period or K, a spacing ≤ 0, or a window without lo < hi, and
/// OperationStopped when `stop` is requested.
[[nodiscard]] std::vector<PeriodicOrbit> findSymmetricPeriodicOrbitsIn(long double K, int period,
                                                                       std::span<const LineWindow> windows,
                                                                       long double spacing, std::stop_token stop = {},
                                                                       const std::function<bool(PhysicalPoint)>& accept = {});

/// General (not necessarily symmetric) periodic orbit: damped Newton on Qⁿ(z) − z from `guess`, in __float128.
/// Returns the orbit (z_0 = the converged point) when Newton converged to a point of minimal period n,
/// nothing otherwise.
[[nodiscard]] std::optional<PeriodicOrbit> refinePeriodicOrbit(long double K, int period, PhysicalPoint guess,
                                                               int maxIterations = 100);

/// The same damped Newton as refinePeriodicOrbit(), returning the converged point itself in __float128 (113 bits):
/// for callers that need the orbit to quad precision (the invariant manifolds of core/manifolds are built on it;
/// PeriodicOrbit keeps long double points).  Nothing when K or the guess is not finite, the period is < 1, or
/// Newton did not converge (|Qⁿ(z) − z| above 1e-24); the minimal period is not checked.
[[nodiscard]] std::optional<smooth::Point<quad>> polishPeriodicPoint(long double K, int period,
                                                                     smooth::Point<quad> guess,
                                                                     int maxIterations = 100);

/// The abscissa s of a symmetric orbit's point on `line` (a root of the shooting problem of period n that starts on
/// `line`, SmoothQuadraticMap.hpp), polished by the finder's own Newton along the line in __float128 from `s`
/// (steps above `maxStep` are refused: the result stays s).  For callers that need a symmetric orbit to quad precision
/// (PeriodicOrbit keeps long double points; core/manifolds/MmpFlux.hpp rebuilds the orbit from this point, half
/// forward and half by the reversor, so that rounding grows as √|λ|, not |λ|).
[[nodiscard]] quad polishSymmetricPoint(long double K, int period, smooth::SymmetryLine line, quad s, quad maxStep);

/// The orbit nearest to the guess: the nearest symmetric one, else the general Newton result from the guess.
/// Throws std::invalid_argument for invalid input and NotFound ("no periodic orbit of period n found near (x, y)
/// ...") when neither method succeeds.
/// Throws OperationStopped when `stop` is requested.
[[nodiscard]] PeriodicOrbit findPeriodicOrbit(long double K, const PeriodicOrbitSearch& search, std::stop_token stop = {});

/// What a search or a computation throws when it ran to its end without an answer for this input, which was in
/// range: no periodic orbit of the period near the guess, no symmetric homoclinic crossing within the domains, a
/// turnstile lobe below the resolution of __float128 (K too small).  Another guess, period or K may have one.  The
/// front ends print it as any error; Python raises archipelago.NotFoundError, a ValueError (issue 36: it was a bare
/// RuntimeError).
struct NotFound : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a search stopped through its std::stop_token throws (not an error of the search: the caller asked).
struct OperationStopped : std::runtime_error {
  OperationStopped() : std::runtime_error("stopped") {}
};

}  // namespace archipelago
