#pragma once
/// \file PolygonRegion.hpp
/// \brief A region of the plane bounded by closed polygons (one or several disjoint rings): area (shoelace) and a
/// fast point-in-region test.
///
/// The regions of core/manifolds — a resonance zone bounded by manifold arcs, a turnstile lobe — are polygons of
/// thousands of vertices queried at every step of millions of orbit points (the Kac check, the chain-entry
/// count).  contains() uses the even–odd rule (a point is inside when a ray from it crosses the boundary an odd
/// number of times) accelerated by a uniform grid over the bounding box: the inside status of each cell's centre
/// is precomputed row by row (one horizontal ray per row of cells), and a query crosses only the edges that
/// overlap its cell, on the segment from the point to that cell's centre.  A query costs O(1) away from the
/// boundary and O(edges in the cell) near it.  Points exactly on an edge, or on a segment through a vertex, may go
/// either way (a set of measure zero).
///
/// area() is the shoelace formula ½ Σ (x_i y_{i+1} − x_{i+1} y_i) about the first vertex, accumulated in
/// __float128: counter-clockwise positive.

#include <vector>

#include "core/map/FixedPointMap.hpp"  // PhysicalPoint
#include "core/view/Viewport.hpp"  // PhysicalRect

namespace archipelago {

/// ½ Σ (x_i y_{i+1} − x_{i+1} y_i) of the closed polygon (the last vertex joins the first): the signed area,
/// counter-clockwise positive; computed about the first vertex and summed in __float128.
[[nodiscard]] long double signedShoelaceArea(const std::vector<PhysicalPoint>& vertices) noexcept;

class PolygonRegion {
 public:
  /// The region bounded by the closed polygon `vertices` (at least 3, all finite; the last joins the first).
  /// `gridCells` ≥ 1 cells per side of the acceleration grid (0: chosen from the number of vertices).  Throws
  /// std::invalid_argument for fewer than 3 vertices or a non-finite one.
  explicit PolygonRegion(std::vector<PhysicalPoint> vertices, int gridCells = 0);
  /// The region bounded by several closed polygons (even–odd rule over all their edges: the union of disjoint
  /// rings, e.g. the six zones of a sub-chain around six islands).  Each ring as above.
  explicit PolygonRegion(const std::vector<std::vector<PhysicalPoint>>& rings, int gridCells = 0);

  /// Whether (x, y) is inside (even–odd rule).
  [[nodiscard]] bool contains(long double x, long double y) const noexcept;
  /// Σ |signedShoelaceArea(ring)| over the rings.
  [[nodiscard]] long double area() const noexcept { return area_; }
  /// Σ signedShoelaceArea(ring).
  [[nodiscard]] long double signedArea() const noexcept { return signedArea_; }
  /// The bounding box of the vertices.
  [[nodiscard]] const PhysicalRect& bounds() const noexcept { return bounds_; }

 private:
  struct Cell {
    bool centreInside = false;
    std::vector<int> edges;
  };
  [[nodiscard]] int column(long double x) const noexcept;
  [[nodiscard]] int row(long double y) const noexcept;

  void build(int gridCells);

  std::vector<PhysicalPoint> vertices_;       ///< all rings' vertices, ring after ring
  std::vector<std::pair<int, int>> edges_;    ///< vertex indices of each edge (a ring's last vertex joins its first)
  PhysicalRect bounds_;
  long double area_ = 0;
  long double signedArea_ = 0;
  int columns_ = 1;
  int rows_ = 1;
  long double cellWidth_ = 1;
  long double cellHeight_ = 1;
  std::vector<Cell> cells_;
};

}  // namespace archipelago
