// The portable scalar orbit iteration (VectorKernels.hpp): the reference the vector paths are tested against.
// Orbits are stepped kLanes at a time in lockstep (ScalarStep.hpp), so that their products overlap.

#include <algorithm>

#include "kernels/VectorKernels.hpp"
#include "map/ScalarStep.hpp"

namespace archipelago {

namespace {
constexpr std::size_t kLanes = 8;

/// Advances n ≤ kLanes orbits by `steps` steps; after each, `visit(j, X, Y)` sees the lanes' states.
template <std::size_t Lanes, class Visit>
void stepLanes(const ScalarStep& c, MapDirection direction, UnitState* orbits, std::uint64_t steps, Visit&& visit) {
  std::uint64_t X[Lanes], Y[Lanes], unused[Lanes] = {};
  for (std::size_t l = 0; l < Lanes; ++l) {
    X[l] = orbits[l].X;
    Y[l] = orbits[l].Y;
  }
  for (std::uint64_t j = 0; j < steps; ++j) {
    if (direction == MapDirection::backward) {
      ARCHIPELAGO_UNROLL_LANES
      for (std::size_t l = 0; l < Lanes; ++l) c.backward(X[l], Y[l], unused[l]);
    } else {
      ARCHIPELAGO_UNROLL_LANES
      for (std::size_t l = 0; l < Lanes; ++l) c.forward(X[l], Y[l]);
    }
    visit(j, X, Y);
  }
  for (std::size_t l = 0; l < Lanes; ++l) orbits[l] = {X[l], Y[l]};
}

/// Runs stepLanes over all orbits, kLanes at a time and the remainder one by one; visit(first, lanes, j, X, Y).
template <class Visit>
void stepAll(const ScalarStep& c, MapDirection direction, std::span<UnitState> orbits, std::uint64_t steps,
             Visit&& visit) {
  std::size_t first = 0;
  for (; first + kLanes <= orbits.size(); first += kLanes)
    stepLanes<kLanes>(c, direction, orbits.data() + first, steps,
                      [&](std::uint64_t j, const std::uint64_t* X, const std::uint64_t* Y) { visit(first, kLanes, j, X, Y); });
  for (; first < orbits.size(); ++first)
    stepLanes<1>(c, direction, orbits.data() + first, steps,
                 [&](std::uint64_t j, const std::uint64_t* X, const std::uint64_t* Y) { visit(first, 1, j, X, Y); });
}
}  // namespace

void iterateOrbitsScalar(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                         std::uint64_t steps, UnitState* trace) {
  const ScalarStep c(coefficients);
  const std::size_t n = orbits.size();
  stepAll(c, direction, orbits, steps,
          [&](std::size_t first, std::size_t lanes, std::uint64_t j, const std::uint64_t* X, const std::uint64_t* Y) {
            if (!trace) return;
            for (std::size_t l = 0; l < lanes; ++l) trace[j * n + first + l] = {X[l], Y[l]};
          });
}

std::uint64_t binDensityScalar(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                               const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries) {
  const ScalarStep c(coefficients);
  std::uint64_t binned = 0;
  stepAll(c, MapDirection::forward, orbits, steps,
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
