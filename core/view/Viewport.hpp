#pragma once
/// \file Viewport.hpp
/// \brief A rectangle of the torus of Q*, with its centre held exactly on the 52-bit grid.
///
/// The explorer zooms to widths of 10⁻¹⁰ and below, where a `double` centre (53 bits for |x| ≈ 0.3) keeps
/// only a few significant digits of the view.  So the centre is stored as integer unit coordinates (X, Y) of
/// the map's grid (FixedPointMap.hpp: x = xmin + L·X/2^52, y = −L/2 + L·Y/2^52) and the width and height in
/// grid units as long double (64-bit mantissa, so a width of 2^52 units still has 12 fractional bits).
/// Zoom and pan move the centre by rounded integer offsets: the centre is then exact, and its rounding error
/// is at most half a grid unit (L·2^−53 ≈ 1.4·10⁻¹⁶ for L = 1.3), far below a pixel of any allowed view.
///
/// Valid views lie inside the box [xmin, xmax] × [−L/2, L/2] (the torus is not unrolled: a view does not
/// straddle the seam) and are at least kMinWidthUnits grid units wide and high, i.e. L·2^−42 ≈ 3·10⁻¹³ for
/// the paper's box — below that the pixels of a 1024-pixel raster would be smaller than the grid.
/// Zoom and pan clamp into that range; constructors reject views outside it with a clear message.

#include <cstdint>
#include <optional>
#include <string>

#include "core/map/FixedPointMap.hpp"

namespace archipelago {

/// A rectangle in physical coordinates: x0 < x1, y0 < y1.
struct PhysicalRect {
  long double x0 = 0;
  long double x1 = 0;
  long double y0 = 0;
  long double y1 = 0;
};

/// A view typed as text, "x0,x1,y0,y1" in physical coordinates (issue 35: one parser for the CLI's --view of
/// portrait, indicator and manifold and the GUI's --view).  Throws std::invalid_argument "<option> '<text>' must be
/// four finite numbers x0,x1,y0,y1 (physical coordinates)"; the bounds' rules are fromPhysical()'s.
[[nodiscard]] PhysicalRect parsePhysicalRect(const std::string& text, const std::string& option = "--view");

class Viewport {
 public:
  /// The smallest width and height, in grid units (2^10; L·2^−42 in physical length).
  static constexpr long double kMinSizeUnits = 1024;
  /// The largest: the whole box, 2^52 units.
  static constexpr long double kMaxSizeUnits = static_cast<long double>(FixedPointMap::kOne);

  /// The whole box.
  Viewport() = default;
  [[nodiscard]] static Viewport wholeBox() noexcept { return {}; }

  /// The view with physical bounds r (x0 < x1, y0 < y1) for the map with parameters `map`.
  /// Throws std::invalid_argument, naming the bound and the rule, when a bound is not finite, when a width
  /// is zero or negative, below the resolution limit, or when the view leaves the box.
  [[nodiscard]] static Viewport fromPhysical(const MapParameters& map, const PhysicalRect& r);
  /// The first violated rule of fromPhysical(), or nothing when r is a valid view.
  [[nodiscard]] static std::optional<std::string> validationError(const MapParameters& map, const PhysicalRect& r);

  /// The view centred exactly on `centre` with the given size in grid units.  Throws std::invalid_argument
  /// when a size is not finite, outside [kMinSizeUnits, kMaxSizeUnits], or the view leaves the box.
  [[nodiscard]] static Viewport fromUnits(UnitState centre, long double widthUnits, long double heightUnits);

  /// The exact centre, in unit coordinates.
  [[nodiscard]] UnitState centre() const noexcept { return centre_; }
  [[nodiscard]] long double widthUnits() const noexcept { return width_; }
  [[nodiscard]] long double heightUnits() const noexcept { return height_; }
  /// The physical bounds (long double: about 19 significant digits).
  [[nodiscard]] PhysicalRect physical(const MapParameters& map) const noexcept;
  /// The physical centre.
  [[nodiscard]] PhysicalPoint physicalCentre(const MapParameters& map) const noexcept;

  /// Zoom by `factor` (> 1 in, < 1 out) keeping fixed the point at offset (dx, dy) grid units from the
  /// centre.  The size is clamped to [kMinSizeUnits, kMaxSizeUnits] and the view shifted back inside the
  /// box if needed.  A non-finite or non-positive factor leaves the view unchanged.
  [[nodiscard]] Viewport zoomedAbout(long double dxUnits, long double dyUnits, long double factor) const noexcept;
  /// The same, with the fixed point given as fractions of the view: (0, 0) the bottom-left corner,
  /// (1, 1) the top-right one.
  [[nodiscard]] Viewport zoomedAboutFraction(long double fx, long double fy, long double factor) const noexcept;
  /// The sub-rectangle [fx0, fx1] × [fy0, fy1] of the view in fractions (0 = left/bottom, 1 = right/top),
  /// e.g. a rubber band; clamped like zoomedAbout().  Unchanged when the fractions are not finite or empty.
  [[nodiscard]] Viewport cropped(long double fx0, long double fx1, long double fy0, long double fy1) const noexcept;
  /// Moves the view by (fx·width, fy·height), clamped inside the box.
  [[nodiscard]] Viewport panned(long double fx, long double fy) const noexcept;

  /// Offset (grid units, possibly fractional) of a physical point from the centre.
  [[nodiscard]] PhysicalPoint unitOffset(const MapParameters& map, long double x, long double y) const noexcept;

  friend bool operator==(const Viewport&, const Viewport&) = default;

 private:
  Viewport(UnitState centre, long double w, long double h) : centre_(centre), width_(w), height_(h) {}
  /// Clamps sizes and shifts the centre so that the view lies inside the box.
  [[nodiscard]] static Viewport clamped(long double cx, long double cy, long double w, long double h) noexcept;

  UnitState centre_{FixedPointMap::kHalf, FixedPointMap::kHalf};
  long double width_ = kMaxSizeUnits;
  long double height_ = kMaxSizeUnits;
};

/// The unit state of the centre of seed cell (i, j) (i across, j up from the bottom) of a columns × rows grid over
/// the view: the portraits' Orbits mode and the indicator maps seed their orbits there.
[[nodiscard]] UnitState orbitSeed(const Viewport& view, std::uint32_t columns, std::uint32_t rows, std::uint32_t i,
                                  std::uint32_t j) noexcept;

/// The rule of a view's width asked for by a front end (the GUI's Go to): a number > 0 and at most the box's width
/// L = xmax − xmin (issue 53, finding 21: 1e300 silently meant the whole box), or nothing.
[[nodiscard]] std::optional<std::string> viewWidthError(long double width, const MapParameters& map);

}  // namespace archipelago
