#pragma once
/// \file PaperNumbers.hpp
/// \brief The numbers Karney (1983) states about the quadratic map Q (§2, §4), as functions: the rotation at
/// the elliptic fixed point, the residues, the period-doubling cascade and its accumulation, and the decay
/// exponent of f_t for g(x) = x^m.
///
/// Q: y' = y + 2(x² − K), x' = x + y' (eq. qu).  DQ(x, y) = [[1 + 4x, 1], [4x, 1]], det 1, trace 2 + 4x.
/// Greene's residue of a period-n orbit is R = (2 − trace DQⁿ)/4 (0 < R < 1 elliptic, R = 1 period doubling).
///
/// Paper numbers that live elsewhere (one definition of each fact; tests/core/theory/test_paper_numbers.cpp
/// checks them against the paper too):
///   - λ = 1 + 2√K + 2√(√K + K) ≈ 1 + 2K^(1/4) at the hyperbolic point (√K, 0) (§4; the paper prints
///     "(0, √K)", a slip): smallk::positiveKLyapunovNumber.
///   - the decay rate of f_t for K > 0, ½ log λ: smallk::positiveKDecayRate.  It gives 0.177 at K = 10⁻³ and
///     0.311 at K = 10⁻² (the values quoted in issue 14); the small-K form K^(1/4) gives 0.178 and 0.316.
///   - the K = 0 trapping time T(X0) = 2∫_{X0}^∞ dX/√(4(X³ − X0³)/3) = A X0^(−1/2) for X0 > 0 and √3 A |X0|^(−1/2)
///     for X0 < 0, A = Γ(1/3)√π/Γ(5/6) = 4.2065 (the paper's "4.207" with its stacked {1, √3} for X0 ≷ 0):
///     smallk::zeroKTrappingTime, smallk::zeroKTimeConstant.
///
/// Functions of K return NaN outside their domain (GeographicLib's convention); periodDoublingCascade throws.

#include <vector>

namespace archipelago::paper {

/// cos α = 1 − 2√K (§2): α is the rotation per step about the elliptic fixed point (−√K, 0) of Q, since
/// trace DQ(−√K, 0) = 2 − 4√K = 2 cos α.  Exact to rounding.  NaN unless 0 ≤ K ≤ 1 (for K > 1 the point is
/// hyperbolic with reflection and there is no rotation angle).
[[nodiscard]] double ellipticRotationCosine(double K) noexcept;

/// Greene's residue of the elliptic fixed point (−√K, 0): R = (2 − (2 − 4√K))/4 = √K.  It reaches 1, the
/// period doubling, at K = 1 (§2).  NaN unless K ≥ 0.
[[nodiscard]] double ellipticFixedPointResidue(double K) noexcept;

/// Greene's residue of the hyperbolic fixed point (√K, 0): R = −√K.  NaN unless K ≥ 0.
[[nodiscard]] double hyperbolicFixedPointResidue(double K) noexcept;

/// The small-K form of the Lyapunov number at (√K, 0), λ ≈ 1 + 2K^(1/4) (§4; the exact λ is
/// smallk::positiveKLyapunovNumber, and λ − 1 − 2K^(1/4) = O(√K)).  NaN unless K ≥ 0.
[[nodiscard]] double smallKLyapunovNumber(double K) noexcept;

/// The exponent of f_t ∝ t^(−(3m+1)/(m−1)) for a kick g(x) = x^m at the tangent bifurcation (§4): 7 for the
/// quadratic map (m = 2), → 3 as m → ∞.  NaN unless m > 1.
[[nodiscard]] double segmentDecayExponent(double m) noexcept;

/// The first two period doublings, exactly: the fixed point's R = √K reaches 1 at K₀ = 1; the period-2 orbit
/// born there, (x₁, x₁ − x₂) ↔ (x₂, x₂ − x₁) with x₁,₂ = −1 ∓ √(K − 1), has trace DQ² = 2 + 8(x₁ + x₂) + 16x₁x₂
/// = 18 − 16K, so R = 4(K − 1) = 1 at K₁ = 5/4.
inline constexpr double kFirstPeriodDoubling = 1;
inline constexpr double kSecondPeriodDoubling = 1.25;

/// The period-doubling cascade of the central fixed point (§2: it accumulates at K = 1.2840).
struct PeriodDoublingCascade {
  /// K_n, n = 0 … levels − 1: the K at which the period-2ⁿ orbit of the cascade has R = 1 (and the period
  /// 2ⁿ⁺¹ orbit is born).  K₀ = 1 and K₁ = 5/4 are exact; later ones are found numerically (see below) to
  /// ~1e-15 absolute.
  std::vector<double> bifurcations;
  /// δ_n = (K_{n−1} − K_{n−2}) / (K_n − K_{n−1}), n = 2 … levels − 1 (→ 8.7210972, the area-preserving
  /// Feigenbaum constant).
  std::vector<double> ratios;
  /// K_∞ ≈ K_n + (K_n − K_{n−1}) / (δ_n − 1) with the last level n (geometric extrapolation).
  double accumulation = 0;
  /// |the same extrapolation from level n − 1 − accumulation|: the size of the extrapolation error.
  double accumulationChange = 0;
};

/// K_n for n = 0 … levels − 1 (3 ≤ levels ≤ 7, periods up to 64; 0.5 s for 7) and the extrapolated
/// accumulation point.  Method, for n ≥ 2: the period-2ⁿ orbit is found at K_{n−1} + 10⁻³(K_{n−1} − K_{n−2})
/// by the symmetric-orbit finder (periodic/PeriodicOrbitFinder.hpp) within 20√(K − K_{n−1}) of the parent
/// orbit (it is born ~√(K − K_{n−1}) from it), elliptic only; it is followed in K with steps growing by 25%,
/// each time by the finder near its last position (Newton alone can fall back onto the parent, which also
/// solves Qⁿ(z) = z), until R ≥ 1; K_n is then the root of R(K) = 1 by bisection in long double to 1e-16 (R
/// itself from DQⁿ in __float128).  Results: K₂ = 1.28011312, K₃ = 1.28359098, K₄ = 1.28399001,
/// K₅ = 1.28403577, K₆ = 1.28404102; δ₆ = 8.72103; K_∞ = 1.2840417 (paper: 1.2840).  accumulationChange is 0
/// for levels = 3.  Throws std::invalid_argument for levels out of range and std::runtime_error if an orbit
/// is lost.
[[nodiscard]] PeriodDoublingCascade periodDoublingCascade(int levels);

}  // namespace archipelago::paper
