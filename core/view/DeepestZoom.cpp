#include "core/view/DeepestZoom.hpp"

#include <cstdio>

namespace archipelago {

bool atDeepestZoom(const Viewport& view) noexcept {
  return view.widthUnits() <= Viewport::kMinSizeUnits || view.heightUnits() <= Viewport::kMinSizeUnits;
}

std::string deepestZoomNote(const MapParameters& map) {
  char width[32];
  std::snprintf(width, sizeof width, "%.2g",
                static_cast<double>(map.width() * Viewport::kMinSizeUnits / Viewport::kMaxSizeUnits));
  // Short enough for the status bar at 1280 pixels.
  return "Deepest zoom: the view is " + std::to_string(static_cast<int>(Viewport::kMinSizeUnits)) + " grid cells (" +
         width + ") wide; the map's states are integers, 2^52 across the box";
}

}  // namespace archipelago
