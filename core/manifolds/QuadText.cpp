#include "core/manifolds/QuadText.hpp"

#include <algorithm>
#include <string>

namespace archipelago {

std::string quadCoordinateText(quad v, quad other, int digits) {
  const quad a = v < 0 ? -v : v, b = other < 0 ? -other : other;
  quad below = a > b ? a : b;
  for (int i = 0; i < digits; ++i) below /= 10;
  return a < below ? std::string("0") : quadText(v, digits);
}

std::string quadText(quad v, int digits) {
  // Exact decimal expansion by repeated multiplication: libquadmath is not linked (GCC's libgcc gives the
  // arithmetic only).  |v| < 1e300 here; digits ≤ 36.
  if (v != v) return "nan";
  std::string sign = v < 0 ? "-" : "";
  if (v < 0) v = -v;
  if (v == 0) return "0";
  int exponent = 0;
  while (v >= 10) {
    v /= 10;
    ++exponent;
  }
  while (v < 1) {
    v *= 10;
    --exponent;
  }
  std::string mantissa;
  for (int i = 0; i < digits; ++i) {
    const int d = static_cast<int>(v);
    mantissa += static_cast<char>('0' + std::min(d, 9));
    v = (v - d) * 10;
  }
  if (exponent >= -6 && exponent < 0)  // 0.000ddd…: plain decimal for the sizes of areas and actions
    return sign + "0." + std::string(static_cast<std::size_t>(-exponent - 1), '0') + mantissa;
  if (exponent >= 0 && exponent < digits - 1)
    return sign + mantissa.substr(0, static_cast<std::size_t>(exponent) + 1) + "." +
           mantissa.substr(static_cast<std::size_t>(exponent) + 1);
  return sign + mantissa.substr(0, 1) + "." + mantissa.substr(1) + "e" + std::to_string(exponent);
}

}  // namespace archipelago
