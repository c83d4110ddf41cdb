#pragma once
/// \file IndicatorMap.hpp
/// \brief A chaos-indicator map of a view: one orbit per pixel, its measure (OrbitMeasures.hpp) as the value.
///
/// One entry point, computeIndicatorMap(request, observer, stop): an immutable request in, a raster out, a
/// progress observer and a stop token (the shape of PortraitRenderer.hpp, which the GUI and the CLI both use).
///
/// The orbit of pixel (col, row) starts at the centre of the pixel's cell, exactly where a portrait in Orbits
/// mode seeds it (orbitSeed(view, width, height, col, height − 1 − row): row 0 is the top of the view), rounded
/// to the 52-bit grid; its value is OrbitMeasures.hpp's for the request's kind and iterations.
///
/// Progressive refinement: pass k = 0 … passes − 1 computes the pixels whose column and row are multiples of
/// 2^(passes − 1 − k) and were not computed before, so the first pass is a coarse raster (1/4^(passes−1) of the
/// pixels) that arrives quickly and each pass fills in between; every pixel is computed once, so the final
/// raster does not depend on `passes`.  After each pass the observer gets a snapshot; IndicatorRaster::filled()
/// shows a partial raster by giving each pixel not yet computed the value of the computed pixel at the top-left
/// corner of its block.  Within a pass the pixels go in rounds of about roundPixels; the observer hears of
/// progress after each round, and the stop token is checked between chunks of 2^14 steps of every group of
/// orbits (OrbitMeasurer), so after a stop request each thread finishes at most one chunk.
///
/// Parallel over groups of pixels (parallel/ParallelFor.hpp); every pixel is computed by one thread from its own
/// start, so the raster does not depend on the number of threads, the path or the passes.

#include <cstdint>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/measures/OrbitMeasures.hpp"
#include "core/view/Viewport.hpp"

namespace archipelago {

/// Everything that defines an indicator map, as plain values.
struct IndicatorRequest {
  MeasureSettings measure;         ///< map, kind, iterations, threshold, kernel
  Viewport view;                   ///< default: the whole box
  int width = 256;                 ///< pixels, 1 … limits::kRasterSide
  int height = 256;                ///< pixels, 1 … limits::kRasterSide; width·height ≤ limits::kIndicatorPixels
  std::uint32_t passes = 4;        ///< progressive refinement, 1 … 12
  std::uint32_t roundPixels = 1u << 14;  ///< pixels per progress report within a pass, 1 … 2^26
  int threads = 0;                 ///< 0: OpenMP's default
};

/// The first violated rule, naming the field, or nothing.
[[nodiscard]] std::optional<std::string> validationError(const IndicatorRequest& r);

/// The pixels: row-major, row 0 the top of the view (largest y), column 0 its left edge (as PortraitRaster).
struct IndicatorRaster {
  int width = 0;
  int height = 0;
  IndicatorKind kind = IndicatorKind::Dig;
  std::vector<double> values;         ///< OrbitMeasure::value (NaN: no number, or not computed yet)
  std::vector<double> digits;         ///< OrbitMeasure::digits (Dig, Rotation; NaN otherwise)
  std::vector<OrbitVerdict> verdicts;
  std::uint64_t pixelsDone = 0;

  [[nodiscard]] std::size_t pixelCount() const noexcept {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  /// values with every pixel not yet computed given the value of the computed pixel at the top-left corner of
  /// its block (the coarse pixels of the passes so far); pixels of no computed block stay NaN.
  [[nodiscard]] std::vector<double> filled() const;
  /// The same for verdicts.
  [[nodiscard]] std::vector<OrbitVerdict> filledVerdicts() const;
  /// How many pixels have verdict v.
  [[nodiscard]] std::size_t count(OrbitVerdict v) const noexcept;
};

/// Progress, reported on the calling thread after every round (never inside a parallel region).
struct IndicatorProgress {
  std::uint64_t pixelsDone = 0;
  std::uint64_t pixelsTotal = 0;
  std::uint32_t pass = 0;    ///< the pass in progress (0-based), or the one just finished
  std::uint32_t passes = 0;
  std::uint32_t stride = 1;  ///< of that pass: pixels whose column and row are multiples of it
  const IndicatorRaster* snapshot = nullptr;  ///< non-null after a pass ended: the raster so far
  bool final = false;                         ///< the last snapshot
};

using IndicatorObserver = std::function<void(const IndicatorProgress&)>;

struct IndicatorResult {
  IndicatorRaster raster;
  bool cancelled = false;       ///< stopped before the last pass ended
  std::uint32_t passesDone = 0;
  double seconds = 0;           ///< wall time of the computation
};

/// Computes the map; throws std::invalid_argument when validationError(request) is set.  On a stop request,
/// returns at once (within one chunk per thread) the raster so far, cancelled set.
[[nodiscard]] IndicatorResult computeIndicatorMap(const IndicatorRequest& request, const IndicatorObserver& observer = {},
                                                  std::stop_token stop = {});

/// The start of pixel (col, row) (row 0 at the top), as computeIndicatorMap starts it.
[[nodiscard]] UnitState indicatorPixelStart(const Viewport& view, int width, int height, int col, int row) noexcept;

}  // namespace archipelago
