#include "core/manifolds/ManifoldViewPlan.hpp"

#include <algorithm>

namespace archipelago {

std::vector<ManifoldCurveRequest> manifoldPlanForView(const MapParameters& box, const std::optional<PeriodicOrbit>& orbit,
                                                      const PhysicalRect& view) {
  const int period = orbit ? orbit->period : 1;
  const int points = period <= kManifoldViewAllPointsPeriod ? period : 1;
  const long double width = std::max(view.x1 - view.x0, view.y1 - view.y0);
  std::vector<BranchSide> sides{BranchSide::Inward};
  if (orbit) sides.push_back(BranchSide::Outward);
  const std::size_t branches = 2 * sides.size() * static_cast<std::size_t>(points);
  std::vector<ManifoldCurveRequest> plan;
  plan.reserve(branches);
  for (ManifoldKind kind : {ManifoldKind::Unstable, ManifoldKind::Stable})
    for (BranchSide side : sides)
      for (int i = 0; i < points; ++i) {
        ManifoldCurveRequest r;
        r.K = box.K;
        r.orbit = orbit;
        r.point = i;
        r.kind = kind;
        r.side = side;
        r.length = orbit ? 2.0L : 8.0L;
        r.maxSpacing = std::clamp(width / 400, kMinManifoldSpacing, 2e-3L);
        r.view = view;
        r.box = box;
        r.maxPoints = kManifoldViewPointsBudget / branches;
        plan.push_back(std::move(r));
      }
  return plan;
}

}  // namespace archipelago
