#pragma once
/// \file RotationPlateaus.hpp
/// \brief The plateaus of a rotation profile (issue 37, finding 17): the runs of consecutive points that name the
/// same p/q — the island chains the line crosses (a plateau at p/q is a chain of period q).  The GUI labels them;
/// `rotation --line` writes the rational of every point (RotationProfile.hpp), from which they follow.

#include <cstddef>
#include <string>
#include <vector>

#include "core/measures/RotationProfile.hpp"

namespace archipelago {

struct RotationPlateau {
  std::size_t first = 0, last = 0;  ///< indices of the profile's points, first ≤ last
  Rational rational;                ///< the p/q every point of the run names
  double rotation = 0;              ///< the mean measured rotation number over the run (turns per step)
};

/// Points a run needs to be a plateau by default: a lone point naming a small-denominator rational is not a chain.
inline constexpr std::size_t kPlateauMinPoints = 3;
/// How far from p/q (turns) a regular point may measure and still lie on its plateau without naming p/q itself: an
/// orbit about a sub-island of the chain converges more slowly (13 digits, not 16) and names no rational at its own
/// accuracy, though it turns at p/q about the centre to 10⁻¹² (K = 0.1's six islands: `rotation --line`).
inline constexpr double kPlateauTolerance = 1e-9;

/// The plateaus along the profile, in order.  A plateau starts at a point that names p/q and goes on over the
/// following regular points that name p/q or no rational and measure within kPlateauTolerance of p/q; it ends at
/// the first other point (another p/q, farther, chaotic or escaping).  Runs of fewer than `minPoints` (≥ 1) points
/// are not plateaus.
[[nodiscard]] std::vector<RotationPlateau> rotationPlateaus(const RotationProfile& profile,
                                                            std::size_t minPoints = kPlateauMinPoints);

}  // namespace archipelago
