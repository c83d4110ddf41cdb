// What a portrait draws of an atlas island (AtlasIslandView.hpp): how many boundary points, the island's circle cut
// out of the chain's orbit, the frame about it, and an orbit kept as one point found again whole.
#include <gtest/gtest.h>

#include "core/atlas/AtlasIslandView.hpp"
#include "core/limits/Limits.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {
namespace {

const MapParameters kMap{0.1, -0.8, 0.5};

TEST(AtlasIslandView, BoundaryStepsAreFourThousandPerIslandWithinTheirBounds) {
  EXPECT_EQ(atlasBoundarySteps(1), kAtlasMinBoundaryPoints);  // 4000 < 20000
  EXPECT_EQ(atlasBoundarySteps(6), 24'000u);
  EXPECT_EQ(atlasBoundarySteps(138), 552'000u);
  EXPECT_EQ(atlasBoundarySteps(100'000), std::min(kAtlasMaxBoundaryPoints, limits::kOrbitLength));
}

TEST(AtlasIslandView, TheIslandsCircleIsEveryNthPointFromTheOneNearestItsCentre) {
  // Three islands at x = 0, 10, 20; the orbit visits them in turn, its first point on the island at 0.
  std::vector<PhysicalPoint> orbit;
  for (int k = 0; k < 12; ++k) orbit.push_back({10.0L * (k % 3) + 0.01L * k, 0});
  const std::vector<PhysicalPoint> own = islandCircle(orbit, 3, {10, 0});
  ASSERT_EQ(own.size(), 4u);
  for (const PhysicalPoint& p : own) EXPECT_NEAR(static_cast<double>(p.x), 10, 0.2);
  EXPECT_EQ(own.front().x, orbit[1].x);
  EXPECT_EQ(islandCircle(orbit, 1, {20, 0}).size(), orbit.size());  // the centre: the whole orbit
  EXPECT_TRUE(islandCircle({}, 3, {0, 0}).empty());
}

TEST(AtlasIslandView, TheCentralIslandIsFramedAboutItsCircleWithAQuarterMargin) {
  AtlasNode centre;
  centre.period = 1;
  centre.orbit = *refinePeriodicOrbit(0.1L, 1, {-0.3162L, 0});
  centre.centre = centre.orbit.points.front();
  centre.boundaryFound = true;
  centre.boundaryPoint = {centre.centre.x + 0.2L, 0};
  const AtlasIslandView view = atlasIslandView(kMap, centre);
  EXPECT_EQ(view.boundary.size(), kAtlasMinBoundaryPoints + 1);  // the start and its images
  ASSERT_TRUE(view.island);
  const SegmentRegion bare = dwellRegion(view.boundary, 1.0, 64, 0);
  EXPECT_NEAR(static_cast<double>(view.island->width()), 1.5 * static_cast<double>(bare.width()), 1e-12);
  EXPECT_LT(view.island->x0, centre.centre.x);
  EXPECT_GT(view.island->x1, centre.boundaryPoint.x);
  ASSERT_TRUE(view.chain);
  EXPECT_EQ(view.chain->period, 1);
  EXPECT_FALSE(view.partner);
  EXPECT_TRUE(view.missing.empty()) << view.missing;
}

TEST(AtlasIslandView, AnOrbitKeptAsOnePointIsFoundAgainWhole) {
  const PeriodicOrbit six = *refinePeriodicOrbit(0.1L, 6, {0.052L, 0.096L});
  PeriodicOrbit kept = six;  // as an atlas read from JSON keeps it
  kept.points.resize(1);
  const std::optional<PeriodicOrbit> whole = wholeOrbit(0.1L, kept);
  ASSERT_TRUE(whole);
  ASSERT_EQ(whole->points.size(), 6u);
  EXPECT_NEAR(static_cast<double>(whole->points[0].x), static_cast<double>(six.points[0].x), 1e-12);
  EXPECT_EQ(wholeOrbit(0.1L, six)->points.size(), 6u);  // whole already: as it is
  PeriodicOrbit none = six;
  none.points.clear();
  EXPECT_FALSE(wholeOrbit(0.1L, none));

  AtlasNode chain;  // no boundary: nothing traced, the chain whole, a partner that Newton cannot find named
  chain.period = 6;
  chain.parent = 0;
  chain.orbit = kept;
  PeriodicOrbit lost;
  lost.period = 6;
  lost.points = {{std::nanl(""), 0}};  // no Newton converges from here
  chain.flux.partner = lost;
  const AtlasIslandView view = atlasIslandView(kMap, chain);
  EXPECT_TRUE(view.boundary.empty());
  EXPECT_FALSE(view.island);
  ASSERT_TRUE(view.chain);
  EXPECT_EQ(view.chain->points.size(), 6u);
  EXPECT_FALSE(view.partner);
  EXPECT_EQ(view.missing, "the hyperbolic partner (not found again)");
}

}  // namespace
}  // namespace archipelago
