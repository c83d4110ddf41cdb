#pragma once
/// \file ScalarLanes.hpp
/// \brief The scalar lane loop: orbits stepped by N or N⁻¹ several at a time in lockstep, visiting every state.
///
/// The three products of a step form one long dependency chain (ScalarStep.hpp); stepping kScalarLanes
/// independent orbits together lets the CPU overlap them.  The portable orbit kernels (OrbitKernelScalar.cpp)
/// and the Orbits mode of portraits (PortraitRenderer.cpp), which must see every point, share this loop.

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/kernels/VectorKernels.hpp"
#include "core/map/ScalarStep.hpp"

namespace archipelago {

inline constexpr std::size_t kScalarLanes = 8;

/// Advances the `Lanes` orbits at `orbits` by `steps` steps; after step j (0-based), visit(j, X, Y) sees the
/// lanes' states.  When `wrapped` is not null, wrapped[l] |= 1 when orbit l wrapped (FixedPointMap.hpp).
template <std::size_t Lanes, class Visit>
void stepLanes(const ScalarStep& c, MapDirection direction, UnitState* orbits, std::uint64_t steps,
               std::uint8_t* wrapped, Visit&& visit) {
  std::uint64_t X[Lanes], Y[Lanes], wrap[Lanes] = {};
  for (std::size_t l = 0; l < Lanes; ++l) {
    X[l] = orbits[l].X;
    Y[l] = orbits[l].Y;
  }
  for (std::uint64_t j = 0; j < steps; ++j) {
    if (direction == MapDirection::backward) {
      ARCHIPELAGO_UNROLL_LANES
      for (std::size_t l = 0; l < Lanes; ++l) c.backward(X[l], Y[l], wrap[l]);
    } else if (wrapped) {
      ARCHIPELAGO_UNROLL_LANES
      for (std::size_t l = 0; l < Lanes; ++l) c.forward(X[l], Y[l], wrap[l]);
    } else {
      ARCHIPELAGO_UNROLL_LANES
      for (std::size_t l = 0; l < Lanes; ++l) c.forward(X[l], Y[l]);
    }
    visit(j, X, Y);
  }
  for (std::size_t l = 0; l < Lanes; ++l) orbits[l] = {X[l], Y[l]};
  if (wrapped)
    for (std::size_t l = 0; l < Lanes; ++l) wrapped[l] |= wrap[l] >= fixedpoint::kOne ? 1 : 0;
}

/// stepLanes() over all `orbits`, kScalarLanes at a time and the remainder one by one; visit(first, lanes, j,
/// X, Y) sees orbits first … first + lanes − 1 after step j.  `wrapped`: null, or one flag per orbit.
template <class Visit>
void stepAllLanes(const ScalarStep& c, MapDirection direction, std::span<UnitState> orbits, std::uint64_t steps,
                  std::uint8_t* wrapped, Visit&& visit) {
  std::size_t first = 0;
  for (; first + kScalarLanes <= orbits.size(); first += kScalarLanes)
    stepLanes<kScalarLanes>(c, direction, orbits.data() + first, steps, wrapped ? wrapped + first : nullptr,
                            [&](std::uint64_t j, const std::uint64_t* X, const std::uint64_t* Y) {
                              visit(first, kScalarLanes, j, X, Y);
                            });
  for (; first < orbits.size(); ++first)
    stepLanes<1>(c, direction, orbits.data() + first, steps, wrapped ? wrapped + first : nullptr,
                 [&](std::uint64_t j, const std::uint64_t* X, const std::uint64_t* Y) { visit(first, 1, j, X, Y); });
}

}  // namespace archipelago
