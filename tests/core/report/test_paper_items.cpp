// core/report: the marks follow the tolerances, and the statements the report checks without a run carry the
// paper's own numbers (Karney 1983, §2, §4, §6, §7) — the reference values below are typed from the paper.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/report/PaperItems.hpp"
#include "core/stats/RunEnsemble.hpp"
#include "core/stats/RunStatistics.hpp"

namespace archipelago::report {
namespace {

TEST(PaperItems, MarkFollowsToleranceAndError) {
  PaperItem it;
  it.paper = 1.0;
  it.ours = 1.05;
  it.tolerance = 0.1;
  markByTolerance(it);
  EXPECT_EQ(it.mark, Mark::agrees);
  it.ours = 1.2;
  markByTolerance(it);
  EXPECT_EQ(it.mark, Mark::differs);
  it.error = 0.05;  // |1.2 − 1| = 0.2 ≤ 0.1 + 3 × 0.05
  markByTolerance(it);
  EXPECT_EQ(it.mark, Mark::agrees);
  it.ours = std::nullopt;
  markByTolerance(it);
  EXPECT_EQ(it.mark, Mark::notReproduced);
  it.ours = std::nan("");
  markByTolerance(it);
  EXPECT_EQ(it.mark, Mark::notReproduced);
}

TEST(PaperItems, TheoryItemsCarryThePapersNumbersAndAgree) {
  std::map<std::string, PaperItem> byId;
  for (const auto& it : theoryItems()) byId[it.id] = it;
  const std::map<std::string, double> paper = {
      {"tmax", 5.1454},   {"tmax-X0", -0.5536}, {"F-smallT", 6.205e5},      {"F-cutoff", 3.024},
      {"A-const", 4.207}, {"t7", 7},            {"pd-accumulation", 1.2840}, {"chain138-x", 0.352},
      {"chain138-y", 0.034}, {"factor056", 0.56}};
  for (const auto& [id, value] : paper) {
    ASSERT_TRUE(byId.count(id)) << id;
    const PaperItem& it = byId[id];
    ASSERT_TRUE(it.paper && it.ours) << id;
    EXPECT_EQ(*it.paper, value) << id;
    EXPECT_EQ(it.mark, Mark::agrees) << id << ": ours " << *it.ours;
    EXPECT_FALSE(it.command.empty()) << id;
  }
}

TEST(PaperItems, HeavyTailItemsAreNotClaimedOnAShortRun) {
  TrappingParameters p = k01Parameters(false);
  p.T = 20000;  // 2·10⁷ steps: far too short for D
  const TrappingState run = runTrapping(startTrapping(p), TrappingRunOptions{});
  const auto items = k01Items(run, statisticsOf(run), analyseTail(ensembleOf({run})), false);
  for (const auto& it : items)
    if (it.id == "D" || it.id == "longest") {
      EXPECT_EQ(it.mark, Mark::notAtThisSize) << it.id;
    }
}

// §5's local exponent range: only the resolved points past the block structure count (τ ≥ 10q, error in (0, 0.15]).
TEST(PaperItems, LocalExponentRangeUsesOnlyResolvedPoints) {
  TrappingState run;
  run.params.q = 16;  // points below τ = 160 are the block structure's
  TrappingStatistics s;
  s.localExponent.x = {100, 200, 1000, 5000, 20000, 40000, 80000};
  s.localExponent.value = {0.1, 0.3, 0.26, 0.7, 1.4, 2.5, 9.0};
  s.localExponent.error = {0.01, 0.01, 0.01, 0.05, 0.1, 0.5, 0.0};  // 2.5: too uncertain; 9.0: unresolved (0)
  auto items = localExponentRangeItems(run, s, false);
  ASSERT_EQ(items.size(), 2u);
  ASSERT_TRUE(items[0].ours && items[1].ours);
  EXPECT_EQ(*items[0].ours, 0.26);
  EXPECT_EQ(items[0].error, 0.01);
  EXPECT_EQ(items[0].mark, Mark::agrees);  // |0.26 − ¼| ≤ 0.06
  EXPECT_EQ(*items[1].ours, 1.4);
  EXPECT_EQ(items[1].mark, Mark::agrees);  // |1.4 − 3/2| ≤ 0.25
  s.localExponent.value[4] = 0.9;          // the far tail not reached: not claimed on a short run
  items = localExponentRangeItems(run, s, false);
  EXPECT_EQ(*items[1].ours, 0.9);
  EXPECT_EQ(items[1].mark, Mark::notAtThisSize);
  items = localExponentRangeItems(run, s, true);  // a full run that resolves τ ≥ 10⁴ and misses 3/2: it differs
  EXPECT_EQ(items[1].mark, Mark::differs);
}

// §5's K scan: "most K" means more than half show segments beyond 10⁴ steps.
TEST(PaperItems, KScanItemCountsTheKWithLongSegments) {
  std::vector<ScanRunSummary> runs(4);
  const std::uint64_t longest[] = {50'000, 12'000, 9'999, 10'000};
  for (int i = 0; i < 4; ++i) {
    runs[i].point.K = 0.05 * (i + 1);
    runs[i].point.longestSteps = longest[i];
  }
  PaperItem it = kScanItem(runs, false);
  ASSERT_TRUE(it.ours);
  EXPECT_EQ(*it.ours, 0.75);
  EXPECT_EQ(it.mark, Mark::agrees);
  EXPECT_NE(it.note.find("K = 0.15"), std::string::npos) << it.note;  // the one without, named
  runs[0].point.longestSteps = runs[1].point.longestSteps = 100;
  it = kScanItem(runs, false);
  EXPECT_EQ(*it.ours, 0.25);
  EXPECT_EQ(it.mark, Mark::differs);
  EXPECT_FALSE(kScanItem({}, false).ours);
}

// The report's scan is the paper's list of K, and its command names the same parameters.
TEST(PaperItems, KScanRequestIsThePapersList) {
  const KScanRequest r = kScanRequest(false, "scan");
  ASSERT_EQ(r.K.size(), 26u);
  EXPECT_EQ(r.K.front(), 0.05);
  EXPECT_EQ(r.K.back(), 1.3);
  EXPECT_FALSE(kScanValidationError(r));
  const std::string c = kScanCommand(false);
  EXPECT_NE(c.find("--T " + std::to_string(r.base.parameters.T)), std::string::npos) << c;
  EXPECT_NE(c.find("--M " + std::to_string(r.base.parameters.M)), std::string::npos) << c;
}

// Appendix B: the Cray's numbers against a timing (75 ns / 0.25 ns = 300×; 3.2·10¹² steps at 10⁹/s = 0.889 h).
TEST(PaperItems, TimingItemsCompareWithTheCray) {
  StepTiming t;
  t.nsPerStepOneThread = 0.25;
  t.stepsPerSecond = 1e9;
  t.threads = 2;
  t.kernel = "scalar";
  const auto items = timingItems(t);
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(*items[0].paper, 75);
  EXPECT_EQ(*items[0].ours, 0.25);
  EXPECT_NE(items[0].note.find("300×"), std::string::npos) << items[0].note;
  EXPECT_EQ(*items[1].paper, 65);
  EXPECT_NEAR(*items[1].ours, 3.2e12 / 1e9 / 3600, 1e-12);
  for (const auto& it : items) EXPECT_EQ(it.mark, Mark::differsExplained);
}

// Fig. 2b frames the 138-chain's member, and the finder finds the elliptic period-138 orbit there (§7).
TEST(PaperItems, FigureTwoEnlargementHoldsThe138Member) {
  const auto orbit = chain138Orbit();
  ASSERT_TRUE(orbit);
  EXPECT_EQ(orbit->period, 138);
  const PortraitRequest r = figureTwoRequest(false, true);
  EXPECT_FALSE(validationError(r));
  const PhysicalRect v = r.view.physical(r.map);
  int inside = 0;
  for (const auto& z : orbit->points) inside += z.x >= v.x0 && z.x <= v.x1 && z.y >= v.y0 && z.y <= v.y1;
  EXPECT_GE(inside, 1);
  EXPECT_TRUE(v.x0 < 0.352L - std::sqrt(0.1L) && 0.352L - std::sqrt(0.1L) < v.x1);
}

}  // namespace
}  // namespace archipelago::report
