// The sizes of an exported portrait image (ExportSizing.hpp): the image cut to the view's aspect, the raster for
// its canvas and its points.
#include <gtest/gtest.h>

#include "core/portrait/ExportSizing.hpp"

namespace archipelago {
namespace {

TEST(ExportSizing, TheImageLosesTheCanvasExcessWidthOrHeight) {
  // A 1000 × 800 image whose canvas is 900 × 700 (axes take 100 pixels each way).
  // A square view: the canvas is 200 too wide, the image loses 200 of its width.
  EXPECT_EQ(exportImageSize({1000, 800}, 900, 700, 1.0), (PixelSize{800, 800}));
  // A view twice as wide as high: the canvas should be 900 × 450, the image loses 250 of its height.
  EXPECT_EQ(exportImageSize({1000, 800}, 900, 700, 2.0), (PixelSize{1000, 550}));
  // Already the view's aspect: unchanged.
  EXPECT_EQ(exportImageSize({1000, 800}, 900, 700, 900.0 / 700.0), (PixelSize{1000, 800}));
  // Rounded to the nearest pixel.
  EXPECT_EQ(exportImageSize({1000, 800}, 900.4, 700, 1.0), (PixelSize{800, 800}));
  EXPECT_EQ(exportImageSize({1000, 800}, 900.6, 700, 1.0), (PixelSize{799, 800}));
  // No canvas (an image too small for the axes) or no aspect: as requested.
  EXPECT_EQ(exportImageSize({50, 40}, 0, 10, 1.0), (PixelSize{50, 40}));
  EXPECT_EQ(exportImageSize({50, 40}, 10, -1, 1.0), (PixelSize{50, 40}));
  EXPECT_EQ(exportImageSize({50, 40}, 10, 10, 0.0), (PixelSize{50, 40}));
}

TEST(ExportSizing, TheRasterIsTheCanvasRoundedAndClamped) {
  EXPECT_EQ(exportRasterSize(800.4, 599.6), (PixelSize{800, 600}));
  EXPECT_EQ(exportRasterSize(3, 0), (PixelSize{kMinExportRaster, kMinExportRaster}));
  EXPECT_EQ(exportRasterSize(10000, 9000.5), (PixelSize{kMaxExportRaster, kMaxExportRaster}));
}

TEST(ExportSizing, ThePointsFollowTheScreensDensityWithinBounds) {
  // 2^30 points on a 1000 × 1000 screen raster: 1073.74 a pixel; a 100 × 100 export gets 1.07e7.
  EXPECT_EQ(exportPoints(std::uint64_t{1} << 30, 1'000'000, {100, 100}),
            static_cast<std::uint64_t>(static_cast<double>(std::uint64_t{1} << 30) / 1e6 * 100 * 100));
  // Few points so far, or no screen raster yet: the floor.
  EXPECT_EQ(exportPoints(0, 0, {16, 16}), static_cast<std::uint64_t>(kMinExportPoints));
  EXPECT_EQ(exportPoints(1000, 1'000'000, {4000, 4000}), static_cast<std::uint64_t>(kMinExportPoints));
  // A long accumulation: the ceiling (fewer points a pixel than the screen, not more).
  EXPECT_EQ(exportPoints(std::uint64_t{1} << 40, 1'000'000, {4000, 4000}), static_cast<std::uint64_t>(kMaxExportPoints));
  // No screen raster counts as one pixel.
  EXPECT_EQ(exportPoints(std::uint64_t{1} << 24, 0, {16, 16}), static_cast<std::uint64_t>(kMaxExportPoints));
}

}  // namespace
}  // namespace archipelago
