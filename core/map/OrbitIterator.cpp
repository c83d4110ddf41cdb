#include "core/map/OrbitIterator.hpp"

namespace archipelago {

OrbitRequest orbitRequestAt(const MapParameters& map, long double x, long double y, std::uint64_t steps,
                            bool backward) {
  OrbitRequest r;
  r.map = map;
  r.start = FixedPointMap(map).toUnit(x, y);
  r.steps = steps;
  r.backward = backward;
  return r;
}

std::optional<std::string> validationError(const OrbitRequest& r) {
  if (auto e = mapError(r.map)) return e;
  if (r.start.X >= FixedPointMap::kOne || r.start.Y >= FixedPointMap::kOne)
    return std::string("the start (X0, Y0) must lie in [0, 2^52) (unit coordinates)");
  return rangeError("steps", r.steps, 0, static_cast<long long>(limits::kOrbitLength));
}

}  // namespace archipelago
