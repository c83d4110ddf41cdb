#include "core/stats/StatisticsTable.hpp"

#include "core/paper/PaperTable.hpp"

#include <array>

namespace archipelago {

namespace {

constexpr std::string_view kSubsetError = "one sigma: standard error of the mean over the subsets of orbits";
constexpr AxisScale kLog = AxisScale::logarithmic;
constexpr AxisScale kLinear = AxisScale::linear;

// Figures are numbered as in docs/design.md, "Figures": 3 small-K f_t (fsmall), 6 the K = 0.1 statistics (expense), 7 S_t and
// D_t (spread).  File stems differ even where case does not count (macOS, Windows): p_t's is not "p_t", which
// would name the same file as P_t's there.
constexpr std::array<StatisticInfo, 8> kTable = {{
    {
        .statistic = Statistic::f,
        .key = "f_t",
        .symbol = "f_t",
        .symbolRich = "f<sub>t</sub>",
        .description = "distribution of trapping times",
        .abscissa = "t",
        .abscissaLabel = "t (steps)",
        .abscissaLabelRich = "t (steps)",
        .valueLabel = "f_t (per step)",
        .valueLabelRich = "f<sub>t</sub> (per step)",
        .fileStem = "f_t",
        .error = kSubsetError,
        .abscissaScale = kLog,
        .valueScale = kLog,
        .member = &TrappingStatistics::f,
        .plotted = true,
    },
    {
        .statistic = Statistic::p,
        .key = "p_t",
        .symbol = "p_t",
        .symbolRich = "p<sub>t</sub>",
        .description = "probability that a segment has length t",
        .abscissa = "t",
        .abscissaLabel = "t (steps)",
        .abscissaLabelRich = "t (steps)",
        .valueLabel = "p_t (per step)",
        .valueLabelRich = "p<sub>t</sub> (per step)",
        .fileStem = "p_t_probability",
        .error = kSubsetError,
        .abscissaScale = kLog,
        .valueScale = kLog,
        .member = &TrappingStatistics::p,
        .plotted = false,
    },
    {
        .statistic = Statistic::P,
        .key = "P_t",
        .symbol = "P_t",
        .symbolRich = "P<sub>t</sub>",
        .description = "probability that a segment lasts longer than t",
        .abscissa = "t",
        .abscissaLabel = "t (steps)",
        .abscissaLabelRich = "t (steps)",
        .valueLabel = "P_t",
        .valueLabelRich = "P<sub>t</sub>",
        .fileStem = "P_t",
        .error = kSubsetError,
        .abscissaScale = kLog,
        .valueScale = kLog,
        .member = &TrappingStatistics::P,
        .plotted = true,
    },
    {
        .statistic = Statistic::C,
        .key = "C_tau",
        .symbol = "C_tau",
        .symbolRich = "C<sub>τ</sub>",
        .description = "correlation function",
        .abscissa = "tau",
        .abscissaLabel = "tau (steps)",
        .abscissaLabelRich = "τ (steps)",
        .valueLabel = "C_tau",
        .valueLabelRich = "C<sub>τ</sub>",
        .fileStem = "C_tau",
        .error = kSubsetError,
        .abscissaScale = kLog,
        .valueScale = kLog,
        .member = &TrappingStatistics::C,
        .plotted = true,
    },
    {
        .statistic = Statistic::localExponent,
        .key = "local_exponent",
        .symbol = "-dlogC_tau/dlogtau",
        .symbolRich = "−d log C<sub>τ</sub> / d log τ",
        .description = "local exponent of C_tau",
        .abscissa = "tau",
        .abscissaLabel = "tau (steps)",
        .abscissaLabelRich = "τ (steps)",
        .valueLabel = "-d log C_tau / d log tau",
        .valueLabelRich = "−d log C<sub>τ</sub> / d log τ",
        .fileStem = "local_exponent",
        .error = kSubsetError,
        .abscissaScale = kLog,
        .valueScale = kLinear,
        .member = &TrappingStatistics::localExponent,
        .plotted = true,
    },
    {
        .statistic = Statistic::S,
        .key = "S_t",
        .symbol = "S_t",
        .symbolRich = "S<sub>t</sub>",
        .description = "spreading of the drunkard's walk",
        .abscissa = "t",
        .abscissaLabel = "t (steps)",
        .abscissaLabelRich = "t (steps)",
        .valueLabel = "S_t (steps^2)",
        .valueLabelRich = "S<sub>t</sub> (steps<sup>2</sup>)",
        .fileStem = "S_t",
        .error = kSubsetError,
        .abscissaScale = kLog,
        .valueScale = kLog,
        .member = &TrappingStatistics::S,
        .plotted = true,
    },
    {
        .statistic = Statistic::Scompensated,
        .key = "S_t_compensated",
        .symbol = "S_t/t^1.5",
        .symbolRich = "S<sub>t</sub>/t<sup>3/2</sup>",
        .description = "S_t against t^{3/2} (flat where S_t ~ t^{3/2})",
        .abscissa = "t",
        .abscissaLabel = "t (steps)",
        .abscissaLabelRich = "t (steps)",
        .valueLabel = "S_t / t^1.5 (steps^0.5)",
        .valueLabelRich = "S<sub>t</sub> / t<sup>3/2</sup> (steps<sup>1/2</sup>)",
        .fileStem = "S_t_compensated",
        .error = kSubsetError,
        .abscissaScale = kLog,
        .valueScale = kLog,
        .member = &TrappingStatistics::Scompensated,
        .plotted = false,
    },
    {
        .statistic = Statistic::Dt,
        .key = "D_t",
        .symbol = "D_t",
        .symbolRich = "D<sub>t</sub>",
        .description = "running diffusion coefficient S_t/2t",
        .abscissa = "t",
        .abscissaLabel = "t (steps)",
        .abscissaLabelRich = "t (steps)",
        .valueLabel = "D_t (steps)",
        .valueLabelRich = "D<sub>t</sub> (steps)",
        .fileStem = "D_t",
        .error = kSubsetError,
        .abscissaScale = kLog,
        .valueScale = kLog,
        .member = &TrappingStatistics::Dt,
        .plotted = true,
    },
}};

// statisticInfo() indexes the table by the enum.
constexpr bool inEnumOrder() {
  for (std::size_t i = 0; i < kTable.size(); ++i)
    if (static_cast<std::size_t>(kTable[i].statistic) != i) return false;
  return true;
}
static_assert(inEnumOrder(), "the rows of kTable must follow the order of enum Statistic");

}  // namespace

std::span<const StatisticInfo> statisticsTable() noexcept { return kTable; }

const StatisticInfo& statisticInfo(Statistic s) noexcept { return kTable[static_cast<std::size_t>(s)]; }

std::string figurePanelsOf(Statistic s) { return paper::panelsShowing(statisticInfo(s).key); }

std::optional<Statistic> statisticWithKey(std::string_view key) noexcept {
  for (const StatisticInfo& row : kTable)
    if (row.key == key) return row.statistic;
  return std::nullopt;
}

const Series& seriesOf(const TrappingStatistics& statistics, Statistic s) noexcept {
  return statistics.*(statisticInfo(s).member);
}

}  // namespace archipelago
