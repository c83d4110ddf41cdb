#pragma once
/// \file ManifoldParameterization.hpp
/// \brief The stable and unstable manifolds of a hyperbolic periodic orbit of Q as analytic curves: the
/// parameterization method, with the stable manifold from the inverse map or from a reversing symmetry.
///
/// Glossary (orbit z_0 … z_{n−1} of HyperbolicOrbit.hpp, indices mod n, multiplier λ of DQⁿ, |λ| > 1):
///   - unstable manifold of z_j: the curve Φ_j(σ), σ ∈ ℝ, with Φ_j(0) = z_j, |Φ_j'(0)| = 1 and
///         Q(Φ_j(σ)) = Φ_{j+1}(μ_j σ),        μ_0 μ_1 ⋯ μ_{n−1} = λ,
///     so that Qⁿ(Φ_j(σ)) = Φ_j(λσ): σ is a coordinate in which Qⁿ is multiplication by λ (Koenigs/Poincaré);
///   - stable manifold of z_j: Ψ_j(σ) with Ψ_j(0) = z_j, |Ψ_j'(0)| = 1 and Q⁻¹(Ψ_j(σ)) = Ψ_{j−1}(ν_j σ),
///     ν_0 ⋯ ν_{n−1} = λ — the unstable manifold of Q⁻¹ (whose inverse is exact: x = x' − y', y = y' − g(x));
///   - branches: σ > 0 and σ < 0.  The linear terms are oriented so that σ > 0 is the "outward" branch: away from
///     the centre the chain winds around — (−√K, 0) for the fixed point and the chains around the central island,
///     the island a sub-chain surrounds (the 138-chain of §6); decided at the point of the orbit where the branch is
///     most nearly radial and carried around the orbit (Q maps branches onto branches).  For a chain the outward
///     branches form its outer separatrix, the inward ones its inner separatrix.  For λ < 0 the two branches of z_j
///     are exchanged by Qⁿ (a branch is invariant under Q²ⁿ);
///   - fundamental domain: [ρ/|λ|, ρ] (or [ρ/λ², ρ] when λ < 0): every point of a branch is an image of one.
///
/// Method (Cabré, Fontich & de la Llave, Indiana Univ. Math. J. 52 (2003) 283; Haro et al., "The
/// Parameterization Method for Invariant Manifolds", Springer 2016): the invariance equation is solved
/// order by order in σ.  Q is quadratic, so the coefficient of σᵏ (k ≥ 2) of Q(Φ_j) is
///     DQ(z_j) a_{j,k} + (2c_{j,k}, 2c_{j,k}),      c_{j,k} = Σ_{i=1}^{k−1} x_{j,i} x_{j,k−i},
/// and invariance gives a_{j+1,k} = μ_j^{−k} (DQ(z_j) a_{j,k} + b_{j,k}): a cyclic 2×2 system around the orbit,
///     (I − λ^{−k} DQⁿ(z_0)) a_{0,k} = r_k,
/// solvable for every k ≥ 2 since λ^{−k}DQⁿ has eigenvalues λ^{1−k}, λ^{−1−k} ≠ 1 (no resonance).  For Q⁻¹
/// (x − y, y − g(x − y)) the same with DQ⁻¹ and the nonlinear term (0, −2 Σ d_i d_{k−i}), d_i = x_i − y_i.
/// The Φ_j are entire functions (Q is polynomial); the coefficients (order 48) are computed in __float128 and
/// the series is used within the radius ρ_j where its last three terms are below 1e−32 of the linear one and
/// no term exceeds it (so no digits are lost to cancellation).  Beyond it, Φ_j(σ) = Q^m(Φ_{j−m}(σ/(μ_{j−1}⋯μ_{j−m}))),
/// iterated in the caller's precision.
///
/// Accuracy: a point Φ_j(σ) is computed to the working precision transversally to the manifold, at every σ:
/// forward iteration of Q contracts errors off W^u (backward iteration of Q contracts them off W^s), while
/// errors along the curve, which grow like |λ|^m, only move the point along it (the parameter σ of a far point
/// is uncertain by its relative rounding ε·|λ|^m, the point is not).  Tests: invariance at every order
/// (|Q(Φ_j(σ)) − Φ_{j+1}(μ_jσ)|), agreement of the inverse-map stable manifold with the reversed unstable one.
///
/// Reversing symmetries (SmoothQuadraticMap.hpp): Q = I₂ ∘ I₁ and I Q I = Q⁻¹ for I = I₁, I₂, so I maps W^u(z)
/// onto W^s(I z).  For an orbit that I maps onto itself, I ∘ Φ_i is a parameterization of W^s(I z_i) with the
/// same dynamics, hence Ψ_j(c_j σ) = I(Φ_i(σ)) with the constant c_j = (I·Φ_i'(0)) · Ψ_j'(0); reversedUnstable()
/// computes that second construction of the stable manifold.

