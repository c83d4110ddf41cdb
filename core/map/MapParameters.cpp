#include "core/map/MapParameters.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace archipelago {

namespace {
std::string describe(const char* name, double value, const char* rule) {
  std::ostringstream s;
  s.precision(17);
  s << name << " = " << value << ' ' << rule;
  return s.str();
}
}  // namespace

std::optional<std::string> validationError(const MapParameters& p) {
  if (!std::isfinite(p.K)) return describe("K", p.K, "must be a finite number");
  if (!std::isfinite(p.xmin)) return describe("xmin", p.xmin, "must be a finite number");
  if (!std::isfinite(p.xmax)) return describe("xmax", p.xmax, "must be a finite number");
  if (!(p.xmax > p.xmin)) {
    std::ostringstream s;
    s.precision(17);
    s << "xmax = " << p.xmax << " must be > xmin = " << p.xmin << " (the box width L = xmax - xmin must be > 0)";
    return s.str();
  }
  if (!std::isfinite(p.width())) return describe("xmax - xmin", p.width(), "must be a finite number");
  if (p.K >= 0) {
    const double edge = -std::sqrt(p.K);
    if (!(p.xmin < edge)) {
      std::ostringstream s;
      s.precision(17);
      s << "xmin = " << p.xmin << " must be < -sqrt(K) = " << edge
        << " (the elliptic fixed point must lie inside the box; appendix B)";
      return s.str();
    }
  } else if (!(p.xmin < 0)) {
    return describe("xmin", p.xmin, "must be < 0 when K < 0 (so that b = -4 xmin > 0; appendix B)");
  }
  return std::nullopt;
}

void validate(const MapParameters& p) {
  if (auto error = validationError(p)) throw std::invalid_argument(*error);
}

}  // namespace archipelago
