#include "core/periodic/OrbitClassification.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace archipelago {

OrbitClassification classifyOrbit(long double residue) {
  if (std::isnan(residue)) throw std::invalid_argument("residue = nan: the orbit has no class");
  OrbitClassification c;
  c.residue = residue;
  if (residue < 0)
    c.stability = OrbitStability::Hyperbolic;
  else if (residue > 1)
    c.stability = OrbitStability::HyperbolicReflection;
  else if (residue == 0 || residue == 1)
    c.stability = OrbitStability::Parabolic;
  else
    c.stability = OrbitStability::Elliptic;
  // cos 2πω = 1 − 2R is R = sin²(πω), so ω = atan2(√R, √(1 − R))/π: accurate at both ends (acos(1 − 2R)
  // loses R below ε, giving ω = 0 for an elliptic orbit), and exactly 0 and 1/2 at R = 0 and R = 1.
  if (residue >= 0 && residue <= 1)
    c.rotationNumber = std::atan2(std::sqrt(residue), std::sqrt(1 - residue)) / std::numbers::pi_v<long double>;
  return c;
}

const char* OrbitClassification::description() const noexcept {
  switch (stability) {
    case OrbitStability::Hyperbolic: return "hyperbolic, R < 0";
    case OrbitStability::Parabolic: return residue == 0 ? "parabolic, R = 0" : "parabolic, R = 1";
    case OrbitStability::Elliptic: return "elliptic, 0 < R < 1";
    case OrbitStability::HyperbolicReflection: return "hyperbolic with reflection, R > 1";
  }
  return "?";
}

const char* toString(OrbitStability s) noexcept {
  switch (s) {
    case OrbitStability::Hyperbolic: return "hyperbolic";
    case OrbitStability::Parabolic: return "parabolic";
    case OrbitStability::Elliptic: return "elliptic";
    case OrbitStability::HyperbolicReflection: return "hyperbolic with reflection";
  }
  return "?";
}

}  // namespace archipelago
