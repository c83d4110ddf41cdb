#pragma once
/// \file
/// \brief One run summary (issue 35, item 3; docs/design.md, "Trapping statistics"): D, its error and where that
/// error comes from, the dominance verdict, the spliced and the run-only values, α and the tail's γ_P — what
/// `stats`, Python's Run.statistics(), the K scan, the report and the GUI all show.  Each of them prints this
/// summary; none assembles D's error itself (they once disagreed: Python paired the spliced D with the bootstrap
/// error of the run alone).
///
/// The rules, in one place:
///  - no tail analysis yet (a live run, or too few segments to resample): D has no error, and the note says why;
///  - the longest segments dominate D (TailAnalysis::dominated()): no error, the note is dominanceMessage();
///  - the run alone: the bootstrap over segments (supportedDError), never the 16-subset error, which the heavy
///    tail makes far too small (§5);
///  - spliced with a q = 1 companion (statistics.splicedAt > 0): the spliced D with the subsets' error of the
///    spliced statistics, as `stats --short` prints it; the run alone (runD, runDError) keeps the bootstrap.
/// The tail analysis is always the run's own (the companion is a small fraction of its steps and holds none of
/// the longest segments, which carry D's error).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/stats/TailAnalysis.hpp"
#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

struct TrappingState;

/// Where D's error comes from.
enum class DErrorSource {
  none,       ///< no error can be given (see RunSummary::DErrorNote)
  bootstrap,  ///< the bootstrap over segments (core/stats/Bootstrap.hpp)
  subsets,    ///< the standard error over the subsets of orbits, of the spliced statistics
};

/// The source in words, as every front end labels it: "none", "bootstrap over segments", "subsets of orbits".
[[nodiscard]] std::string_view toString(DErrorSource source) noexcept;
/// The short key of Python's dict and of JSON: "none", "bootstrap", "subsets".
[[nodiscard]] std::string_view keyOf(DErrorSource source) noexcept;

struct RunSummary {
  bool spliced = false;           ///< the statistics are spliced with a q = 1 companion
  double splicedAt = 0;           ///< steps; 0 when not spliced
  std::uint64_t segments = 0;
  double alpha = 0, alphaError = 0;  ///< mean segment length (steps) and its subsets' error
  double sumTf = 0;

  double D = 0;                   ///< the statistics' D (eq. ddef): spliced when spliced
  double DError = kTailUndefined; ///< NaN when none
  DErrorSource errorSource = DErrorSource::none;
  std::string DErrorNote;         ///< one line: where the error comes from, or why there is none
  double DSubsetsError = 0;       ///< the statistics' 16-subset error, for reference only (it underestimates)

  bool judged = false;            ///< a tail analysis was available
  bool dominated = false;         ///< the longest segments dominate D
  std::string verdict;            ///< dominanceMessage(), empty when the bootstrap error stands

  double runD = 0;                ///< the run alone (equal to D when not spliced)
  double runDError = kTailUndefined;  ///< its bootstrap error; NaN when dominated or not judged

  double gammaP = kTailUndefined; ///< −d log P/d log t over the tail fit's window [t_end/10, t_end]; NaN if none
  ConfidenceInterval gammaPInterval;
  /// γ_P in words, as `stats` prints it after "gamma_P": "1.57 [1.41, 1.73] over 1000 <= t <= 1e+04"
  /// (gammaPText), or why the data cannot decide it (kNoTailFit); empty when not judged.
  std::string gammaPText;
  /// The tail's verdict, as `stats` prints it after "verdict" (tailVerdictText); empty when not judged.
  std::string tailVerdict;

  /// "6400 ± 800 (bootstrap over segments)"-like text: D with its error and source, or why there is none.
  [[nodiscard]] std::string DText() const;
};

/// `stats`'s words when the tail has too few long segments for a fit (no γ_P).
inline constexpr std::string_view kNoTailFit =
    "too few long segments for a tail fit (fewer than 10 beyond 3 max(10, 2q) steps): the data cannot decide the "
    "tail's exponent";

/// A window's γ_P with its interval and range, 4 significant digits: "1.57 [1.41, 1.73] over 1000 <= t <= 1e+04".
[[nodiscard]] std::string gammaPText(const TailWindow& window);

/// The tail's verdict: dominanceMessage(), or that the tail does not dominate D and its bootstrap error stands.
[[nodiscard]] std::string tailVerdictText(const TailAnalysis& tail);

/// The summary of statistics (spliced or not) with the tail analysis of the run alone (nullptr: not judged yet;
/// `whyNotJudged` then says why, e.g. "its error is judged when the run pauses or ends").
[[nodiscard]] RunSummary summarizeRun(const TrappingStatistics& statistics, const TailAnalysis* runTail,
                                      std::string_view whyNotJudged = "no tail analysis");

/// The same, analysing the run's tail here with the default options (the bootstrap's default seed and
/// replicates, as `stats` without options); too few segments to resample leave D without error, and say so.
/// `tail`, when given, receives the analysis (empty when it could not be done).
[[nodiscard]] RunSummary summarizeRun(const TrappingState& run, const TrappingStatistics& statistics,
                                      std::optional<TailAnalysis>* tail = nullptr);

}  // namespace archipelago
