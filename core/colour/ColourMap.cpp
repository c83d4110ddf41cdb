#include "core/colour/ColourMap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
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

ColourMapName colourMapNamed(std::string_view name, std::string_view option) {
  if (const auto known = parseColourMap(name)) return *known;
  const std::vector<ColourMapName> all = allColourMaps();
  std::string names;
  for (std::size_t k = 0; k < all.size(); ++k)
    names += std::string(k == 0 ? "" : k + 1 == all.size() ? " or " : ", ") + std::string(toString(all[k]));
  throw std::invalid_argument(std::string(option) + " '" + std::string(name) + "' must be " + names);
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

namespace {

/// Hue `label` golden-ratio steps round the circle (neighbouring labels well separated) at saturation s, value v.
Rgb goldenHue(std::uint32_t label, double s, double v) noexcept {
  const double golden = 0.6180339887498949;
  const double h = std::fmod(static_cast<double>(label) * golden, 1.0) * 6.0;
  const double f = h - std::floor(h);
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

}  // namespace

Rgb orbitColour(std::uint32_t label) noexcept { return goldenHue(label, 0.75, 1.0); }

Rgb launchedOrbitColour(std::uint32_t id) noexcept { return goldenHue(id, 0.35, 1.0); }

}  // namespace archipelago
