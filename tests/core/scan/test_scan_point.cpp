// The K scan of §5 (core/scan/ScanBox.hpp, ScanPoint.hpp): the box rule, the list of K, and the per-K figures of the summary.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/stats/RunStatistics.hpp"
#include "core/scan/ScanPoint.hpp"

namespace archipelago {
namespace {

TEST(KScan, BoxHoldsTheIslandWithItsMarginAndIsValid) {
  for (int i = 0; i <= 26; ++i) {  // the paper's scan, 0 … 1.3 by 0.05
    const double K = 0.05 * i;
    const MapParameters box = scanBox(K);
    EXPECT_EQ(box.K, K);
    EXPECT_FALSE(validationError(box).has_value()) << K << ": " << *validationError(box);
    // The small-K island (eq. hamb) spans −2√K ≤ x ≤ √K; 0.2 to spare on each side.
    EXPECT_NEAR(box.xmin, -2 * std::sqrt(K) - 0.2, 1e-15);
    EXPECT_NEAR(box.xmax, std::sqrt(K) + 0.2, 1e-15);
    if (K > 1)  // the period-2 orbit born at K = 1 (§2), x = −1 ∓ √(K − 1), lies inside
      for (const double x : {-1 - std::sqrt(K - 1), -1 + std::sqrt(K - 1)}) {
        EXPECT_GT(x, box.xmin + 0.1) << K;
        EXPECT_LT(x, box.xmax - 0.1) << K;
      }
  }
  EXPECT_NEAR(scanBox(0.1).xmin, -0.832, 1e-3);  // close to the paper's (−0.8, 0.5)
  EXPECT_NEAR(scanBox(0.1).xmax, 0.516, 1e-3);
}

TEST(KScan, BoxRefusesKOutsideItsRange) {
  for (const double K : {-0.1, 4.5, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    EXPECT_THROW((void)scanBox(K), std::invalid_argument) << K;
  EXPECT_NO_THROW((void)scanBox(kScanMaxK));
}

TEST(KScan, ValuesOfARangeAreTheDecimalsTyped) {
  const std::vector<double> paper = scanValues(0.05, 1.3, 0.05);
  ASSERT_EQ(paper.size(), 26u);
  EXPECT_EQ(paper.front(), 0.05);
  EXPECT_EQ(paper[2], 0.15);  // not 0.15000000000000002
  EXPECT_EQ(paper[5], 0.3);
  EXPECT_EQ(paper.back(), 1.3);
  EXPECT_EQ(scanValues(0, 0.1, 0.05), (std::vector<double>{0, 0.05, 0.1}));
  EXPECT_EQ(scanValues(0.1, 0.1, 1), (std::vector<double>{0.1}));
  EXPECT_EQ(scanValues(0, 0.25, 0.1), (std::vector<double>{0, 0.1, 0.2}));  // `to` off the grid: not included
  EXPECT_THROW((void)scanValues(0.3, 0.1, 0.05), std::invalid_argument);
  EXPECT_THROW((void)scanValues(0, 1, 0), std::invalid_argument);
  EXPECT_THROW((void)scanValues(0, 1, -0.1), std::invalid_argument);
  EXPECT_THROW((void)scanValues(0, 1, 1e-9), std::invalid_argument);
}

TEST(KScan, TimeFractionInLongSegmentsFromTheLengthSums) {
  TrappingHistogram h;
  for (int i = 0; i < 10; ++i) h.add(1);  // 10 segments of 16 steps (q = 16)
  h.add(1000);                            // one of 16000 steps
  EXPECT_DOUBLE_EQ(timeFractionInSegmentsAtLeast(h, 16, 1e4), 16000.0 / 16160.0);
  EXPECT_DOUBLE_EQ(timeFractionInSegmentsAtLeast(h, 16, 16), 1.0);
  EXPECT_EQ(timeFractionInSegmentsAtLeast(h, 16, 2e4), 0.0);
  EXPECT_EQ(timeFractionInSegmentsAtLeast(TrappingHistogram{}, 16, 1), 0.0);
}

TEST(KScan, PointOfARunHasItsDAndLongestSegment) {
  TrappingParameters p;
  p.map = scanBox(0.2);
  p.M = 4;
  p.T = 2000;
  p.subsets = 2;
  const TrappingState s = runTrapping(startTrapping(p), TrappingRunOptions{});
  const TrappingStatistics st = statisticsOf(s);
  const ScanPoint point = scanPointOf(s, st, stochasticAreaOf(p.map, 0.5));
  EXPECT_EQ(point.K, 0.2);
  EXPECT_EQ(point.blocksDone, 2000u);
  EXPECT_EQ(point.D, st.D);
  ASSERT_FALSE(s.longest.items().empty());
  EXPECT_EQ(point.longestSteps, s.longest.items().front().length * p.q);
  ASSERT_TRUE(point.boxInvariant.has_value());
  EXPECT_DOUBLE_EQ(point.boxInvariant->b2D, 0.5 * p.map.width() * p.map.width() * st.D);
  EXPECT_FALSE(scanPointOf(s, st).boxInvariant.has_value());
}

}  // namespace
}  // namespace archipelago
