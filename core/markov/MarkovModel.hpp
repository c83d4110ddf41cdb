#pragma once
/// \file MarkovModel.hpp
/// \brief The Markov-chain model of a stochastic sea with trapped segments (Karney 1983, appendix C):
/// the correlation function C(τ) (eq. cmark), its deviation ε(τ) from the island term, and the diffusion
/// coefficient D by the matrix formula and by eq. (dmark), at the cost of an (m + 1)-point problem.
///
/// The model (appendix C).  N points; M trapped segments T_k = {p_k⁽¹⁾, …, p_k⁽ᵐᵏ⁾} of lengths m_k ≥ 1,
/// m = Σ m_k; q_k is the pre-image of p_k⁽¹⁾; S = complement of T (the sea, n = N − m points, pre-images
/// included); S′ = S without the pre-images (n′ = N − m − M points).  One step of the chain:
///   p_k⁽ⁱ⁾ → p_k⁽ⁱ⁺¹⁾ (i < m_k);   q_k → p_k⁽¹⁾;   p_k⁽ᵐᵏ⁾ and every point of S′ → each point of S with
///   probability 1/n.
/// The entry P_ji is the probability of going from point i to point j (column i says where i goes), as in
/// the 7-point example, eq. (pex): N = 7, m = 3, points 1–3 trapped, 4–6 the points of S′, 7 the pre-image q
/// (the paper's text says "points 4–8 … point 8", a slip for 4–7 and 7: the matrix is 7 × 7).  P is doubly
/// stochastic (every row also sums to 1), so the uniform distribution is stationary and P^τ → C = [1/N];
/// with n′ ≥ 1 a point of S′ returns to itself with probability 1/n > 0, so the chain is aperiodic and
/// Q = P − C has Q^τ → 0.
///
/// Observable h (a value per point) with Σ h = 0, so that h·C·h = 0 and P may be replaced by Q:
///   C(τ) = h·P^τ·h / N                                        (eq. cmark)
///   D    = h·(½I + Σ_{τ≥1} Q^τ)·h / N = h·(½I + Q(I − Q)⁻¹)·h / N
///   D    = (1/2N) (Σ_{j∈S′} h_j² + Σ_k (Σ_{i∈T′_k} h_i)²),   T′_k = {q_k} ∪ T_k      (eq. dmark)
///
/// The lumped (m + 1)-dimensional chain, derived here (the paper only says "the computational effort is the
/// same as for (m + 1) × (m + 1) matrices").  Evolve a vector F by F ← P F:
///   F′(p_k⁽¹⁾) = F(q_k),  F′(p_k⁽ⁱ⁺¹⁾) = F(p_k⁽ⁱ⁾),  F′(s) = (Σ_{S′} F + Σ_k F(p_k⁽ᵐᵏ⁾)) / n  for all s ∈ S,
/// because every row of P in S is the same.  So after one step F is one constant a on all of S, pre-images
/// included, and the state (F on T, a) ∈ R^(m+1) evolves by the (m + 1) × (m + 1) matrix R:
///   F′(p_k⁽¹⁾) = a,  F′(p_k⁽ⁱ⁺¹⁾) = F(p_k⁽ⁱ⁾),  a′ = (n′ a + Σ_k F(p_k⁽ᵐᵏ⁾)) / n,
/// a shift along each segment plus one row: O(m) work per step.  Of h on S′ only two numbers matter: its sum
/// (fixed by Σ h = 0) and its sum of squares (in C(0) and D only); hence LumpedObservable.
///   - C(τ), τ ≥ 1: F(1) = P h (F(1)(p_k⁽¹⁾) = h(q_k), F(1)(p_k⁽ⁱ⁺¹⁾) = h(p_k⁽ⁱ⁾), a(1) = (Σ_{S′} h +
///     Σ_k h(p_k⁽ᵐᵏ⁾))/n), F(τ) = R^(τ−1) F(1), and N C(τ) = Σ_T h F(τ) + a(τ) Σ_S h.
///   - D: y = Σ_{τ≥1} P^τ h = Q(I − Q)⁻¹ h is the solution of y = P h + P y with Σ y = 0 (the solutions of
///     the first equation differ by constants: the chain is irreducible).  y is constant (a_y) on S, and
///     along a segment y(p_k⁽ⁱ⁾) = a_y + s_k(i − 1), s_k(j) = h(q_k) + Σ_{l≤j} h(p_k⁽ˡ⁾) the partial sums
///     along T′_k; the equation for a_y holds identically (it is Σ h = 0) and Σ y = 0 gives
///     a_y = −Σ_{k,i} s_k(i − 1) / N.  Then D = h·h/(2N) + (Σ_T h y + a_y Σ_S h)/N: O(m).
///     Since Σ_S h = −Σ_T h, a_y cancels and Σ_i h(p_k⁽ⁱ⁾) s_k(i − 1) = ((Σ_{T′_k} h)² − Σ_{T′_k} h²)/2,
///     which is eq. (dmark): the paper's Macsyma result holds exactly, for any M and any h with Σ h = 0.
///     (diffusionCoefficient() evaluates the solve, a_y included; diffusionCoefficientDmark() the formula.)
///
/// The island term (§6 with A₁ = N, B₁ = m, f*_t = Σ_k δ_{t m_k}/m), for h = h₀ on T:
///   C_is(τ) = h₀² Σ_k max(m_k − τ, 0) / N   (one segment: (m − τ)/N for τ ≤ m, 0 beyond),
///   D_is = ½ h₀² Σ_k m_k² / N,    ε(τ) = (C(τ) − C_is(τ)) / C_is(0),  C_is(0) = h₀² m / N.
/// The paper's statements for one segment, h = 1 on T, 0 on q (tests/core/markov): after a transient ε(τ)
/// oscillates with half-period ≈ m and decays ≈ n^(−τ/m) (exactly: the root λ = r e^(iθ), θ ∈ (π/m, 2π/m), of
/// λ^m (n(λ − 1) + 1) = 1 gives half-period π/θ and decay −log r); the most negative C(τ) is at τ = m; and
/// Σ_{τ≥1} ε(τ) = 0.  The bound "|ε(τ)| ≤ m/N for τ > 0" holds only for N ≥ m²: the largest |ε| is
/// ε(1) = (m − 1)/(N − m) exactly, which exceeds m/N (by < 11%) at N = 10m for m = 20, 50.
/// Eq. (dmark) gives D = (1/2N)(Σ_S h² + h₀² Σ_k m_k²) (the paper's eq. after (dmark)), i.e. an island part
/// D − Σ_S h²/2N equal to D_is, exactly when h = h₀ on T and Σ_k m_k h(q_k) = 0.
///
/// Accuracy: all sums and the recursion in long double.  Tests: C(τ) and D agree with the dense N × N
/// evaluation to 1e-13 absolute (|h| ≤ 2, N ≤ 200), the hand values of the 7-point example to 1 ulp, and ε(1)
/// with its closed form to 1e-11 relative up to N = 5·10⁷; the recursion's rounding floor for ε is ~1e-40.
/// Sizes: 1 ≤ M, m_k ≥ 1, m ≤ kMaxTrappedPoints, m + M + 1 ≤ N ≤ kMaxPoints (N exact in a double), and
/// (m + 1)(τmax + 1) ≤ kMaxWork for correlation() (about a second of work).  Functions throw
/// std::invalid_argument naming the first offending quantity.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace archipelago::markov {

