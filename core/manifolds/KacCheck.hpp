#pragma once
/// \file KacCheck.hpp
/// \brief Flux and trapping tied together: the mean residence time of orbits entering a resonance zone equals the
/// zone's transit area divided by the flux (Kac's lemma for the turnstile).
///
/// MacKay, Meiss & Percival, Physica D 13 (1984) 55; Meiss, Rev. Mod. Phys. 64 (1992) 795.  Let Z be the zone of
/// TurnstileFlux.hpp (by default the fixed point's (√K, 0), inner branch; or a symmetric hyperbolic orbit's), E its
/// entry lobe (outside Z, Q(E) ⊂ Z) and X its exit lobe (inside Z, Q(X) outside).  An orbit started in E makes τ ≥ 1
/// steps inside Z (Q¹z … Q^τ z ∈ Z) and leaves from X.  The sets Qᵏ(E ∩ {τ ≥ k}), k ≥ 1, tile the transit region
/// T ⊂ Z (the points of Z that entered, which are those that will leave: Z minus its invariant islands) without
/// overlap, because a point of Z has one last entry; Q preserves area, so
///     ∫_E τ dA = area(T),   i.e.   ⟨τ⟩_E = area(T) / Φ,   Φ = area(E), the flux per step.
/// At a finite horizon the same tiling with k ≤ T gives the exact identity
///     Φ · ⟨min(τ, T)⟩_E = area{w ∈ Z : τ_b(w) ≤ T} = area{w ∈ Z : τ_f(w) ≤ T},
/// τ_b(w) the steps back to the last entry, τ_f(w) the steps forward to the exit.  The last equality holds for any
/// zone: each visit has one entry point (in Q(E)) and one exit point (in X), Q^{τ−1} carries the first onto the
/// second preserving area, so the visits of each length τ have equal areas at their entries and at their exits, and
/// tiling from the exits gives Φ ⟨min(τ, T)⟩ = area{τ_f ≤ T}.  As T → ∞ both sides tend to ⟨τ⟩ and area(T)/Φ; the
/// still-trapped fraction says how far from that limit a measurement is (sticky orbits near the islands make the
/// approach slow).  The same holds for Q⁻¹ (the trapping runs' N⁻¹) with entries through Q(X) and exits into E.
///
/// Measurement: the plane map Q in double precision (rounding gives a shadowing orbit, statistically the same);
/// E, X and Z are the polygons of TurnstileFlux (2048 vertices per arc, PolygonRegion.hpp; their chords miss the
/// arcs by < 1e−9, a negligible set of points).  An orbit in Z leaves at its next step exactly when it is in X, so
/// only X is tested at every step; Z is tested every 1024 steps as a safety net (an orbit found outside Z without
/// having passed X counts as `inconsistent`, expected 0).
///   - left side: `entrySamples` points uniform in E (rejection from its bounding box, counter-based random numbers
///     of core/random, so the result does not depend on the thread count), τ capped at T = maxSteps;
///     ⟨min(τ, T)⟩ ± its standard error;
///   - right side: `zoneSamples` points uniform in Z; the fraction p that leaves within T steps (± √(p(1−p)/N));
///     area(T) = p · area(Z) — a box-counting-free indicator of the islands: their points never leave.
/// Report: both sides of the finite-T identity with errors, the still-trapped fraction of E's orbits, and
/// area(Z)(1 − p), the area of the regular islands (plus orbits sticky beyond T) inside the zone.

#include <cstdint>
#include <optional>
#include <stop_token>
#include <string>

#include "core/manifolds/TurnstileFlux.hpp"

namespace archipelago {

struct KacRequest {
  long double K = 0.1L;                        ///< (0, 1]
  std::optional<PeriodicOrbit> orbit;          ///< a symmetric hyperbolic orbit; none: the fixed point (√K, 0)
  BranchSide side = BranchSide::Inward;        ///< the separatrix (TurnstileRequest::side)
  std::uint64_t entrySamples = 10000;          ///< orbits started in the entry lobe, [1, 10⁹]
  std::uint64_t zoneSamples = 10000;           ///< points of the zone for the transit area, [1, 10⁹]
  std::uint64_t maxSteps = 100000;             ///< T, [1, 10¹²]: residence times are capped here on both sides
  std::uint64_t seed = 1;                      ///< of the counter-based random numbers
  int threads = 0;                             ///< 0: OpenMP's default
};

[[nodiscard]] std::optional<std::string> validationError(const KacRequest& r);

struct KacResult {
  long double flux = 0;                 ///< Φ: the lobe area by the action method (TurnstileFlux)
  long double zoneArea = 0;             ///< area(Z) by the action method
  std::uint64_t maxSteps = 0;           ///< T
  // Left side: orbits started in the entry lobe.
  std::uint64_t entryOrbits = 0;
  double meanResidence = 0;             ///< ⟨min(τ, T)⟩, steps
  double meanResidenceError = 0;        ///< its standard error
  std::uint64_t stillInside = 0;        ///< orbits with τ > T
  std::uint64_t longestResidence = 0;   ///< max min(τ, T)
  // Right side: points of the zone.
  std::uint64_t zonePoints = 0;
  double transitFraction = 0;           ///< p: the fraction leaving within T steps
  double transitFractionError = 0;      ///< √(p(1 − p)/N)
  double transitArea = 0;               ///< p · area(Z)
  double transitAreaError = 0;
  double predictedResidence = 0;        ///< transitArea / Φ
  double predictedResidenceError = 0;
  double islandArea = 0;                ///< area(Z) (1 − p): islands and orbits trapped longer than T
  std::uint64_t inconsistent = 0;       ///< orbits found outside Z without passing X (expected 0)
  std::uint64_t steps = 0;              ///< map steps taken, both sides
  double seconds = 0;

  /// (left − right) / √(σ_left² + σ_right²): the discrepancy in combined standard errors.
  [[nodiscard]] double discrepancy() const noexcept;
};

/// Runs the check.  progress (on the calling thread, between batches) and stop as in TurnstileFlux.hpp; a stop
/// request throws std::runtime_error("stopped").  Throws std::invalid_argument for an invalid request.
[[nodiscard]] KacResult runKacCheck(const KacRequest& request, const ManifoldProgressCallback& progress = {},
                                    std::stop_token stop = {});

}  // namespace archipelago
