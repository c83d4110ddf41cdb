#pragma once
// A long-double |a − b| ≤ tolerance assertion for the periodic-orbit tests (EXPECT_NEAR rounds both to double).
#include <gtest/gtest.h>

#include <cmath>

namespace archipelago {

inline ::testing::AssertionResult Near(long double a, long double b, long double tolerance) {
  if (std::fabs(a - b) <= tolerance) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << static_cast<double>(a) << " vs " << static_cast<double>(b) << " differ by "
                                       << static_cast<double>(std::fabs(a - b)) << " > " << static_cast<double>(tolerance);
}

}  // namespace archipelago
