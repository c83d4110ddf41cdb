#pragma once
/// \file BruteForceSurvival.hpp
/// \brief The brute-force P_t of `run` at the sampler's levels, and the comparison of the two (issue #29,
/// deliverable 2: agreement where both have data; the steps each needs for the same relative error).
///
/// A run's histograms (TrappingHistogram.hpp) count segment lengths in bins; a level L (blocks) with L + 1 a
/// bin's lower edge separates whole bins, so the count of segments longer than L is exact there.  The estimator
/// is the one of core/stats (TrappingStatistics.hpp, appendix A): each bin's segments weigh
/// w_i = n_i/(M (T + 1 − t̄_i)) (t̄_i their mean length in blocks), and
///     P(t = qL) = Σ_{bins above L} w_i / Σ_i w_i,
/// which is what computeStatistics() gives for P_t at t = qL whenever its grid holds that t (a test checks that
/// they agree).  The error is the standard error of the mean over the run's subsets of orbits (each subset's own
/// P; subsets without a segment are left out), as `stats` reports it.  Several runs of the same parameters but
/// the seed are pooled, subsets of every run counted.
///
/// Steps for the same relative error.  A brute-force run of S steps with relative error r_b at t would need
/// S (r_b/r)² steps for the sampler's relative error r (the error of a count falls as 1/√steps).  Where the run
/// has no segment beyond t the count estimate α/(P r²) is given instead (S P/α segments are longer than t in S
/// steps, α the mean segment length in steps, and a count of n has relative error 1/√n).

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/run/TrappingRun.hpp"
#include "core/tail/TailResult.hpp"

namespace archipelago {

struct BruteForceLevel {
  double t = 0;               ///< steps (q·L)
  double P = std::numeric_limits<double>::quiet_NaN();  ///< NaN when L + 1 is not a bin edge
  double PError = 0;
  std::uint64_t segmentsBeyond = 0;  ///< segments longer than t
};

/// The brute-force survival of the pooled runs at `levels` (blocks).  Throws std::invalid_argument when `runs`
/// is empty, or when the runs differ in any parameter but the seed or in the blocks done.
[[nodiscard]] std::vector<BruteForceLevel> bruteForceSurvival(const std::vector<TrappingState>& runs,
                                                              const std::vector<std::uint64_t>& levels);

/// Whether P(length > L) is exact from histogram bins: L + 1 is the lower edge of a bin.
[[nodiscard]] bool isHistogramEdgeLevel(std::uint64_t L) noexcept;

/// One level of the sampler set against the brute force.
struct TailComparisonLevel {
  double t = 0;
  double P = 0, PError = 0;                   ///< the sampler
  bool reliable = false;
  double bruteP = 0, bruteError = 0;          ///< the runs
  std::uint64_t bruteSegments = 0;            ///< segments of the runs longer than t
  /// (P − bruteP)/√(PError² + bruteError²); NaN when either has no error or the runs have no segment beyond t.
  double z = std::numeric_limits<double>::quiet_NaN();
  double tailSteps = 0;                       ///< the sampler's steps up to this level (all replicas)
  double bruteStepsSameError = std::numeric_limits<double>::quiet_NaN();  ///< see the file comment
  bool bruteStepsMeasured = false;            ///< from the runs' own error (else the count estimate)
  std::vector<double> replicaP;               ///< the sampler's replicas' P_r(t) (TailLevelResult::replicaP)
};

struct TailComparison {
  std::vector<TailComparisonLevel> levels;
  double bruteSteps = 0;     ///< steps of the runs, M·T·q summed
  double alpha = 0;          ///< the runs' mean segment length, steps
};

/// The comparison of a sampler result with runs of the same process (the caller checks that the parameters
/// match: tailRunMismatch()).
[[nodiscard]] TailComparison compareWithRuns(const TailState& state, const TailResult& result,
                                             const std::vector<TrappingState>& runs);

/// The levels pooled with their covariance (issue 39, deliverable 2): one number that a uniform bias of the sampler
/// (all levels scaled by 1 + β) moves, where the largest |z| of correlated levels could not see a 20–30 % bias.
///
/// At the levels compared (reliable, at least `minSegments` segments of the runs beyond t, both P and errors
/// finite and positive), d_i = ln(P_i/B_i) (sampler over runs).  Its covariance is the sum of the two independent
/// estimators': the sampler's C^s_ij = ρ_ij s_i s_j, s_i = PError_i/P_i and ρ_ij the correlation of the replicas'
/// P_r(t_i), P_r(t_j) (1 with fewer than three replicas or a replica spread of zero: the conservative bound); the
/// runs' C^b_ij = u_i² for t_i ≤ t_j, u_i = bruteError_i/B_i (an empirical survival function counts the segments
/// beyond t_j among those beyond t_i: Cov(ln B_i, ln B_j) = Var(ln B_i), the earlier level's).  The pooled log-ratio
/// b = Σ w_i d_i with inverse-variance weights w_i ∝ 1/C_ii, its error σ = √(wᵀCw) with the whole C, and
/// z = b/σ.  A uniform bias β moves b by ln(1 + β): the test |z| ≤ 3 detects it with probability ½ at
/// e^{3σ} − 1 and 97.7 % at e^{5σ} − 1 (`detectable`).
struct TailPooledBias {
  std::size_t levels = 0;   ///< levels pooled
  double tFrom = 0, tTo = 0;  ///< the first and last of them, steps
  double logRatio = std::numeric_limits<double>::quiet_NaN();       ///< b
  double logRatioError = std::numeric_limits<double>::quiet_NaN();  ///< σ
  double z = std::numeric_limits<double>::quiet_NaN();              ///< b/σ
  double detectable = std::numeric_limits<double>::quiet_NaN();     ///< e^{5σ} − 1: a bias found 97.7 % of the time
  double detectableHalf = std::numeric_limits<double>::quiet_NaN(); ///< e^{3σ} − 1: found half of the time
};
[[nodiscard]] TailPooledBias pooledBias(const TailComparison& comparison, std::uint64_t minSegments = 10);

/// Nothing when `run` iterates the sampler's process (map, box, Xr, q); else which parameter differs.  (The seed,
/// T, M, subsets and longestKept may differ.)
[[nodiscard]] std::optional<std::string> tailRunMismatch(const TailRequest& request, const TrappingState& run);

}  // namespace archipelago
