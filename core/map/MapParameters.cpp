#include "core/map/MapParameters.hpp"

#include <cmath>
#include <charconv>
#include <stdexcept>

#include "core/map/FixedPointMap.hpp"

namespace archipelago {

std::string shortestDecimal(double v) {
  char text[32];
  const auto result = std::to_chars(text, text + sizeof text, v);  // shortest round trip (C++17)
  return std::string(text, result.ptr);
}

std::vector<ParameterError> validationErrors(const MapParameters& p) {
  std::vector<ParameterError> errors;
  const auto add = [&](std::vector<std::string> fields, std::string message) {
    errors.push_back({std::move(fields), std::move(message)});
  };
  if (!std::isfinite(p.K)) add({"K"}, "K = " + shortestDecimal(p.K) + " must be a finite number");
  if (!std::isfinite(p.xmin)) add({"xmin"}, "xmin = " + shortestDecimal(p.xmin) + " must be a finite number");
  if (!std::isfinite(p.xmax)) add({"xmax"}, "xmax = " + shortestDecimal(p.xmax) + " must be a finite number");
  if (std::isfinite(p.K) && std::isfinite(p.xmin)) {
    // The largest K any box holds (issue 53, finding 17: K = 1e300 marked xmin, "must be < −√K = -1e+150", though
    // no xmin could do): xmin < −√K, and the 64-bit map's −4 xmin < 2^kMaxShift, need √K < 2^(kMaxShift − 2).
    const double maxK = std::ldexp(1.0, 2 * (FixedPointMap::kMaxShift - 2));
    if (p.K >= maxK) {
      add({"K"}, "K = " + shortestDecimal(p.K) + " is too large: it must be < " + shortestDecimal(maxK) +
                     ", as the box must hold the elliptic fixed point (xmin < −√K) and the 64-bit fixed-point map "
                     "holds only boxes with −4 xmin < " + shortestDecimal(std::ldexp(1.0, FixedPointMap::kMaxShift)) +
                     " (appendix B)");
    } else if (p.K >= 0) {
      const double edge = -std::sqrt(p.K);
      if (!(p.xmin < edge))
        add({"xmin"}, "xmin = " + shortestDecimal(p.xmin) + " must be < −√K = " + shortestDecimal(edge) +
                          " (the elliptic fixed point must lie inside the box; appendix B)");
    } else if (!(p.xmin < 0)) {
      add({"xmin"}, "xmin = " + shortestDecimal(p.xmin) + " must be < 0 when K < 0 (so that b = −4 xmin > 0; appendix B)");
    }
  }
  // After xmin's own rule: xmin = 0.6 > xmax = 0.5 is first xmin's error (it must be < −√K), then both edges'.
  if (std::isfinite(p.xmin) && std::isfinite(p.xmax)) {
    if (!(p.xmax > p.xmin))
      add({"xmax", "xmin"}, "xmax = " + shortestDecimal(p.xmax) + " must be > xmin = " + shortestDecimal(p.xmin) +
                                " (the box width L = xmax − xmin must be > 0)");
    else if (!std::isfinite(p.width()))
      add({"xmax", "xmin"}, "xmax − xmin = " + shortestDecimal(p.width()) + " must be a finite number");
  }
  return errors;
}

std::optional<std::string> validationError(const MapParameters& p) {
  auto errors = validationErrors(p);
  if (errors.empty()) return std::nullopt;
  return std::move(errors.front().message);
}

void validate(const MapParameters& p) {
  if (auto error = validationError(p)) throw std::invalid_argument(*error);
}

}  // namespace archipelago
