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

/// Where a run of q > 1 and its q = 1 companion are spliced (issue #26): the smallest abscissa x ≥ 10 q of the run's
/// f_t at which the two f_t agree within errors, |f_run − f_companion| ≤ 2 √(σ_run² + σ_companion²) (the
/// companion's f_t interpolated linearly in log-log at x; its one-sigma errors from the subsets).  Throws
/// std::invalid_argument when they agree nowhere beyond 10 q within the companion's range (a longer companion is
/// needed).
[[nodiscard]] double spliceCrossover(const TrappingStatistics& run, const TrappingStatistics& companion, std::uint32_t q);

/// The composite statistics of a run of q > 1 and its q = 1 companion (core/stats/TrappingStatistics.hpp,
/// computeSplicedStatistics) at spliceCrossover().  Throws std::invalid_argument naming what differs when the two
/// are not a run and its companion: the map, Xr, the number of subsets and orbits, q (the run's > 1, the
/// companion's 1), or when they do not cross.
[[nodiscard]] TrappingStatistics splicedStatisticsOf(const TrappingState& run, const TrappingState& companion);

}  // namespace archipelago
