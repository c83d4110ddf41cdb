// The Kac check (core/manifolds/KacCheck.hpp), small: the finite-T identity Φ⟨min(τ, T)⟩ = area{τ_f ≤ T} holds within
// the statistical errors, no orbit leaves the zone other than through the exit lobe, and the result does not depend
// on the number of threads.  (The full-size measurement: scripts/kac-check.sh, docs/manifolds.md.)
#include <gtest/gtest.h>

#include <cmath>

#include "core/manifolds/KacCheck.hpp"

namespace archipelago {
namespace {

// Both sides are means of independent samples: their difference over the combined standard error is ~N(0, 1).
// |z| < 4 fails by chance with probability 6e−5 per K.
TEST(KacCheck, ResidenceTimeEqualsTransitAreaOverFlux) {
  for (long double K : {0.2L, 0.1L}) {
    KacRequest r;
    r.K = K;
    r.entrySamples = 3000;
    r.zoneSamples = 3000;
    r.maxSteps = 2000;
    r.threads = 2;
    const KacResult k = runKacCheck(r);
    EXPECT_EQ(k.inconsistent, 0u);
    EXPECT_LT(std::fabs(k.discrepancy()), 4) << "K " << static_cast<double>(K) << ": " << k.meanResidence << " +- "
                                             << k.meanResidenceError << " vs " << k.predictedResidence << " +- "
                                             << k.predictedResidenceError;
    // A real test: the residence is many steps and measured to a few per cent.
    EXPECT_GT(k.meanResidence, 10);
    EXPECT_LT(k.meanResidenceError, 0.1 * k.meanResidence);
    EXPECT_GT(k.islandArea, 0);  // the central island never leaves
    EXPECT_NEAR(k.transitArea + k.islandArea, static_cast<double>(k.zoneArea), 1e-12);
  }
}

TEST(KacCheck, IndependentOfTheThreadCount) {
  KacRequest r;
  r.K = 0.2L;
  r.entrySamples = 700;
  r.zoneSamples = 500;
  r.maxSteps = 500;
  r.threads = 1;
  const KacResult one = runKacCheck(r);
  r.threads = 2;
  const KacResult two = runKacCheck(r);
  EXPECT_EQ(one.meanResidence, two.meanResidence);
  EXPECT_EQ(one.transitFraction, two.transitFraction);
  EXPECT_EQ(one.steps, two.steps);
}

TEST(KacCheck, Validates) {
  KacRequest r;
  r.entrySamples = 0;
  EXPECT_TRUE(validationError(r).has_value());
  r.entrySamples = 10;
  r.maxSteps = 0;
  EXPECT_TRUE(validationError(r).has_value());
  r.maxSteps = 10;
  r.K = 2;
  EXPECT_TRUE(validationError(r).has_value());
  r.K = 0.1L;
  EXPECT_FALSE(validationError(r).has_value());
  r.threads = -1;
  EXPECT_THROW((void)runKacCheck(r), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago
