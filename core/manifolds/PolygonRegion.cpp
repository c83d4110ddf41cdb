#include "core/manifolds/PolygonRegion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/periodic/SmoothQuadraticMap.hpp"  // quad

namespace archipelago {

namespace {

/// The sign of the cross product (b − a) × (c − a): which side of the line a→b the point c is on.
int orientation(const PhysicalPoint& a, const PhysicalPoint& b, const PhysicalPoint& c) noexcept {
  const long double v = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  return (v > 0) - (v < 0);
}

/// Whether the segments p–q and a–b cross (proper crossings only).
bool crosses(const PhysicalPoint& p, const PhysicalPoint& q, const PhysicalPoint& a, const PhysicalPoint& b) noexcept {
  return orientation(p, q, a) * orientation(p, q, b) < 0 && orientation(a, b, p) * orientation(a, b, q) < 0;
}

}  // namespace

long double signedShoelaceArea(const std::vector<PhysicalPoint>& v) noexcept {
  if (v.size() < 3) return 0;
  const long double cx = v.front().x, cy = v.front().y;
  quad sum = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const PhysicalPoint& a = v[i];
    const PhysicalPoint& b = v[(i + 1) % v.size()];
    sum += quad((a.x - cx) * (b.y - cy)) - quad((b.x - cx) * (a.y - cy));
  }
  return static_cast<long double>(sum / 2);
}

PolygonRegion::PolygonRegion(std::vector<PhysicalPoint> vertices, int gridCells)
    : PolygonRegion(std::vector<std::vector<PhysicalPoint>>{std::move(vertices)}, gridCells) {}

PolygonRegion::PolygonRegion(const std::vector<std::vector<PhysicalPoint>>& rings, int gridCells) {
  if (rings.empty()) throw std::invalid_argument("a polygon region needs at least one ring");
  for (const std::vector<PhysicalPoint>& ring : rings) {
    if (ring.size() < 3) throw std::invalid_argument("a polygon region needs at least 3 vertices per ring");
    const long double a = signedShoelaceArea(ring);
    signedArea_ += a;
    area_ += std::fabs(a);
    const int first = static_cast<int>(vertices_.size()), n = static_cast<int>(ring.size());
    for (int i = 0; i < n; ++i) edges_.emplace_back(first + i, first + (i + 1) % n);
    vertices_.insert(vertices_.end(), ring.begin(), ring.end());
  }
  build(gridCells);
}

void PolygonRegion::build(int gridCells) {
  bounds_ = {vertices_[0].x, vertices_[0].x, vertices_[0].y, vertices_[0].y};
  for (const PhysicalPoint& p : vertices_) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw std::invalid_argument("a polygon vertex is not finite");
    bounds_.x0 = std::min(bounds_.x0, p.x);
    bounds_.x1 = std::max(bounds_.x1, p.x);
    bounds_.y0 = std::min(bounds_.y0, p.y);
    bounds_.y1 = std::max(bounds_.y1, p.y);
  }
  const int n = static_cast<int>(edges_.size());
  const int cells = gridCells > 0 ? gridCells : std::clamp(static_cast<int>(std::sqrt(static_cast<double>(n))) * 2, 8, 512);
  columns_ = rows_ = cells;
  // Cells a little larger than the box so that every vertex falls strictly inside the grid.
  const long double w = std::max(bounds_.x1 - bounds_.x0, 1e-300L), h = std::max(bounds_.y1 - bounds_.y0, 1e-300L);
  cellWidth_ = w * (1 + 1e-9L) / columns_;
  cellHeight_ = h * (1 + 1e-9L) / rows_;
  cells_.assign(static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_), {});
  for (int e = 0; e < n; ++e) {
    const PhysicalPoint& a = vertices_[static_cast<std::size_t>(edges_[static_cast<std::size_t>(e)].first)];
    const PhysicalPoint& b = vertices_[static_cast<std::size_t>(edges_[static_cast<std::size_t>(e)].second)];
    const int c0 = column(std::min(a.x, b.x)), c1 = column(std::max(a.x, b.x));
    const int r0 = row(std::min(a.y, b.y)), r1 = row(std::max(a.y, b.y));
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) cells_[static_cast<std::size_t>(r) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(c)].edges.push_back(e);
  }
  // Inside status of the cell centres, one horizontal ray per row (half-open rule at vertices).
  std::vector<long double> crossings;
  for (int r = 0; r < rows_; ++r) {
    const long double y = bounds_.y0 + (r + 0.5L) * cellHeight_;
    crossings.clear();
    for (const auto& [i, j] : edges_) {
      const PhysicalPoint& a = vertices_[static_cast<std::size_t>(i)];
      const PhysicalPoint& b = vertices_[static_cast<std::size_t>(j)];
      if ((a.y > y) != (b.y > y)) crossings.push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
    std::sort(crossings.begin(), crossings.end());
    std::size_t left = 0;
    for (int c = 0; c < columns_; ++c) {
      const long double x = bounds_.x0 + (c + 0.5L) * cellWidth_;
      while (left < crossings.size() && crossings[left] < x) ++left;
      cells_[static_cast<std::size_t>(r) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(c)].centreInside = left % 2 == 1;
    }
  }
}

int PolygonRegion::column(long double x) const noexcept {
  return std::clamp(static_cast<int>(std::floor((x - bounds_.x0) / cellWidth_)), 0, columns_ - 1);
}

int PolygonRegion::row(long double y) const noexcept {
  return std::clamp(static_cast<int>(std::floor((y - bounds_.y0) / cellHeight_)), 0, rows_ - 1);
}

bool PolygonRegion::contains(long double x, long double y) const noexcept {
  if (!(x >= bounds_.x0 && x <= bounds_.x1 && y >= bounds_.y0 && y <= bounds_.y1)) return false;
  const int c = column(x), r = row(y);
  const Cell& cell = cells_[static_cast<std::size_t>(r) * static_cast<std::size_t>(columns_) + static_cast<std::size_t>(c)];
  if (cell.edges.empty()) return cell.centreInside;
  const PhysicalPoint p{x, y};
  const PhysicalPoint centre{bounds_.x0 + (c + 0.5L) * cellWidth_, bounds_.y0 + (r + 0.5L) * cellHeight_};
  bool inside = cell.centreInside;
  for (int e : cell.edges) {
    const auto& [i, j] = edges_[static_cast<std::size_t>(e)];
    if (crosses(p, centre, vertices_[static_cast<std::size_t>(i)], vertices_[static_cast<std::size_t>(j)])) inside = !inside;
  }
  return inside;
}

}  // namespace archipelago
