#pragma once
/// \file TailResult.hpp
/// \brief What a sampler run (TailSampler.hpp) estimates: P_t at every level reached, its error from the
/// replicas, the survivors and lineages behind it, whether it is reliable, and the local exponent between
/// neighbouring reliable levels.
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
///   local exponent between neighbouring reliable levels a < b (the sampler's own; to be unified with core/stats'
///                  running exponent γ(t) of issue #26):
///                  γ = −(ln P(t_b) − ln P(t_a))/(ln t_b − ln t_a), plotted at √(t_a t_b), with the error
///                  propagated from the replicas to first order, covariance included (the two levels share
///                  their histories):  var = V_a/P_a² + V_b/P_b² − 2 C_ab/(P_a P_b),  V = s²/R,
///                  C_ab = Σ_r (P_ra − P_a)(P_rb − P_b)/(R(R − 1)), and at least level b's binomial term
///                  (1 − p_b)/(n_b p_b) (the floor above, for the one survival fraction between the two levels).

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

/// The local exponent between two neighbouring reliable levels.
struct TailExponent {
  double tFrom = 0, tTo = 0;  ///< steps
  double t = 0;               ///< √(tFrom·tTo), where it is plotted
  double gamma = 0;
  double gammaError = std::numeric_limits<double>::quiet_NaN();  ///< NaN with one replica
};

struct TailResult {
  std::vector<TailLevelResult> levels;    ///< every level reached by every replica
  std::vector<TailExponent> exponents;    ///< between consecutive levels that are both reliable
  double steps = 0;                       ///< TailState::steps
  bool finished = false;
};

/// The estimates of a sampler state (finished or not).  A pure function.
[[nodiscard]] TailResult tailResult(const TailState& state);

/// The one call for a caller that wants the levels (the reproduction report): startTail(request), runTail() to the
/// end (or until `stop`), tailResult().  Throws std::invalid_argument for a bad request (tailRequestError()).
[[nodiscard]] TailResult runTailSampler(const TailRequest& request, const TailRunOptions& options = {},
                                        const TailObserver& observer = {}, std::stop_token stop = {});

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
