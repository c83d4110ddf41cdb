// Island-chain identification from a segment (core/periodic/IslandChain.hpp), on synthetic orbits of Q
// started inside known islands at K = 0.1.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/periodic/IslandChain.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"
#include "LongDoubleNear.hpp"

namespace archipelago {
namespace {

std::vector<PhysicalPoint> orbitOfQ(long double K, PhysicalPoint start, int steps) {
  std::vector<PhysicalPoint> points;
  smooth::Point<long double> z{start.x, start.y};
  for (int t = 0; t < steps; ++t) {
    points.push_back({z.x, z.y});
    z = smooth::step(K, z);
  }
  return points;
}

TEST(IslandChain, OrbitInsideASixIslandGivesPeriodSixAndItsEllipticOrbit) {
  // Start 0.01 from the centre (0.05090, 0.09741) of one of the six islands.
  const std::vector<PhysicalPoint> segment = orbitOfQ(0.1L, {0.0609L, 0.0974L}, 5000);
  const IslandChain chain = identifyIslandChain(0.1L, segment);
  EXPECT_EQ(chain.period, 6);
  EXPECT_EQ(chain.hierarchy, (std::vector<int>{1, 6}));
  EXPECT_TRUE(Near(chain.rotationNumber, 1.0L / 6, 1e-3L));
  EXPECT_LT(std::hypot(chain.member.x - 0.0509L, chain.member.y - 0.0974L), 0.01L);
  ASSERT_TRUE(chain.centre.has_value());
  EXPECT_EQ(chain.centre->period, 6);
  EXPECT_TRUE(chain.centre->stable());
  EXPECT_TRUE(Near(chain.centre->residue, 0.1482764292L, 1e-9L));
  EXPECT_TRUE(Near(chain.centre->points[0].x, 0.0509024128L, 1e-9L));
  EXPECT_TRUE(Near(chain.centre->points[0].y, 0.0974089444L, 1e-9L));
}

TEST(IslandChain, OrbitInsideASatelliteGivesPeriod138) {
  // Start 5e-4 from the elliptic period-138 point (0.036029, 0.034181) of §6.
  const std::vector<PhysicalPoint> segment = orbitOfQ(0.1L, {0.0365L, 0.0342L}, 5000);
  const IslandChain chain = identifyIslandChain(0.1L, segment);
  EXPECT_EQ(chain.period, 138);
  EXPECT_EQ(chain.hierarchy, (std::vector<int>{1, 6, 138}));
  ASSERT_TRUE(chain.centre.has_value());
  EXPECT_EQ(chain.centre->period, 138);
  EXPECT_TRUE(chain.centre->stable());
  EXPECT_TRUE(Near(chain.centre->points[0].x, 0.036028653309L, 1e-11L));
  EXPECT_TRUE(Near(chain.centre->points[0].y, 0.034180912451L, 1e-11L));
}

TEST(IslandChain, KamCurveAroundTheCentreIsPeriodOneDespiteNearReturns) {
  // ω ≈ 0.189 per step: 127 steps nearly return (127 ω ≈ 24.003), a false chain of 127 that the
  // turning test rejects.
  const std::vector<PhysicalPoint> segment = orbitOfQ(0.1L, {-0.25L, 0.0L}, 5000);
  const IslandChain chain = identifyIslandChain(0.1L, segment);
  EXPECT_EQ(chain.period, 1);
  ASSERT_TRUE(chain.centre.has_value());
  EXPECT_TRUE(Near(chain.centre->points[0].x, -std::sqrt(0.1L), 1e-15L));
  EXPECT_TRUE(Near(chain.centre->residue, std::sqrt(0.1L), 1e-15L));
}

TEST(IslandChain, RejectsShortOrNonFiniteSegments) {
  std::vector<PhysicalPoint> segment = orbitOfQ(0.1L, {-0.25L, 0.0L}, 10);
  EXPECT_THROW((void)identifyIslandChain(0.1L, segment), std::invalid_argument);
  segment = orbitOfQ(0.1L, {-0.25L, 0.0L}, 100);
  segment[50].x = std::nanl("");
  EXPECT_THROW((void)identifyIslandChain(0.1L, segment), std::invalid_argument);
  IslandChainOptions bad;
  bad.confinementRatio = 1.5L;
  EXPECT_THROW((void)identifyIslandChain(0.1L, orbitOfQ(0.1L, {-0.25L, 0.0L}, 100), bad), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago
