#pragma once
/// \file BirkhoffAverage.hpp
/// \brief The weighted Birkhoff average of an orbit and its "digits" of convergence.
///
/// A time average (1/T) Σ f(z_n) over an orbit converges like 1/T on an invariant circle.  Weighting the terms
/// by a bump that vanishes with all its derivatives at both ends makes it converge faster than any power of T
/// on a quasi-periodic orbit (Das, Saiki, Sander & Yorke, "Quantitative quasiperiodicity", Nonlinearity 30
/// (2017) 4111; Sander & Meiss, "Birkhoff averages and rotational invariant circles for area-preserving maps",
/// Physica D 411 (2020) 132569), while on a chaotic orbit it still converges like T^−½.  So the difference of
/// two consecutive averages tells the two apart:
///   - weight:  g(s) = exp(−1/(s(1 − s))) for 0 < s < 1, 0 outside;
///   - average of a block of T terms f_0 … f_{T−1}:  WB = Σ g(n/T) f_n / Σ g(n/T)   (n = 0 … T − 1; g(0) = 0);
///   - digits:  −log₁₀ |WB(block 1) − WB(block 2)|, the two blocks consecutive (terms 0 … T − 1 and T … 2T − 1),
///     capped at kMaxDigits (two equal averages, e.g. on a periodic orbit, give kMaxDigits).
/// At T = 10⁴ a regular orbit of Q reaches 13–15 digits and a chaotic one 2–5 (docs/instruments.md shows the
/// measured histogram); kDefaultDigitsThreshold separates them.
///
/// The sums are compensated (MeasureMath.hpp, twoSumAdd), so that rounding does not limit the digits below
/// ~15; the weights are computed once per T in double (std::exp, relative error < 10⁻¹⁵, the same for every
/// instruction-set path since the table is shared).

#include <cstdint>
#include <span>
#include <stop_token>
#include <vector>

namespace archipelago {

/// g(s) = exp(−1/(s(1 − s))) on (0, 1), 0 elsewhere (and for NaN).
[[nodiscard]] double birkhoffWeight(double s) noexcept;

/// The weights of one block of T terms: g(n/T) for n = 0 … T − 1, and their sum (compensated).
struct BirkhoffWeights {
  std::vector<double> g;
  double sum = 0;
};

/// Iterations T per block: at least kMinIterations (so that Σ g > 0 and the average means something), at most
/// kMaxIterations (the weight table, 8·T bytes, is held in memory).
inline constexpr std::uint64_t kMinIterations = 16;
inline constexpr std::uint64_t kMaxIterations = 10'000'000;
/// The default block length of every surface (CLI, GUI, Python).
inline constexpr std::uint64_t kDefaultIterations = 10'000;
/// The largest number of digits reported; two equal block averages give this.
inline constexpr double kMaxDigits = 16;
/// An orbit with fewer digits than this is called chaotic (docs/instruments.md: the histogram at T = 10⁴ has
/// a gap between 7 and 11 digits; 9 sits in it).
inline constexpr double kDefaultDigitsThreshold = 9;

/// The weights for blocks of T terms; throws std::invalid_argument unless kMinIterations ≤ T ≤ kMaxIterations.
/// A stop request (looked at every 2^16 weights: 10⁷ of them take ~1.6 s) returns them unfinished, which the caller
/// must not use (issue 36: Ctrl-C waited for them).
[[nodiscard]] BirkhoffWeights birkhoffWeights(std::uint64_t T, std::stop_token stop = {});

/// −log₁₀ |a − b|, capped at kMaxDigits (and kMaxDigits when a = b); NaN when a or b is NaN.
[[nodiscard]] double convergenceDigits(double a, double b) noexcept;

/// The weighted average of f_0 … f_{T−1} (T = f.size(), kMinIterations ≤ T ≤ kMaxIterations), with weights
/// g(n/T), summed with compensation: the reference the orbit measures are tested against.
[[nodiscard]] double weightedBirkhoffAverage(std::span<const double> f);

}  // namespace archipelago
