#pragma once
/// \file Bootstrap.hpp
/// \brief The bootstrap over segments (issue #14, item 2): replicate r of a histogram draws every bin's count from
/// a Poisson law of mean n_i (independently per bin: the number of segments of a run is random too) and keeps
/// the bin's mean length, Σ*_i = round(n*_i Σ_i/n_i); the statistics of a replicate are computeStatistics() of
/// it, the one definition of f, P, C and D.  The random numbers are core/random's counter generator (key =
/// orbitKey(seed, r); core/random/Poisson.hpp), so a bootstrap is reproducible from its seed.  Intervals are
/// percentile intervals of the replicates.  A bootstrap cannot draw a segment longer than the longest seen.

#include <cstdint>
#include <vector>

#include "core/stats/TrappingStatistics.hpp"
#include "core/trapping/TrappingHistogram.hpp"

namespace archipelago {

struct BootstrapOptions {
  std::uint32_t replicates = 1000;  ///< 20 to 100000
  std::uint64_t seed = 14;          ///< of the resampling (printed with the results)
  double confidence = 0.95;         ///< of the percentile intervals, in (0, 1)
};

struct ConfidenceInterval {
  double lo = kTailUndefined, hi = kTailUndefined;
};

/// The percentile p ∈ [0, 1] of sorted finite values, linearly interpolated (NaN for none).
[[nodiscard]] double percentile(const std::vector<double>& sorted, double p);

/// The percentile interval of the finite values at `confidence`; undefined when fewer than 90 % of them are
/// finite (the statistic then has no value in too many replicates to be trusted).
[[nodiscard]] ConfidenceInterval percentileInterval(std::vector<double> values, double confidence);

/// Replicate `replicate` of the Poisson bootstrap of `h` (see the file comment).
[[nodiscard]] TrappingHistogram resampleHistogram(const TrappingHistogram& h, std::uint64_t seed,
                                                  std::uint64_t replicate);

}  // namespace archipelago
