#include "core/scan/ScanHeatMap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

Rgb heatMapColour(double value) noexcept {
  if (std::isnan(value)) return kHeatMapNoData;
  const double s = std::clamp(value / kHeatMapTop, 0.0, 1.0);
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

}  // namespace archipelago
