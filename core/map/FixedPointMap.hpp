#pragma once
/// \file FixedPointMap.hpp
/// \brief The exact, one-to-one fixed-point realisation N of the periodic quadratic map Q*.
///
/// Karney (1983), appendix B, with 52 fractional bits instead of the Cray's 48 (so that AVX-512 IFMA
/// multiplies the lanes natively).  Glossary:
///   - unit coordinates  X, Y : integers in [0, 2^52), meaning X/2^52 and Y/2^52 in the unit square;
///   - physical coordinates x, y : x = xmin + L·X/2^52,  y = −L/2 + L·Y/2^52,  L = xmax − xmin;
///   - G(X) = 2^m (A·X² − B·X + C) in fixed point, the image of g(x) = 2(x² − K) (eq. qu) divided by L;
///   - N    : Y ← Y + G(X),  X ← X + Y − 2^51   (both mod 2^52)          — one step of Q*;
///   - N⁻¹  : X ← X − Y + 2^51,  Y ← Y − G(X)   (both mod 2^52)          — what trapping runs iterate;
///   - J    : X ← X − Y + 2^51,  Y ← −Y         (both mod 2^52), J² = 1, N⁻¹ = J N J.
/// A step "wraps" when a sum leaves [0, 2^52) before reduction: the orbit looped around the torus and the
/// trapped segment ends (§3).
///
/// Exactness: every operation is integer arithmetic with floor division of non-negative numbers, so N is a
/// bijection of the 2^104 grid points and all kernels (scalar, vector, MPI, resumed) agree bit for bit.
/// The only approximation is G itself: A, B, C are the coefficients rounded to 52 − m bits, and the two
/// floor divisions lose less than one unit each, so G differs from L⁻¹ g(x) by less than 4·2^m units of
/// 2^−52 (that bounds how far the fixed points move, see tests/core/test_fixed_point_map.cpp).

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "core/map/MapParameters.hpp"

namespace archipelago {

/// 128-bit integers (a GCC/Clang extension) for the exact 52×52-bit products.
__extension__ typedef unsigned __int128 uint128;
__extension__ typedef __int128 int128;

/// A point of the torus in unit coordinates: 0 ≤ X, Y < 2^52.
struct UnitState {
  std::uint64_t X = 0;
  std::uint64_t Y = 0;
  friend bool operator==(const UnitState&, const UnitState&) = default;
};

/// A point in physical coordinates (x, y) of Q.  Long double keeps ~64 bits, more than the 52-bit grid.
struct PhysicalPoint {
  long double x = 0;
  long double y = 0;
};

/// The integers that define the map exactly (appendix B): G(X) = 2^m (⌊A⌊X²/2^52⌋/2^52⌋ − ⌊B X/2^52⌋ + C).
/// They, not K, are what a run file records.
struct MapCoefficients {
  std::int64_t A = 0;  ///< round(a·2^(52−m)), a = 2L
  std::int64_t B = 0;  ///< round(b·2^(52−m)), b = −4 xmin
  std::int64_t C = 0;  ///< round(c·2^(52−m)), c = 2(xmin² − K)/L
  int m = 0;           ///< the shift: smallest m ≥ 0 with A, B, C < 2^52
  friend bool operator==(const MapCoefficients&, const MapCoefficients&) = default;
};

/// Computes (A, B, C, m) by docs/design.md, "Arithmetic contract": a, b, c in IEEE double without FMA contraction, in the
/// order L = xmax − xmin, a = 2L, b = −4·xmin, c = 2(xmin·xmin − K)/L; m the smallest m ≥ 0 with a, b, c < 2^m;
/// A, B, C = llround(ldexp(·, 52 − m)), increasing m while any of them reaches 2^52.
/// Throws std::invalid_argument for invalid parameters, or when m would exceed FixedPointMap::kMaxShift
/// (a box so large that 2^m·G no longer fits in 64 bits).
[[nodiscard]] MapCoefficients computeCoefficients(const MapParameters& p);

/// The one check of a map that every request building one starts with (trapping parameters, portraits, b₂, the
/// GUI's portrait view): the first rule of validationError(p), or the box-size limit of computeCoefficients(),
/// as a message naming the parameter; nothing when computeCoefficients(p) succeeds.
[[nodiscard]] std::optional<std::string> mapError(const MapParameters& p);
/// Every violated rule: validationErrors(p), or, when there is none, the box-size limit (about xmin and xmax).
[[nodiscard]] std::vector<ParameterError> mapErrors(const MapParameters& p);

namespace fixedpoint {
inline constexpr int kBits = 52;
inline constexpr std::uint64_t kOne = std::uint64_t{1} << kBits;
inline constexpr std::uint64_t kHalf = kOne >> 1;
inline constexpr std::uint64_t kMask = kOne - 1;
}  // namespace fixedpoint

/// G(X) = 2^m (⌊A⌊X²/2^52⌋/2^52⌋ − ⌊B X/2^52⌋ + C), in units of 2^−52; exact.
[[nodiscard]] inline std::int64_t fixedPointG(const MapCoefficients& k, std::uint64_t X) noexcept {
  using namespace fixedpoint;
  const std::uint64_t x2 = static_cast<std::uint64_t>((uint128{X} * X) >> kBits);
  const auto ax2 = static_cast<std::int64_t>((uint128(static_cast<std::uint64_t>(k.A)) * x2) >> kBits);
  const auto bx = static_cast<std::int64_t>((uint128(static_cast<std::uint64_t>(k.B)) * X) >> kBits);
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(ax2 - bx + k.C) << k.m);
}

