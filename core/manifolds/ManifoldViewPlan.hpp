#pragma once
/// \file ManifoldViewPlan.hpp
/// \brief Which manifold branches a portrait draws for the view it shows (docs/design.md, "Front ends fill, call
/// and format": a plan is core's).  The GUI computes each request with computeManifoldCurve() and only draws them.
///
/// The plan: of the fixed point (no orbit), the two inward branches (unstable and stable: the loop about the
/// central island and its turnstile; the outward ones wrap around the torus into the sea), 8 units long; of a
/// periodic orbit, both sides of each branch (the separatrices of its chain), 2 units long, at every point of a
/// short orbit (period ≤ kManifoldViewAllPointsPeriod: the six of the period-6 chain) and only at the first of a
/// long one.  Each branch is refined in the view (chord at most 1/400 of its larger side, clamped to
/// [kMinManifoldSpacing, 2e-3]) and in the box of Q*; the points drawn, kManifoldViewPointsBudget in all, are shared
/// equally between the branches.

#include <cstddef>
#include <optional>
#include <vector>

#include "core/manifolds/ManifoldCurve.hpp"

namespace archipelago {

/// Orbit points drawn in all for a view at most: a manifold refined at a deep zoom stays drawable.
inline constexpr std::size_t kManifoldViewPointsBudget = 1'500'000;
/// An orbit of at most this period has the branches of every one of its points drawn; a longer one, of its first.
inline constexpr int kManifoldViewAllPointsPeriod = 24;

/// The branches to draw for `view` of the portrait of Q* in `box` (box.K the map's parameter): unstable ones first,
/// then stable ones, each kind by side (inward, then outward) then by orbit point.  orbit: a hyperbolic periodic
/// orbit, or none for the fixed point.  Pure: no work, no validation (computeManifoldCurve() validates each).
[[nodiscard]] std::vector<ManifoldCurveRequest> manifoldPlanForView(const MapParameters& box,
                                                                    const std::optional<PeriodicOrbit>& orbit,
                                                                    const PhysicalRect& view);

}  // namespace archipelago
