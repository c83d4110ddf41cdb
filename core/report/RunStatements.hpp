#pragma once
/// \file RunStatements.hpp
/// \brief The statements of the paper's table measured on the report's runs (ReportRuns.hpp): §4's small-K runs,
/// §5's K = 0.1 run (spliced with its q = 1 companion), b₂, the tail, the K scan and the Cray's timing.  Every fit
/// is core/stats/LogFits' (equal weight per unit of log t; issue #26), every error the subsets' or the bootstrap's;
/// no value compares theory with theory.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/markovtree/MarkovTree.hpp"
#include "core/stochasticarea/StochasticArea.hpp"
#include "core/report/ReportItem.hpp"
#include "core/report/ReportRuns.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/scan/ScanSummary.hpp"
#include "core/stats/TailAnalysis.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/tail/BruteForceSurvival.hpp"
#include "core/tail/TailScan.hpp"

namespace archipelago::report {

/// The window over which an exponential decay rate is fitted to f_t of a run at small K > 0: from 6/K^¼ steps (orbits
/// passing the hyperbolic point at ξ₀ ≤ e⁻³, where §4's linearisation holds) to the last point of f_t whose bin holds at least
/// 20 segments (relative error ≤ ¼).
struct DecayFit {
  double rate = kTailUndefined, error = kTailUndefined, from = 0, to = 0;
  std::size_t points = 0;
};
[[nodiscard]] DecayFit decayRateOf(const TrappingState& run, const TrappingStatistics& stats);

/// §4: tmax-measured (fig. 3a's run against the finite-box prediction), t7 (fig. 3b's run), decay-0.0001 (fig.
/// 3c's run), decay-0.001 and decay-0.01 (decayRun()); `size` names the runs in the items' commands.
[[nodiscard]] std::vector<ReportItem> smallKStatements(const TrappingState& runA, const TrappingState& runB,
                                                       const TrappingState& runC, const TrappingState& decay3,
                                                       const TrappingState& decay2, ReportSize size);

/// §7 (later work, issue #29): tail-splitting, the tail sampler's P_t against the run's at the sampler's reliable
/// levels where the run has at least kTailSplittingMinSegments segments beyond t (core/tail's compareWithRuns), pooled
/// with their covariance (pooledBias, issue 39): the item is |z| of the pooled ln(P_split/P_run), and its note states
/// the smallest uniform bias the test detects at the report's size.
inline constexpr std::uint64_t kTailSplittingMinSegments = 10;
[[nodiscard]] ReportItem tailSplittingStatement(const TailComparison& comparison, const std::string& command);

/// §7 (later work, issue 55): tail-gamma-K, the exponent of P_t over the one window [kTailGammaKFrom, kTailGammaKTo]
/// (steps) averaged over K, against Cristadoro & Ketzmerick's 1.57 averaged over parameters.  `gamma` holds each K's
/// γ there (tailGammaKExponents; gamma NaN where the K does not reach 10⁶ reliably: left out, the note names it);
/// γ̄, its error √(Σσ_K²)/n and the spread s over K are the tail scan's (tailScanAverage).  The item agrees when
/// |γ̄ − 1.57| ≤ 2√(error² + s²/n) (makeItemWithin): the K are a sample of parameters, so s/√n is the sampling error
/// of an average over them, the error the sampler's.  Fewer than two K, or an unknown error: no value.
inline constexpr double kTailGammaKFrom = 1e4;
inline constexpr double kTailGammaKTo = 1e6;
[[nodiscard]] ReportItem tailGammaKStatement(const std::vector<double>& K, const std::vector<TailExponent>& gamma,
                                             bool full, const std::string& command);
/// Each K's γ over [kTailGammaKFrom, kTailGammaKTo] (tailScanExponentOver), in the scan's order of K.
[[nodiscard]] std::vector<TailExponent> tailGammaKExponents(const TailScanSummary& scan);

/// §7 (later work, issue 40): markov-tree, the Meiss–Ott tree of an atlas of the run's map (core/markovtree, no
/// fitted parameter) against the tail sampler's reliable levels from 10³ steps: ours is the comparison's reach, the
/// last level at which the tree's P_t is within kMarkovTreeAgreementFactor of the sampler's —
/// reported, never marked; the note gives every level's ratio and the atlas level holding the model's survivors.
/// `atlasDepth` and `states` describe the tree in the note.
[[nodiscard]] ReportItem markovTreeStatement(const MarkovTreeComparison& comparison, const MarkovTree& tree,
                                             int atlasDepth, double alpha, double b2, const std::string& command);

/// §5 and §7 on the K = 0.1 run: alpha-quarter, p-five-quarters, alpha-min, alpha-max, S-superdiffusive, D,
/// longest.  `stats` are the spliced statistics of the run and its companion (or the run's alone, when none);
/// `tail` the run's TailAnalysis; `full` whether the run has the paper's size.
[[nodiscard]] std::vector<ReportItem> k01Statements(const TrappingState& run, const TrappingStatistics& stats,
                                                    const TailAnalysis& tail, bool full, const std::string& runCommand);

/// §5, §6: b2 and factor056 (b₂ of a box of the paper's size), b2D and enhancement (b₂ of the run's box times its D).
[[nodiscard]] std::vector<ReportItem> stochasticAreaStatements(const StochasticAreaResult& paperBox,
                                                               const MapParameters& paperBoxMap,
                                                               const StochasticAreaResult& runBox,
                                                               const TrappingState& run, const TrappingStatistics& stats,
                                                               const TailAnalysis& tail, bool full,
                                                               const std::string& b2Command);

/// §7 (later work): tail-gamma and tail-forecast from the run's TailAnalysis.
[[nodiscard]] std::vector<ReportItem> tailStatements(const TailAnalysis& tail, bool full);

/// §5's "most K": the fraction of the scan's K whose longest segment reaches kScanLongSegmentSteps.
[[nodiscard]] ReportItem kScanStatement(const std::vector<ScanRunSummary>& runs, bool full, const std::string& command);

/// Appendix B's timing: the Cray-1's 75 ns per step and 65 h for fig. 6, against this machine (measured by
/// measureStepTiming()).
struct StepTiming {
  double nsPerStepOneThread = 0;  ///< wall time per step of one thread
  double stepsPerSecond = 0;      ///< of all `threads`
  int threads = 0;
  std::string kernel;             ///< the instruction-set path that ran
};
/// Times runs of the quick K = 0.1 parameters of about `seconds` each, on one thread and on `threads` (0: all).
[[nodiscard]] StepTiming measureStepTiming(int threads, double seconds = 1.0);
[[nodiscard]] std::vector<ReportItem> timingStatements(const StepTiming& timing);

}  // namespace archipelago::report
