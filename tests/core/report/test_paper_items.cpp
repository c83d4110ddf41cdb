// core/report: the marks follow the tolerances, and the statements the report checks without a run carry the
// paper's own numbers (Karney 1983, §2, §4, §6, §7) — the reference values below are typed from the paper.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/report/PaperItems.hpp"
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

TEST(PaperItems, PendingItemsHaveNoValue) {
  for (const auto& it : pendingItems()) {
    EXPECT_FALSE(it.ours) << it.id;
    EXPECT_EQ(it.mark, Mark::notReproduced) << it.id;
  }
}

TEST(PaperItems, HeavyTailItemsAreNotClaimedOnAShortRun) {
  TrappingParameters p = k01Parameters(false);
  p.T = 20000;  // 2·10⁷ steps: far too short for D
  const TrappingState run = runTrapping(startTrapping(p), TrappingRunOptions{});
  const auto items = k01Items(run, statisticsOf(run), false);
  for (const auto& it : items)
    if (it.id == "D" || it.id == "longest") {
      EXPECT_EQ(it.mark, Mark::notAtThisSize) << it.id;
    }
}

}  // namespace
}  // namespace archipelago::report