#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/manifolds/HyperbolicOrbit.hpp"

namespace archipelago {

/// Which manifold: W^u (points leave the orbit under Q) or W^s (they approach it).
enum class ManifoldKind { Unstable, Stable };

[[nodiscard]] const char* toString(ManifoldKind kind) noexcept;
/// "stable" or "unstable" → the kind (the names toString() prints; issue 35: one parser for every front end);
/// throws std::invalid_argument "<option> '<text>' must be stable or unstable" otherwise.
[[nodiscard]] ManifoldKind parseManifoldKind(const std::string& text, const std::string& option = "branch");

/// A branch of a manifold at a point of the orbit: σ > 0 (outward at z_0, see the file comment) or σ < 0.
enum class BranchSide { Outward = 1, Inward = -1 };

[[nodiscard]] const char* toString(BranchSide side) noexcept;

/// The branch every front end draws by default: inward for the fixed point (its inner branch bounds the central
/// island's resonance zone), outward for a periodic orbit (its outer separatrix faces the chaotic sea).
[[nodiscard]] constexpr BranchSide defaultSide(bool fixedPoint) noexcept {
  return fixedPoint ? BranchSide::Inward : BranchSide::Outward;
}

/// "inward", "outward" or "auto" (defaultSide) → the side; throws std::invalid_argument naming `option` otherwise.
[[nodiscard]] BranchSide parseBranchSide(const std::string& text, bool fixedPoint, const std::string& option = "side");

/// One of the two reversing involutions of Q (SmoothQuadraticMap.hpp): I₁(x, y) = (x, −y − g(x)) with fixed line
/// S₁: y = K − x², I₂(x, y) = (x − y, −y) with fixed line S₂: y = 0.
enum class Reversor { I1, I2 };

/// I(z) in precision Real.
template <class Real>
[[nodiscard]] constexpr smooth::Point<Real> reverse(Reversor r, Real K, smooth::Point<Real> z) noexcept {
  if (r == Reversor::I1) return {z.x, -z.y - smooth::kick(K, z.x)};
  return {z.x - z.y, -z.y};
}

class ManifoldParameterization {
 public:
  static constexpr int kDefaultOrder = 48;

  /// The `kind` manifold of `orbit` (the stable one from Q⁻¹).  `order` in [2, 200].  Throws
  /// std::invalid_argument for an order out of range.
  ManifoldParameterization(HyperbolicOrbit orbit, ManifoldKind kind, int order = kDefaultOrder);

  [[nodiscard]] const HyperbolicOrbit& orbit() const noexcept { return orbit_; }
  [[nodiscard]] ManifoldKind kind() const noexcept { return kind_; }
  [[nodiscard]] int period() const noexcept { return orbit_.period; }
  [[nodiscard]] int order() const noexcept { return order_; }
  /// λ (Qⁿ multiplies σ by λ on W^u, Q⁻ⁿ multiplies it by λ on W^s).
  [[nodiscard]] quad multiplier() const noexcept { return orbit_.multiplier; }
  /// The factor one step multiplies σ by: μ_j (unstable: Q maps point j to point j+1) or ν_j (stable: Q⁻¹ maps
  /// point j to point j−1).
  [[nodiscard]] quad stretch(int j) const { return stretch_.at(static_cast<std::size_t>(index(j))); }
  /// ρ_j: the series of point j is used for |σ| ≤ ρ_j.
  [[nodiscard]] quad radius(int j) const { return radius_.at(static_cast<std::size_t>(index(j))); }
  /// The k-th Taylor coefficient of point j (k = 0: z_j; k = 1: the unit tangent).
  [[nodiscard]] smooth::Point<quad> coefficient(int j, int k) const;

