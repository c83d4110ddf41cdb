#pragma once
/// \file RunStatistics.hpp
/// \brief The statistics of a run (or of a run in progress).  Their table is stats/StatisticsTable.hpp, their
/// CSV files export/StatisticsCsv.hpp.

#include <cstdint>
#include <vector>

#include "core/stats/TrappingStatistics.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago {

/// Orbits that fed each subset histogram: orbit i of [orbitBegin, orbitEnd) goes to subset i mod subsets.
[[nodiscard]] std::vector<std::uint64_t> orbitsPerSubset(const TrappingState& state);

/// computeStatistics() of the state's subsets, over the blocks done so far.
[[nodiscard]] TrappingStatistics statisticsOf(const TrappingState& state);

}  // namespace archipelago
