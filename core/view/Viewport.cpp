#include "core/view/Viewport.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/io/NumberText.hpp"

namespace archipelago {

PhysicalRect parsePhysicalRect(const std::string& text, const std::string& option) {
  const auto v = io::parseNumbers<long double>(option, text, ',', 4, "four finite numbers x0,x1,y0,y1 (physical coordinates)");
  return {v[0], v[1], v[2], v[3]};
}

namespace {
constexpr long double kOneUnits = Viewport::kMaxSizeUnits;  // 2^52

// Physical → unit coordinate, unrounded: the grid position of x (resp. y) in units of 2^−52.
long double unitX(const MapParameters& map, long double x) {
  return std::ldexp((x - map.xmin) / static_cast<long double>(map.width()), FixedPointMap::kBits);
}
long double unitY(const MapParameters& map, long double y) {
  const long double L = map.width();
  return std::ldexp((y + L / 2) / L, FixedPointMap::kBits);
}

}  // namespace

std::optional<std::string> Viewport::validationError(const MapParameters& map, const PhysicalRect& r) {
  if (auto e = archipelago::validationError(map)) return e;
  std::ostringstream s;
  s.precision(19);
  const char* names[] = {"x0", "x1", "y0", "y1"};
  const long double values[] = {r.x0, r.x1, r.y0, r.y1};
  for (int i = 0; i < 4; ++i) {
    if (!std::isfinite(values[i])) {
      s << "view bound " << names[i] << " = " << values[i] << " must be a finite number";
      return s.str();
    }
  }
  if (!(r.x1 > r.x0)) {
    s << "view width x1 - x0 = " << (r.x1 - r.x0) << " must be > 0 (x0 = " << r.x0 << ", x1 = " << r.x1 << ")";
    return s.str();
  }
  if (!(r.y1 > r.y0)) {
    s << "view height y1 - y0 = " << (r.y1 - r.y0) << " must be > 0 (y0 = " << r.y0 << ", y1 = " << r.y1 << ")";
    return s.str();
  }
  const long double L = map.width();
  const long double minimum = std::ldexp(L, -FixedPointMap::kBits) * kMinSizeUnits;
  if (r.x1 - r.x0 < minimum || r.y1 - r.y0 < minimum) {
    s << "view size " << (r.x1 - r.x0) << " x " << (r.y1 - r.y0) << " is below the resolution limit " << minimum
      << " (" << static_cast<double>(kMinSizeUnits) << " grid units of L/2^52)";
    return s.str();
  }
  // Half a grid unit of slack: bounds printed from a valid view and read back must stay valid.
  const long double slack = std::ldexp(L, -FixedPointMap::kBits - 1);
  const bool inside = r.x0 >= map.xmin - slack && r.x1 <= map.xmax + slack && r.y0 >= -L / 2 - slack &&
                      r.y1 <= L / 2 + slack;
  if (!inside) {
    s << "view [x0, x1] x [y0, y1] = [" << r.x0 << ", " << r.x1 << "] x [" << r.y0 << ", " << r.y1
      << "] is not inside the box [xmin, xmax] x [-L/2, L/2] = [" << map.xmin << ", " << map.xmax << "] x ["
      << -L / 2 << ", " << L / 2 << "]";
    return s.str();
  }
  return std::nullopt;
}

Viewport Viewport::fromPhysical(const MapParameters& map, const PhysicalRect& r) {
  if (auto e = validationError(map, r)) throw std::invalid_argument(*e);
  const long double u0 = unitX(map, r.x0), u1 = unitX(map, r.x1);
  const long double v0 = unitY(map, r.y0), v1 = unitY(map, r.y1);
  return clamped((u0 + u1) / 2, (v0 + v1) / 2, u1 - u0, v1 - v0);
}

Viewport Viewport::fromUnits(UnitState centre, long double widthUnits, long double heightUnits) {
  std::ostringstream s;
  s.precision(19);
  for (long double size : {widthUnits, heightUnits}) {
    if (!(std::isfinite(size) && size >= kMinSizeUnits && size <= kMaxSizeUnits)) {
      s << "view size " << size << " grid units must lie in [" << kMinSizeUnits << ", 2^52]";
      throw std::invalid_argument(s.str());
    }
  }
  const auto cx = static_cast<long double>(centre.X), cy = static_cast<long double>(centre.Y);
  if (centre.X >= FixedPointMap::kOne || centre.Y >= FixedPointMap::kOne || cx - widthUnits / 2 < 0 ||
      cx + widthUnits / 2 > kOneUnits || cy - heightUnits / 2 < 0 || cy + heightUnits / 2 > kOneUnits) {
    s << "view centred at (X, Y) = (" << centre.X << ", " << centre.Y << ") of size " << widthUnits << " x "
      << heightUnits << " grid units is not inside the box [0, 2^52]^2";
    throw std::invalid_argument(s.str());
  }
  return {centre, widthUnits, heightUnits};
}

Viewport Viewport::clamped(long double cx, long double cy, long double w, long double h) noexcept {
  w = std::clamp(w, kMinSizeUnits, kMaxSizeUnits);
  h = std::clamp(h, kMinSizeUnits, kMaxSizeUnits);
  // Round the centre to the grid, then shift it (by whole units) until the view fits in [0, 2^52].
  auto fit = [](long double c, long double size) {
    long double rounded = std::nearbyint(c);
    if (rounded - size / 2 < 0) rounded = std::ceil(size / 2);
    if (rounded + size / 2 > kOneUnits) rounded = std::floor(kOneUnits - size / 2);
    return static_cast<std::uint64_t>(rounded);
  };
  return {UnitState{fit(cx, w), fit(cy, h)}, w, h};
}

PhysicalRect Viewport::physical(const MapParameters& map) const noexcept {
  const long double unit = std::ldexp(static_cast<long double>(map.width()), -FixedPointMap::kBits);
  const PhysicalPoint c = physicalCentre(map);
  return {c.x - unit * width_ / 2, c.x + unit * width_ / 2, c.y - unit * height_ / 2, c.y + unit * height_ / 2};
}

PhysicalPoint Viewport::physicalCentre(const MapParameters& map) const noexcept {
  const long double L = map.width();
  return {map.xmin + L * std::ldexp(static_cast<long double>(centre_.X), -FixedPointMap::kBits),
          -L / 2 + L * std::ldexp(static_cast<long double>(centre_.Y), -FixedPointMap::kBits)};
}

Viewport Viewport::zoomedAbout(long double dx, long double dy, long double factor) const noexcept {
  if (!(std::isfinite(factor) && factor > 0 && std::isfinite(dx) && std::isfinite(dy))) return *this;
  const long double w = std::clamp(width_ / factor, kMinSizeUnits, kMaxSizeUnits);
  const long double h = std::clamp(height_ / factor, kMinSizeUnits, kMaxSizeUnits);
  // The fixed point keeps its fractional position: c' = p − (p − c)·(w'/w), with p = c + d.
  const long double cx = static_cast<long double>(centre_.X) + dx * (1 - w / width_);
  const long double cy = static_cast<long double>(centre_.Y) + dy * (1 - h / height_);
  return clamped(cx, cy, w, h);
}

Viewport Viewport::zoomedAboutFraction(long double fx, long double fy, long double factor) const noexcept {
  return zoomedAbout((fx - 0.5L) * width_, (fy - 0.5L) * height_, factor);
}

Viewport Viewport::cropped(long double fx0, long double fx1, long double fy0, long double fy1) const noexcept {
  for (long double f : {fx0, fx1, fy0, fy1})
    if (!std::isfinite(f)) return *this;
  if (!(fx1 > fx0 && fy1 > fy0)) return *this;
  const long double cx = static_cast<long double>(centre_.X) + ((fx0 + fx1) / 2 - 0.5L) * width_;
  const long double cy = static_cast<long double>(centre_.Y) + ((fy0 + fy1) / 2 - 0.5L) * height_;
  return clamped(cx, cy, (fx1 - fx0) * width_, (fy1 - fy0) * height_);
}

Viewport Viewport::panned(long double fx, long double fy) const noexcept {
  if (!(std::isfinite(fx) && std::isfinite(fy))) return *this;
  return clamped(static_cast<long double>(centre_.X) + fx * width_, static_cast<long double>(centre_.Y) + fy * height_,
                 width_, height_);
}

PhysicalPoint Viewport::unitOffset(const MapParameters& map, long double x, long double y) const noexcept {
  return {unitX(map, x) - static_cast<long double>(centre_.X), unitY(map, y) - static_cast<long double>(centre_.Y)};
}

UnitState orbitSeed(const Viewport& view, std::uint32_t columns, std::uint32_t rows, std::uint32_t i,
                    std::uint32_t j) noexcept {
  const long double dx = ((i + 0.5L) / columns - 0.5L) * view.widthUnits();
  const long double dy = ((j + 0.5L) / rows - 0.5L) * view.heightUnits();
  const auto ox = static_cast<std::int64_t>(std::llround(dx)), oy = static_cast<std::int64_t>(std::llround(dy));
  return {(view.centre().X + static_cast<std::uint64_t>(ox)) & FixedPointMap::kMask,
          (view.centre().Y + static_cast<std::uint64_t>(oy)) & FixedPointMap::kMask};
}

std::optional<std::string> viewWidthError(long double width, const MapParameters& map) {
  const std::string box = shortestDecimal(map.width());
  if (!(width > 0 && std::isfinite(width)))
    return "the width = " + io::shortestText(width) + " must be a number in (0, " + box + "]";
  if (width > static_cast<long double>(map.width()))
    return "the width = " + io::shortestText(width) + " must be at most the box's width L = xmax − xmin = " + box +
           " (Home shows the whole box)";
  return std::nullopt;
}

}  // namespace archipelago
