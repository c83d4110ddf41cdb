#include "core/measures/IndicatorMap.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/limits/Limits.hpp"
#include "core/view/Viewport.hpp"  // orbitSeed: the portraits' seed of a cell

namespace archipelago {

namespace {
constexpr std::uint32_t kMaxPasses = 12;

/// The stride of pass k of `passes`.
int strideOf(std::uint32_t pass, std::uint32_t passes) { return 1 << (passes - 1 - pass); }

/// Whether pixel (col, row) belongs to pass k (computed there for the first time).
bool inPass(int col, int row, std::uint32_t pass, std::uint32_t passes) {
  const int s = strideOf(pass, passes);
  if (col % s != 0 || row % s != 0) return false;
  return pass == 0 || col % (2 * s) != 0 || row % (2 * s) != 0;
}

/// For every pixel, the index of the computed pixel that stands for it (itself when computed), or −1.
template <class Value>
std::vector<Value> fill(const IndicatorRaster& r, const std::vector<Value>& v, Value none) {
  std::vector<Value> out(v.size(), none);
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      for (int s = 1; s <= (1 << (kMaxPasses - 1)); s *= 2) {
        const std::size_t i = static_cast<std::size_t>(row - row % s) * static_cast<std::size_t>(r.width) +
                              static_cast<std::size_t>(col - col % s);
        if (r.verdicts[i] != OrbitVerdict::NotComputed) {
          out[static_cast<std::size_t>(row) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(col)] = v[i];
          break;
        }
      }
    }
  return out;
}
IndicatorProgress progressOf(const IndicatorRaster& raster, std::uint32_t pass, std::uint32_t passes,
                             const IndicatorRaster* snapshot) {
  IndicatorProgress p;
  p.pixelsDone = raster.pixelsDone;
  p.pixelsTotal = raster.pixelCount();
  p.pass = pass;
  p.passes = passes;
  p.stride = static_cast<std::uint32_t>(strideOf(pass, passes));
  p.snapshot = snapshot;
  p.final = snapshot && pass + 1 == passes;
  return p;
}
}  // namespace

std::vector<double> IndicatorRaster::filled() const { return fill(*this, values, std::nan("")); }

std::vector<OrbitVerdict> IndicatorRaster::filledVerdicts() const {
  return fill(*this, verdicts, OrbitVerdict::NotComputed);
}

std::size_t IndicatorRaster::count(OrbitVerdict v) const noexcept {
  return static_cast<std::size_t>(std::count(verdicts.begin(), verdicts.end(), v));
}

std::optional<std::string> validationError(const IndicatorRequest& r) {
  if (auto e = validationError(r.measure)) return e;
  if (auto e = rasterSizeError(r.width, r.height, limits::kIndicatorPixels)) return e;
  if (auto e = rangeError("passes", r.passes, 1, kMaxPasses)) return e;
  if (auto e = rangeError("roundPixels", r.roundPixels, 1, 1u << 26)) return e;
  if (auto e = threadsError(r.threads)) return e;
  return std::nullopt;
}

UnitState indicatorPixelStart(const Viewport& view, int width, int height, int col, int row) noexcept {
  return orbitSeed(view, static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height),
                   static_cast<std::uint32_t>(col), static_cast<std::uint32_t>(height - 1 - row));
}

IndicatorResult computeIndicatorMap(const IndicatorRequest& r, const IndicatorObserver& observer, std::stop_token stop) {
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const auto begin = std::chrono::steady_clock::now();
  const OrbitMeasurer measurer(r.measure);
  IndicatorResult result;
  IndicatorRaster& raster = result.raster;
  raster.width = r.width;
  raster.height = r.height;
  raster.kind = r.measure.kind;
  raster.values.assign(raster.pixelCount(), std::nan(""));
  raster.digits.assign(raster.pixelCount(), std::nan(""));
  raster.verdicts.assign(raster.pixelCount(), OrbitVerdict::NotComputed);

  std::vector<std::size_t> pixels;
  std::vector<UnitState> starts;
  std::vector<OrbitMeasure> measured;
  for (std::uint32_t pass = 0; pass < r.passes && !result.cancelled; ++pass) {
    pixels.clear();
    for (int row = 0; row < r.height; ++row)
      for (int col = 0; col < r.width; ++col)
        if (inPass(col, row, pass, r.passes))
          pixels.push_back(static_cast<std::size_t>(row) * static_cast<std::size_t>(r.width) + static_cast<std::size_t>(col));
    for (std::size_t first = 0; first < pixels.size(); first += r.roundPixels) {
      const std::size_t n = std::min<std::size_t>(r.roundPixels, pixels.size() - first);
      starts.resize(n);
      measured.assign(n, OrbitMeasure{});
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t p = pixels[first + i];
        starts[i] = indicatorPixelStart(r.view, r.width, r.height, static_cast<int>(p % static_cast<std::size_t>(r.width)),
                                        static_cast<int>(p / static_cast<std::size_t>(r.width)));
      }
      const bool complete = measurer.measure(starts, measured, stop, r.threads);
      for (std::size_t i = 0; i < n; ++i) {
        if (measured[i].verdict == OrbitVerdict::NotComputed) continue;
        const std::size_t p = pixels[first + i];
        raster.values[p] = measured[i].value;
        raster.digits[p] = measured[i].digits;
        raster.verdicts[p] = measured[i].verdict;
        ++raster.pixelsDone;
      }
      if (!complete) {
        result.cancelled = true;
        break;
      }
      if (observer && first + n < pixels.size()) observer(progressOf(raster, pass, r.passes, nullptr));
    }
    if (result.cancelled) break;
    result.passesDone = pass + 1;
    if (observer) observer(progressOf(raster, pass, r.passes, &raster));
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  return result;
}

}  // namespace archipelago
