#include "stats/StatisticsTable.hpp"

#include <array>

namespace archipelago {

namespace {

constexpr std::string_view kSubsetError = "one sigma: standard error of the mean over the subsets of orbits";
constexpr AxisScale kLog = AxisScale::logarithmic;
constexpr AxisScale kLinear = AxisScale::linear;

// File stems differ even where case does not count (macOS, Windows): p_t's is not "p_t", which would name
// the same file as P_t's there.  Figures are numbered as in DESIGN.md: 3 small-K f_t (fsmall), 6 the K = 0.1 statistics (expense),
// 7 S_t and D_t (spread).
const std::array<StatisticInfo, 7> kTable = {{
    {Statistic::f, "f_t", "f_t", "f<sub>t</sub>", "distribution of trapping times",  //
     "t", "t (steps)", "t (steps)", "f_t (per step)", "f<sub>t</sub> (per step)", "f_t", kSubsetError, kLog, kLog,
     &TrappingStatistics::f, "3, 6(a)", true},
    {Statistic::p, "p_t", "p_t", "p<sub>t</sub>", "probability that a segment has length t",  //
     "t", "t (steps)", "t (steps)", "p_t (per step)", "p<sub>t</sub> (per step)", "p_t_probability", kSubsetError, kLog, kLog,
     &TrappingStatistics::p, "", false},
    {Statistic::P, "P_t", "P_t", "P<sub>t</sub>", "probability that a segment lasts longer than t",  //
     "t", "t (steps)", "t (steps)", "P_t", "P<sub>t</sub>", "P_t", kSubsetError, kLog, kLog,
     &TrappingStatistics::P, "6(b)", true},
    {Statistic::C, "C_tau", "C_tau", "C<sub>τ</sub>", "correlation function",  //
     "tau", "tau (steps)", "τ (steps)", "C_tau", "C<sub>τ</sub>", "C_tau", kSubsetError, kLog, kLog,
     &TrappingStatistics::C, "6(c)", true},
    {Statistic::localExponent, "local_exponent", "-dlogC_tau/dlogtau", "−d log C<sub>τ</sub> / d log τ",
     "local exponent of C_tau",  //
     "tau", "tau (steps)", "τ (steps)", "-d log C_tau / d log tau", "−d log C<sub>τ</sub> / d log τ",
     "local_exponent", kSubsetError, kLog, kLinear, &TrappingStatistics::localExponent, "6(d)", true},
    {Statistic::S, "S_t", "S_t", "S<sub>t</sub>", "spreading of the drunkard's walk",  //
     "t", "t (steps)", "t (steps)", "S_t (steps^2)", "S<sub>t</sub> (steps<sup>2</sup>)", "S_t", kSubsetError,
     kLog, kLog, &TrappingStatistics::S, "7(a)", true},
    {Statistic::Dt, "D_t", "D_t", "D<sub>t</sub>", "running diffusion coefficient S_t/2t",  //
     "t", "t (steps)", "t (steps)", "D_t (steps)", "D<sub>t</sub> (steps)", "D_t", kSubsetError, kLog, kLog,
     &TrappingStatistics::Dt, "7(c)", true},
}};

}  // namespace

std::span<const StatisticInfo> statisticsTable() noexcept { return kTable; }

const StatisticInfo& statisticInfo(Statistic s) noexcept { return kTable[static_cast<std::size_t>(s)]; }

std::optional<Statistic> statisticWithKey(std::string_view key) noexcept {
  for (const StatisticInfo& row : kTable)
    if (row.key == key) return row.statistic;
  return std::nullopt;
}

const Series& seriesOf(const TrappingStatistics& statistics, Statistic s) noexcept {
  return statistics.*(statisticInfo(s).member);
}

}  // namespace archipelago
