#pragma once
/// \file KScan.hpp
/// \brief The K scan of §5 ("We have measured f_t for K between 0 and 1.3 at intervals of 0.05"): the list of K,
/// the box of each K, and what the scan reports per K.
///
/// The box rule.  The paper does not give its boxes for the scan; appendix B only requires xmin < −√K, and
/// appendix A shows that a larger box adds short segments without changing b₂ f_t for large t (eq. A3).  The
/// box must hold the island: for small K the island of eq. (hamb) runs from the separatrix's far crossing
/// X = −2 to the hyperbolic point X = 1 in units of √K, i.e. −2√K ≤ x ≤ √K.  We take that extent with a margin
/// of 0.2 on each side:
///     xmin = −2√K − 0.2,   xmax = √K + 0.2.
/// At K = 0.1 this is (−0.832, 0.516), close to the paper's (−0.8, 0.5); at K = 0 (no island) a box of side 0.4
/// around the tangent point; at K = 1.3 (past the period doublings at K = 1, 1.25, whose orbits lie at
/// x = −1 ∓ √(K − 1), §2) (−2.48, 1.34), which still holds them.

#include <cstdint>
#include <optional>
#include <vector>

#include "core/map/MapParameters.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

inline constexpr double kScanBoxMargin = 0.2;
/// The scan's K must lie in [0, kScanMaxK]: the box rule needs √K, and beyond 4 the box's side exceeds 6.
inline constexpr double kScanMaxK = 4;

/// The box of K (the rule above).  Throws std::invalid_argument naming K when K is not in [0, kScanMaxK].
[[nodiscard]] MapParameters scanBox(double K);

/// K = from, from + step, …, up to `to` (included when it is within 10⁻⁹ step of a grid point), each rounded to
/// 12 significant digits so that 0.05·3 is 0.15, not 0.15000000000000002.  Throws std::invalid_argument when
/// step ≤ 0, to < from, or the list would have more than 10⁴ values.
[[nodiscard]] std::vector<double> scanValues(double from, double to, double step);

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
