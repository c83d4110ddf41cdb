#include "core/periodic/FloquetFrame.hpp"

#include <cmath>
#include <numbers>

namespace archipelago {

PhysicalPoint FloquetFrame::normal(PhysicalPoint v) const noexcept {
  return {toNormal.xx * v.x + toNormal.xy * v.y, toNormal.yx * v.x + toNormal.yy * v.y};
}

PhysicalPoint FloquetFrame::physical(PhysicalPoint u) const noexcept {
  return {fromNormal.xx * u.x + fromNormal.xy * u.y, fromNormal.yx * u.x + fromNormal.yy * u.y};
}

std::optional<FloquetFrame> floquetFrame(long double K, PhysicalPoint c, long n) {
  smooth::Matrix2<long double> M;
  (void)smooth::iterate(K, smooth::Point<long double>{c.x, c.y}, n, &M);
  const long double cosine = M.trace() / 2;
  if (!(std::fabs(cosine) < 1)) return std::nullopt;
  const long double sine = std::sqrt(1 - cosine * cosine);
  const long double a = (M.xx - cosine) / sine, b = M.xy / sine, g = M.yx / sine;  // G = [[a, b], [g, −a]]
  const long double sign = g < 0 ? 1 : -1;  // S = ±J·G = ±[[−g, a], [a, b]], positive definite
  const long double s11 = -sign * g, s12 = sign * a, s22 = sign * b;
  if (!(s11 > 0)) return std::nullopt;
  FloquetFrame f;
  const long double r11 = std::sqrt(s11), r12 = s12 / r11, r22 = std::sqrt(std::max(s22 - r12 * r12, 0.0L));
  if (!(r22 > 0)) return std::nullopt;
  f.toNormal = {r11, r12, 0, r22};
  f.fromNormal = {1 / r11, -r12 / (r11 * r22), 0, 1 / r22};
  f.rotation = std::acos(cosine) / (2 * std::numbers::pi_v<long double>);
  const long double mean = (s11 + s22) / 2, spread = std::hypot((s11 - s22) / 2, s12);  // S's eigenvalues: mean ± spread
  f.axisRatio = std::sqrt((mean + spread) / (mean - spread));
  // The linear map's largest step of the physical angle: ½ − atan(cot(πν)/r)/π turn (in the ellipses' axes a point
  // at normal-form angle φ lies at physical angle atan(tan φ / r); the largest step straddles the short axis).
  f.foldMargin = std::atan(1 / (std::tan(std::numbers::pi_v<long double> * f.rotation) * f.axisRatio)) /
                 std::numbers::pi_v<long double>;
  return f;
}

}  // namespace archipelago
