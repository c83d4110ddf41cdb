// The portrait's axis labels at any depth (core/view/AxisLabels.hpp; issue 37, findings 2 and 18).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/view/AxisLabels.hpp"

namespace archipelago {
namespace {

TEST(AxisLabels, PlainWhileSevenDigitsTellTheTicksApart) {
  const AxisLabels whole = axisLabelsFor(-0.8, 0.5);  // the paper's box
  EXPECT_FALSE(whole.offset);
  EXPECT_EQ(axisTickLabel(whole, -0.8), "-0.8");
  EXPECT_EQ(axisTickLabel(whole, 0.25), "0.25");
  EXPECT_EQ(axisTitleSuffix(whole), "");
  const AxisLabels narrow = axisLabelsFor(-0.1505, -0.1495);  // 10⁻³ wide: 6 digits
  EXPECT_FALSE(narrow.offset);
  EXPECT_EQ(axisTickLabel(narrow, -0.1502), "-0.1502");
  EXPECT_FALSE(axisLabelsFor(0, 0).offset);  // degenerate: plain
}

TEST(AxisLabels, OffsetsFromTheReferenceAtDepth_Issue37Finding2) {
  // A view 3·10⁻⁷ wide about x = −0.15 (Home, then + about 45 times).
  const AxisLabels deep = axisLabelsFor(-0.15000015, -0.14999985);
  ASSERT_TRUE(deep.offset);
  EXPECT_EQ(deep.exponent, -7);
  EXPECT_DOUBLE_EQ(deep.reference, -0.15);
  EXPECT_EQ(axisTickLabel(deep, -0.15), "0");
  EXPECT_EQ(axisTickLabel(deep, -0.1500001), "-1");
  EXPECT_EQ(axisTickLabel(deep, -0.14999995), "0.5");
  EXPECT_EQ(axisTitleSuffix(deep), " − (−0.15) [×10⁻⁷]");
  // Deeper, off a round centre: the reference keeps the digits above the unit.
  const AxisLabels deeper = axisLabelsFor(-0.15000000323, -0.14999999923);
  ASSERT_TRUE(deeper.offset);
  EXPECT_EQ(deeper.exponent, -9);
  EXPECT_EQ(axisTitleSuffix(deeper), " − (−0.150000001) [×10⁻⁹]");
  EXPECT_EQ(axisTickLabel(deeper, -0.150000002), "-1");
}

TEST(AxisLabels, TicksAreRoundAndEvenAtTheDeepestView_Issue53Finding7) {
  // The deepest view of the paper's box (1024 grid cells, 2.96·10⁻¹³ wide) about x = −0.3162: Qwt's own ticks began
  // at the view's edge ("−1.268, −0.7676, …", the last interval 0.456).
  const double lo = -0.31622776601683794 - 1.48e-13, hi = -0.31622776601683794 + 1.48e-13;
  const AxisLabels labels = axisLabelsFor(lo, hi);
  ASSERT_TRUE(labels.offset);
  const AxisTicks ticks = axisTicks(labels, lo, hi);
  ASSERT_GE(ticks.major.size(), 3u);
  const double step = ticks.major[1] - ticks.major[0];
  double previous = std::stod(axisTickLabel(labels, ticks.major[0]));
  const double labelStep = std::stod(axisTickLabel(labels, ticks.major[1])) - previous;
  EXPECT_DOUBLE_EQ(labelStep, 0.5);  // 3·10⁻¹³ / 8 → a step of 0.5·10⁻¹³
  for (std::size_t i = 0; i < ticks.major.size(); ++i) {
    EXPECT_GE(ticks.major[i], lo);
    EXPECT_LE(ticks.major[i], hi);
    if (i > 0) {
      EXPECT_NEAR(ticks.major[i] - ticks.major[i - 1], step, 1e-2 * step);
    }
    const double label = std::stod(axisTickLabel(labels, ticks.major[i]));
    EXPECT_NEAR(label / labelStep, std::round(label / labelStep), 1e-12) << axisTickLabel(labels, ticks.major[i]);
    if (i > 0) {
      EXPECT_NEAR(label - previous, labelStep, 1e-12);
    }
    previous = label;
  }
  EXPECT_FALSE(ticks.minor.empty());
  for (const double m : ticks.minor)
    for (const double t : ticks.major) EXPECT_GT(std::fabs(m - t), 0.1 * step);
  // A plain axis: multiples of a round step from 0, as Qwt gives them.
  const AxisTicks whole = axisTicks(axisLabelsFor(-0.8, 0.5), -0.8, 0.5);
  ASSERT_EQ(whole.major.size(), 7u);
  EXPECT_DOUBLE_EQ(whole.major.front(), -0.8);
  EXPECT_NEAR(whole.major.back(), 0.4, 1e-15);
  EXPECT_TRUE(axisTicks(labels, 1, 1).major.empty());
}

}  // namespace
}  // namespace archipelago
