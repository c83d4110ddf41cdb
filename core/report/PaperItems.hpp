#pragma once
/// \file PaperItems.hpp
/// \brief The quantitative statements of Karney (1983) that the reproduction report (app/reproduce) lists,
/// each with the paper's value, ours (from the existing core functions: theory, periodic, markov, stats), an
/// honest error, the tolerance, a mark and the one CLI command that reproduces the item alone.
///
/// No maths lives here: every value is asked of the module that defines it (smallk::, paper::, periodic,
/// markov, stats).  An item this build cannot compute is listed with mark notReproduced and no value, never a
/// made-up one.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/scan/ScanRun.hpp"
#include "core/periodic/PeriodicOrbit.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/stats/TailAnalysis.hpp"
#include "core/stats/TrappingStatistics.hpp"

namespace archipelago::report {

enum class Mark {
  agrees,            ///< |ours − paper| ≤ tolerance (and ≤ 3 × error where an error is known)
  differsExplained,  ///< outside the tolerance, for a reason stated in `note`
  differs,           ///< outside the tolerance, unexplained: a failure of the report
  notAtThisSize,     ///< the quantity needs a larger run than this one (the --full report computes it)
  notReproduced      ///< not yet computed by the report (listed, no value)
};

[[nodiscard]] const char* markText(Mark m) noexcept;

struct PaperItem {
  std::string id;          ///< stable identifier, e.g. "tmax"
  std::string section;     ///< "§4", "App. C"
  std::string statement;   ///< the paper's statement in words
  std::string paperValue;  ///< as the paper prints it
  std::optional<double> paper;  ///< the paper's number, when it is one
  std::optional<double> ours;   ///< our value, when computed
  double error = 0;             ///< our one-sigma error (0: exact to rounding)
  double tolerance = 0;         ///< allowed |ours − paper|
  Mark mark = Mark::notReproduced;
  std::string command;     ///< one archipelago-cli command that reproduces the item alone
  std::string note;        ///< how it is computed, or why it differs
};

/// Marks an item from its values: agrees when |ours − paper| ≤ tolerance + 3·error, else differs (the caller
/// turns that into differsExplained when it has a reason); notReproduced without a value.
void markByTolerance(PaperItem& item);

/// The statements that need no trapping run (§2, §4, §6, §7, appendix C): closed forms, the period-doubling
/// cascade, the period-138 orbit, the Markov model.  Takes a few seconds.
[[nodiscard]] std::vector<PaperItem> theoryItems();

/// The run of the report at K = 0.1 in the default box: quick (seconds, CI) or the paper's fig. 6 size.
[[nodiscard]] TrappingParameters k01Parameters(bool full);

/// The statements measured on the K = 0.1 run (§5, figs. 6–7): α ≈ ¼, p ≈ 5/4, S_t, D (with the honest error of
/// `tail`: supportedDError()), the longest segment.  `full` says whether the run has the paper's size (otherwise
/// the heavy-tail items are notAtThisSize).
[[nodiscard]] std::vector<PaperItem> k01Items(const TrappingState& run, const TrappingStatistics& stats,
                                              const TailAnalysis& tail, bool full);

/// §5: "the power at which C_τ decays varying between about ¼ and 3/2" (fig. 6d).  The smallest and the largest
/// local exponent −d log C/d log τ over the points that are past the block structure (τ ≥ 10q) and resolved
/// (one-sigma subset error in (0, kLocalExponentMaxError]), each with its point's error.  The largest needs the far
/// tail (τ ~ 10⁴–10⁶): on a run whose resolved points end before τ = 10⁴ it is notAtThisSize.
inline constexpr double kLocalExponentMaxError = 0.15;
[[nodiscard]] std::vector<PaperItem> localExponentRangeItems(const TrappingState& run, const TrappingStatistics& stats,
                                                             bool full);

/// Not in the paper (its open question, §7): the tail exponent γ of P_t ~ t^−γ over the tail fit's decade with its
/// bootstrap interval, against Cristadoro & Ketzmerick's 1.57 (core/stats/TailAnalysis.hpp), and the steps that
/// would decide between 1.57 and 3 at this K and box.  notAtThisSize unless `full`.
[[nodiscard]] std::vector<PaperItem> tailItems(const TailAnalysis& tail, bool full);

/// §5's K scan ("K between 0 and 1.3 at intervals of 0.05"): the scan of the report in `dir` (core's runKScan,
/// the box rule of core/scan/ScanBox.hpp).  Quick: M = 64 orbits of 2·10⁵ blocks of q = 16 per K (3.3·10⁸ steps
/// per K, ~15 s for the 26 K); full: M = 64 × 5·10⁶ blocks (8·10⁹ steps per K).
[[nodiscard]] KScanRequest kScanRequest(bool full, const std::filesystem::path& dir);
[[nodiscard]] std::string kScanCommand(bool full);

/// "At most of the values of K a slow algebraic decay of f_t is seen" (§5).  Ours: the fraction of the scan's K
/// whose longest segment reaches kScanLongSegmentSteps = 10⁴ steps.  An exponential decay at the rate of §4
/// (½ log λ ≥ 0.16 for K ≥ 0.05) makes a segment of 10⁴ steps impossible (e^−1600 per segment), so such a
/// segment is the algebraic tail.  Agrees when more than half of the K show it ("most").
[[nodiscard]] PaperItem kScanItem(const std::vector<ScanRunSummary>& runs, bool full);

/// Appendix B's timing: "the time for one iteration on a Cray-1 is a little less than 75 ns" and fig. 6's
/// 3.2·10¹² steps took "about 65 hours of CPU time".  Ours: measured by measureStepTiming().
struct StepTiming {
  double nsPerStepOneThread = 0;   ///< wall time per step of one thread
  double stepsPerSecond = 0;       ///< of all `threads`
  int threads = 0;
  std::string kernel;              ///< the instruction-set path that ran
};
/// Times runs of the report's K = 0.1 parameters (q = 16, 64 orbits) of about `seconds` each, on one thread and
/// on `threads` (0: one per core).
[[nodiscard]] StepTiming measureStepTiming(int threads, double seconds = 1.0);
[[nodiscard]] std::vector<PaperItem> timingItems(const StepTiming& timing);

}  // namespace archipelago::report

