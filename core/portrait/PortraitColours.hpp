#pragma once
/// \file PortraitColours.hpp
/// \brief The conversion of a PortraitRaster into RGB pixels (colour/ColourMap.hpp), shared by the CLI and the GUI.
/// Scales:
///   - Density: t = (log c − log m)/(2w) + ½ clamped to [0, 1], m the median visited count and w the larger of
///     log(m/c₅%) and log(c₉₉.₅%/m): the sea is nearly uniform, so a log scale centred on its bulk shows where
///     sticky orbits linger (between its extremes the bulk saturated the top of the map: issue 25, finding 14);
///   - Stickiness: t = (log10 L − log10 Lmin) / (log10 Lmax − log10 Lmin), L the mean segment length (§3);
///   - Orbits: each label gets its own hue (golden-ratio steps around the colour wheel), not a scale;
///     orbits that wrapped around the torus (the sea and accelerator modes) are shaded by log visits through
///     the dim part [kSeaLowest, kSeaHighest] of the colour map, over the robust range of Density widened to
///     at least [median/10, median·√10] (so that counting noise does not fill the scale).
/// Non-empty pixels use t in [kLowest, 1] (ColourMap.hpp) so that the faintest visit stays distinguishable from an empty
/// pixel, which gets the map's colour at 0 (black for inferno) or the background of the Orbits mode.

#include "core/colour/ColourMap.hpp"
#include "core/portrait/PortraitRaster.hpp"

namespace archipelago {

/// Colours a raster as described above.
[[nodiscard]] RasterImage colourize(const PortraitRaster& raster, ColourMapName map);

}  // namespace archipelago
