#pragma once
/// \file MeasureExport.hpp
/// \brief Indicator maps as NumPy .npy files with a JSON sidecar (the conventions of PortraitExport.hpp), as RGB
/// images, and single-orbit results as JSON — what the CLI, the Python module and the GUI export.
///
/// The sidecar (FILE.json next to FILE.npy) records the parameters numpy.load cannot: the kind and its units,
/// the map (K, xmin, xmax and the exact integers A, B, C, m), the viewport (exact centre in unit coordinates,
/// physical bounds with 19 significant digits), the request (iterations, steps per orbit, digits threshold,
/// passes), the verdict codes and their counts, `"rows": "row 0 is the top (largest y)"`.

#include <optional>
#include <string>

#include "core/measures/ChainIdentification.hpp"
#include "core/measures/IndicatorMap.hpp"
#include "core/colour/ColourMap.hpp"
#include "core/provenance/Provenance.hpp"

namespace archipelago {

/// What the values of a kind mean, with units: e.g. "rotation number about (-sqrt K, 0), turns per step,
/// positive clockwise; NaN: chaotic or escaping (see verdicts)".
[[nodiscard]] std::string indicatorQuantity(IndicatorKind kind);

/// Where an indicator map came from (its PNG's text, the CLI's and the GUI's): the program, the map, the view
/// (PortraitExport.hpp's addView), the kind, the size, the iterations and the digits threshold.
[[nodiscard]] Provenance indicatorProvenance(const IndicatorRequest& request);

/// The sidecar's JSON text (pretty-printed).  `verdictsFile`: the name of the verdicts array written beside it,
/// if any.
[[nodiscard]] std::string indicatorMetadataJson(const IndicatorRequest& request, const IndicatorResult& result,
                                                const std::string& verdictsFile = {});

/// Writes the values (<f8, NaN where there is no number) to npyPath, the verdict codes (<u4, OrbitVerdict's
/// numbers) to verdictsPath when it is not empty, and the sidecar to sidecarPath(npyPath), each atomically.
/// Throws std::runtime_error naming the file that could not be written.
void exportIndicatorNpy(const std::string& npyPath, const IndicatorRequest& request, const IndicatorResult& result,
                        const std::string& verdictsPath = {});

/// The colour of pixels without a number: Chaotic (dark grey) and Escaping (dark blue), for every kind that
/// gives them (Rotation); NotComputed pixels are black.
inline constexpr Rgb kChaoticColour{48, 48, 48};
inline constexpr Rgb kEscapingColour{16, 24, 72};

/// Colours a raster (its filled() values, so a partial raster shows its coarse pixels): Dig on the fixed scale
/// 0 … 16 digits; the other kinds linearly between the 1st and 99th percentiles of their finite values; pixels
/// without a number by kChaoticColour / kEscapingColour.  scaleMin/scaleMax/quantity describe the scale.
[[nodiscard]] RasterImage colourizeIndicator(const IndicatorRaster& raster, ColourMapName map);

/// A single orbit's rotation number and island chain as JSON text (the CLI's `rotation --json`): the map, the
/// start (physical and unit), the iterations, the rotation about the centre with digits and verdict, and the
/// chain (period, factors, summary, levels with their centres, rotations and periodic orbits' residues).
[[nodiscard]] std::string rotationReportJson(const ChainRequest& request, const ChainIdentification& chain);

}  // namespace archipelago
