#pragma once
/// \file SmallKTheory.hpp
/// \brief The small-K theory of Karney (1983), §4: trapping times and trapping statistics near the tangent
/// bifurcation of Q, as pure functions (no state, thread-safe), for drawing over measured f_t and C_τ.
///
/// Scaled variables (§4).  For small |K| put K = ∓ε⁴, x = ε²X, y = ε³Y, t = T/ε (so ε = |K|^(1/4); the paper
/// prints the exponents α, β of x and y swapped).  Q then becomes the flow of
///   K < 0:  H = ½Y² − ⅔X³ − 2X   (eq. hama),
///   K = 0:  H = ½Y² − ⅔X³        (eq. ham),
///   K > 0:  H = ½Y² − ⅔X³ + 2X   (eq. hamb),
/// and a trajectory's trapping time is the time it takes to run from Y = −∞ to Y = +∞.  X0 names the
/// trajectory by its intercept with Y = 0.  Functions named "...Shape" take unscaled t (iterations of Q) and K
/// and return a curve proportional to f_t or C_τ; the constant of proportionality depends on the
/// normalisation of the data and is fitted with fitAmplitude().
///
/// K < 0.  T(X0) (eq. tneg) reduces exactly to a complete elliptic integral of the first kind.  With
/// X = X0 + u², then u = s·v, s⁴ = 3(X0² + 1), then v = tan θ and φ = 2θ:
///   T(X0) = 2√3 ∫₀^∞ du / √(u⁴ + 3X0u² + 3X0² + 3) = 2·3^(1/4) K(m) / (X0² + 1)^(1/4),
///   m = (1 − β)/2,  β = (√3/2) X0 / √(X0² + 1)  ∈ (−√3/2, √3/2),
/// so 0.067 < m < 0.933 for every real X0 and K(m), E(m) come from the arithmetic–geometric mean in long
/// double.  T and T' are accurate to a few units in the last place of a double (tests compare with direct
/// quadrature of eq. (tneg) to 1e-13).  F(T) = Σ 2(X0² + 1)/|T'(X0)| over the two branches of T(X0) = T
/// (eq. fneg) has relative accuracy ~1e-13 away from Tmax, degrading as ~1e-16·Tmax/(Tmax − T) near it
/// (the inversion is ill-conditioned there: 3e-8 at Tmax − T = 1e-8); within 1e-9 of Tmax the cutoff law
/// c/√(Tmax − T), itself accurate to ~8(Tmax − T), is used instead.
///
/// K = 0.  T(X0) = A·X0^(−1/2) for X0 > 0 and √3·A·|X0|^(−1/2) for X0 < 0, A = Γ(1/3)√π/Γ(5/6) = 4.2065…
/// (the paper's "4.207"; its stacked "{1, √3}" factor belongs to X0 ≷ 0).  Hence f_t ∝ t⁻⁷, C_τ ∝ τ⁻⁵.
///
/// K > 0.  Long-time behaviour from the hyperbolic fixed point (x, y) = (√K, 0): f_t ∝ exp(−½ log λ · t) with
/// λ = 1 + 2√K + 2√(√K + K) ≈ 1 + 2K^(1/4), so ½ log λ ≈ K^(1/4).  C_τ decays at the same rate.
///
/// Inputs outside a function's domain give NaN (GeographicLib's convention), never an exception, so a plot
/// can sample freely; fitAmplitude() is the exception (mismatched array sizes are a programming error).

#include <optional>
#include <string>
#include <cstddef>
#include <functional>
#include <limits>
#include <span>

