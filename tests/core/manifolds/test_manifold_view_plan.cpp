// The manifold branches a portrait draws for a view (ManifoldViewPlan.hpp): which kinds, sides and orbit points,
// their lengths, the view's spacing and the shared point budget.  Pure: no branch is computed here.
#include <gtest/gtest.h>

#include "core/manifolds/ManifoldViewPlan.hpp"

namespace archipelago {
namespace {

PeriodicOrbit orbitOfPeriod(int period) {
  PeriodicOrbit o;
  o.K = 0.1L;
  o.period = period;
  o.points.assign(static_cast<std::size_t>(period), PhysicalPoint{0.1L, 0.0L});
  return o;
}

const MapParameters kBox{0.1, -0.8, 0.5};
const PhysicalRect kWholeBox{-0.8L, 0.5L, -0.65L, 0.65L};

TEST(ManifoldViewPlan, FixedPointDrawsItsTwoInwardBranches) {
  const auto plan = manifoldPlanForView(kBox, std::nullopt, kWholeBox);
  ASSERT_EQ(plan.size(), 2u);
  EXPECT_EQ(plan[0].kind, ManifoldKind::Unstable);
  EXPECT_EQ(plan[1].kind, ManifoldKind::Stable);
  for (const ManifoldCurveRequest& r : plan) {
    EXPECT_EQ(r.side, BranchSide::Inward);
    EXPECT_FALSE(r.orbit);
    EXPECT_EQ(r.point, 0);
    EXPECT_EQ(r.length, 8.0L);
    EXPECT_EQ(r.K, static_cast<long double>(kBox.K));
    ASSERT_TRUE(r.box);
    EXPECT_EQ(*r.box, kBox);
    ASSERT_TRUE(r.view);
    EXPECT_EQ(r.view->x0, kWholeBox.x0);
    EXPECT_EQ(r.view->y1, kWholeBox.y1);
    EXPECT_EQ(r.maxSpacing, 2e-3L);  // 1.3/400 clamped to the default bound
    EXPECT_EQ(r.maxPoints, kManifoldViewPointsBudget / 2);
    EXPECT_FALSE(validationError(r)) << *validationError(r);
  }
}

TEST(ManifoldViewPlan, ShortOrbitDrawsBothSidesAtEveryPoint) {
  const auto plan = manifoldPlanForView(kBox, orbitOfPeriod(6), kWholeBox);
  ASSERT_EQ(plan.size(), 2u * 2u * 6u);
  std::size_t i = 0;
  for (ManifoldKind kind : {ManifoldKind::Unstable, ManifoldKind::Stable})
    for (BranchSide side : {BranchSide::Inward, BranchSide::Outward})
      for (int point = 0; point < 6; ++point, ++i) {
        EXPECT_EQ(plan[i].kind, kind) << i;
        EXPECT_EQ(plan[i].side, side) << i;
        EXPECT_EQ(plan[i].point, point) << i;
        EXPECT_EQ(plan[i].length, 2.0L);
        ASSERT_TRUE(plan[i].orbit);
        EXPECT_EQ(plan[i].orbit->period, 6);
        EXPECT_EQ(plan[i].maxPoints, kManifoldViewPointsBudget / 24);
      }
}

TEST(ManifoldViewPlan, LongOrbitDrawsItsFirstPointOnly) {
  const auto at = manifoldPlanForView(kBox, orbitOfPeriod(kManifoldViewAllPointsPeriod), kWholeBox);
  EXPECT_EQ(at.size(), 4u * static_cast<std::size_t>(kManifoldViewAllPointsPeriod));
  const auto plan = manifoldPlanForView(kBox, orbitOfPeriod(kManifoldViewAllPointsPeriod + 1), kWholeBox);
  ASSERT_EQ(plan.size(), 4u);
  for (const ManifoldCurveRequest& r : plan) {
    EXPECT_EQ(r.point, 0);
    EXPECT_EQ(r.maxPoints, kManifoldViewPointsBudget / 4);
  }
}

TEST(ManifoldViewPlan, SpacingFollowsTheViewDownToTheFinestBound) {
  // The larger side over 400.
  const PhysicalRect zoom{0.0L, 0.04L, 0.0L, 0.01L};
  EXPECT_EQ(manifoldPlanForView(kBox, std::nullopt, zoom)[0].maxSpacing, 0.04L / 400);
  const PhysicalRect tall{0.0L, 0.01L, 0.0L, 0.08L};
  EXPECT_EQ(manifoldPlanForView(kBox, std::nullopt, tall)[0].maxSpacing, 0.08L / 400);
  // A deep zoom is clamped to kMinManifoldSpacing (issue 36: a finer bound recursed for hours).
  const PhysicalRect deep{0.1L, 0.1L + 1e-15L, 0.0L, 1e-15L};
  EXPECT_EQ(manifoldPlanForView(kBox, std::nullopt, deep)[0].maxSpacing, kMinManifoldSpacing);
}

}  // namespace
}  // namespace archipelago
