#pragma once
/// \file SmoothQuadraticMap.hpp
/// \brief The smooth quadratic map Q in any floating-point type, its Jacobian and its reversing involutions.
///
/// Karney (1983), §2, eq. (qu):  Q:  y' = y + g(x),  x' = x + y',  g(x) = 2(x² − K).
/// Inside the box [xmin, xmax) × [−L/2, L/2) the periodic map Q* of the trapping runs equals Q, so periodic
/// orbits that stay in the box are periodic orbits of Q*; they are found here with Q itself, in extended
/// precision (long double, or the 113-bit `__float128` of GCC), not with the 52-bit integer map.
///
/// Glossary (physical coordinates throughout):
///   - DQ(x, y) = [[1 + 4x, 1], [4x, 1]] (rows x', y'; columns x, y), det DQ = 1: Q preserves area;
///   - reversibility: Q = I₂ ∘ I₁ with the involutions
///       I₁(x, y) = (x, −y − g(x)),   fixed line S₁: y = −g(x)/2 = K − x²,
///       I₂(x, y) = (x − y, −y),       fixed line S₂: y = 0
///     (I₂ is the involution J of appendix B in physical coordinates).  Since I Q I = Q⁻¹ for I = I₁, I₂:
///       z ∈ S₁ and Qᵐ z ∈ S₁  ⇒  Q²ᵐ z = z;        z ∈ S₂ and Qᵐ z ∈ S₂  ⇒  Q²ᵐ z = z;
///       z ∈ S₁ and Qᵐ z ∈ S₂  ⇒  Q²ᵐ⁻¹ z = z;      z ∈ S₂ and Qᵐ z ∈ S₁  ⇒  Q²ᵐ⁺¹ z = z,
///     so a symmetric orbit of period n is found by shooting ⌊n/2⌋ or ⌈n/2⌉ steps from one symmetry line to
///     the other (or the same) line: a one-dimensional root search (PeriodicOrbitFinder.hpp).
///   - fixed points: (±√K, 0), both on S₁ ∩ S₂; (−√K, 0) is the elliptic centre of the central island
///     (0 < K < 1), with trace DQ = 2 − 4√K, hence Greene's residue R = (2 − trace)/4 = √K.

#include <type_traits>

namespace archipelago {

/// 113-bit IEEE quadruple precision (GCC/Clang extension; arithmetic comes from libgcc, no libquadmath).
__extension__ typedef __float128 quad;

namespace smooth {

/// |v| for any of our floating types (std::abs has no __float128 overload without libquadmath).
template <class Real>
[[nodiscard]] constexpr Real absolute(Real v) noexcept {
  return v < 0 ? -v : v;
}

/// √v for v ≥ 0, to the working precision of Real: a long double seed and two Newton steps (each doubles
/// the number of correct bits, 64 → 113 for quad).
template <class Real>
[[nodiscard]] Real squareRoot(Real v) noexcept {
  if (!(v > 0)) return Real(0);
  long double seed = static_cast<long double>(v);
  Real r = static_cast<Real>(__builtin_sqrtl(seed));
  for (int i = 0; i < 2; ++i) r = (r + v / r) / 2;
  return r;
}

/// A point (x, y) of the plane in precision Real.
template <class Real>
struct Point {
  Real x = 0;
  Real y = 0;
};

/// A 2×2 matrix [[xx, xy], [yx, yy]] acting on column vectors (δx, δy).
template <class Real>
struct Matrix2 {
  Real xx = 1, xy = 0, yx = 0, yy = 1;
  [[nodiscard]] Real trace() const noexcept { return xx + yy; }
  /// this · b (apply b first).
  [[nodiscard]] Matrix2 operator*(const Matrix2& b) const noexcept {
    return {xx * b.xx + xy * b.yx, xx * b.xy + xy * b.yy, yx * b.xx + yy * b.yx, yx * b.xy + yy * b.yy};
  }
};

/// g(x) = 2(x² − K), the kick of eq. (qu).
template <class Real>
[[nodiscard]] constexpr Real kick(Real K, Real x) noexcept {
  return 2 * (x * x - K);
}

/// One step of Q (eq. qu).
template <class Real>
[[nodiscard]] constexpr Point<Real> step(Real K, Point<Real> z) noexcept {
  const Real y = z.y + kick(K, z.x);
  return {z.x + y, y};
}

/// One step of Q⁻¹:  x = x' − y',  y = y' − g(x).
template <class Real>
[[nodiscard]] constexpr Point<Real> inverseStep(Real K, Point<Real> z) noexcept {
  const Real x = z.x - z.y;
  return {x, z.y - kick(K, x)};
}

/// DQ at z (rows x', y'; columns x, y); det = 1.
template <class Real>
[[nodiscard]] constexpr Matrix2<Real> jacobian(Point<Real> z) noexcept {
  const Real g1 = 4 * z.x;  // g'(x)
  return {1 + g1, 1, g1, 1};
}

/// Iterates Q n times from z, accumulating DQⁿ = DQ(z_{n−1}) ⋯ DQ(z_0) into *product when it is non-null.
template <class Real>
[[nodiscard]] Point<Real> iterate(Real K, Point<Real> z, long n, Matrix2<Real>* product = nullptr) noexcept {
  for (long i = 0; i < n; ++i) {
    if (product) *product = jacobian(z) * *product;
    z = step(K, z);
  }
  return z;
}

/// The two symmetry lines, the fixed sets of the involutions I₁ and I₂.
enum class SymmetryLine {
  S1,  ///< y = K − x², the fixed set of I₁(x, y) = (x, −y − g(x))
  S2,  ///< y = 0, the fixed set of I₂(x, y) = (x − y, −y)
};

/// The point of the line with abscissa x (both lines are graphs over x).
template <class Real>
[[nodiscard]] constexpr Point<Real> onLine(SymmetryLine line, Real K, Real x) noexcept {
  return {x, line == SymmetryLine::S1 ? K - x * x : Real(0)};
}

/// Signed vertical offset of z from the line: y − y_line(x); zero exactly on the line.
template <class Real>
[[nodiscard]] constexpr Real offsetFromLine(SymmetryLine line, Real K, Point<Real> z) noexcept {
  return line == SymmetryLine::S1 ? z.y - (K - z.x * z.x) : z.y;
}

/// d/dx of the line's ordinate: −2x for S₁, 0 for S₂.
template <class Real>
[[nodiscard]] constexpr Real lineSlope(SymmetryLine line, Real x) noexcept {
  return line == SymmetryLine::S1 ? -2 * x : Real(0);
}

}  // namespace smooth
}  // namespace archipelago
