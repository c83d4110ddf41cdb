#pragma once
/// \file ColourMap.hpp
/// \brief Colour maps and the RGB image of a raster of the phase plane, shared by the CLI and the GUI: portraits
/// (portrait/PortraitColours.hpp) and indicator maps (measures/MeasureExport.hpp) are coloured with them.
///
/// The perceptual maps are the matplotlib maps "inferno" and "viridis" (van der Walt & Smith, CC0),
/// evaluated from degree-6 polynomial fits (max error < 1/255 per channel), plus a grey ramp.
/// Non-empty pixels use t in [kLowest, 1] so that the faintest visit stays distinguishable from an empty
/// pixel, which gets the map's colour at 0 (black for inferno) or the background of the Orbits mode.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace archipelago {

struct Rgb {
  std::uint8_t r = 0;
  std::uint8_t g = 0;
  std::uint8_t b = 0;
  friend bool operator==(const Rgb&, const Rgb&) = default;
};

enum class ColourMapName { Inferno, Viridis, Grey };

[[nodiscard]] std::string_view toString(ColourMapName name) noexcept;
[[nodiscard]] std::optional<ColourMapName> parseColourMap(std::string_view name) noexcept;
[[nodiscard]] std::vector<ColourMapName> allColourMaps();
/// The colour map of that name; throws std::invalid_argument "<option> '<name>' must be inferno, viridis or grey"
/// (the names of allColourMaps()) for any other name.
[[nodiscard]] ColourMapName colourMapNamed(std::string_view name, std::string_view option);

/// A 256-entry table; at(t) picks the entry nearest t ∈ [0, 1] (clamped; NaN gives entry 0).
class ColourMap {
 public:
  explicit ColourMap(ColourMapName name);
  [[nodiscard]] Rgb at(double t) const noexcept;
  [[nodiscard]] const std::array<Rgb, 256>& table() const noexcept { return table_; }
  [[nodiscard]] ColourMapName name() const noexcept { return name_; }

 private:
  ColourMapName name_;
  std::array<Rgb, 256> table_;
};

/// The colour of orbit label `label` (≥ 1) in Orbits mode: golden-ratio steps in hue, saturation 0.75 and value 1
/// (each channel at least 64 and one at 255).
[[nodiscard]] Rgb orbitColour(std::uint32_t label) noexcept;

/// The colour of orbit `id` (≥ 1) launched over the portrait (issue 53, finding 14): the same steps in hue, pale
/// (saturation 0.35, each channel at least 166), so that it stands apart from every orbit of the portrait: 102 or more
/// in the channel where theirs is lowest.
[[nodiscard]] Rgb launchedOrbitColour(std::uint32_t id) noexcept;

/// A raster as RGB, row 0 at the top, and the range of the scale for a colour bar.
struct RasterImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< 3 bytes per pixel, row-major
  double scaleMin = 0;            ///< the colour bar's range, in `quantity` (log10 units; 0 … 0 in Orbits mode)
  double scaleMax = 0;
  std::string quantity;           ///< e.g. "log10(visits)", "log10(mean segment length / steps)"
};

/// The lowest t given to a non-empty pixel.
inline constexpr double kLowest = 0.12;
/// Orbits mode: the range of t that shades the sea, below the bright hues of the island orbits.
inline constexpr double kSeaLowest = 0.15;
inline constexpr double kSeaHighest = 0.55;

}  // namespace archipelago
