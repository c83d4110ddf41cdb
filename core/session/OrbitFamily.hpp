#pragma once
/// \file OrbitFamily.hpp
/// \brief Many orbits launched at once (issue 37, finding 15): a line of n starts between two points, or a grid of
/// n × m starts over the rectangle two corners span.  Each start is then launched, drawn and measured like a clicked
/// one; their number is bounded by the launched orbits' one bound (kMaxSessionOrbits: what a session holds, and so
/// what the portrait keeps), counting those already launched.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/map/FixedPointMap.hpp"

namespace archipelago {

/// A line (rows = 1) or a grid of starts: `columns` points from `from` to `to` along x (the line's points along
/// the segment between them), `rows` rows from from.y to to.y.  A count of 1 puts that coordinate at `from`.
struct OrbitFamily {
  PhysicalPoint from, to;
  std::uint64_t columns = 1;  ///< orbits of a line, or of a grid's row
  std::uint64_t rows = 1;     ///< 1: a line from `from` to `to`
};

/// The starts, row by row: the i-th of n along an axis at from + (to − from)·i/(n − 1), the ends exactly `from`
/// and `to`.  Throws
/// std::invalid_argument with core/limits' wording when a count is 0, when the family and the `launched` orbits
/// already shown together exceed kMaxSessionOrbits, or when a coordinate is not finite.  Whether each start lies
/// in the box is its own orbit's rule (it is measured, or says why not).
[[nodiscard]] std::vector<PhysicalPoint> orbitFamilyStarts(const OrbitFamily& family, std::size_t launched = 0);

}  // namespace archipelago
