#pragma once
/// \file ExportSizing.hpp
/// \brief The sizes of an exported portrait image (the GUI's PNG export): the image cut to the view's aspect, the
/// raster rendered anew for its canvas, and the points that raster gets.  The widget measures its plot's layout
/// (the canvas an image of a size leaves inside the axes) and asks these; it decides nothing itself
/// (docs/design.md, "Front ends fill, call and format").

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace archipelago {

/// A size in pixels.
struct PixelSize {
  int width = 0;
  int height = 0;
  friend bool operator==(const PixelSize&, const PixelSize&) = default;
};

/// The export's raster: its canvas rounded, each side in [kMinExportRaster, kMaxExportRaster].
inline constexpr int kMinExportRaster = 16;
inline constexpr int kMaxExportRaster = 8192;
/// The export's points: as many per pixel as the screen's raster has so far, in [kMinExportPoints,
/// kMaxExportPoints] in all (about a second with two cores: an export after a long accumulation has fewer points
/// per pixel than the screen, not more).
inline constexpr double kMinExportPoints = 0x1p22;
inline constexpr double kMaxExportPoints = 0x1p27;

/// With equal aspect, the image of `requested` size cut so that its canvas (canvasWidth × canvasHeight pixels in
/// the requested image) takes the view's aspect (width/height of the view): the excess width or height of the
/// canvas is taken off the image.  An empty canvas or an aspect that is not positive leaves the size as requested.
[[nodiscard]] inline PixelSize exportImageSize(PixelSize requested, double canvasWidth, double canvasHeight,
                                               double viewAspect) {
  if (!(canvasWidth > 0 && canvasHeight > 0 && viewAspect > 0)) return requested;
  PixelSize size = requested;
  if (canvasWidth > canvasHeight * viewAspect)
    size.width = static_cast<int>(std::lround(size.width - (canvasWidth - canvasHeight * viewAspect)));
  else
    size.height = static_cast<int>(std::lround(size.height - (canvasHeight - canvasWidth / viewAspect)));
  return size;
}

/// The raster rendered for a canvas of canvasWidth × canvasHeight pixels (rounded and clamped as above).
[[nodiscard]] inline PixelSize exportRasterSize(double canvasWidth, double canvasHeight) {
  return {std::clamp(static_cast<int>(std::lround(canvasWidth)), kMinExportRaster, kMaxExportRaster),
          std::clamp(static_cast<int>(std::lround(canvasHeight)), kMinExportRaster, kMaxExportRaster)};
}

/// The points of the export's raster: pointsSoFar/screenPixels per pixel (screenPixels 0: no screen raster yet,
/// counted as one pixel; pointsSoFar 0 counted as one point), times its pixels, clamped as above.
[[nodiscard]] inline std::uint64_t exportPoints(std::uint64_t pointsSoFar, std::uint64_t screenPixels,
                                                PixelSize raster) {
  const double perPixel = static_cast<double>(std::max<std::uint64_t>(pointsSoFar, 1)) /
                          std::max(static_cast<double>(screenPixels), 1.0);
  return static_cast<std::uint64_t>(std::clamp(perPixel * raster.width * raster.height, kMinExportPoints,
                                               kMaxExportPoints));
}

}  // namespace archipelago
