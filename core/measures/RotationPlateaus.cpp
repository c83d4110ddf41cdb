#include "core/measures/RotationPlateaus.hpp"

#include <algorithm>
#include <cmath>

namespace archipelago {

std::vector<RotationPlateau> rotationPlateaus(const RotationProfile& profile, std::size_t minPoints) {
  minPoints = std::max<std::size_t>(minPoints, 1);
  std::vector<RotationPlateau> plateaus;
  const auto& points = profile.points;
  for (std::size_t i = 0; i < points.size();) {
    if (!points[i].rational) {
      ++i;
      continue;
    }
    const Rational r = *points[i].rational;
    const double value = static_cast<double>(r.p) / static_cast<double>(r.q);
    const auto onIt = [&](const RotationProfilePoint& p) {
      if (p.rational) return *p.rational == r;
      return p.measure.verdict == OrbitVerdict::Regular && std::fabs(p.measure.value - value) <= kPlateauTolerance;
    };
    std::size_t j = i;
    double sum = 0;
    while (j < points.size() && onIt(points[j])) sum += points[j++].measure.value;
    if (j - i >= minPoints) plateaus.push_back({i, j - 1, r, sum / static_cast<double>(j - i)});
    i = j;
  }
  return plateaus;
}

}  // namespace archipelago
