#include "core/scan/ScanHeatMap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/io/Png.hpp"
#include "core/provenance/Provenance.hpp"

namespace archipelago {

ScanHeatMap localExponentHeatMap(const std::vector<ScanRunSummary>& runs) {
  ScanHeatMap map;
  std::vector<double> taus;
  for (const ScanRunSummary& r : runs) {
    map.K.push_back(r.point.K);
    taus.insert(taus.end(), r.statistics.localExponent.x.begin(), r.statistics.localExponent.x.end());
  }
  std::sort(taus.begin(), taus.end());
  taus.erase(std::unique(taus.begin(), taus.end()), taus.end());
  map.tau = taus;
  map.value.assign(map.tau.size() * map.K.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t c = 0; c < runs.size(); ++c) {
    const Series& e = runs[c].statistics.localExponent;
    for (std::size_t i = 0; i < e.x.size(); ++i) {
      const auto row = static_cast<std::size_t>(std::lower_bound(taus.begin(), taus.end(), e.x[i]) - taus.begin());
      map.value[row * map.K.size() + c] = e.value[i];
    }
  }
  return map;
}

std::span<const HeatMapStop> heatMapStops() noexcept {
  static constexpr std::array<HeatMapStop, 3> stops{{{0.0, {255, 255, 255}}, {0.5, {226, 128, 64}}, {1.0, {140, 0, 0}}}};
  return stops;
}

Rgb heatMapColour(double value, double top) noexcept {
  if (std::isnan(value)) return kHeatMapNoData;
  const double s = std::clamp(value / top, 0.0, 1.0);
  const auto stops = heatMapStops();
  std::size_t i = 1;
  while (i + 1 < stops.size() && s > stops[i].position) ++i;
  const HeatMapStop& a = stops[i - 1];
  const HeatMapStop& b = stops[i];
  const double w = (s - a.position) / (b.position - a.position);
  const auto mix = [w](std::uint8_t x, std::uint8_t y) {
    return static_cast<std::uint8_t>(std::lround((1 - w) * x + w * y));
  };
  return {mix(a.colour.r, b.colour.r), mix(a.colour.g, b.colour.g), mix(a.colour.b, b.colour.b)};
}

void writeHeatMapPng(const std::filesystem::path& path, const ScanHeatMap& map, const std::string& image) {
  if (map.K.empty() || map.tau.empty() || !(map.tau.front() > 0)) return;
  constexpr int kRowsPerDecade = 30, cellH = 4;
  const double lo = std::log10(map.tau.front()), hi = std::log10(map.tau.back());
  const int rows = static_cast<int>(std::ceil((hi - lo) * kRowsPerDecade)) + 1;
  const int cellW = std::max(4, 480 / static_cast<int>(map.K.size()));
  const int width = cellW * static_cast<int>(map.K.size()), height = cellH * rows;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    const double logTau = hi - static_cast<double>(y / cellH) / kRowsPerDecade;  // large τ on top
    auto it = std::lower_bound(map.tau.begin(), map.tau.end(), std::pow(10.0, logTau));
    if (it == map.tau.end() || (it != map.tau.begin() && logTau - std::log10(*(it - 1)) < std::log10(*it) - logTau)) --it;
    const auto row = static_cast<std::size_t>(it - map.tau.begin());
    for (int x = 0; x < width; ++x) {
      const Rgb c = heatMapColour(map.value[row * map.K.size() + static_cast<std::size_t>(x / cellW)], map.top);
      std::uint8_t* px = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      px[0] = c.r;
      px[1] = c.g;
      px[2] = c.b;
    }
  }
  Provenance provenance = programProvenance();
  provenance.add("Image", image).add("K first", map.K.front()).add("K last", map.K.back());
  io::writePng(path.string(), width, height, rgb, provenance.fields);
}

}  // namespace archipelago
