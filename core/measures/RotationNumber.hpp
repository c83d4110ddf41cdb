#pragma once
/// \file RotationNumber.hpp
/// \brief The rotation number of one orbit of the exact map N in its n-th iterate, about any point: the
/// measurement each level of an island-chain identification (ChainIdentification.hpp) makes.
///
/// Convention (docs/instruments.md): a rotation number is in turns per application of Qⁿ, positive in the
/// sense in which Qⁿ turns points near the elliptic point it is measured about.  About the elliptic fixed point
/// (−√K, 0) of Q (n = 1) that sense is clockwise in the (x, y) plane, and the rotation number tends to α/2π,
/// cos α = 1 − 2√K (the paper's §2; 0.1900993 at K = 0.1), near it; an island chain of period n around the
/// centre has p/n.  About an elliptic periodic orbit of period n the sense is that of DQⁿ there (clockwise
/// when its lower-left element is negative, as DQ's is at the centre), so that the rotation tends to the linear
/// rotation number ν, R = sin²(πν) (R Greene's residue, PeriodicOrbit.hpp), near it.
///
/// Method: the sub-sequence w_k = z_{kn} (k = 0 … 2T) of the exact orbit from `start`; the clockwise angle
/// increments of w_k − c, each in (−π, π] (MeasureMath.inl's portable atan2, the same arithmetic as the
/// Rotation indicator), are averaged with the weights of BirkhoffAverage.hpp over the two blocks k < T and
/// T ≤ k < 2T; the rotation number is the mean of the two averages times the sense, in turns, and the digits
/// those of their difference.  With n = 1 about (−√K, 0) this is exactly the Rotation indicator of
/// OrbitMeasures.hpp (tests/core/measures checks it bit for bit).  An orbit whose steps wrap (it left the box,
/// where Q* ≠ Q) is Escaping; one with fewer digits than the threshold is Chaotic; neither gets a number.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <stop_token>

#include "core/map/FixedPointMap.hpp"
#include "core/measures/OrbitMeasures.hpp"

namespace archipelago {

/// The point a rotation is measured about, and the sense counted as positive.
struct RotationCentre {
  PhysicalPoint units;  ///< unit coordinates (X, Y) of the point, as long doubles (it need not be a grid point)
  int sense = 1;        ///< +1: clockwise in the (x, y) plane is positive; −1: counter-clockwise
};

/// The elliptic fixed point (−√K, 0), clockwise: the centre of the paper's central island.
[[nodiscard]] RotationCentre centralFixedPoint(const MapParameters& map) noexcept;

/// One measured rotation number.
struct RotationMeasurement {
  double rotation = std::nan("");  ///< turns per application of Qⁿ, in the centre's sense; NaN unless Regular
  double digits = std::nan("");    ///< −log₁₀ |difference of the two block averages| (turns), ≤ kMaxDigits: the
                                   ///< convergence on the computed (52-bit grid) orbit, not the accuracy against Q
                                   ///< (docs/instruments.md; issue 39: 11.3 digits, 10.1 against Q, at the 138-chain)
  double difference = std::nan("");  ///< that difference itself: the measured accuracy of `rotation`
  OrbitVerdict verdict = OrbitVerdict::NotComputed;  ///< Regular, Chaotic or Escaping (NotComputed if stopped)
};

/// What to measure.
struct RotationRequest {
  MapParameters map;                                 ///< the box of Q* (its orbit must stay inside to count)
  UnitState start;                                   ///< z_0, unit coordinates
  RotationCentre centre;
  std::uint64_t power = 1;                           ///< n ≥ 1: the rotation of Qⁿ (1 … 10⁵)
  std::uint64_t iterations = kDefaultIterations;     ///< T: points of w per block (kMinIterations … kMaxIterations)
  double digitsThreshold = kDefaultDigitsThreshold;  ///< Regular when digits ≥ this
  /// The angle of z − c taken in the coordinates B·(z − c), B = {xx, xy, yx, yy} finite and invertible: a thin
  /// island's normal-form frame (FloquetFrame::toNormal), where each step turns by about ν < ½ and none folds, as
  /// it may in (x, y) (issue 50).  Empty: B = 1.  The grid is square, so B acts on unit offsets as on physical ones.
  std::optional<std::array<double, 4>> frame;
};

/// Measures it on the calling thread (2T·n steps of N, scalar), checking the stop token every 2^16 steps; a
/// stopped measurement is NotComputed.  Throws std::invalid_argument for invalid input (the map's rules, the
/// ranges above, sense not ±1, a non-finite centre).
[[nodiscard]] RotationMeasurement measureRotation(const RotationRequest& request, std::stop_token stop = {});

/// The centroid (mean of the unit coordinates) of z_0, z_n, z_{2n}, …, z_{(m−1)n} of the exact orbit, and the
/// largest distance (unit coordinates) of those points from it; `wrapped` when a step wrapped.  (Where the
/// sub-sequence of an orbit of an island chain of period n lingers: about the chain member it encircles.)
struct SubsequenceCloud {
  PhysicalPoint centroid;
  long double radius = 0;
  bool wrapped = false;
};
[[nodiscard]] SubsequenceCloud subsequenceCloud(const MapParameters& map, UnitState start, std::uint64_t power,
                                                std::uint64_t count);

}  // namespace archipelago
