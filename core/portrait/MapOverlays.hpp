#pragma once
/// \file MapOverlays.hpp
/// \brief What a portrait view draws over the raster: the fixed points of Q* and single orbits.

#include <cstdint>
#include <iosfwd>
#include <vector>

#include "core/map/FixedPointMap.hpp"

namespace archipelago {

/// A fixed point of Q (eq. qu): y = 0, x² = K.
struct FixedPoint {
  PhysicalPoint position;
  bool elliptic = false;  ///< x = −√K (the centre of the central island, stable for 0 < K < 1); else hyperbolic
};

/// The fixed points of Q* inside the box [xmin, xmax): (±√K + nL, 0) for every integer n (g is periodic in
/// x with period L, eq. gstar).  None when K < 0.  Elliptic means |trace| < 2 of the Jacobian
/// [[1 + 4x, 1], [4x, 1]], i.e. −1 < x < 0.
[[nodiscard]] std::vector<FixedPoint> fixedPoints(const MapParameters& map);

/// The orbit of the exact map N (N⁻¹ when `backward`) from the grid point nearest (x, y): the start and `steps`
/// images, in physical coordinates, by core's one orbit loop (core/map/OrbitIterator.hpp; `steps` at most
/// limits::kOrbitLength).
[[nodiscard]] std::vector<PhysicalPoint> traceOrbit(const MapParameters& map, long double x, long double y,
                                                    std::uint64_t steps, bool backward = false);

/// The same orbit as CSV, `archipelago-cli orbit`'s output: "step,x,y,X,Y,wrapped" and one row per point (step 0
/// is the start; x, y physical to 21 digits, X, Y the exact grid state, wrapped = 1 when that step wrapped around
/// the box).  One writer for the CLI and the GUI's Export CSV of a launched orbit (issue 37, finding 20).
void writeOrbitCsv(std::ostream& out, const MapParameters& map, long double x, long double y, std::uint64_t steps,
                   bool backward = false);

}  // namespace archipelago
