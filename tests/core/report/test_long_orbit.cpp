// core/report/LongOrbit: fig. 8's choice of segments (§7: the longest segment and the 138 = 6 × 23 chain).
#include <gtest/gtest.h>

#include "core/report/LongOrbit.hpp"
#include "core/report/ReportRuns.hpp"

namespace archipelago::report {
namespace {

TEST(LongOrbit, The138ChainIsRecognisedAtAnyLevel) {
  IslandChain c;
  c.period = 6;
  c.hierarchy = {1, 6};
  EXPECT_FALSE(isChain138(c));
  c.period = 138;
  c.hierarchy = {1, 6, 138};
  EXPECT_TRUE(isChain138(c));
  c.period = 138 * 5;  // a deeper level around the 138-chain still sticks to it
  c.hierarchy = {1, 6, 138, 690};
  EXPECT_TRUE(isChain138(c));
  c.period = 23;
  c.hierarchy = {1, 23};
  EXPECT_FALSE(isChain138(c));
}

TEST(LongOrbit, TheLongestSegmentIsReplayedFramedAndNamed) {
  TrappingParameters p = k01Run(ReportSize::quick).params;
  p.T = 40'000;  // 4·10⁷ steps: long segments of ~10⁴–10⁵ steps
  const TrappingState run = runTrapping(startTrapping(p), TrappingRunOptions{});
  ASSERT_GE(run.longest.items().size(), 3u);
  const LongOrbitFigures f = longOrbitFigures(run, 3, 1000, "k01.json");
  EXPECT_GE(f.examined, 1u);
  EXPECT_LE(f.examined, 3u);
  ASSERT_TRUE(f.longest);
  const LongOrbitView& v = *f.longest;
  EXPECT_EQ(v.record, run.longest.items().at(v.rank));
  EXPECT_EQ(v.steps, v.record.length * p.q);
  EXPECT_GE(v.points.size(), 3u);
  EXPECT_LE(v.points.size(), 1000u);
  // A square inside the box that frames the island where the segment spent its time.
  EXPECT_NEAR(double(v.view.width()), double(v.view.height()), 1e-12);
  EXPECT_GE(v.view.x0, p.map.xmin);
  EXPECT_LE(v.view.x1, p.map.xmax);
  EXPECT_LE(v.view.x0, v.chain.island.x0);
  EXPECT_GE(v.view.x1, v.chain.island.x1);
  EXPECT_NE(v.command.find("replay k01.json --segment " + std::to_string(v.rank) + " --identify"), std::string::npos);
  // No segment of so short a run reaches the 138-chain, and the search says how far it looked.
  if (!f.chain138) {
    EXPECT_EQ(f.examined, 3u);
  }
  EXPECT_THROW((void)longOrbitFigures(run, 3, 2, "k01.json"), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago::report
