// Counter-based random numbers (docs/design.md, "Arithmetic contract"): reference values computed independently in Python.
#include <gtest/gtest.h>

#include "core/random/CounterRng.hpp"

namespace archipelago {

TEST(CounterRng, Mix64MatchesReferenceValues) {
  EXPECT_EQ(mix64(0), 0u);  // the finaliser fixes 0
  EXPECT_EQ(mix64(1), 0x5692161d100b05e5ULL);
  EXPECT_EQ(mix64(0x123456789abcdefULL), 0xb2c058e4ebb5112cULL);
}

TEST(CounterRng, OrbitDrawsMatchReferenceValues) {
  const std::uint64_t key = orbitKey(42, 7);
  EXPECT_EQ(key, 0x92ed6459045eb613ULL);
  EXPECT_EQ(orbitDraw(key, 1), 156596695972101ULL);
  EXPECT_EQ(orbitDraw(key, 2), 1412171168441648ULL);
  EXPECT_EQ(orbitDraw(key, 3), 3309316825434084ULL);
}

TEST(CounterRng, DrawsAre52BitFractions) {
  const std::uint64_t key = orbitKey(1, 0);
  std::uint64_t orBits = 0;
  for (std::uint64_t k = 1; k <= 100000; ++k) {
    const std::uint64_t u = orbitDraw(key, k);
    ASSERT_LT(u, std::uint64_t{1} << 52);
    orBits |= u;
  }
  EXPECT_EQ(orBits, (std::uint64_t{1} << 52) - 1);  // every bit is used
}

}  // namespace archipelago