/// The shape of the chain: segment lengths m_k and the number of points N.
struct MarkovModel {
  std::vector<std::int64_t> segmentLengths;  ///< m_k ≥ 1, k = 1 … M
  std::int64_t points = 0;                   ///< N ≥ m + M + 1

  static constexpr std::int64_t kMaxTrappedPoints = 1'000'000;         ///< bound on m = Σ m_k
  static constexpr std::int64_t kMaxPoints = std::int64_t{1} << 53;    ///< bound on N (exact in a double)
  static constexpr std::int64_t kMaxWork = 500'000'000;                ///< bound on (m + 1)(τmax + 1)
  /// Memory per lag of a caller holding C, C_is and ε (each made through a long double copy): checked against
  /// the memory available (io::checkMemory, std::runtime_error) before a series is computed.
  static constexpr std::uintmax_t kBytesPerLag = 96;

  [[nodiscard]] std::int64_t trappedPoints() const noexcept;     ///< m = Σ m_k
  [[nodiscard]] std::int64_t seaPoints() const noexcept;         ///< n = N − m (S, pre-images included)
  [[nodiscard]] std::int64_t freeSeaPoints() const noexcept;     ///< n′ = N − m − M (S′)
};

/// Throws std::invalid_argument unless the model is within the documented range.
void validate(const MarkovModel& model);

