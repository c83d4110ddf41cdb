#pragma once
/// \file GeneratingFunction.hpp
/// \brief The Lagrangian generating function of Q, its sign convention, and the actions of orbits.
///
/// Karney (1983), eq. (qu):  Q:  y' = y + g(x),  x' = x + y',  g(x) = 2(x² − K).
///
/// Derivation.  Eliminating y (y' = x' − x and y = x − x₋, where x₋ is the previous x) gives the second-order
/// recurrence of a discretised particle in the potential V with V' = g:
///     x_{t+1} − 2 x_t + x_{t−1} = g(x_t),      V(x) = (2/3) x³ − 2K x.
/// It is the Euler–Lagrange equation of the action W = Σ_t L(x_t, x_{t+1}) with
///     L(x, x') = ½ (x' − x)² + V(x),
/// because ∂W/∂x_t = ∂₂L(x_{t−1}, x_t) + ∂₁L(x_t, x_{t+1}) = (x_t − x_{t−1}) − (x_{t+1} − x_t) + g(x_t).
/// The momenta are
///     y' = ∂L/∂x' = x' − x,        y = −∂L/∂x = (x' − x) − g(x)   (indeed y' = y + g(x)),
/// so that, for a point moving along a curve γ and its image moving along Q(γ),
///     y' dx' − y dx = dL(x, x')          (the sign convention: L generates Q with y = −∂₁L, y' = +∂₂L).
/// Integrating along γ:  ∫_{Q(γ)} y dx − ∫_γ y dx = L(end) − L(start), the ends evaluated as (x, x') pairs.
///
/// Actions of homoclinic and heteroclinic orbits (MacKay, Meiss & Percival, Physica D 13 (1984) 55;
/// Meiss, Chaos 25 (2015) 097602).  Let h_t (t ∈ ℤ) be an orbit with h_t → z_{a+t} as t → −∞ and
/// h_t → z_{b+t} as t → +∞, where z_0 … z_{n−1} is a hyperbolic periodic orbit (indices mod n; n = 1 and
/// a = b = 0 for the fixed point (√K, 0)).  Define
///     ΔW(h) = Σ_{t<0} [L(h_t, h_{t+1}) − L(z_{a+t}, z_{a+t+1})] + Σ_{t≥0} [L(h_t, h_{t+1}) − L(z_{b+t}, z_{b+t+1})]
/// (x-coordinates in L).  Applying the identity above to the unstable arc U_t from z_{a+t} to h_t (Q(U_{t−1}) = U_t,
/// and U_t shrinks to a point as t → −∞) and to the stable arc S_t from h_t to z_{b+t} (Q(S_t) = S_{t+1}, shrinking
/// as t → +∞) gives
///     ΔW(h) = ∫_{U_0} y dx + ∫_{S_0} y dx = ∮ y dx   along  z_a —W^u→ h_0 —W^s→ z_b.
/// For two heteroclinic points h, h' from z_a to z_b the common parts cancel, and
///     ΔW(h) − ΔW(h') = ∮ y dx  around the lobe  h' —W^u→ h —W^s→ h',
/// i.e. the lobe's area, with the sign of ∮ y dx = −(counter-clockwise area): positive for a lobe whose boundary
/// runs clockwise.  The flux per iteration across the separatrix of a fixed point is one lobe's area
/// |ΔW(h) − ΔW(h')| for the two primary homoclinic orbits (MacKay–Meiss–Percival 1984; Meiss 2015);
/// for a period-n orbit whose separatrix is made of n such arcs, images of each other, one lobe still crosses per
/// step (each of the n turnstiles acts once in n steps; TurnstileFlux.hpp).  The area of the resonance zone bounded
/// by W^u[z → h] and W^s[h → z] is ΔW(h) itself (summed over the n arcs).
///
/// Convergence: with δ_t = h_t − z_t = O(λ^(−|t|/n)), the summand is ∂₁L δ_t + ∂₂L δ_{t+1} + O(δ²).  The first-order
/// parts telescope (z is an orbit: ∂₂L(z_{t−1}, z_t) + ∂₁L(z_t, z_{t+1}) = 0), leaving a boundary term y_{t+1} δ_{t+1} at
/// the truncation; at the fixed point y = 0 and each summand is O(δ²).  So the sums converge geometrically, and are
/// stopped when the summands fall below 1e−40 of the sum (HomoclinicPoints.cpp).
///
/// Arithmetic: the terms are evaluated in the caller's Real; core/manifolds sums them in __float128 (113 bits):
/// ΔW is O(K^{5/4}) while the lobe, the difference of two such actions, is exponentially small in K^{−1/4}
/// (10⁻⁴ of the zone at K = 0.05, 10⁻¹⁶ at K = 0.001), so the difference needs the digits quad has and double
/// (53 bits) or long double (64 bits) do not.

#include "core/periodic/SmoothQuadraticMap.hpp"

namespace archipelago {

/// V(x) = (2/3) x³ − 2K x, the potential with V' = g (eq. qu).
template <class Real>
[[nodiscard]] constexpr Real kickPotential(Real K, Real x) noexcept {
  return (2 * x * x * x) / 3 - 2 * K * x;
}

/// L(x, x') = ½ (x' − x)² + V(x), the generating function above: y = −∂L/∂x, y' = ∂L/∂x'.
template <class Real>
[[nodiscard]] constexpr Real generatingFunction(Real K, Real x, Real xNext) noexcept {
  const Real d = xNext - x;
  return d * d / 2 + kickPotential(K, x);
}

}  // namespace archipelago
