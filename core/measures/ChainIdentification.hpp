#pragma once
/// \file ChainIdentification.hpp
/// \brief Which island chain an orbit belongs to, from its rotation numbers: "6 × 23 = 138, rotation 1/6 about
/// the centre, 2/23 about its island".
///
/// Karney (1983), §6 and fig. 8: the central island of Q at K = 0.1 is surrounded by a chain of six islands,
/// each of those by chains of their own (23 islands around each of the six form the chain of order
/// 6 × 23 = 138 where the longest trapped segment sticks), and so on.  An orbit of such a chain has a rational
/// rotation number at every level but the last.  The recursion (docs/instruments.md):
///   1. level 0: the rotation number ω₀ of the orbit about the elliptic fixed point (−√K, 0)
///      (RotationNumber.hpp, n = 1);
///   2. the rational p/q of smallest denominator within the measured accuracy of ω (smallestDenominatorRational,
///      a Stern–Brocot descent), with q at most maxPeriod / n; none: the orbit lies on an invariant curve about
///      the current centre, and the recursion ends;
///   3. n ← n·q; the elliptic periodic orbit of minimal period n that the orbit encircles: Newton's method
///      (PeriodicOrbitFinder.hpp, refinePeriodicOrbit) from the centroid of the orbit's points z_0, z_n, z_2n, …
///      (they circle the chain member the orbit's island surrounds), else the symmetric-orbit search
///      (findSymmetricPeriodicOrbits) around it for n ≤ kMaxSymmetricSearchPeriod; the member nearest the
///      centroid is the new centre;
///   4. level k: the rotation number of Qⁿ about that member, positive in the sense DQⁿ turns there
///      (RotationNumber.hpp); it must be regular and not 0 (an orbit that does not turn about the member is not
///      in its island); then back to 2.
/// The chain's period is the product of the denominators (138 = 6 × 23); its levels list each rotation and
/// centre, the last one the orbit's own invariant curve about the deepest island.  The measured accuracy is
/// kAccuracyFactor times the difference of the two block averages (at least 2^−50): on an island chain the
/// rotation is exactly p/q and the averages agree to ~10⁻¹⁴ at T = 10⁴, on an invariant curve the nearest
/// rationals of small denominator are farther.
///
/// Cost: level k iterates 2T·n steps of N (scalar) plus a Newton solve of period n in quad precision; a few
/// tenths of a second for the 138-chain at T = 10⁴.

#include <cstdint>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/measures/RotationNumber.hpp"
#include "core/periodic/PeriodicOrbit.hpp"

