#pragma once
/// \file DeepestZoom.hpp
/// \brief The resolution limit of a view (issue 53, finding 7: zoom clicks at the deepest view silently did nothing):
/// when a view is at it, and what a zoom in there says.

#include <string>

#include "core/view/Viewport.hpp"

namespace archipelago {

/// True at the resolution limit: the width or the height is Viewport::kMinSizeUnits (1024 grid cells), and zooming in
/// changes nothing more.
[[nodiscard]] bool atDeepestZoom(const Viewport& view) noexcept;

/// The deepest view's width, in grid cells and physically for `map`, and why no view is narrower.
[[nodiscard]] std::string deepestZoomNote(const MapParameters& map);

}  // namespace archipelago
