#pragma once
/// \file LogFits.hpp
/// \brief The one way a slope is fitted to the statistics (issue #26): power laws on a logarithmic grid, with equal
/// weight per unit of log t, and exponential decay rates weighted by the data's errors.
///
/// The statistics' own grid is dense in integers (0, 1, …, min(50q, 4096)) and then 30 points per decade, so a
/// least-squares fit over its points weighted short times 800 to 4096 times more than a decade of long times, and
/// differently for different q.  Here a power-law fit first samples log y on a grid of `perDecade` points per
/// decade (log y interpolated linearly in log x between the series' neighbouring points: exact for a power law),
/// then fits a straight line with equal weights.  Its error propagates the series' one-sigma errors at the grid
/// points as if they were independent; for cumulative statistics (P_t, C_τ, S_t) neighbouring points are
/// correlated, so this understates the error: the error over independent subsets of orbits
/// (RunStatistics.hpp, slopeOverSubsets) is the honest one.

#include <cstddef>
#include <vector>

#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

/// A fitted slope over [from, to] (the part of the requested range the data cover).
struct SlopeFit {
  double slope = kTailUndefined;
  double error = kTailUndefined;  ///< one sigma (see the file comment); NaN when unknown
  std::size_t points = 0;         ///< grid points (power laws) or series points (decay rates) used
  double from = kTailUndefined, to = kTailUndefined;
  [[nodiscard]] bool valid() const noexcept { return points >= 3 && slope == slope; }
};

/// d log y / d log x over [from, to] on a log grid of kLogGridPerDecade points per decade (TrappingStatistics.hpp; the file comment).  Points with y ≤ 0 are skipped; NaN slope
/// (valid() false) with fewer than 3 grid points.
[[nodiscard]] SlopeFit logLogSlope(const Series& s, double from, double to, int perDecade = kLogGridPerDecade);

/// A series' usable points (x > 0, y > 0 and finite) as logarithms, taken once for several fits of the same series
/// (the tail analysis fits every window of the running exponent in each bootstrap replicate).  With a range, only
/// the points fits inside [from, to] read: fits of windows outside it are not those of the series.
class LogSeries {
 public:
  explicit LogSeries(const Series& s);
  LogSeries(const Series& s, double from, double to);
  struct Point {
    long double u, v, sigma;  ///< ln x, ln y, σ(y)/y
  };
  [[nodiscard]] const std::vector<Point>& points() const noexcept { return points_; }

 private:
  std::vector<Point> points_;
};

/// logLogSlope() of the series the LogSeries holds: the same numbers, to the last bit (for a window inside its range).
[[nodiscard]] SlopeFit logLogSlope(const LogSeries& s, double from, double to, int perDecade = kLogGridPerDecade);

/// −d log y / d log x (a decay exponent, positive for a decaying power law): −logLogSlope().slope, NaN when the
/// fit is not valid.  `points` receives the number of grid points.
[[nodiscard]] double fitLogSlope(const Series& s, double from, double to, std::size_t* points = nullptr);
[[nodiscard]] double fitLogSlope(const LogSeries& s, double from, double to, std::size_t* points = nullptr);

/// d ln y / d x over the series' points in [from, to] with y > 0 (an exponential's rate, negative for a decay),
/// weighted least squares with weights (y/σ)² (σ the point's error; points with σ = 0 are left out unless every
/// point has σ = 0, when the weights are equal).  The error is the weighted fit's.
[[nodiscard]] SlopeFit logLinearSlope(const Series& s, double from, double to);

/// A window [from, to] (steps) of the running exponent.
struct LogWindow {
  double from = 0, to = 0;
};

/// The running exponent's windows, one definition for the statistics' tail analysis (TailAnalysis.hpp) and the tail
/// sampler (TailResult.hpp): decades ending at tEnd·10^(−k/2), k = 0, 1, … (at most 16), while they start at or
/// above `lowest`; the first (k = 0, the tail fit) starts at `lowest` when tEnd/10 is below it; none when tEnd <
/// 3·lowest (less than half a decade to fit) or either is not finite and positive.  γ over a window is
/// fitLogSlope() of P_t over it.
[[nodiscard]] std::vector<LogWindow> runningExponentWindows(double tEnd, double lowest);

}  // namespace archipelago
