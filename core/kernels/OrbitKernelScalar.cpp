// The portable scalar orbit iteration (VectorKernels.hpp): the reference the vector paths are tested against.
// Orbits are stepped kScalarLanes at a time in lockstep (ScalarLanes.hpp), so that their products overlap.

#include "core/kernels/ScalarLanes.hpp"

namespace archipelago {

void iterateOrbitsScalar(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                         std::uint64_t steps, UnitState* trace) {
  const ScalarStep c(coefficients);
  const std::size_t n = orbits.size();
  stepAllLanes(c, direction, orbits, steps, nullptr,
               [&](std::size_t first, std::size_t lanes, std::uint64_t j, const std::uint64_t* X, const std::uint64_t* Y) {
                 if (!trace) return;
                 for (std::size_t l = 0; l < lanes; ++l) trace[j * n + first + l] = {X[l], Y[l]};
               });
}

std::uint64_t binDensityScalar(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                               const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries) {
  const ScalarStep c(coefficients);
  std::uint64_t binned = 0;
  stepAllLanes(c, MapDirection::forward, orbits, steps, nullptr,
               [&](std::size_t, std::size_t lanes, std::uint64_t, const std::uint64_t* X, const std::uint64_t* Y) {
                 for (std::size_t l = 0; l < lanes; ++l) {
                   const std::int64_t p = grid.pixelOf({X[l], Y[l]});
                   if (p < 0) continue;
                   binned += 1;
                   if (++counts[p] == 0) carries.push_back(static_cast<std::uint32_t>(p));
                 }
               });
  return binned;
}

}  // namespace archipelago
