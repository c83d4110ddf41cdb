#include "core/portrait/PortraitColours.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace archipelago {

namespace {
/// The Density scale, in log10 visits: centred on the median visited pixel, as wide on each side as the farther
/// of the 5% and 99.5% quantiles.  The sea is nearly uniform, so between robust extremes (0.5% … 99.9%, as
/// before) its bulk sat at the top of the scale and the portrait was almost all saturated yellow (issue 25,
/// finding 14); centred, the bulk spans the middle of the map, the stickier pixels rise towards its top and the
/// few grazed ones at the islands' edges fall towards its bottom.  (0, 0) when no pixel was visited; lo = hi when
/// every visited pixel has the same count.
std::pair<double, double> logRange(std::vector<std::uint64_t>& visited) {
  if (visited.empty()) return {0.0, 0.0};
  auto quantile = [&](double f) {
    auto it = visited.begin() + static_cast<std::ptrdiff_t>(f * static_cast<double>(visited.size() - 1));
    std::nth_element(visited.begin(), it, visited.end());
    return std::log10(static_cast<double>(*it));
  };
  const double median = quantile(0.5);
  const double halfWidth = std::max(median - quantile(0.05), quantile(0.995) - median);
  return {median - halfWidth, median + halfWidth};
}
}  // namespace

RasterImage colourize(const PortraitRaster& raster, ColourMapName name) {
  const ColourMap map(name);
  RasterImage image;
  image.width = raster.width;
  image.height = raster.height;
  const std::size_t n = raster.pixelCount();
  image.rgb.assign(3 * n, 0);
  auto put = [&](std::size_t i, Rgb c) {
    image.rgb[3 * i] = c.r;
    image.rgb[3 * i + 1] = c.g;
    image.rgb[3 * i + 2] = c.b;
  };
  auto scaled = [](double t) { return kLowest + (1 - kLowest) * t; };
  switch (raster.mode) {
    case PortraitMode::Density: {
      // Log scale centred on the median visited pixel (logRange above), clamped at its ends.
      std::vector<std::uint64_t> visited;
      for (std::size_t i = 0; i < n; ++i)
        if (raster.counts[i] > 0) visited.push_back(raster.counts[i]);
      const auto [lo, hi] = logRange(visited);
      image.quantity = "log10(visits)";
      image.scaleMin = lo;
      image.scaleMax = hi;
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t c = raster.counts[i];
        put(i, c == 0 ? map.at(0)
                      : map.at(scaled(hi > lo ? std::clamp((std::log10(static_cast<double>(c)) - lo) / (hi - lo), 0.0, 1.0)
                                              : 1)));
      }
      break;
    }
    case PortraitMode::Stickiness: {
      double lo = INFINITY, hi = -INFINITY;
      for (std::size_t i = 0; i < n; ++i) {
        if (raster.counts[i] == 0) continue;
        const double l = std::log10(raster.meanSegmentLength(i));
        lo = std::min(lo, l);
        hi = std::max(hi, l);
      }
      image.quantity = "log10(mean segment length / steps)";
      if (lo <= hi) image.scaleMin = lo, image.scaleMax = hi;
      for (std::size_t i = 0; i < n; ++i) {
        if (raster.counts[i] == 0) {
          put(i, map.at(0));
          continue;
        }
        const double l = std::log10(raster.meanSegmentLength(i));
        put(i, map.at(scaled(hi > lo ? (l - lo) / (hi - lo) : 1)));
      }
      break;
    }
    case PortraitMode::Orbits: {
      // Island orbits get their own hues; the sea (orbits that wrapped) is shaded by its visits on a log
      // scale through the dim part of the colour map, so that it stays behind the islands' hues and still
      // shows where orbits linger.  At K = 0 every seed wraps (no island of Q, fig. 3b): one flat sea colour
      // made that portrait look blank; the shading shows the sticky region about the parabolic point.
      image.quantity = "orbit";
      const Rgb background{16, 16, 24};
      auto wrappedAt = [&](std::uint32_t label) {
        return label > 0 && label <= raster.orbitWrapped.size() && raster.orbitWrapped[label - 1] != 0;
      };
      std::vector<std::uint64_t> visited;
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t label = i < raster.labels.size() ? raster.labels[i] : 0;
        if (wrappedAt(label) && raster.counts[i] > 0) visited.push_back(raster.counts[i]);
      }
      // The scale spans at least a decade below the median and half a decade above it, so that the
      // counting noise of a young raster (±20 % at 25 visits a pixel) stays a small part of it while the
      // regions where orbits linger (several times the median) stand out.
      double lo = 0, hi = 0;
      if (!visited.empty()) {
        auto middle = visited.begin() + static_cast<std::ptrdiff_t>(visited.size() / 2);
        std::nth_element(visited.begin(), middle, visited.end());
        const double median = std::log10(static_cast<double>(*middle));
        const auto [qlo, qhi] = logRange(visited);
        lo = std::min(qlo, median - 1.0);
        hi = std::max(qhi, median + 0.5);
      }
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t label = i < raster.labels.size() ? raster.labels[i] : 0;
        if (label == 0) {
          put(i, background);
        } else if (wrappedAt(label)) {
          const double c = static_cast<double>(std::max<std::uint64_t>(raster.counts[i], 1));
          const double t = hi > lo ? std::clamp((std::log10(c) - lo) / (hi - lo), 0.0, 1.0) : 0.5;
          put(i, map.at(kSeaLowest + (kSeaHighest - kSeaLowest) * t));
        } else {
          put(i, orbitColour(label));
        }
      }
      break;
    }
  }
  return image;
}

}  // namespace archipelago