namespace archipelago::smallk {

// ---------------------------------------------------------------------------------------------------------
// K < 0, scaled variables (eq. hama)

/// T(X0) = ∫_{X0}^∞ dX / √(X³/3 + X − X0³/3 − X0)  (eq. tneg), for any finite real X0.  T > 0, T → 0 as
/// |X0| → ∞ (as the K = 0 law), maximum negativeKMaximum().T at X0 ≈ −0.5536.  NaN for non-finite X0.
[[nodiscard]] double negativeKTrappingTime(double X0) noexcept;

/// dT/dX0, from the derivatives of K(m) in closed form (dK/dm = (E − (1 − m)K) / (2m(1 − m))).
[[nodiscard]] double negativeKTrappingTimeDerivative(double X0) noexcept;

/// The maximum trapping time (paper: Tmax = 5.1454 at X0 = −0.5536).
struct TrappingTimeMaximum {
  double X0;         ///< the argmax, the root of T'(X0) = 0, to full double precision
  double T;          ///< Tmax = T(X0)
  double curvature;  ///< T''(X0) < 0 (Richardson-extrapolated central difference of T', ~1e-12 relative)
};
/// Computed once on first call (thread-safe static initialisation).
[[nodiscard]] const TrappingTimeMaximum& negativeKMaximum();

/// The two trajectories with trapping time T: left < X0max ≤ right, T(left) = T(right) = T.  Both NaN unless
/// 0 < T ≤ Tmax (both equal X0max at T = Tmax).  Safeguarded Newton; |T(X0) − T| within a few ulps of T.
struct TrappingTimeBranches {
  double left;
  double right;
};
[[nodiscard]] TrappingTimeBranches negativeKInverse(double T);

/// F(T) = Σ_branches 2(X0² + 1) / |T'(X0)|  (eq. fneg): the density of segments of length T, up to a
/// constant.  0 < T < Tmax; 0 for T > Tmax (no longer trapping exists); +∞ at T = Tmax; NaN for T ≤ 0.
[[nodiscard]] double negativeKSegmentDensity(double T);

/// lim_{T→0} T⁷ F(T) = 4(A⁶ + (√3A)⁶) = 112 A⁶ ≈ 6.2055e5 (paper: 6.205e5), A = zeroKTimeConstant().
/// The approach is fast: T⁷F(T) = 112A⁶ (1 + O(T⁴)).
[[nodiscard]] double negativeKSmallTCoefficient();

/// lim_{T→Tmax} √(Tmax − T) F(T) = 2√2 (X0max² + 1) / √|T''(X0max)| ≈ 3.024 (paper: 3.024).  The two
/// branches' O(√(Tmax − T)) corrections cancel, so √(Tmax − T) F(T) = c (1 + O(Tmax − T)).
[[nodiscard]] double negativeKCutoffCoefficient();

/// C(Θ) = ∫_Θ^Tmax (T − Θ) F(T) dT = ∫_{left}^{right} (T(X0) − Θ) 2(X0² + 1) dX0 (branches of Θ), the scaled
/// correlation function up to a constant (§4: C'' = F, and C ≈ (4/3)c (Tmax − Θ)^(3/2) near Tmax with c the
/// cutoff coefficient).  Composite Gauss–Legendre in w = asinh X0, relative accuracy ~1e-12.  0 for Θ ≥ Tmax,
/// NaN for Θ ≤ 0 (the integral diverges as Θ⁻⁵).
[[nodiscard]] double negativeKCorrelation(double Theta);

/// Unscaled K < 0: the longest trapping t_max = Tmax |K|^(−1/4) (iterations of Q).  NaN unless K < 0.
[[nodiscard]] double negativeKMaximumTime(double K) noexcept;
/// The longest trapping in a finite box (issue #26): a run of Q* ends a segment when the orbit leaves the box
/// x ∈ [xmin, xmax), |y| < L/2 (L = xmax − xmin), so its longest segment is shorter than t_max by the time the
/// trajectory of eq. (hama) spends beyond the box.  In the scaled variables x = ε²X, y = ε³Y, t = T/ε (ε = |K|^¼),
/// the trajectory through (X₀, 0) has Y(X) = 2√(⅓(X³ − X₀³) + X − X₀) and spends
///     T_box(X₀) = 2 ∫_{X₀}^{X_e} dX / Y(X),   X_e = min(xmax/ε², the X where |Y| = (L/2)/ε³),
/// inside (both branches leave on the right: Y > 0 going out, Y < 0 coming in; eq. tneg is X_e → ∞).  With
/// X = X₀ + u² the integrand is smooth: T_box = ∫_0^{√(X_e − X₀)} 2 du / √(⅓(X² + X X₀ + X₀²) + 1); Gauss–Legendre.  This returns
/// max over X₀ of T_box, in steps (÷ ε): the continuous limit (ε → 0) of the longest segment a run in that box can
/// record.  For xmax → ∞ it tends to negativeKMaximumTime(K).  NaN unless K < 0 and xmin < 0 < xmax.
[[nodiscard]] double negativeKMaximumTimeInBox(double K, double xmin, double xmax);

/// Unscaled K < 0: x of the longest-trapped trajectory on y = 0, X0max √|K|.  NaN unless K < 0.
[[nodiscard]] double negativeKMaximumPosition(double K) noexcept;
/// f_t ∝ F(|K|^(1/4) t) for t = O(|K|^(−1/4)), K < 0.  NaN unless K < 0 and t > 0.
[[nodiscard]] double negativeKSegmentShape(double t, double K);
/// C_τ ∝ C(|K|^(1/4) τ), K < 0.  NaN unless K < 0 and τ > 0.
[[nodiscard]] double negativeKCorrelationShape(double tau, double K);

// ---------------------------------------------------------------------------------------------------------
// K = 0 (eq. ham)

/// A = √3 ∫₁^∞ dZ/√(Z³ − 1) = ∫_{−1}^∞ dZ/√(Z³ + 1) = Γ(1/3)√π / Γ(5/6) = 4.20654… (from std::tgamma, to
/// a few ulps), so that T(X0) = A X0^(−1/2) for X0 > 0.
[[nodiscard]] double zeroKTimeConstant() noexcept;
/// T(X0) = 2∫_{X0}^∞ dX/√(4(X³ − X0³)/3): A X0^(−1/2) for X0 > 0, √3 A |X0|^(−1/2) for X0 < 0, +∞ at 0.
[[nodiscard]] double zeroKTrappingTime(double X0) noexcept;
/// f_t ∝ t⁻⁷ (t > 0; NaN otherwise).  In scaled variables F(T) = 112 A⁶ T⁻⁷ exactly.
[[nodiscard]] double zeroKSegmentShape(double t) noexcept;
/// C_τ ∝ τ⁻⁵ (τ > 0; NaN otherwise).
[[nodiscard]] double zeroKCorrelationShape(double tau) noexcept;

// ---------------------------------------------------------------------------------------------------------
// K > 0 (eq. hamb)

/// λ = 1 + 2√K + 2√(√K + K), the larger eigenvalue of Q's Jacobian at (√K, 0) (trace 2 + 4√K, det 1).
/// NaN unless K ≥ 0.
[[nodiscard]] double positiveKLyapunovNumber(double K) noexcept;
/// ½ log λ ≈ K^(1/4) (0.0998 at K = 1e-4), computed as ½ log1p(λ − 1).  NaN unless K ≥ 0.
[[nodiscard]] double positiveKDecayRate(double K) noexcept;
/// f_t ∝ exp(−½ log λ · t) (and C_τ likewise), valid for t ≫ K^(−1/4).  NaN unless K > 0.
[[nodiscard]] double positiveKSegmentShape(double t, double K) noexcept;

// ---------------------------------------------------------------------------------------------------------
// Any small K

/// The rule of the shapes' arguments (a time t ≥ 0 in steps and a finite K; anything else is an error, not NaN):
/// "t = <t> must be a finite time >= 0 (steps)", "K = <K> must be a finite number", or nothing.
[[nodiscard]] std::optional<std::string> shapeArgumentError(double t, double K);

/// The shape of f_t for this K: negativeKSegmentShape, zeroKSegmentShape or positiveKSegmentShape.
[[nodiscard]] double segmentShape(double t, double K);
/// The shape of C_τ for this K: negativeKCorrelationShape, zeroKCorrelationShape or positiveKSegmentShape.
[[nodiscard]] double correlationShape(double tau, double K);

/// The amplitude a that best fits a·shape(t) to data in log space: log a = mean of log(f_i / shape(t_i)) over
/// the points with tLow ≤ t_i ≤ tHigh, f_i > 0 and shape(t_i) finite and > 0 (a geometric mean of ratios,
/// the least-squares solution for log f = log a + log shape).
struct AmplitudeFit {
  double amplitude = std::numeric_limits<double>::quiet_NaN();       ///< NaN when no point qualifies
  std::size_t points = 0;                                            ///< points used
  double rmsLogResidual = std::numeric_limits<double>::quiet_NaN();  ///< rms of log(f_i / (a shape(t_i)))
  [[nodiscard]] bool valid() const noexcept { return points > 0; }
};
/// Throws std::invalid_argument when t and f differ in size.
[[nodiscard]] AmplitudeFit fitAmplitude(std::span<const double> t, std::span<const double> f, double tLow,
                                        double tHigh, const std::function<double(double)>& shape);

}  // namespace archipelago::smallk