  /// The point with parameter σ on the manifold of point j (any j, reduced mod n), in precision Real (long double,
  /// quad or double), and its derivative d/dσ in *tangent when non-null.  NaN coordinates when more than
  /// kMaxSteps steps would be needed or the iterates overflow (σ beyond where the curve escapes to infinity).
  template <class Real>
  [[nodiscard]] smooth::Point<Real> point(int j, Real sigma, smooth::Point<Real>* tangent = nullptr) const;

  /// The number of steps of Q (Q⁻¹) point(j, σ) takes: how far σ is from the local series, in steps.
  [[nodiscard]] long stepsTo(int j, long double sigma) const;

  /// The radii and stretches in the precision Real (quad, or rounded once to long double / double).
  template <class Real>
  [[nodiscard]] Real radiusAs(std::size_t i) const noexcept {
    if constexpr (std::is_same_v<Real, quad>) return radius_[i];
    else return static_cast<Real>(radiusLd_[i]);
  }
  template <class Real>
  [[nodiscard]] Real stretchAs(std::size_t i) const noexcept {
    if constexpr (std::is_same_v<Real, quad>) return stretch_[i];
    else return static_cast<Real>(stretchLd_[i]);
  }

  /// The first half of point(): the point of the local series from which `*steps` steps of Q (unstable) or Q⁻¹
  /// (stable) lead to the point with parameter σ at point j, for callers that iterate another map from there (the
  /// torus map Q* of ManifoldCurve.hpp).  *steps = −1 and NaN when more than kMaxSteps would be needed.
  template <class Real>
  [[nodiscard]] smooth::Point<Real> localPoint(int j, Real sigma, long* steps) const;

  /// The step a branch of point j takes: σ → Λσ with Λ = λ (Λ = λ² when λ < 0) after stepsPerDomain() steps.
  [[nodiscard]] quad domainFactor() const noexcept;
  [[nodiscard]] int stepsPerDomain() const noexcept;

  /// The largest number of map steps point() takes.
  static constexpr long kMaxSteps = 1'000'000;

 private:
  [[nodiscard]] int index(int j) const noexcept { return ((j % orbit_.period) + orbit_.period) % orbit_.period; }

  HyperbolicOrbit orbit_;
  ManifoldKind kind_;
  int order_;
  std::vector<std::vector<smooth::Point<quad>>> coefficients_;       ///< [j][k]
  std::vector<std::vector<smooth::Point<long double>>> coefficientsLd_;
  std::vector<quad> stretch_;
  std::vector<quad> radius_;
  std::vector<long double> stretchLd_;  ///< the same in long double: converting quad costs ~100 ns a value
  std::vector<long double> radiusLd_;
};

/// The index i with I(z_i) = z_j (within 1e-20), or nothing when I does not map the orbit onto itself.
[[nodiscard]] std::optional<int> reversedIndex(const HyperbolicOrbit& orbit, Reversor r, int j);

/// The stable manifold by the reversing symmetry: the point I(Φ_i(σ)) of W^s(z_j), where I(z_i) = z_j and Φ is
/// `unstable`.  With c = reversalScale(unstable, r, j), it equals stable.point(j, c·σ) (same curve, same dynamics).
/// Throws std::invalid_argument when `unstable` is not an unstable manifold or I does not map the orbit onto itself.
template <class Real>
[[nodiscard]] smooth::Point<Real> reversedUnstable(const ManifoldParameterization& unstable, Reversor r, int j, Real sigma);

/// c_j = (I·Φ_i'(0)) · Ψ_j'(0) for the stable parameterization `stable` (see the file comment).
[[nodiscard]] quad reversalScale(const ManifoldParameterization& unstable, const ManifoldParameterization& stable,
                                 Reversor r, int j);

}  // namespace archipelago
