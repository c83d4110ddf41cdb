// core/scan/ScanBox: the one reader of K lists (issue #24: the CLI and the GUI once parsed them twice) and the
// one colour scale of the local exponent's heat map (the CLI's PNG and the dialog once differed).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "core/scan/ScanBox.hpp"
#include "core/scan/ScanHeatMap.hpp"

namespace archipelago {
namespace {

TEST(ScanBox, OneKListReaderForEveryFrontEnd) {
  EXPECT_EQ(parseScanValues("0.05:1.3:0.05").size(), 26u);  // the paper's 26 K (§5)
  EXPECT_EQ(parseScanValues(kPaperScanValuesText), parseScanValues("0.05:1.3:0.05"));
  EXPECT_EQ(parseScanValues(" 0.1 , 0.2,0.3 "), (std::vector<double>{0.1, 0.2, 0.3}));
  for (const char* bad : {"", " ", "0.1,,0.2", "0.1,abc", "nan", "0.1:0.2", "0.1:0.2:0.05:1", "0.1,0.1", "-0.1", "5",
                          "0.1.2", "0.1;0.2", "inf", "0.2:0.1:0.05"})
    EXPECT_THROW((void)parseScanValues(bad), std::invalid_argument) << '"' << bad << '"';
  try {
    (void)parseScanValues("0.1," + std::string(1000, 'x'));
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_LT(std::string(e.what()).size(), 100u) << "a long word is quoted short";
  }
}

TEST(ScanHeatMap, OneColourScale) {
  EXPECT_EQ(heatMapColour(0), (Rgb{255, 255, 255}));
  EXPECT_EQ(heatMapColour(kHeatMapTop / 2), (Rgb{226, 128, 64}));
  EXPECT_EQ(heatMapColour(kHeatMapTop), (Rgb{140, 0, 0}));
  EXPECT_EQ(heatMapColour(10), heatMapColour(kHeatMapTop));  // clipped at the top
  EXPECT_EQ(heatMapColour(-1), heatMapColour(0));
  EXPECT_EQ(heatMapColour(std::numeric_limits<double>::quiet_NaN()), kHeatMapNoData);
  // Linear between the stops: a quarter of the way is the mean of white and orange.
  EXPECT_EQ(heatMapColour(kHeatMapTop / 4), (Rgb{241, 192, 160}));
  // Monotone: darker as the exponent grows.
  int previous = 3 * 255 + 1;
  for (double v = 0; v <= kHeatMapTop; v += 0.01) {
    const Rgb c = heatMapColour(v);
    const int sum = c.r + c.g + c.b;
    EXPECT_LE(sum, previous);
    previous = sum;
  }
}

}  // namespace
}  // namespace archipelago
