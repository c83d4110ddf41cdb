#include "core/session/OrbitFamily.hpp"

#include <cmath>
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/limits/Limits.hpp"
#include "core/session/SessionFile.hpp"

namespace archipelago {

std::vector<PhysicalPoint> orbitFamilyStarts(const OrbitFamily& f, std::size_t launched) {
  for (const long double v : {f.from.x, f.from.y, f.to.x, f.to.y})
    if (!std::isfinite(v)) throw std::invalid_argument("the corners of a line or grid of orbits must be finite numbers");
  const long long most = static_cast<long long>(kMaxSessionOrbits);
  for (const auto& [name, n] : {std::pair{"orbits per row", f.columns}, std::pair{"rows of orbits", f.rows}})
    if (const auto e = rangeError(name, n, 1, most)) throw std::invalid_argument(*e);
  const long long free = most - static_cast<long long>(std::min<std::size_t>(launched, kMaxSessionOrbits));
  const std::uint64_t count = f.columns * f.rows;  // each ≤ 500: no overflow
  if (const auto e = rangeError("orbits launched at once", count, 1, free,
                                "the portrait keeps at most " + std::to_string(kMaxSessionOrbits) + " launched orbits; " +
                                    std::to_string(launched) + " launched already"))
    throw std::invalid_argument(*e);
  const auto at = [](long double a, long double b, std::uint64_t i, std::uint64_t n) {
    if (n == 1 || i == 0) return a;
    if (i + 1 == n) return b;  // the far end exactly as typed
    return a + (b - a) * static_cast<long double>(i) / static_cast<long double>(n - 1);
  };
  std::vector<PhysicalPoint> starts;
  starts.reserve(count);
  for (std::uint64_t r = 0; r < f.rows; ++r)
    for (std::uint64_t c = 0; c < f.columns; ++c) {
      if (f.rows == 1)  // a line: along the segment from → to
        starts.push_back({at(f.from.x, f.to.x, c, f.columns), at(f.from.y, f.to.y, c, f.columns)});
      else
        starts.push_back({at(f.from.x, f.to.x, c, f.columns), at(f.from.y, f.to.y, r, f.rows)});
    }
  return starts;
}

}  // namespace archipelago
