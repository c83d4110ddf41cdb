#pragma once
/// \file PeriodicOrbit.hpp
/// \brief A periodic orbit of the quadratic map Q with its residue and rotation number.
///
/// Karney (1983), §6: the islands around islands.  An island chain of order n is centred on an elliptic
/// orbit of period n; between its islands lies a hyperbolic orbit of the same period.  Greene's residue
///   R = (2 − trace DQⁿ)/4
/// classifies the orbit (classifyOrbit(), OrbitClassification.hpp: the one place that does): R < 0 hyperbolic,
/// R = 0 parabolic, 0 < R < 1 elliptic (linearly stable), R = 1 parabolic, R > 1 hyperbolic with reflection.
/// For 0 ≤ R ≤ 1, R = sin²(πν), ν the linear rotation number of nearby orbits about it.
///
/// Rotation number about the centre: the angle θ_k of z_k − (−√K, 0) is followed over one period; the
/// *clockwise* turns W (an integer for a periodic orbit) give ω = W/n.  Q turns points about the elliptic
/// centre (−√K, 0) clockwise in the (x, y) plane (a point (−√K + δ, 0), δ > 0, moves to y = −4√K δ < 0), so
/// with this sign convention orbits around the central island have ω > 0: the chain of six islands at K = 0.1
/// has ω = 1/6, a chain of order 138 = 6 × 23 around those six islands has W = 23, ω = 23/138 = 1/6.
/// Each step's angle increment is taken in (−π, π]; the fixed point (−√K, 0) itself has no angle and is given
/// its linear rotation number ω₀ = arccos(1 − 2R)/(2π) (R = √K, so ω₀ → √K/π for small K; at K = 0 the fixed
/// point is parabolic, R = 0 and ω₀ = 0), which hyperbolic fixed points (K > 1) do not have.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/map/FixedPointMap.hpp"  // PhysicalPoint
#include "core/map/MapParameters.hpp"
#include "core/periodic/OrbitClassification.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"  // quad

namespace archipelago {

/// How an orbit was found, and which symmetry line it meets (SmoothQuadraticMap.hpp).
enum class OrbitSymmetry {
  None,       ///< found by the general two-dimensional Newton method; symmetry not checked
  LineS1,     ///< has a point on S₁: y = K − x²
  LineS2,     ///< has a point on S₂: y = 0
};

[[nodiscard]] const char* toString(OrbitSymmetry s) noexcept;

/// A periodic orbit z_0, …, z_{n−1} of Q with z_{k+1} = Q(z_k) and Q(z_{n−1}) = z_0 (to `closure`).
struct PeriodicOrbit {
  long double K = 0;                 ///< the map parameter
  int period = 0;                    ///< n, the minimal period
  std::vector<PhysicalPoint> points; ///< z_0 … z_{n−1}, physical coordinates, rounded from __float128
  long double trace = 0;             ///< trace DQⁿ, accumulated in __float128
  long double residue = 0;           ///< Greene's residue R = (2 − trace)/4
  long windingTurns = 0;             ///< W: clockwise turns about (−√K, 0) over one period
  long double rotationNumber = 0;    ///< ω = W/n (linear ω₀ for the central fixed point itself; NaN there
                                     ///< when it has none: use rotationNumberText() to show it)
  bool linearRotation = false;       ///< the central fixed point: rotationNumber is its linear ω₀
  long double closure = 0;           ///< |Qⁿ(z_0) − z_0| evaluated in __float128 (Euclidean, physical)
  OrbitSymmetry symmetry = OrbitSymmetry::None;

  /// classifyOrbit(residue).  Throws std::invalid_argument when the residue is NaN.
  [[nodiscard]] OrbitClassification classification() const { return classifyOrbit(residue); }
  /// Linearly stable (elliptic, 0 < R < 1, as classifyOrbit() says); false for a NaN residue.
  [[nodiscard]] bool stable() const noexcept;
  /// Index of the point nearest to p.
  [[nodiscard]] std::size_t nearestIndex(PhysicalPoint p) const noexcept;
  /// Distance from p to the nearest point of the orbit.
  [[nodiscard]] long double distanceTo(PhysicalPoint p) const noexcept;
  /// Whether every point lies in the box [xmin, xmax) × [−L/2, L/2), where Q* = Q (so this is also an orbit of
  /// the map Q* of the trapping runs).
  [[nodiscard]] bool insideBox(const MapParameters& box) const noexcept;
  /// The same orbit relabelled so that point `first` becomes z_0.
  [[nodiscard]] PeriodicOrbit rotatedToStart(std::size_t first) const;
};

/// Builds the PeriodicOrbit from one point z_0 given in quad precision: iterates Q in __float128 to get the
/// points, the closure error, trace DQⁿ (hence R) and the winding about (−√K, 0).  `period` must be ≥ 1.
/// Does not check that z_0 is periodic: look at `closure`.
[[nodiscard]] PeriodicOrbit analysePeriodicOrbit(long double K, int period, quad x0, quad y0,
                                                 OrbitSymmetry symmetry);

/// The orbit's rotation number as every surface shows it, with `digits` significant digits:
///   "0.1666666667 = 23/138 = 1/6 (clockwise turns about (-sqrt K, 0) per step)", or for the central fixed
///   point "0.1011 (linear, at the central fixed point)", "0 = 0/1 (linear, …)" at R = 0, or
///   "none (hyperbolic fixed point: nearby orbits do not turn about it)".  Never "nan".
[[nodiscard]] std::string rotationNumberText(const PeriodicOrbit& orbit, int digits = 18);

/// Clockwise turns about (cx, cy) of the closed polygon z_0 → z_1 → … → z_{n−1} → z_0 (each step's angle
/// increment in (−π, π]).  Used for orbits and, in IslandChain.hpp, for segments.
[[nodiscard]] long clockwiseTurns(std::span<const PhysicalPoint> points, long double cx, long double cy) noexcept;

}  // namespace archipelago
