// The hyperbolic partner of an island chain (core/periodic/HyperbolicPartner.hpp): for the central island, the six
// islands and the 138-chain of Karney (1983) §6, an unstable orbit of the same period and winding between the islands.
#include <gtest/gtest.h>

#include <cmath>

#include "core/periodic/HyperbolicPartner.hpp"

namespace archipelago {
namespace {

PeriodicOrbit elliptic(int period, PhysicalPoint near, long double radius) {
  PeriodicOrbitSearch s;
  s.period = period;
  s.near = near;
  s.searchRadius = radius;
  s.stableOnly = true;
  return findPeriodicOrbit(0.1L, s);
}

/// Every point of `partner` between two neighbouring points of `chain`: nearer to the chain than the chain's widest
/// gap between neighbours, and not on any of its points.
void expectBetween(const PeriodicOrbit& partner, const PeriodicOrbit& chain) {
  long double widest = 0;
  for (std::size_t i = 0; i < chain.points.size(); ++i) {
    long double nearest = INFINITY;
    for (std::size_t j = 0; j < chain.points.size(); ++j)
      if (j != i) nearest = std::min(nearest, std::hypot(chain.points[i].x - chain.points[j].x, chain.points[i].y - chain.points[j].y));
    widest = std::max(widest, nearest);
  }
  for (const PhysicalPoint& p : partner.points) {
    EXPECT_LE(chain.distanceTo(p), widest);
    EXPECT_GT(chain.distanceTo(p), 1e-6L);
  }
}

TEST(HyperbolicPartner, OfTheCentralIslandIsTheFixedPoint) {
  const PeriodicOrbit centre = elliptic(1, {-0.32L, 0}, 0.01L);
  const std::optional<PeriodicOrbit> partner = findHyperbolicPartner(centre);
  ASSERT_TRUE(partner);
  EXPECT_NEAR(static_cast<double>(partner->points[0].x), std::sqrt(0.1), 1e-18);
  EXPECT_LT(partner->residue, 0);
}

// The six islands: residues of opposite signs (elliptic 0.148, hyperbolic −0.132 for this near-integrable pair),
// the same rotation 1/6, the partner between the islands.
TEST(HyperbolicPartner, OfTheSixIslands) {
  const PeriodicOrbit six = elliptic(6, {-0.602L, -0.262L}, 0.05L);
  const std::optional<PeriodicOrbit> partner = findHyperbolicPartner(six);
  ASSERT_TRUE(partner);
  EXPECT_EQ(partner->period, 6);
  EXPECT_EQ(partner->windingTurns, six.windingTurns);
  EXPECT_NEAR(static_cast<double>(partner->residue), -0.132008, 1e-6);
  expectBetween(*partner, six);
}

// The 138-chain (23 islands around each of the six): other unstable orbits of period 138 and winding 23 lie near the
// guess (residues −62 and 72.5, tens of spacings away from the chain somewhere); the partner, between the islands,
// has R ≈ −0.717 against the chain's 0.689.
TEST(HyperbolicPartner, OfThe138ChainIsBetweenItsIslands) {
  const PeriodicOrbit chain = elliptic(138, {0.0358L, 0.034L}, 0.005L);
  ASSERT_EQ(chain.windingTurns, 23);
  const std::optional<PeriodicOrbit> partner = findHyperbolicPartner(chain);
  ASSERT_TRUE(partner);
  EXPECT_EQ(partner->windingTurns, 23);
  EXPECT_NEAR(static_cast<double>(partner->residue), -0.71721, 1e-4);
  expectBetween(*partner, chain);
  // A guess inside one of the chain's islands gives the partner too.
  PeriodicOrbitSearch s;
  s.period = 138;
  s.near = {0.0358L, 0.034L};
  s.searchRadius = 0.005L;
  const PeriodicOrbit found = findHyperbolicOrbit(0.1L, s);
  EXPECT_NEAR(static_cast<double>(found.residue), static_cast<double>(partner->residue), 1e-12);
}

TEST(HyperbolicPartner, RejectsWhatIsNotAnEllipticChain) {
  PeriodicOrbitSearch s;
  s.period = 6;
  s.near = {0.0157L, 0};
  const PeriodicOrbit hyperbolic = findPeriodicOrbit(0.1L, s);
  ASSERT_FALSE(hyperbolic.stable());
  EXPECT_THROW((void)findHyperbolicPartner(hyperbolic), std::invalid_argument);
  s.near = {5, 5};
  EXPECT_THROW((void)findHyperbolicOrbit(0.1L, s), std::runtime_error);
}

}  // namespace
}  // namespace archipelago
