#pragma once
/// \file ScanPoint.hpp
/// \brief What the K scan of §5 reports per K (ScanBox.hpp has the list of K and the box of each).

#include <cstdint>
#include <optional>
#include <vector>

#include "core/run/TrappingRun.hpp"
#include "core/scan/ScanBox.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

/// The fraction of the time (steps) spent in segments of at least `minSteps` steps: Σ_{t ≥ minSteps} t f_t /
/// Σ t f_t, from the histogram's length sums.  A logarithmic bin that straddles minSteps is counted whole when
/// its mean length (in steps) is ≥ minSteps (the statistics treat a bin as a point mass at its mean,
/// TrappingStatistics.hpp).  0 for an empty histogram.
[[nodiscard]] double timeFractionInSegmentsAtLeast(const TrappingHistogram& h, std::uint32_t q, double minSteps);

/// The threshold of the scan's summary: the paper's "slow algebraic decay" shows in segments beyond 10⁴ steps.
inline constexpr double kScanLongSegmentSteps = 1e4;

/// One K of the scan, as reported in its summary.
struct ScanPoint {
  double K = 0;
  MapParameters box;
  std::uint64_t blocksDone = 0, blocksTotal = 0;
  std::uint64_t segments = 0;
  double D = 0;                         ///< eq. ddef
  double DError = 0;                    ///< supportedDError(): the bootstrap over segments; NaN when the tail
                                        ///< dominates D or there are too few segments (never the subset error)
  std::uint64_t longestSteps = 0;       ///< the longest segment seen, in steps; 0 when none, or unknown (a run
                                        ///< with longestKept = 0 whose top bin holds several segments)
  double longFraction = 0;              ///< timeFractionInSegmentsAtLeast(total, q, kScanLongSegmentSteps)
  std::optional<BoxInvariantQuantities> boxInvariant;  ///< when b₂ was computed for this K
};

/// The scan point of a run (finished or not) and its statistics; `b2` when computed.
[[nodiscard]] ScanPoint scanPointOf(const TrappingState& state, const TrappingStatistics& statistics,
                                    const std::optional<StochasticAreaValue>& b2 = std::nullopt);

}  // namespace archipelago
