#pragma once
/// \file PaperItems.hpp
/// \brief The quantitative statements of Karney (1983) that the reproduction report (app/reproduce) lists,
/// each with the paper's value, ours (from the existing core functions: theory, periodic, markov, stats), an
/// honest error, the tolerance, a mark and the one CLI command that reproduces the item alone.
///
/// No maths lives here: every value is asked of the module that defines it (smallk::, paper::, periodic,
/// markov, stats).  An item this build cannot compute is listed with mark notReproduced and no value, never a
/// made-up one.

#include <optional>
#include <string>
#include <vector>

#include "core/portrait/PortraitRenderer.hpp"
#include "core/run/TrappingRun.hpp"
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

/// The statements measured on the K = 0.1 run (§5, figs. 6–7): α ≈ ¼, D, the longest segment.
/// `full` says whether the run has the paper's size (otherwise the heavy-tail items are notAtThisSize).
[[nodiscard]] std::vector<PaperItem> k01Items(const TrappingState& run, const TrappingStatistics& stats, bool full);

/// The statements not yet reproduced by the report, listed honestly without a value.
[[nodiscard]] std::vector<PaperItem> pendingItems();

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

/// Appendix C: the Markov model's ε(τ) for one segment of m = 20 points among N = 1000, τ = 0 … 200.
struct MarkovCurve {
  std::vector<double> tau, epsilon;
  std::string command;
};
[[nodiscard]] MarkovCurve markovEpsilon();

/// b₂ (§5, an area) of the K = 0.1 run's box by box counting (quick 2²⁷ steps, full 2³⁰), and with the run's D the
/// box-invariant b₂·D (eq. A3: the paper's 0.693 × 6400) and the §6 enhancement ≥ 360/n².
[[nodiscard]] std::vector<PaperItem> stochasticAreaItems(const TrappingState& run, const TrappingStatistics& stats,
                                                         bool full);

/// Fig. 4: the small-K Hamiltonians in scaled variables (core/theory/SmallKTheory.hpp's file comment):
/// H = ½Y² − ⅔X³ + s·2X with s = −1 (K < 0, eq. hama), 0 (K = 0, eq. ham), +1 (K > 0, eq. hamb).
[[nodiscard]] double smallKHamiltonian(double X, double Y, int sign) noexcept;

}  // namespace archipelago::report
