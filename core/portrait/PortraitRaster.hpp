#pragma once
/// \file PortraitRaster.hpp
/// \brief The pixels of a phase portrait: integer counts accumulated from orbits of the exact map.
///
/// Layout: row-major, `width` columns by `height` rows; row 0 is the TOP of the view (largest y) and column
/// 0 its left edge (smallest x), as in an image and as NumPy's imshow(origin="upper") shows it.  Pixel
/// (col, row) covers x in [x0 + col·Δx, x0 + (col+1)·Δx) and y in (y1 − (row+1)·Δy, y1 − row·Δy].
/// All accumulators are integers, so rasters merge exactly and the result does not depend on the number of
/// threads or the order in which orbits were processed.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <optional>
#include <vector>

namespace archipelago {

/// What a portrait shows.
enum class PortraitMode {
  Density,     ///< (a) visits of long orbits of the chaotic sea of Q*
  Orbits,      ///< (b) orbits from a grid of seeds inside the view (KAM curves of the islands), one label each
  Stickiness,  ///< (c) mean length of the trapped segments (§3) passing through each pixel
};

[[nodiscard]] std::string_view toString(PortraitMode mode) noexcept;
/// "density", "orbits" or "stickiness"; nothing for any other name.
[[nodiscard]] std::optional<PortraitMode> parsePortraitMode(std::string_view name) noexcept;

/// Orbits mode: below this share of the iterated points inside the view, the seeds' orbits leave it (a deep view of
/// the sea or of a sticky layer, issue 53 finding 22): ten times the budget visits at most ten times as few pixels
/// more, while an indicator map (one orbit from every pixel) colours them all.
inline constexpr double kOrbitsLeaveViewFraction = 0.01;

struct PortraitRaster {
  int width = 0;
  int height = 0;
  PortraitMode mode = PortraitMode::Density;
  /// Visits per pixel.  In Stickiness mode only the points of completed segments count.
  std::vector<std::uint64_t> counts;
  /// Orbits mode: 1 + the smallest index of the seeds whose orbit visits the pixel, 0 for none (else empty).
  std::vector<std::uint32_t> labels;
  /// Orbits mode: for each seed, 1 when its orbit has wrapped around the torus (a chaotic-sea orbit, or one
  /// in a spurious accelerator-mode island of Q*, §2), 0 for an orbit that stayed inside the box (an island of
  /// Q).  Drawing uses it to paint the sea in one colour instead of a noise of labels.
  std::vector<std::uint8_t> orbitWrapped;
  /// Stickiness mode: Σ over the visits of the length, in steps of N⁻¹, of the segment making it (else empty).
  std::vector<std::uint64_t> lengthSums;
  std::uint64_t pointsIterated = 0;  ///< steps of the map done, all orbits together
  std::uint64_t pointsBinned = 0;    ///< of those, the points that fell inside the view and were counted

  [[nodiscard]] std::size_t pixelCount() const noexcept {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  [[nodiscard]] std::size_t index(int col, int row) const noexcept {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(col);
  }
  /// Stickiness: the mean segment length (steps) over the visits of pixel i; 0 when it has none.
  [[nodiscard]] double meanSegmentLength(std::size_t i) const noexcept {
    return i < lengthSums.size() && counts[i] > 0
               ? static_cast<double>(lengthSums[i]) / static_cast<double>(counts[i])
               : 0.0;
  }
  /// meanSegmentLength() of every pixel.
  [[nodiscard]] std::vector<double> meanSegmentLengths() const;
  /// Pixels with at least one visit.
  [[nodiscard]] std::size_t nonEmptyPixels() const noexcept;
  /// Orbits mode: fewer than kOrbitsLeaveViewFraction of the points iterated fell inside the view.
  [[nodiscard]] bool orbitsLeaveView() const noexcept {
    return mode == PortraitMode::Orbits && pointsIterated > 0 &&
           static_cast<double>(pointsBinned) < kOrbitsLeaveViewFraction * static_cast<double>(pointsIterated);
  }
  /// Orbits mode: every seed's orbit wrapped around the torus, i.e. the view's seeds all lie in the sea (or in
  /// accelerator modes) and no island orbit was drawn (e.g. K = 0, where Q has no island; fig. 3b).
  [[nodiscard]] bool allOrbitsWrapped() const noexcept {
    if (orbitWrapped.empty()) return false;
    for (std::uint8_t w : orbitWrapped)
      if (w == 0) return false;
    return true;
  }
};

}  // namespace archipelago
