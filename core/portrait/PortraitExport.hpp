#pragma once
/// \file PortraitExport.hpp
/// \brief Writes rasters as NumPy .npy files (io/Npy.hpp) with a JSON sidecar, both atomically.
///
/// The sidecar (FILE.json next to FILE.npy) records what numpy.load cannot: the viewport (exact centre in
/// unit coordinates, physical bounds with 19 significant digits), the map (K, xmin, xmax and the exact
/// integers A, B, C, m), the request and the totals; `"rows": "row 0 is the top (largest y)"`.

#include <cstdint>
#include <string>
#include <vector>

#include "core/io/Npy.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/view/ViewExport.hpp"  // sidecarPath, addView

namespace archipelago {

/// Where a portrait came from (its PNG's text, the CLI's and the GUI's): the program, the map, the view, the mode,
/// the size, the points, the orbits (or seed grid), Xr and q in Stickiness mode, the seed.
[[nodiscard]] Provenance portraitProvenance(const PortraitRequest& request);

/// The JSON text of the sidecar (pretty-printed).
[[nodiscard]] std::string portraitMetadataJson(const PortraitRequest& request, const PortraitRaster& raster,
                                               const std::string& arrayName);

/// Writes the raster's main array — counts (<u8) in Density mode, labels (<u4) in Orbits mode, mean segment
/// lengths in steps (<f8) in Stickiness mode — to npyPath and the sidecar to sidecarPath(npyPath).
void exportPortraitNpy(const std::string& npyPath, const PortraitRequest& request, const PortraitRaster& raster);

}  // namespace archipelago
