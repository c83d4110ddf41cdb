#pragma once
/// \file StatisticsTable.hpp
/// \brief The one table of the trapping statistics (Karney 1983, §3 and §5): for each series of
/// TrappingStatistics its key, symbol, axis labels, file name, error and plot.
///
/// Every surface reads this table: the CLI's `stats --csv`, the GUI's plots and exports, the CSV writer
/// (export/StatisticsCsv.hpp) and the theory curves (theory/TheoryCurves.hpp, which name the statistic they
/// belong to by its key).  A series is added here, once, and appears everywhere.
///
/// Units: abscissae t and τ are in steps of N (iterations of Q*), never in blocks of q steps.  f_t and p_t are
/// densities per step (appendix B: f_t = F_i/q²); P_t, C_τ and the local exponent are pure numbers (C_0 ≈ 1);
/// S_t = ⟨(r_t − r_0)²⟩ (eq. spreaddef) is in steps², r being the position of the paper's drunkard who moves
/// one unit per step; D_t = S_t/2t is in steps.
///
/// Errors: every series carries a one-sigma error, the standard error of the mean over the independent
/// subsets of orbits (§5, the paper's D = 6400 ± 800); see TrappingStatistics.hpp.  It may underestimate the
/// true error when a few very long segments dominate (§5).

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

/// The statistics, in the order of the table (the paper's reading order: fig. 6 a–d, then fig. 7).
enum class Statistic { f, p, P, C, localExponent, S, Scompensated, Dt };

/// How an axis is best drawn.
enum class AxisScale { linear, logarithmic };

struct StatisticInfo {
  Statistic statistic;
  std::string_view key;                ///< stable identifier (sessions, theory curves, CSV value column): "f_t"
  std::string_view symbol;             ///< plain text: "f_t", "C_tau"
  std::string_view symbolRich;         ///< rich text (Qt's HTML subset) for titles and legends: "f<sub>t</sub>"
  std::string_view description;        ///< in words, for menus: "distribution of trapping times"
  std::string_view abscissa;           ///< abscissa name, also its CSV column: "t" or "tau"
  std::string_view abscissaLabel;      ///< plain, with units: "t (steps)"
  std::string_view abscissaLabelRich;  ///< rich text: "τ (steps)"
  std::string_view valueLabel;         ///< plain, with units: "f_t (per step)"
  std::string_view valueLabelRich;     ///< rich text: "f<sub>t</sub> (per step)"
  std::string_view fileStem;           ///< descriptive file name without suffix: "f_t" → f_t.csv, f_t.png;
                                       ///< unique even ignoring case (p_t's is "p_t_probability")
  std::string_view error;              ///< what the error column holds
  AxisScale abscissaScale;             ///< hint for plots
  AxisScale valueScale;                ///< hint for plots (the local exponent is log-linear, fig. 6d)
  Series TrappingStatistics::*member;  ///< where the series lives
  bool plotted;                        ///< has its own plot in the GUI's statistics view (p_t = α f_t has not)
};

/// Every statistic, once, in the order of `Statistic`.
[[nodiscard]] std::span<const StatisticInfo> statisticsTable() noexcept;

/// The row of one statistic.
[[nodiscard]] const StatisticInfo& statisticInfo(Statistic s) noexcept;

/// The paper's figure panels that plot `s` ("3, 6a" for f_t; empty when none), from the one table of the paper
/// (core/paper/PaperTable.hpp).
[[nodiscard]] std::string figurePanelsOf(Statistic s);

/// The statistic with this key, or nothing.
[[nodiscard]] std::optional<Statistic> statisticWithKey(std::string_view key) noexcept;

/// The series of `s` in `statistics`.
[[nodiscard]] const Series& seriesOf(const TrappingStatistics& statistics, Statistic s) noexcept;

}  // namespace archipelago
