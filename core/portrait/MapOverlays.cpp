#include "core/portrait/MapOverlays.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <stdexcept>

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
  if (steps > 100'000'000) throw std::invalid_argument("traceOrbit: steps must be <= 10^8");
  const FixedPointMap N(map);
  UnitState z = N.toUnit(x, y);
  std::vector<PhysicalPoint> points;
  points.reserve(static_cast<std::size_t>(steps) + 1);
  points.push_back(N.toPhysical(z));
  for (std::uint64_t i = 0; i < steps; ++i) {
    if (backward) N.backward(z);
    else N.forward(z);
    points.push_back(N.toPhysical(z));
  }
  return points;
}

void writeOrbitCsv(std::ostream& out, const MapParameters& map, long double x, long double y, std::uint64_t steps,
                   bool backward) {
  const FixedPointMap N(map);  // throws std::invalid_argument with the rule that failed
  UnitState z = N.toUnit(x, y);
  out << "step,x,y,X,Y,wrapped\n";
  char line[160];
  const auto row = [&](std::uint64_t step, bool wrapped) {
    const PhysicalPoint p = N.toPhysical(z);
    std::snprintf(line, sizeof line, "%llu,%.21Lg,%.21Lg,%llu,%llu,%d\n", static_cast<unsigned long long>(step), p.x,
                  p.y, static_cast<unsigned long long>(z.X), static_cast<unsigned long long>(z.Y), wrapped ? 1 : 0);
    out << line;
  };
  row(0, false);
  for (std::uint64_t i = 1; i <= steps; ++i) row(i, backward ? N.backward(z) : N.forward(z));
}

}  // namespace archipelago
