#pragma once
/// \file ViewJson.hpp
/// \brief Core-internal: the parts of a raster sidecar (portrait/PortraitExport.hpp) that every raster of a view shares —
/// the map with its exact integers and the viewport — as nlohmann::json values, so that the portrait and the
/// indicator-map sidecars (measures/MeasureExport.hpp) describe them in one way.

#include <nlohmann/json.hpp>

#include "core/map/MapParameters.hpp"
#include "core/view/Viewport.hpp"

namespace archipelago {

/// {"K", "xmin", "xmax", "coefficients": {"A", "B", "C", "m"}}: the map and the integers that define it.
[[nodiscard]] nlohmann::json mapWithCoefficientsJson(const MapParameters& map);

/// {"centre_unit": {"X", "Y"}, "width_units", "height_units", "physical": {"x0", "x1", "y0", "y1"}, "unit"}, the
/// long doubles as text with 19 significant digits.
[[nodiscard]] nlohmann::json viewportJson(const MapParameters& map, const Viewport& view);

}  // namespace archipelago
