#pragma once
/// \file OrbitClassification.hpp
/// \brief The one classification of a periodic orbit by Greene's residue, with its words.
///
/// Greene's residue of an orbit of period n is R = (2 − trace DQⁿ)/4 (PeriodicOrbit.hpp).  DQⁿ has
/// determinant 1, so its eigenvalues λ, 1/λ solve λ + 1/λ = trace = 2 − 4R:
///   R < 0       hyperbolic: λ > 1 real, positive (unstable);
///   R = 0       parabolic: λ = 1 double (the boundary where a tangent bifurcation creates a pair of orbits,
///               as at K = 0 for the fixed point x = y = 0 of Q; Karney 1983, §2: "not a hyperbolic point since
///               its stability is determined by the quadratic terms");
///   0 < R < 1   elliptic: λ = exp(±2πiω), linearly stable, with cos 2πω = 1 − 2R, i.e. R = sin²(πω);
///   R = 1       parabolic: λ = −1 double (the period-doubling boundary);
///   R > 1       hyperbolic with reflection: λ < −1 real, negative (unstable).
/// The boundaries are exact comparisons of the computed residue (no tolerance: a residue within rounding of
/// 0 or 1 is classified by its computed value, which is what was measured).
///
/// The linear rotation number ω ∈ [0, 1/2] (turns per period of DQⁿ about the orbit, from cos 2πω = 1 − 2R)
/// is defined on the closed interval 0 ≤ R ≤ 1: ω = 0 at R = 0, ω = 1/2 at R = 1; hyperbolic orbits have none.

#include <optional>

namespace archipelago {

/// Linear stability of a periodic orbit, by its residue R (above).
enum class OrbitStability {
  Hyperbolic,            ///< R < 0
  Parabolic,             ///< R = 0 or R = 1
  Elliptic,              ///< 0 < R < 1
  HyperbolicReflection,  ///< R > 1
};

/// An orbit's class, with the linear rotation number where it is defined.
struct OrbitClassification {
  OrbitStability stability = OrbitStability::Elliptic;
  long double residue = 0;                     ///< R, as given
  std::optional<long double> rotationNumber;   ///< ω ∈ [0, 1/2] with cos 2πω = 1 − 2R, for 0 ≤ R ≤ 1

  /// Linearly stable: elliptic, 0 < R < 1.
  [[nodiscard]] bool stable() const noexcept { return stability == OrbitStability::Elliptic; }
  /// The class and its range of R, e.g. "elliptic, 0 < R < 1" or "parabolic, R = 0" (the words every surface,
  /// CLI and GUI, shows).
  [[nodiscard]] const char* description() const noexcept;
};

/// The class of an orbit of residue R (any R but NaN, ±∞ included).  Throws std::invalid_argument for NaN.
[[nodiscard]] OrbitClassification classifyOrbit(long double residue);

/// "hyperbolic", "parabolic", "elliptic" or "hyperbolic with reflection".
[[nodiscard]] const char* toString(OrbitStability s) noexcept;

}  // namespace archipelago
