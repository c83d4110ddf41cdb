#pragma once
/// \file RunStatistics.hpp
/// \brief The statistics of a run (or of a run in progress), and their export as CSV.

#include <filesystem>
#include <string>
#include <vector>

#include "stats/TrappingStatistics.hpp"
#include "trapping/TrappingRun.hpp"

namespace archipelago {

/// Orbits that fed each subset histogram: orbit i of [orbitBegin, orbitEnd) goes to subset i mod subsets.
[[nodiscard]] std::vector<std::uint64_t> orbitsPerSubset(const TrappingState& state);

/// computeStatistics() of the state's subsets, over the blocks done so far.
[[nodiscard]] TrappingStatistics statisticsOf(const TrappingState& state);

/// One series as CSV text: a header "xName,valueName,error" and one row per point (17 significant digits).
[[nodiscard]] std::string seriesCsv(const Series& s, const std::string& xName, const std::string& valueName);

/// The name, abscissa name and value name of every series of TrappingStatistics, in a fixed order
/// (f, p, P, C, local_exponent, S, D_t), with a pointer to the member.
struct SeriesField {
  const char* file;   ///< file stem, e.g. "f"
  const char* x;      ///< abscissa name, e.g. "t"
  const char* value;  ///< value name, e.g. "f_t"
  Series TrappingStatistics::*member;
};
[[nodiscard]] const std::vector<SeriesField>& statisticsSeriesFields();

/// Writes every series as DIR/<file>.csv and the scalars (α, D, Σ t f_t, segments, …) as DIR/summary.csv.
/// Creates DIR if needed.  Throws std::runtime_error naming the file on failure.
void writeStatisticsCsv(const std::filesystem::path& dir, const TrappingStatistics& stats);

}  // namespace archipelago
