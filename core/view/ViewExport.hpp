#pragma once
/// \file ViewExport.hpp
/// \brief What every exported raster of a view records, whatever it shows (portraits, portrait/PortraitExport.hpp;
/// indicator maps, measures/MeasureExport.hpp): the sidecar's path next to its .npy file, and the view in the
/// provenance.  The sidecar's shared JSON parts are core-internal (ViewJson.hpp).

#include <string>

#include "core/map/MapParameters.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/view/Viewport.hpp"

namespace archipelago {

/// The sidecar's path: FILE.npy → FILE.json (any other name: name + ".json").
[[nodiscard]] std::string sidecarPath(const std::string& npyPath);

/// The view's edges as the fields "View x0", "View x1", "View y0", "View y1" (physical coordinates, shortest exact
/// text of the long doubles): the view of every image of the phase plane.
void addView(Provenance& provenance, const MapParameters& map, const Viewport& view);
/// The same fields for edges already physical (a replayed orbit's frame in the report).
void addView(Provenance& provenance, const PhysicalRect& edges);

}  // namespace archipelago
