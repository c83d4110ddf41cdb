#include "core/scan/ScanPoint.hpp"

#include "core/stats/RunSummary.hpp"
#include "core/stats/TailAnalysis.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

namespace archipelago {

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
  // D's error as `stats` gives it for the same run file: core's one run summary (issue 35).
  p.DError = summarizeRun(state, statistics).DError;
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
