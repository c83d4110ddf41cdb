#include "core/portrait/MapOverlays.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>

#include "core/map/OrbitIterator.hpp"

namespace archipelago {

std::vector<FixedPoint> fixedPoints(const MapParameters& map) {
  validate(map);
  std::vector<FixedPoint> points;
  if (map.K < 0) return points;
  const double L = map.width();
  const double root = std::sqrt(map.K);
  for (double base : {-root, root}) {
    // All copies base + nL in [xmin, xmax).
    for (double n = std::ceil((map.xmin - base) / L); base + n * L < map.xmax; n += 1) {
      const double x = base + n * L;
      if (x < map.xmin) continue;
      points.push_back({{x, 0}, x > -1 && x < 0});
    }
  }
  std::sort(points.begin(), points.end(),
            [](const FixedPoint& a, const FixedPoint& b) { return a.position.x < b.position.x; });
  return points;
}

std::vector<PhysicalPoint> traceOrbit(const MapParameters& map, long double x, long double y, std::uint64_t steps,
                                      bool backward) {
  const OrbitRequest r = orbitRequestAt(map, x, y, steps, backward);
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const FixedPointMap N(map);
  std::vector<PhysicalPoint> points;
  points.reserve(static_cast<std::size_t>(steps) + 1);
  iterateOrbit(r, [&](std::uint64_t, const UnitState& z, bool) { points.push_back(N.toPhysical(z)); });
  return points;
}

void writeOrbitCsv(std::ostream& out, const MapParameters& map, long double x, long double y, std::uint64_t steps,
                   bool backward) {
  // core's one orbit loop and its rules (the map's, the length limit), checked before the header is written.
  const OrbitRequest r = orbitRequestAt(map, x, y, steps, backward);
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const FixedPointMap N(map);
  out << "step,x,y,X,Y,wrapped\n";
  char line[160];
  iterateOrbit(r, [&](std::uint64_t step, const UnitState& z, bool wrapped) {
    const PhysicalPoint p = N.toPhysical(z);
    std::snprintf(line, sizeof line, "%llu,%.21Lg,%.21Lg,%llu,%llu,%d\n", static_cast<unsigned long long>(step), p.x,
                  p.y, static_cast<unsigned long long>(z.X), static_cast<unsigned long long>(z.Y), wrapped ? 1 : 0);
    out << line;
  });
}

}  // namespace archipelago
