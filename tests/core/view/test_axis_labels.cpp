// The portrait's axis labels at any depth (core/view/AxisLabels.hpp; issue 37, findings 2 and 18).
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace archipelago