namespace archipelago {

/// A fraction p/q, q ≥ 1, in lowest terms.
struct Rational {
  std::int64_t p = 0;
  std::int64_t q = 1;
  friend bool operator==(const Rational&, const Rational&) = default;
};

/// The fraction of smallest denominator in the closed interval [lo, hi] (lo ≤ hi, finite), found by descending
/// the Stern–Brocot tree with runs of equal steps taken at once (a few dozen steps for any interval); among
/// fractions of that denominator the one nearest (lo + hi)/2.  Nothing when every such fraction has q >
/// maxDenominator (1 ≤ maxDenominator ≤ 2^31).  Throws std::invalid_argument for lo > hi or non-finite bounds.
[[nodiscard]] std::optional<Rational> smallestDenominatorRational(double lo, double hi, std::int64_t maxDenominator);

/// How far a measured rotation may be from p/q and still name it: kAccuracyFactor × `difference` (the difference
/// of the measurement's two block averages, turns), at least 2^−50.
[[nodiscard]] double rotationAccuracy(double difference) noexcept;

/// The one step from a measured rotation number to the rational it names (issue 51: it stood in four files): the
/// fraction of smallest denominator, at most maxDenominator, within rotationAccuracy(difference) of `rotation`
/// (smallestDenominatorRational); nothing when there is none: at that accuracy the orbit lies on an invariant
/// circle.  The chain identification, the rotation profile, the atlas's classifier and its proof, and the box
/// check all call it.
[[nodiscard]] std::optional<Rational> rationalOfRotation(double rotation, double difference,
                                                         std::int64_t maxDenominator);

/// "p/q", e.g. "2/23", "-1/6", "0/1".
[[nodiscard]] std::string toString(const Rational& r);

/// What to identify.
struct ChainRequest {
  MapParameters map;                                 ///< 0 < K < 1 (the centre must be elliptic)
  UnitState start;                                   ///< z_0, unit coordinates
  std::uint64_t iterations = kDefaultIterations;     ///< T per block, at every level
  double digitsThreshold = kDefaultDigitsThreshold;
  std::uint64_t maxPeriod = 10'000;                  ///< the largest chain period tried, 1 … 100000
  int maxLevels = 6;                                 ///< levels below the centre, 0 … 16
};

/// How far the measured rotation number may be from p/q and still name it: kAccuracyFactor × the difference of
/// the two block averages.
inline constexpr double kAccuracyFactor = 8;
/// Chains of period above this are searched with Newton from the centroid only (the symmetric search scans
/// windows of n/2 steps in quad precision: too slow for long periods).
inline constexpr std::uint64_t kMaxSymmetricSearchPeriod = 2000;

/// One level of the recursion.
struct ChainLevel {
  std::uint64_t power = 1;            ///< n: the rotation is that of Qⁿ
  PhysicalPoint centre;               ///< the point it is measured about, physical (x, y)
  int sense = 1;                      ///< +1: clockwise in the (x, y) plane, −1: counter-clockwise
  std::optional<PeriodicOrbit> orbit; ///< level ≥ 1: the elliptic periodic orbit of period n (centre = a member)
  RotationMeasurement rotation;
  std::optional<Rational> rational;   ///< p/q named by the measured rotation (it led to the next level, or not)
};

/// The identification.
struct ChainIdentification {
  std::vector<ChainLevel> levels;        ///< level 0 about (−√K, 0), then one per island
  std::vector<std::int64_t> factors;     ///< the denominators that led to deeper islands, e.g. {6, 23}
  std::uint64_t period = 1;              ///< their product: the chain's order (1: no chain)
  std::string ending;                    ///< why the recursion ended (one phrase)
  /// e.g. "6 × 23 = 138, rotation 1/6 about the centre, 2/23 about its island; an invariant curve of rotation
  /// 0.3116792233 about the period-138 orbit" or "chaotic (4.2 digits)".
  std::string summary;
  bool cancelled = false;
};

/// Step 3 of the recursion on its own (core/atlas finds each chain's orbit with it): the centroid of z_0, z_n, z_2n, …
/// (at most min(iterations, 4096) of them) of the exact orbit from `start`, their largest distance from it (physical
/// units), and the elliptic periodic orbit of minimal period n about the centroid (Newton from it, else the symmetric
/// search within twice that distance for n ≤ kMaxSymmetricSearchPeriod); no orbit when none was found or the orbit
/// wrapped (left the box).
struct EllipticOrbitGuess {
  PhysicalPoint centroid;
  long double radius = 0;
  std::optional<PeriodicOrbit> orbit;
};
[[nodiscard]] EllipticOrbitGuess ellipticOrbitAround(const MapParameters& map, UnitState start, std::uint64_t n,
                                                     std::uint64_t iterations);

/// The sense in which DQⁿ turns points about the elliptic point z of period n: +1 clockwise in the (x, y) plane (as
/// DQ does at the centre), −1 counter-clockwise.
[[nodiscard]] int rotationSense(long double K, PhysicalPoint z, std::uint64_t n);

/// A rotation centre at the physical point `centre` (unit coordinates as long doubles, not rounded to the lattice).
[[nodiscard]] RotationCentre rotationCentreAt(const MapParameters& map, PhysicalPoint centre, int sense);

/// `request` started at the physical point `start` (issue 35: the recipe the CLI's `rotation`, Python's rotation()
/// and the GUI's launched orbits each wrote out): the measure's rules (0 < K < 1, iterations, threshold), then the
/// start's ("the start (x, y) = … must lie in the box …"), then the start placed on the lattice.  Throws
/// std::invalid_argument with the first rule broken.
[[nodiscard]] ChainRequest chainRequestAt(ChainRequest request, PhysicalPoint start);

/// Runs the recursion.  Throws std::invalid_argument for invalid input (the map's rules, 0 < K < 1, the
/// ranges above); a stop request (checked during every measurement) returns the levels so far, cancelled set.
[[nodiscard]] ChainIdentification identifyChain(const ChainRequest& request, std::stop_token stop = {});

}  // namespace archipelago
