#include "trapping/TrappingParameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace archipelago {

std::optional<std::string> validationError(const TrappingParameters& p) {
  if (auto e = mapError(p.map)) return e;
  std::ostringstream s;
  s.precision(17);
  if (auto e = randomizingZoneError(p.Xr)) return e;
  if (p.q < 1) return "q = 0 must be >= 1 (steps of N^-1 per block)";
  if (p.T < 1) return "T = 0 must be >= 1 (blocks per orbit)";
  if (p.T > (std::uint64_t{1} << 62)) return "T must be < 2^62 blocks";
  if (p.M < 1) return "M = 0 must be >= 1 (number of orbits)";
  if (p.subsets < 1) return "subsets = 0 must be >= 1";
  if (p.subsets > p.M) {
    s << "subsets = " << p.subsets << " must be <= M = " << p.M << " (each subset needs an orbit)";
    return s.str();
  }
  return std::nullopt;
}

void validate(const TrappingParameters& p) {
  if (auto e = validationError(p)) throw std::invalid_argument(*e);
}

std::optional<std::string> randomizingZoneError(double Xr) {
  if (std::isfinite(Xr) && Xr >= 0 && Xr < 1) return std::nullopt;
  std::ostringstream s;
  s.precision(17);
  s << "Xr = " << Xr << " must lie in [0, 1) (width of the randomizing zone in unit X)";
  return s.str();
}

std::uint64_t randomizingThreshold(double Xr) noexcept {
  return static_cast<std::uint64_t>(std::floor(std::ldexp(Xr, FixedPointMap::kBits)));
}

}  // namespace archipelago