/// N⁻¹: X ← X − Y + 2^51, Y ← Y − G(X), both mod 2^52.  Returns true when a sum left [0, 2^52) (a wrap).
inline bool backwardStep(const MapCoefficients& k, UnitState& z) noexcept {
  using namespace fixedpoint;
  const std::uint64_t s = z.X - z.Y + kHalf;  // modulo 2^64: a negative sum becomes ≥ 2^63
  const std::uint64_t X = s & kMask;
  const std::uint64_t u = z.Y - static_cast<std::uint64_t>(fixedPointG(k, X));
  z.X = X;
  z.Y = u & kMask;
  return (s | u) >= kOne;
}

/// N: Y ← Y + G(X), X ← X + Y − 2^51, both mod 2^52; the exact inverse of backwardStep().
inline bool forwardStep(const MapCoefficients& k, UnitState& z) noexcept {
  using namespace fixedpoint;
  const std::uint64_t u = z.Y + static_cast<std::uint64_t>(fixedPointG(k, z.X));
  const std::uint64_t Y = u & kMask;
  const std::uint64_t s = z.X + Y - kHalf;
  z.X = s & kMask;
  z.Y = Y;
  return (s | u) >= kOne;
}

class FixedPointMap {
 public:
  static constexpr int kBits = fixedpoint::kBits;
  static constexpr std::uint64_t kOne = fixedpoint::kOne;  ///< 2^52, the unit
  static constexpr std::uint64_t kHalf = fixedpoint::kHalf;
  static constexpr std::uint64_t kMask = fixedpoint::kMask;
  static constexpr int kMaxShift = 9;  ///< |2^m G| < 2^(53+m) must leave room in int64 for Y − G

  /// Builds the map from validated physical parameters (throws std::invalid_argument otherwise).
  explicit FixedPointMap(const MapParameters& p);

  [[nodiscard]] const MapParameters& parameters() const noexcept { return params_; }
  [[nodiscard]] const MapCoefficients& coefficients() const noexcept { return coef_; }

  /// G(X) in units of 2^−52 (may be negative or exceed 2^52; exact integer arithmetic).
  [[nodiscard]] std::int64_t G(std::uint64_t X) const noexcept { return fixedPointG(coef_, X); }
  /// N⁻¹ (appendix B, steps 7.1–7.2).  Returns true when either sum left [0, 2^52) (the orbit wrapped).
  bool backward(UnitState& z) const noexcept { return backwardStep(coef_, z); }
  /// N, the exact inverse of backward().  Returns true when the orbit wrapped.
  bool forward(UnitState& z) const noexcept { return forwardStep(coef_, z); }

  /// The involution J (appendix B): N⁻¹ = J N J and J² = 1, exactly.
  static void involution(UnitState& z) noexcept {
    z.X = (z.X - z.Y + kHalf) & kMask;
    z.Y = (kOne - z.Y) & kMask;
  }

  /// Physical → unit coordinates, rounded to the nearest grid point and reduced onto the torus.
  [[nodiscard]] UnitState toUnit(long double x, long double y) const noexcept;
  /// Unit → physical coordinates (exact up to long double rounding).
  [[nodiscard]] PhysicalPoint toPhysical(const UnitState& z) const noexcept;
  /// One grid unit in physical length: L / 2^52.
  [[nodiscard]] long double gridUnit() const noexcept;

 private:
  MapParameters params_;
  MapCoefficients coef_;
};

/// The rule of a unit coordinate a front end gives (an integer in [0, 2^52)): "<name> = <text> must lie in [0, 2^52)
/// (unit coordinates)", or nothing.  `value`: nothing when the text is not a 64-bit whole number (negative, too large).
[[nodiscard]] std::optional<std::string> unitCoordinateError(std::string_view name, std::optional<std::uint64_t> value,
                                                             std::string_view text);

}  // namespace archipelago
