// A line or a grid of launched orbits (issue 37, finding 15): the starts, and the one bound of launched orbits
// (kMaxSessionOrbits) with those already launched, in core/limits' wording.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <string>

#include "core/session/OrbitFamily.hpp"
#include "core/session/SessionFile.hpp"

namespace archipelago {
namespace {

std::string errorOf(const OrbitFamily& f, std::size_t launched) {
  try {
    (void)orbitFamilyStarts(f, launched);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TEST(OrbitFamily, ALineIsEquallySpacedFromEndToEnd) {
  const auto s = orbitFamilyStarts({{-0.3L, 0.0L}, {-0.1L, 0.04L}, 5, 1});
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s.front().x, -0.3L);
  EXPECT_EQ(s.back().x, -0.1L);
  EXPECT_EQ(s.back().y, 0.04L);
  EXPECT_NEAR(static_cast<double>(s[2].x), -0.2, 1e-18);
  EXPECT_NEAR(static_cast<double>(s[2].y), 0.02, 1e-18);
  const auto one = orbitFamilyStarts({{0.1L, 0.2L}, {0.3L, 0.4L}, 1, 1});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].x, 0.1L);
}

TEST(OrbitFamily, AGridIsRowByRowOverTheRectangle) {
  const auto s = orbitFamilyStarts({{0.0L, 0.0L}, {0.2L, 0.1L}, 3, 2});
  ASSERT_EQ(s.size(), 6u);
  EXPECT_EQ(s[0].y, 0.0L);
  EXPECT_EQ(s[2].x, 0.2L);
  EXPECT_EQ(s[2].y, 0.0L);  // the first row is along x at y = from.y, not along the diagonal
  EXPECT_EQ(s[3].x, 0.0L);
  EXPECT_EQ(s[5].y, 0.1L);
}

TEST(OrbitFamily, TheCountIsBoundedWithThoseLaunched) {
  EXPECT_EQ(errorOf({{0, 0}, {1, 1}, 0, 1}, 0), "orbits per row = 0 must lie in [1, 500]");
  EXPECT_EQ(errorOf({{0, 0}, {1, 1}, 2, 0}, 0), "rows of orbits = 0 must lie in [1, 500]");
  EXPECT_EQ(errorOf({{0, 0}, {1, 1}, 100, 5}, 0), "");
  EXPECT_EQ(errorOf({{0, 0}, {1, 1}, 100, 5}, 1),
            "orbits launched at once = 500 must lie in [1, 499] (the portrait keeps at most 500 launched orbits; 1 "
            "launched already)");
  EXPECT_EQ(orbitFamilyStarts({{0, 0}, {1, 1}, kMaxSessionOrbits, 1}).size(), kMaxSessionOrbits);
  EXPECT_NE(errorOf({{0, std::numeric_limits<long double>::quiet_NaN()}, {1, 1}, 2, 1}, 0), "");
}

}  // namespace
}  // namespace archipelago
