// The paper's small-K results (§4, fig. 3), reproduced by short runs of the engine.
// Runs: q = 1, box xmin = −0.05, xmax = 0.05 (about 5√|K|, wide enough to hold the islands of §4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/report/ReportRuns.hpp"
#include "core/report/RunStatements.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago {
namespace {

TrappingState smallKRun(double K, std::uint64_t T) {
  TrappingParameters p;
  p.map = {K, -0.05, 0.05};
  p.q = 1;
  p.M = 64;
  p.T = T;
  p.seed = 2026;
  return runTrapping(startTrapping(p), TrappingRunOptions{});
}

// K < 0: no periodic orbits; no segment is longer than t_max = 5.1454 |K|^(−1/4) = 51.45 (lower in a finite
// box, §4), and f_t piles up just below the cut-off (the (Tmax − T)^(−1/2) singularity of F(T), fig. 3a).
TEST(SmallKTrapping, NegativeKHasACutoffBelowTmax) {
  const TrappingState s = smallKRun(-1e-4, 2'000'000);
  const TrappingHistogram h = s.total();
  const int last = h.lastUsedBin();
  const double tmax = 5.1454 * std::pow(1e-4, -0.25);
  EXPECT_LE(static_cast<double>(last), tmax);
  EXPECT_GE(static_cast<double>(last), 0.6 * tmax);
  // The pile-up: f_t falls with t, reaches a minimum, then rises again just below the cut-off.
  int lowest = last - 10;
  for (int i = last - 10; i < last; ++i)
    if (h.count(i) < h.count(lowest)) lowest = i;
  std::uint64_t peak = 0;
  for (int i = lowest; i <= last; ++i) peak = std::max(peak, h.count(i));
  EXPECT_GT(lowest, last - 10) << "no minimum before the cut-off";
  EXPECT_GT(static_cast<double>(peak), 1.25 * static_cast<double>(h.count(lowest)))
      << "no singular pile-up below the cut-off";
}

// §4's statements measured as the report measures them (core/report/RunStatements.hpp) on the report's quick runs
// (the fig. 3 presets with T/10, and K = 10⁻³, 10⁻²), judged with the paper table's tolerances: t_max in the run's
// box, f_t ~ t⁻⁷ at K = 0, the decay rates K^¼ at K = 10⁻⁴, 10⁻³, 10⁻².
TEST(SmallKTrapping, QuickRunsAgreeWithThePaperWithinTheTablesTolerances) {
  const auto runOf = [](const report::ReportRun& r) { return runTrapping(startTrapping(r.params), TrappingRunOptions{}); };
  const auto quick = report::ReportSize::quick;
  const TrappingState a = runOf(report::smallKRun('a', quick)), b = runOf(report::smallKRun('b', quick)),
                      c = runOf(report::smallKRun('c', quick)), d3 = runOf(report::decayRun(1e-3, quick)),
                      d2 = runOf(report::decayRun(1e-2, quick));
  const auto trace = [](const report::ReportItem& it) {
    return std::string(it.id()) + ": ours " + (it.ours ? std::to_string(*it.ours) : "none") + " ± " +
           std::to_string(it.error) + "; " + it.note;
  };
  const auto items = report::smallKStatements(a, b, c, d3, d2, report::ReportSize::quick);
  ASSERT_EQ(items.size(), 5u);
  for (const report::ReportItem& it : items) {
    SCOPED_TRACE(trace(it));
    EXPECT_EQ(it.mark, report::Mark::agrees);
  }
  // The same checks on the wrong runs (each run passed in another's place) must fail: none may agree.
  for (const report::ReportItem& it : report::smallKStatements(c, a, b, d2, d3, report::ReportSize::quick)) {
    SCOPED_TRACE(trace(it));
    EXPECT_TRUE(it.mark == report::Mark::differs || it.mark == report::Mark::notComputed);
  }
}

}  // namespace
}  // namespace archipelago
