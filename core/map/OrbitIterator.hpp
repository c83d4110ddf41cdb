#pragma once
/// \file OrbitIterator.hpp
/// \brief The one loop over an orbit of the exact map (issue 35, item 4): forward (N) or backward (N⁻¹), from a
/// physical or a lattice point, with the one length limit (core/limits: limits::kOrbitLength points held in
/// memory).  The CLI's `orbit`, Python's `orbit()`, the GUI's launched orbits and the overlays all iterate here.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/limits/Limits.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/map/MapParameters.hpp"

namespace archipelago {

struct OrbitRequest {
  MapParameters map;
  UnitState start;             ///< the first point, on the lattice (orbitRequestAt() places a physical point)
  std::uint64_t steps = 1000;  ///< steps after the start: steps + 1 points, 0 … limits::kOrbitLength
  bool backward = false;       ///< N⁻¹ instead of N
};

/// A request from a physical point (x, y), placed on the lattice by FixedPointMap::toUnit (throws
/// std::invalid_argument, as FixedPointMap does, when the map is invalid).
[[nodiscard]] OrbitRequest orbitRequestAt(const MapParameters& map, long double x, long double y, std::uint64_t steps,
                                          bool backward = false);

/// The map's rule, a start off the lattice ("X0 = … must lie in [0, 2^52)"), or the length limit
/// ("steps = … must lie in [0, 100000000]"); nothing when the request is valid.
[[nodiscard]] std::optional<std::string> validationError(const OrbitRequest& r);

/// Calls visit(step, z, wrapped) for step = 0 (the start, wrapped = false), 1, …, r.steps; `wrapped` says that the
/// step from step − 1 wrapped around the torus.  visit may return false to stop early (a void visit never stops).
/// Throws std::invalid_argument with validationError()'s message.
template <class Visit>
void iterateOrbit(const OrbitRequest& r, Visit&& visit) {
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const FixedPointMap N(r.map);
  UnitState z = r.start;
  auto call = [&](std::uint64_t step, bool wrapped) {
    if constexpr (std::is_void_v<decltype(visit(step, z, wrapped))>) {
      visit(step, static_cast<const UnitState&>(z), wrapped);
      return true;
    } else {
      return static_cast<bool>(visit(step, static_cast<const UnitState&>(z), wrapped));
    }
  };
  if (!call(0, false)) return;
  for (std::uint64_t i = 1; i <= r.steps; ++i) {
    const bool wrapped = r.backward ? N.backward(z) : N.forward(z);
    if (!call(i, wrapped)) return;
  }
}

/// How iteratePower() ended.
enum class PowerOrbitEnd {
  done,     ///< all `count` applications of Qⁿ
  wrapped,  ///< a step wrapped around the torus (the orbit left the box, where Q* ≠ Q): z is not visited
  stopped,  ///< visit returned false
};

/// The loop over a power of the map (issue 51: loops over the map stood in the atlas and the box check): applies
/// Qⁿ (n = `power` ≥ 1 steps of N) `count` times from `start`, calling visit(k, z) after the k-th application
/// (k = 1 … count) until visit returns false or a step wraps.  The rotation and trapping kernels keep their own
/// vectorised loops (core/kernels, core/measures' drivers).
template <class Visit>
PowerOrbitEnd iteratePower(const FixedPointMap& N, UnitState z, std::uint64_t power, std::uint64_t count, Visit&& visit) {
  for (std::uint64_t k = 1; k <= count; ++k) {
    for (std::uint64_t j = 0; j < power; ++j)
      if (N.forward(z)) return PowerOrbitEnd::wrapped;
    if (!visit(k, static_cast<const UnitState&>(z))) return PowerOrbitEnd::stopped;
  }
  return PowerOrbitEnd::done;
}

}  // namespace archipelago
