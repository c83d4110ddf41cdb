#include "core/portrait/ColourMap.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace archipelago {

namespace {
// Polynomial fits of matplotlib's maps (coefficients of t^0 … t^6 per channel; Matt Zucker, CC0).
constexpr double kInferno[7][3] = {
    {0.0002189403691192265, 0.001651004631001012, -0.01948089843709184},
    {0.1065134194856116, 0.5639564367884091, 3.932712388889277},
    {11.60249308247187, -3.972853965665698, -15.9423941062914},
    {-41.70399613139459, 17.43639888205313, 44.35414519872813},
    {77.162935699427, -33.40235894210092, -81.80730925738993},
    {-71.31942824499214, 32.62606426397723, 73.20951985803202},
    {25.13112622477341, -12.24266895238567, -23.07032500287172}};
constexpr double kViridis[7][3] = {
    {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
    {0.1050930431085774, 1.404613529898575, 1.384590162594685},
    {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
    {-4.634230498983486, -5.799100973351585, -19.33244095627987},
    {6.228269936347081, 14.17993336680509, 56.69055260068105},
    {4.776384997670288, -13.74514537774601, -65.35303263337234},
    {-5.435455855934631, 4.645852612178535, 26.3124352495832}};

std::uint8_t toByte(double v) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

Rgb polynomial(const double (&c)[7][3], double t) {
  double v[3];
  for (int ch = 0; ch < 3; ++ch) {
    double s = 0;
    for (int k = 6; k >= 0; --k) s = s * t + c[k][ch];
    v[ch] = s;
  }
  return {toByte(v[0]), toByte(v[1]), toByte(v[2])};
}
}  // namespace

std::string_view toString(ColourMapName name) noexcept {
  switch (name) {
    case ColourMapName::Inferno: return "inferno";
    case ColourMapName::Viridis: return "viridis";
    case ColourMapName::Grey: return "grey";
  }
  return "unknown";
}

std::optional<ColourMapName> parseColourMap(std::string_view name) noexcept {
  for (ColourMapName m : allColourMaps())
    if (name == toString(m)) return m;
  return std::nullopt;
}

std::vector<ColourMapName> allColourMaps() { return {ColourMapName::Inferno, ColourMapName::Viridis, ColourMapName::Grey}; }

ColourMap::ColourMap(ColourMapName name) : name_(name) {
  for (std::size_t i = 0; i < table_.size(); ++i) {
    const double t = static_cast<double>(i) / 255.0;
    switch (name) {
      case ColourMapName::Inferno: table_[i] = polynomial(kInferno, t); break;
      case ColourMapName::Viridis: table_[i] = polynomial(kViridis, t); break;
      case ColourMapName::Grey: {
        const auto v = static_cast<std::uint8_t>(255 - i);  // dark = many visits, as in the paper's figures
        table_[i] = {v, v, v};
        break;
      }
    }
  }
}

Rgb ColourMap::at(double t) const noexcept {
  if (!(t > 0)) return table_[0];
  if (t >= 1) return table_[255];
  return table_[static_cast<std::size_t>(std::lround(t * 255.0))];
}

Rgb orbitColour(std::uint32_t label) noexcept {
  // Golden-ratio steps in hue give neighbouring labels well separated colours; full saturation and value.
  const double golden = 0.6180339887498949;
  const double h = std::fmod(static_cast<double>(label) * golden, 1.0) * 6.0;
  const double f = h - std::floor(h);
  const double s = 0.75, v = 1.0;
  const double p = v * (1 - s), q = v * (1 - s * f), u = v * (1 - s * (1 - f));
  double r = v, g = u, b = p;
  switch (static_cast<int>(h)) {
    case 0: r = v, g = u, b = p; break;
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = u; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = u, g = p, b = v; break;
    default: r = v, g = p, b = q; break;
  }
  return {toByte(r), toByte(g), toByte(b)};
}

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
