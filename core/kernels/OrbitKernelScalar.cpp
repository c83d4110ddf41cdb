// The portable scalar orbit iteration (VectorKernels.hpp): the reference the vector paths are tested against.

#include "kernels/VectorKernels.hpp"

namespace archipelago {

void iterateOrbitsScalar(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                         std::uint64_t steps, UnitState* trace) {
  const std::size_t n = orbits.size();
  // Step every orbit once per pass: the independent orbits overlap their multiply latencies.
  for (std::uint64_t j = 0; j < steps; ++j) {
    if (direction == MapDirection::backward) {
      for (auto& z : orbits) backwardStep(coefficients, z);
    } else {
      for (auto& z : orbits) forwardStep(coefficients, z);
    }
    if (trace)
      for (std::size_t i = 0; i < n; ++i) trace[j * n + i] = orbits[i];
  }
}

std::uint64_t binDensityScalar(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                               const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries) {
  std::uint64_t binned = 0;
  for (std::uint64_t j = 0; j < steps; ++j) {
    for (auto& z : orbits) forwardStep(coefficients, z);
    for (const auto& z : orbits) {
      const std::int64_t p = grid.pixelOf(z);
      if (p < 0) continue;
      binned += 1;
      if (++counts[p] == 0) carries.push_back(static_cast<std::uint32_t>(p));
    }
  }
  return binned;
}

}  // namespace archipelago
