#pragma once
/// \file HomoclinicPoints.hpp
/// \brief Primary homoclinic and heteroclinic points of a symmetric hyperbolic orbit of Q, on the symmetry lines,
/// refined in __float128, with their orbits and actions.
///
/// Reversibility (SmoothQuadraticMap.hpp): Q = I₂ ∘ I₁, I Q I = Q⁻¹, so an involution I maps W^u(z) onto W^s(I z).
/// A point h of W^u(z_j) on the fixed line S of I is therefore on W^s(I z_j) as well: a homoclinic (I z_j = z_j)
/// or heteroclinic point, "symmetric".  For an orbit that I₁ (hence I₂ = Q I₁) maps onto itself, every symmetric
/// heteroclinic orbit meets S₁ or S₂ (Devaney, Trans. AMS 218 (1976) 89; MacKay, Meiss & Percival 1984).
///
/// Method.  A crossing of S₁ or S₂ by the branch B_j = Qʲ(B_0) of the unstable manifold (B_0 the chosen branch of
/// z_0) at σ_j is Qʲ of the point σ₀ = σ_j/(μ_0⋯μ_{j−1}) of B_0.  The scan runs over the fundamental domains of σ₀,
/// all n branches and both lines together, 512 points per domain in long double, from 3 domains inside the local
/// series' radius outward; a sign change is bisected in long double, and two crossings whose σ₀ differ by a power of
/// the domain factor Λ are one orbit.  The primary points are the crossing nearest to z_0 along B_0 (smallest |σ₀|),
/// h, and the next orbit along B_0 that goes to the same point z_b of the orbit, h' (|σ_h| < |σ_h'| < Λ|σ_h|): the
/// turnstile lobe lies between them.  After domain k every crossing with |σ₀| below its end is known, so the scan
/// stops once h' is; the distinct orbits up to h' are then refined by bisection and Newton in __float128 along σ
/// (|offset| ≤ 1e−30).  For the fixed point (√K, 0) and its inner branch they are the two classical primary
/// homoclinic points near the tip of the loop (−2√K, 0): h on S₁, h' on S₂.
///
/// Each point's stable parameter follows from the symmetry: I(Φ_j(σ)) = Ψ_b(c_b σ) (ManifoldParameterization.hpp),
/// so h's orbit is computed backward on W^u and forward on W^s, both from their analytic parameterizations, never by
/// iterating Q forward along W^s (which would amplify rounding by λᵗ).
///
/// Action (GeneratingFunction.hpp): ΔW(h) = Σ_{t<0}[L(h_t,h_{t+1}) − L(z_t,z_{t+1})] + Σ_{t≥0}[L(h_t,h_{t+1}) −
/// L(z_{b+t},z_{b+t+1})], summed in __float128 until the terms (O(λ^{−2|t|})) fall below 1e−40 of the sum;
/// it equals ∮ y dx along z_0 —W^u→ h —W^s→ z_b.

#include <optional>
#include <stop_token>
#include <vector>

#include "core/manifolds/ManifoldParameterization.hpp"

namespace archipelago {

/// A heteroclinic point h_0 ∈ W^u(z_0) ∩ W^s(z_b) on the chosen branch of z_0, and its orbit's action.
struct HeteroclinicPoint {
  int target = 0;                       ///< b: h_t → z_{b+t} as t → +∞ (0 for the fixed point: homoclinic)
  quad sigma = 0;                       ///< the unstable parameter of h_0 on Φ_0
  quad mu = 0;                          ///< the stable parameter of h_0 on Ψ_b
  smooth::Point<quad> point;            ///< h_0 = Φ_0(σ)
  smooth::SymmetryLine line = smooth::SymmetryLine::S1;  ///< the line its symmetric point lies on
  int symmetricIndex = 0;               ///< j: Qʲ(h_0) lies on `line`
  quad mismatch = 0;                    ///< |Φ_0(σ) − Ψ_b(μ)| in __float128: the two manifolds' points agree
  quad action = 0;                      ///< ΔW(h_0) (GeneratingFunction.hpp), __float128
  quad actionError = 0;                 ///< bound on its rounding: 4 ε_quad Σ_t (|L(h_t, h_{t+1})| + |L(z_t, z_{t+1})|)
  int actionTerms = 0;                  ///< terms summed (both directions)
};

/// The orbit h_t, t = −past … future, of a heteroclinic point (physical coordinates, __float128), from the
/// parameterizations (backward on W^u, forward on W^s).
[[nodiscard]] std::vector<smooth::Point<quad>> heteroclinicOrbit(const ManifoldParameterization& unstable,
                                                                 const ManifoldParameterization& stable,
                                                                 const HeteroclinicPoint& h, int past, int future);

/// What primaryHeteroclinicPoints() finds.
struct PrimaryIntersections {
  HeteroclinicPoint first;              ///< h: nearest to z_0 along the branch
  HeteroclinicPoint second;             ///< h': the next one to the same z_b, |σ_h| < |σ_h'| < Λ|σ_h|
  std::vector<HeteroclinicPoint> crossings;  ///< the distinct symmetric orbits found up to h', carried to B_0, by |σ|
};

/// The primary intersections of the branch `side` of W^u(z_0) with the stable manifolds of the orbit.  The orbit
/// must be mapped onto itself by I₁ (and so by I₂) and have λ > 0.  At most `maxDomains` fundamental domains are
/// scanned (0: automatic, ⌈30/ln Λ⌉ capped at 1000 — a multiplier near 1, at small K, needs many to reach the
/// intersections; the scan stops as soon as the pair is found).  Throws std::invalid_argument for an orbit that is not symmetric or has λ < 0, and
/// NotFound (PeriodicOrbitFinder.hpp) when fewer than two suitable crossings are found.
[[nodiscard]] PrimaryIntersections primaryHeteroclinicPoints(const ManifoldParameterization& unstable,
                                                             const ManifoldParameterization& stable, BranchSide side,
                                                             int maxDomains = 0, std::stop_token stop = {});

/// ΔW(h) for a point with `target`, `sigma` and `mu` set (fills action and actionTerms).
void computeAction(const ManifoldParameterization& unstable, const ManifoldParameterization& stable,
                   HeteroclinicPoint& h);

}  // namespace archipelago
