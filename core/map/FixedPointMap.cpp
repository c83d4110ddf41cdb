#include "core/map/FixedPointMap.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <stdexcept>

// The coefficients must be computed exactly as docs/design.md, "Arithmetic contract", orders them; core is compiled with
// -ffp-contract=off so that no FMA contraction changes a rounding.

namespace archipelago {

namespace {
// computeCoefficients() without throwing: the coefficients, or why there are none.
std::optional<ParameterError> coefficientsOf(const MapParameters& p, MapCoefficients& k) {
  if (auto errors = validationErrors(p); !errors.empty()) return std::move(errors.front());
  const double L = p.xmax - p.xmin;
  const double a = 2 * L;
  const double b = -4 * p.xmin;
  const double c = 2 * (p.xmin * p.xmin - p.K) / L;
  // Bounded: once 2L or 2(xmin² − K)/L overflows to infinity no m fits, and the loop below says so.
  int m = 0;
  while (m <= FixedPointMap::kMaxShift && !(a < std::ldexp(1.0, m) && b < std::ldexp(1.0, m) && c < std::ldexp(1.0, m)))
    ++m;
  for (;; ++m) {
    if (m > FixedPointMap::kMaxShift) {
      return ParameterError{{"xmin", "xmax"},
                            "the box is too large: max(2L, −4 xmin, 2(xmin² − K)/L) = " +
                                shortestDecimal(std::max({a, b, c})) + " must be < " +
                                shortestDecimal(std::ldexp(1.0, FixedPointMap::kMaxShift)) +
                                " for the 64-bit fixed-point map"};
    }
    k = {std::llround(std::ldexp(a, FixedPointMap::kBits - m)), std::llround(std::ldexp(b, FixedPointMap::kBits - m)),
         std::llround(std::ldexp(c, FixedPointMap::kBits - m)), m};
    const auto one = static_cast<std::int64_t>(FixedPointMap::kOne);
    if (k.A < one && k.B < one && k.C < one) return std::nullopt;
  }
}
}  // namespace

MapCoefficients computeCoefficients(const MapParameters& p) {
  MapCoefficients k;
  if (auto e = coefficientsOf(p, k)) throw std::invalid_argument(e->message);
  return k;
}

std::optional<std::string> mapError(const MapParameters& p) {
  MapCoefficients unused;
  if (auto e = coefficientsOf(p, unused)) return std::move(e->message);
  return std::nullopt;
}

std::vector<ParameterError> mapErrors(const MapParameters& p) {
  std::vector<ParameterError> errors = validationErrors(p);
  MapCoefficients unused;
  if (errors.empty())
    if (auto e = coefficientsOf(p, unused)) errors.push_back(std::move(*e));
  return errors;
}

FixedPointMap::FixedPointMap(const MapParameters& p) : params_(p), coef_(computeCoefficients(p)) {}

long double FixedPointMap::gridUnit() const noexcept {
  return std::ldexp(static_cast<long double>(params_.width()), -kBits);
}

UnitState FixedPointMap::toUnit(long double x, long double y) const noexcept {
  const long double L = params_.width();
  auto reduce = [](long double v) {  // v in units of the box; nearest grid point, reduced mod 1
    v -= std::floor(v);
    const long double scaled = std::nearbyint(std::ldexp(v, kBits));
    return static_cast<std::uint64_t>(scaled) & kMask;
  };
  return {reduce((x - params_.xmin) / L), reduce((y + L / 2) / L)};
}

PhysicalPoint FixedPointMap::toPhysical(const UnitState& z) const noexcept {
  const long double L = params_.width();
  return {params_.xmin + L * std::ldexp(static_cast<long double>(z.X), -kBits),
          -L / 2 + L * std::ldexp(static_cast<long double>(z.Y), -kBits)};
}

std::optional<std::string> unitCoordinateError(std::string_view name, std::optional<std::uint64_t> value,
                                               std::string_view text) {
  if (value && *value < fixedpoint::kOne) return std::nullopt;
  return std::string(name) + " = " + std::string(text) + " must lie in [0, 2^52) (unit coordinates)";
}

}  // namespace archipelago