namespace archipelago::report {

/// The small-K runs of fig. 3 (K = −10⁻⁴, 0, 10⁻⁴: the presets small-k-negative, -zero, -positive), quick or
/// at the presets' size.
[[nodiscard]] TrappingParameters smallKParameters(double K, bool full);

/// §4, fig. 3a, measured: at K = −10⁻⁴ no segment is longer than t_max = 5.1454 |K|^−¼ ≈ 51.5 steps.
[[nodiscard]] PaperItem negativeKCutoffItem(const TrappingState& run);

/// Fig. 1: the islands of Q at K = 0.1 (the central island, its chain of six, the islands around those): an
/// Orbits-mode portrait of the default box, view x ∈ [−0.8, 0.5], y ∈ [−0.65, 0.65] (quick: 600², 2·10⁷
/// points; full: 1200², 2·10⁸).  The command that draws it alone is figureOneCommand().
[[nodiscard]] PortraitRequest figureOneRequest(bool full);
[[nodiscard]] std::string figureOneCommand(bool full);

/// The member of the period-138 = 6 × 23 chain the paper names (§7: "at x + √K ≈ 0.352 and y ≈ 0.034"): where
/// the report looks for it, and the elliptic orbit the periodic-orbit finder converges to from there.
inline constexpr double kChain138X = 0.352 - 0.31622776601683794;  // x, not x + √K
inline constexpr double kChain138Y = 0.034;
[[nodiscard]] std::optional<PeriodicOrbit> chain138Orbit();

/// Fig. 2 (the dark region of the paper: the chaotic sea of Q*, with holes at the islands): a Density-mode
/// portrait, (a) of the whole default box, (b) the enlargement around the 138-chain's member.
[[nodiscard]] PortraitRequest figureTwoRequest(bool full, bool enlargement);
[[nodiscard]] std::string figureTwoCommand(bool full, bool enlargement);

/// Appendix C: the Markov model's ε(τ) for one segment of m = 20 points among N = 1000, τ = 0 … 200.
struct MarkovCurve {
  std::vector<double> tau, epsilon;
  std::string command;
};
[[nodiscard]] MarkovCurve markovEpsilon();

/// b₂ (§5, an area) of the K = 0.1 run's box by box counting (quick 2²⁷ steps, full 2³⁰), and with the run's D the
/// box-invariant b₂·D (eq. A3: the paper's 0.693 × 6400) and the §6 enhancement ≥ 360/n².
[[nodiscard]] std::vector<PaperItem> stochasticAreaItems(const TrappingState& run, const TrappingStatistics& stats,
                                                         const TailAnalysis& tail, bool full);

/// Fig. 4: the small-K Hamiltonians in scaled variables (core/theory/SmallKTheory.hpp's file comment):
/// H = ½Y² − ⅔X³ + s·2X with s = −1 (K < 0, eq. hama), 0 (K = 0, eq. ham), +1 (K > 0, eq. hamb).
[[nodiscard]] double smallKHamiltonian(double X, double Y, int sign) noexcept;

}  // namespace archipelago::report
