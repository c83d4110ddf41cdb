#pragma once
/// \file ScanHeatMap.hpp
/// \brief The local exponent −d log C_τ/d log τ (fig. 6d) over τ and K of a K scan, and its one colour scale: the
/// CLI's scan_local_exponent.png, the K-scan dialog and the report's figure all colour it with heatMapColour()
/// (issue #24: they once used a quadratic formula with grey 160 and linear stops with grey 190).  The tail scan's
/// γ(t, K) (core/tail/TailScan.hpp: tailGammaHeatMap) is a heat map of the same kind, with its own top.

#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/colour/ColourMap.hpp"
#include "core/scan/ScanRunSummary.hpp"

namespace archipelago {

/// The colour scale's top: the local exponent is drawn in [0, kHeatMapTop] (the paper's range is ¼ … 3/2); larger
/// values take the top colour, negative ones the bottom one.
inline constexpr double kHeatMapTop = 2;

/// The local exponent over τ and K: value[row · K.size() + column] at tau[row], K[column]; NaN where undefined.
/// tau is the sorted union of the runs' grids.  `top`: the value drawn in the colour scale's top colour.
struct ScanHeatMap {
  std::vector<double> K;
  std::vector<double> tau;
  std::vector<double> value;
  double top = kHeatMapTop;
};
[[nodiscard]] ScanHeatMap localExponentHeatMap(const std::vector<ScanRunSummary>& runs);

/// A stop of the colour scale: at value·kHeatMapTop, the colour.
struct HeatMapStop {
  double position;  ///< in [0, 1]
  Rgb colour;
};
/// White at 0, orange at the middle, dark red at the top; linear in between.
[[nodiscard]] std::span<const HeatMapStop> heatMapStops() noexcept;
/// The grey of a cell without data (C_τ = 0, or τ beyond that K's run).
inline constexpr Rgb kHeatMapNoData{190, 190, 190};

/// The colour of a local exponent `value` (NaN: kHeatMapNoData), by linear interpolation between the stops at
/// value/top, each channel rounded to the nearest integer.
[[nodiscard]] Rgb heatMapColour(double value, double top = kHeatMapTop) noexcept;

/// The heat map as an image: a column of cells per K (left to right, in the map's order), log τ upwards at 30 rows
/// per decade (each row the τ of the map nearest in log τ), coloured by heatMapColour() up to the map's top (white
/// at 0 through orange to dark red, grey where undefined), as the K-scan dialog and the report colour it.  Its
/// provenance (core/provenance) says `image`.  Nothing is written for a map without K or τ.  Throws
/// std::runtime_error naming the file when it cannot be written.
void writeHeatMapPng(const std::filesystem::path& path, const ScanHeatMap& map, const std::string& image);

}  // namespace archipelago
