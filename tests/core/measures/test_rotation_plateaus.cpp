// The plateaus of a rotation profile (issue 37, finding 17): maximal runs of equal rationals, at least minPoints
// long.  A hand-made profile, so that each rule is seen to choose (a run of 2 is no plateau at 3, a gap splits).
#include <gtest/gtest.h>

#include "core/measures/RotationPlateaus.hpp"

namespace archipelago {
namespace {

RotationProfile profileOf(const std::vector<std::optional<Rational>>& rationals) {
  RotationProfile p;
  for (const auto& r : rationals) {
    RotationProfilePoint point;
    point.rational = r;
    point.measure.value = r ? static_cast<double>(r->p) / static_cast<double>(r->q) : 0.3;
    point.measure.verdict = OrbitVerdict::Regular;
    p.points.push_back(point);
  }
  return p;
}

TEST(RotationPlateaus, MaximalRunsOfEqualRationals) {
  const Rational sixth{1, 6}, fifth{1, 5}, q23{2, 23};
  const RotationProfile p = profileOf({std::nullopt, sixth, sixth, sixth, sixth, std::nullopt, fifth, fifth, q23,
                                       q23, q23, sixth, sixth, sixth});
  const auto plateaus = rotationPlateaus(p);
  ASSERT_EQ(plateaus.size(), 3u);
  EXPECT_EQ(plateaus[0].rational, sixth);
  EXPECT_EQ(plateaus[0].first, 1u);
  EXPECT_EQ(plateaus[0].last, 4u);
  EXPECT_DOUBLE_EQ(plateaus[0].rotation, 1.0 / 6);
  EXPECT_EQ(plateaus[1].rational, q23);  // 1/5 twice is below 3 points
  EXPECT_EQ(plateaus[1].first, 8u);
  EXPECT_EQ(plateaus[2].first, 11u);
  EXPECT_EQ(plateaus[2].last, 13u);  // a run at the end counts
  EXPECT_EQ(rotationPlateaus(p, 2).size(), 4u);
  EXPECT_EQ(rotationPlateaus(p, 5).size(), 0u);
  EXPECT_TRUE(rotationPlateaus(RotationProfile{}).empty());
}

// A regular point that names no rational but measures p/q to 10⁻¹² (an orbit about a sub-island) does not split the
// plateau; one 10⁻⁶ away, or a chaotic point, does.
TEST(RotationPlateaus, ANearPointBridgesAFarOneSplits) {
  const Rational sixth{1, 6};
  RotationProfile p = profileOf({sixth, sixth, std::nullopt, sixth, sixth, std::nullopt, sixth, sixth, sixth});
  p.points[2].measure.value = 1.0 / 6 - 9.4e-13;
  p.points[5].measure.value = 1.0 / 6 + 1e-6;
  auto plateaus = rotationPlateaus(p);
  ASSERT_EQ(plateaus.size(), 2u);
  EXPECT_EQ(plateaus[0].first, 0u);
  EXPECT_EQ(plateaus[0].last, 4u);
  EXPECT_EQ(plateaus[1].first, 6u);
  p.points[2].measure.verdict = OrbitVerdict::Chaotic;
  plateaus = rotationPlateaus(p);
  ASSERT_EQ(plateaus.size(), 1u);  // 0-1 is too short now; 3-4 likewise; 6-8 stays
  EXPECT_EQ(plateaus[0].first, 6u);
}

}  // namespace
}  // namespace archipelago