/// The observable h, lumped: its values on T and on the pre-images, and Σ_{S′} h² (its sum over S′ is
/// −(Σ_T h + Σ_q h), fixed by Σ h = 0).
struct LumpedObservable {
  std::vector<std::vector<double>> trapped;  ///< h(p_k⁽ⁱ⁾): trapped[k][i − 1], sizes m_k
  std::vector<double> preImages;             ///< h(q_k), size M
  double freeSeaSquares = 0;                 ///< Σ_{j∈S′} h_j² ≥ (Σ_{S′} h)²/n′ (Cauchy–Schwarz)

  [[nodiscard]] long double trappedSum() const noexcept;  ///< Σ_T h
  [[nodiscard]] long double freeSeaSum() const noexcept;  ///< Σ_{S′} h = −(Σ_T h + Σ_q h)
};

/// Throws std::invalid_argument unless the observable fits the model (sizes, finite values, Cauchy–Schwarz on
/// S′ to a relative 1e-12).
void validate(const MarkovModel& model, const LumpedObservable& h);

/// The paper's observable (appendix C): h = h₀ on T, 0 on every pre-image, and the constant −h₀ m/n′ on S′
/// (the smallest Σ_{S′} h² with Σ h = 0).  Then Σ_k m_k h(q_k) = 0, so D's island part equals D_is.
[[nodiscard]] LumpedObservable paperObservable(const MarkovModel& model, double h0 = 1);

/// Throws io::NotEnoughMemory (std::runtime_error) when the series C, C_is and ε up to τmax (kBytesPerLag per lag)
/// do not fit in the memory available now.  correlation(), islandCorrelation() and correlationDeviation() check it
/// each; a caller that computes all three calls it once before any of them, so that a series too large is refused
/// before the work, not after the first of three (issue #23: the hostile harness saw a refusal after 40 s).
void checkSeriesMemory(std::int64_t tauMax);

/// The largest τmax of correlation() for the model: kMaxWork/(m + 1) − 1.
[[nodiscard]] std::int64_t maxTau(const MarkovModel& model) noexcept;

/// The rules of the series (issue 35: one message for the CLI's `markov` and Python's markov()): "tau_max = … must
/// lie in [0, maxTau] (kMaxWork/(m + 1) − 1 for m = …)", "h0 = … must be a finite number"; nothing when they hold.
[[nodiscard]] std::optional<std::string> seriesError(const MarkovModel& model, std::int64_t tauMax, double h0 = 1);

/// C(τ) = h·P^τ·h/N for τ = 0 … tauMax (eq. cmark), by the lumped chain: O(m) per τ.
[[nodiscard]] std::vector<double> correlation(const MarkovModel& model, const LumpedObservable& h,
                                              std::int64_t tauMax);

/// C_is(τ) = h₀² Σ_k max(m_k − τ, 0)/N for τ = 0 … tauMax (the island term, §6).
[[nodiscard]] std::vector<double> islandCorrelation(const MarkovModel& model, std::int64_t tauMax, double h0 = 1);

/// ε(τ) = (C(τ) − C_is(τ))/C_is(0), τ = 0 … tauMax, with C_is for h = h0 on T; the difference is taken in
/// long double before rounding (C and C_is agree to ~m/N relative, so ε from the rounded arrays would lose
/// that many digits).
[[nodiscard]] std::vector<double> correlationDeviation(const MarkovModel& model, const LumpedObservable& h,
                                                       std::int64_t tauMax, double h0 = 1);

/// D = h·(½I + Q(I − Q)⁻¹)·h/N, by the lumped solve (O(m); see the derivation above).
[[nodiscard]] double diffusionCoefficient(const MarkovModel& model, const LumpedObservable& h);

/// D by eq. (dmark): (1/2N)(Σ_{S′} h² + Σ_k (Σ_{T′_k} h)²).
[[nodiscard]] double diffusionCoefficientDmark(const MarkovModel& model, const LumpedObservable& h);

/// D_is = ½ h₀² Σ_k m_k² / N (§6, appendix C).
[[nodiscard]] double islandDiffusionCoefficient(const MarkovModel& model, double h0 = 1);

}  // namespace archipelago::markov
