// core/stats/LogFits: fits with equal weight per unit of log t (issue #26, finding 4: fits over the statistics' grid,
// dense in integers, weighted q-dependent parts of t differently).
#include <gtest/gtest.h>

#include <cmath>

#include "core/stats/LogFits.hpp"

namespace archipelago {
namespace {

Series powerLaw(const std::vector<double>& x, double a, double c = 3) {
  Series s;
  for (const double t : x) {
    s.x.push_back(t);
    s.value.push_back(c * std::pow(t, -a));
    s.error.push_back(0.01 * c * std::pow(t, -a));
  }
  return s;
}

TEST(LogFits, PowerLawIsExactOnAnyGrid) {
  std::vector<double> dense;
  for (int t = 1; t <= 4096; ++t) dense.push_back(t);
  for (double t = 4096; t < 1e7; t *= std::pow(10.0, 1.0 / 30)) dense.push_back(std::round(t));
  for (const double a : {0.25, 1.5, 7.0}) {
    const SlopeFit f = logLogSlope(powerLaw(dense, a), 10, 1e6);
    ASSERT_TRUE(f.valid());
    EXPECT_NEAR(f.slope, -a, 1e-9 * a);
    EXPECT_EQ(f.points, 51u);  // 10 per decade over [10, 10⁶], both ends
    EXPECT_NEAR(fitLogSlope(powerLaw(dense, a), 10, 1e6), a, 1e-9 * a);
  }
}

TEST(LogFits, EqualWeightPerUnitOfLogT_Issue26) {
  // A broken power law: slope −1 below t = 100, −2 above.  Over [1, 10⁴] the two decades each side weigh the same
  // on a log grid, so the fit is −1.5 however densely the series samples small t.  The old fit over the series'
  // own points (4096 integers below, 30 per decade above) gave nearly −1.
  Series s;
  for (int t = 1; t <= 4096; ++t) {
    s.x.push_back(t);
    s.value.push_back(t <= 100 ? 1.0 / t : 100.0 / (double(t) * t));
    s.error.push_back(0);
  }
  for (double t = 4096 * std::pow(10.0, 1.0 / 30); t <= 1.01e4; t *= std::pow(10.0, 1.0 / 30)) {
    s.x.push_back(t);
    s.value.push_back(100.0 / (t * t));
    s.error.push_back(0);
  }
  const SlopeFit f = logLogSlope(s, 1, 1e4);
  EXPECT_NEAR(f.slope, -1.5, 0.05);
}

TEST(LogFits, ExponentialRateAndItsError) {
  Series s;
  for (int t = 10; t <= 100; t += 2) {
    s.x.push_back(t);
    s.value.push_back(5 * std::exp(-0.1 * t));
    s.error.push_back(0.05 * s.value.back());
  }
  const SlopeFit f = logLinearSlope(s, 20, 90);
  ASSERT_TRUE(f.valid());
  EXPECT_NEAR(f.slope, -0.1, 1e-12);
  // Weighted least squares: σ(slope) = 1/√Σ w (t − t̄)², w = 1/0.05² for every point.
  double mean = 0, n = 0;
  for (int t = 20; t <= 90; t += 2) mean += t, ++n;
  mean /= n;
  double sxx = 0;
  for (int t = 20; t <= 90; t += 2) sxx += (t - mean) * (t - mean) / (0.05 * 0.05);
  EXPECT_NEAR(f.error, 1 / std::sqrt(sxx), 1e-12);
  EXPECT_FALSE(logLinearSlope(s, 20, 22).valid());  // two points
}

}  // namespace
}  // namespace archipelago
