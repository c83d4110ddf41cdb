#pragma once
/// \file RotationProfile.hpp
/// \brief The rotation number about the centre along a segment of starting points: the staircase whose plateaus
/// are island chains (a plateau at p/q is the chain of period q; 1/6 is the paper's six islands at K = 0.1).
///
/// The points are z_i = from + i/(N − 1)·(to − from), i = 0 … N − 1 (one point, `from`, when N = 1), rounded to
/// the 52-bit grid; each is measured as the Rotation indicator measures a pixel (OrbitMeasures.hpp: the same
/// value, digits and verdict), in parallel.  A regular point also gets the rational p/q of smallest denominator
/// (at most maxDenominator) within kAccuracyFactor × 10^−digits of its rotation number
/// (ChainIdentification.hpp), when there is one: on a plateau of an island chain, the chain's p/q.

#include <cstdint>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/measures/ChainIdentification.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/provenance/Provenance.hpp"

namespace archipelago {

struct RotationProfileRequest {
  MeasureSettings measure;               ///< map, iterations, threshold, kernel (the kind is Rotation)
  PhysicalPoint from;                    ///< physical (x, y), inside the box
  PhysicalPoint to;                      ///< physical (x, y), inside the box
  std::uint32_t points = 1000;           ///< N, 1 … 10⁶
  std::int64_t maxDenominator = 1000;    ///< largest q named, 1 … 10⁶
  int threads = 0;                       ///< 0: OpenMP's default
  /// The centre (issue 37, finding 17: rotation about an island's own centre).  None: the centre (−√K, 0) and the
  /// rotation of Q, as above.  Given: a point z of an elliptic periodic orbit of period `power` (e.g. the one a
  /// click found, core/measures/PeriodicOrbitAt), and the rotation of Q^power about z, positive in the sense
  /// DQ^power turns there — as identifyChain measures each island (RotationNumber.hpp, measureRotation: scalar,
  /// one orbit per thread, 2T·power steps each).
  std::optional<PhysicalPoint> about;
  std::uint64_t power = 1;               ///< with `about`: the period n, 1 … 100000
};

/// The first violated rule, naming the field, or nothing (the measure's rules; N and maxDenominator in range;
/// both ends finite and inside the box [xmin, xmax) × [−L/2, L/2)).
[[nodiscard]] std::optional<std::string> validationError(const RotationProfileRequest& r);

struct RotationProfilePoint {
  PhysicalPoint point;              ///< the start, physical (from the rounded grid point)
  UnitState start;                  ///< the start, unit coordinates
  OrbitMeasure measure;             ///< value = rotation number (NaN unless Regular), digits, verdict
  std::optional<Rational> rational; ///< Regular points only
};

struct RotationProfile {
  std::vector<RotationProfilePoint> points;
  bool cancelled = false;  ///< stopped: the points not measured are NotComputed
};

/// Called on the calling thread after every round of points: (points measured, points in all).
using RotationProfileObserver = std::function<void(std::uint64_t done, std::uint64_t total)>;

/// Computes the profile; throws std::invalid_argument when validationError(request) is set.
[[nodiscard]] RotationProfile computeRotationProfile(const RotationProfileRequest& request,
                                                     const RotationProfileObserver& observer = {},
                                                     std::stop_token stop = {});

/// What a picture of the profile shows (issue 54: every PNG carries its parameters): mapProvenance's map, the line
/// (from, to), its points, the iterations and threshold of each measurement, the largest q named and, about an
/// island, its centre and period — the numbers the CSV's header gives.
[[nodiscard]] Provenance rotationProfileProvenance(const RotationProfileRequest& r);

/// The profile as CSV: '#' lines with the parameters, then the header "index,x,y,rotation,digits,verdict,rational"
/// and one line per point (x, y with 19 significant digits, rotation with 17, empty when the point has none),
/// written atomically (io::AtomicOutputFile).  Throws std::runtime_error naming the file on failure.
void writeRotationProfileCsv(const std::string& path, const RotationProfileRequest& request,
                             const RotationProfile& profile);

}  // namespace archipelago
