#include "core/theory/KScan.hpp"

#include "core/io/NumberText.hpp"
#include "core/stats/RunEnsemble.hpp"
#include "core/stats/TailAnalysis.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace archipelago {

MapParameters scanBox(double K) {
  if (!(K >= 0 && K <= kScanMaxK)) {
    const std::string text = io::formatC("K = %.17g must lie in [0, %g] for a scan (its box is -2 sqrt(K) - %g ... sqrt(K) + %g)",
                                         K, kScanMaxK, kScanBoxMargin, kScanBoxMargin);
    throw std::invalid_argument(text);
  }
  const double r = std::sqrt(K);
  MapParameters box;
  box.K = K;
  box.xmin = -2 * r - kScanBoxMargin;
  box.xmax = r + kScanBoxMargin;
  return box;
}

std::vector<double> scanValues(double from, double to, double step) {
  if (!(step > 0) || !std::isfinite(step)) throw std::invalid_argument("the step of a K range must be positive");
  if (!(to >= from) || !std::isfinite(from) || !std::isfinite(to))
    throw std::invalid_argument("a K range must run upwards (from <= to)");
  const double intervals = (to - from) / step;
  if (intervals > 1e4) throw std::invalid_argument("a K range may hold at most 10^4 values");
  const auto n = static_cast<std::size_t>(std::floor(intervals + 1e-9)) + 1;
  std::vector<double> values;
  values.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string text = io::formatC("%.12g", from + static_cast<double>(i) * step);
    values.push_back(*io::parseDoubleC(text));  // the C locale: "%.12g" never writes a decimal comma here
  }
  return values;
}

double timeFractionInSegmentsAtLeast(const TrappingHistogram& h, std::uint32_t q, double minSteps) {
  long double all = 0, inLong = 0;
  for (int i = 1; i < TrappingHistogram::kBins; ++i) {
    const std::uint64_t n = h.count(i);
    if (n == 0) continue;
    const long double sum = static_cast<long double>(h.lengthSum(i)) * q;  // steps
    all += sum;
    if (sum / n >= minSteps) inLong += sum;
  }
  return all > 0 ? static_cast<double>(inLong / all) : 0.0;
}

ScanPoint scanPointOf(const TrappingState& state, const TrappingStatistics& statistics,
                      const std::optional<StochasticAreaValue>& b2) {
  ScanPoint p;
  p.K = state.params.map.K;
  p.box = state.params.map;
  p.blocksDone = state.blocksDone;
  p.blocksTotal = state.params.T;
  p.segments = statistics.segments;
  p.D = statistics.D;
  // D's error as `stats` gives it for the same run file: the bootstrap over segments (default options), or none.
  p.DError = std::numeric_limits<double>::quiet_NaN();
  if (statistics.segments > 0) {
    try {
      p.DError = supportedDError(analyseTail(ensembleOf({state})));
    } catch (const std::invalid_argument&) {
      // too few segments to resample: no error
    }
  }
  const auto& longest = state.longest.items();
  const TrappingHistogram total = state.total();
  if (!longest.empty()) {
    p.longestSteps = longest.front().length * state.params.q;
  } else if (const int last = total.lastUsedBin(); last > 0 && total.count(last) == 1) {
    p.longestSteps = total.lengthSum(last) * state.params.q;  // longestKept = 0: the top bin, when it holds one
  }
  p.longFraction = timeFractionInSegmentsAtLeast(total, state.params.q, kScanLongSegmentSteps);
  if (b2) p.boxInvariant = boxInvariantQuantities(*b2, statistics.D, p.DError);
  return p;
}

}  // namespace archipelago
