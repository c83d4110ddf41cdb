#pragma once
/// \file TailResult.hpp
/// \brief What a sampler run (TailSampler.hpp) estimates: P_t at every level reached, its error from the
/// replicas, the survivors and lineages behind it, whether it is reliable, and the running exponent γ(t) over
/// decade windows, as the statistics define it.
///
/// Per replica r, P_r(t_0) = s_{r,0}/n_r (stage 0: successes over trials, the estimator of `run`) and
/// P_r(t_{k+1}) = P_r(t_k)·s_{r,k+1}/N (splitting: the product of survival fractions).  Each is an unbiased estimate
/// when clones are exact samples (the first to within O(1/n_r), as a ratio of two counts).
///   P(t_k)       = (1/R) Σ_r P_r(t_k).  Its error is the larger of
///                  - the spread over replicas, s/√R (s the sample standard deviation; none with one replica), and
///                  - the binomial floor P·√(Σ_{j≤k} (1 − p_j)/(n_j p_j)), p_j = survivors/population of level j
///                    pooled over the replicas (n_j walkers; at level 0 the trials): the error the same counts
///                    would have if every walker were independent.  Clones share their ancestors' histories, so
///                    the true error is larger; the floor guards against a few replicas that agree by chance.
///                    Measured (docs/tail.md): with R = 4 the spread alone has three degrees of freedom and its
///                    z-scores follow Student's t₃ (mean z² ≈ 3); with the floor, mean z² 0.95–2.2 below 2.2·10⁵ steps.
///   survivors    = Σ_r s_{r,k};  ancestors = Σ_r (distinct lineages among replica r's survivors).
///   reliable     = R ≥ 2 (an error) and ancestors ≥ minAncestors (TailRequest).  Replicas whose populations
///                  descend from a handful of entries estimate P from those few histories: the spread over the
///                  replicas no longer measures the error (docs/tail.md gives the measurement behind the
///                  threshold).  A replica whose population died out is no exception: its P_r = 0 is an unbiased
///                  sample, and it carries no lineage.  An unreliable level is neither plotted as data nor used
///                  in fits.
///   running exponent γ(t), the one definition of the statistics' (TailAnalysis.hpp, issue #26): over the windows
///                  runningExponentWindows(t_end, lowest) (decades ending at t_end·10^(−k/2)), t_end the largest
///                  reliable level and lowest = max(the first reliable level, 10, 2q), γ = fitLogSlope() of P at the
///                  reliable levels (LogFits.hpp: −d ln P/d ln t, least squares on a log grid, ln P interpolated
///                  linearly in ln t between levels), plotted at √(from·to).  Its error: the fit is linear in
///                  ln P_j, γ = −Σ_j w_j ln P_j, so to first order var = Σ_ij w_i w_j C_ij/(P_i P_j), C_ij the
///                  replicas' covariance of the mean (Σ_r (P_ri − P_i)(P_rj − P_j)/(R(R − 1))), and at least the
///                  binomial floor Σ_k b_k (Σ_{j at or after level k} w_j)², b_k = (1 − p_k)/(n_k p_k) (ln P_j is
///                  the sum of the ln p_k up to j).  Before 2026-11-26 the sampler's exponent was the finite
///                  difference between neighbouring levels (a third of a decade): a second definition.

#include <cstdint>
#include <limits>
#include <stop_token>
#include <vector>

#include "core/run/TrappingRun.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/tail/TailSampler.hpp"

namespace archipelago {

struct TailLevelResult {
  std::uint64_t blocks = 0;       ///< the level L_k, blocks
  double t = 0;                   ///< q·L_k, steps: P is Pr(segment length > t)
  double P = 0;
  double PError = std::numeric_limits<double>::quiet_NaN();  ///< max(PErrorReplicas, PErrorBinomial)
  double PErrorReplicas = std::numeric_limits<double>::quiet_NaN();  ///< s/√R (NaN with one replica)
  double PErrorBinomial = 0;                                         ///< the binomial floor
  std::uint64_t population = 0;   ///< walkers that set out for it, all replicas (stage 0: trials)
  std::uint64_t survivors = 0;
  std::uint64_t ancestors = 0;
  std::uint64_t fewestAncestors = 0;  ///< in one replica
  bool reliable = false;
  std::vector<double> replicaP;   ///< P_r(t_k)
  double steps = 0;               ///< the sampler's steps when every replica had reached it
  /// Metropolis moves accepted / proposed when the survivors were resampled (NaN: perturb, or the last level).
  double acceptance = std::numeric_limits<double>::quiet_NaN();
};

/// The running exponent over one window.
struct TailExponent {
  double tFrom = 0, tTo = 0;  ///< steps
  double t = 0;               ///< √(tFrom·tTo), where it is plotted
  std::size_t points = 0;     ///< log-grid points of the fit
  double gamma = 0;
  double gammaError = std::numeric_limits<double>::quiet_NaN();  ///< NaN with one replica
};

struct TailResult {
  std::vector<TailLevelResult> levels;    ///< every level reached by every replica
  std::vector<TailExponent> exponents;    ///< the running exponent γ(t), one per window (longest t first)
  double steps = 0;                       ///< TailState::steps
  bool finished = false;
};

/// The estimates of a sampler state (finished or not).  A pure function.
[[nodiscard]] TailResult tailResult(const TailState& state);

/// The one call for a caller that wants the levels (the reproduction report): startTail(request), runTail() to the
/// end (or until `stop`), tailResult().  Throws std::invalid_argument for a bad request (tailRequestError()).
[[nodiscard]] TailResult runTailSampler(const TailRequest& request, const TailRunOptions& options = {},
                                        const TailObserver& observer = {}, std::stop_token stop = {});

/// γ over the window [from, to] (steps) by the running exponent's one definition (above): fitLogSlope() of P at the
/// reliable levels, its error from the replicas' covariance with the binomial floor (NaN with one replica); gamma NaN
/// when the window holds fewer than 3 grid points of them.  `exponents` uses runningExponentWindows(); a K scan
/// (TailScan.hpp) uses windows fixed for every K.
[[nodiscard]] TailExponent tailExponentOver(const TailResult& result, double from, double to);

/// The largest t of a reliable level, or 0 when none is.
[[nodiscard]] double largestReliableT(const TailResult& result) noexcept;

/// P_t at the reliable levels (x: t in steps, value: P, error: PError): P_t of the sampled process, whose segments
/// are those of `run` (whole blocks of q steps).
[[nodiscard]] Series reliableSurvival(const TailResult& result);

/// The reliable levels as P_t of the statistics `shown` of `run` (issue #29: the GUI's P_t plot and the report draw
/// them beside the run's).  P_t counts segments: statistics spliced with a q = 1 companion count the q = 1
/// process's, many more and shorter than the q-block process's the sampler follows, while f_t per step is the
/// same above the splice; so P_shown(t) = P(t) · α_shown / α_run, α the mean segment length (§3: α = 1/Σ f_t).  For
/// the run's own statistics the factor is 1.  `factor`, when given, receives it.
[[nodiscard]] Series reliableSurvivalIn(const TailResult& result, const TrappingState& run,
                                        const TrappingStatistics& shown, double* factor = nullptr);

}  // namespace archipelago
