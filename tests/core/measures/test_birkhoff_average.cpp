// Weighted Birkhoff averages (core/measures/BirkhoffAverage.hpp): the weight's definition, the super-convergence
// on a quasi-periodic sequence (against the plain average), and the digits' cap and NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/measures/BirkhoffAverage.hpp"

namespace archipelago {
namespace {

TEST(BirkhoffAverage, WeightIsTheBumpOfDasSaikiSanderYorke) {
  EXPECT_EQ(birkhoffWeight(0.5), std::exp(-4.0));  // 1/(½·½) = 4
  EXPECT_EQ(birkhoffWeight(0.25), std::exp(-1 / (0.25 * 0.75)));
  EXPECT_EQ(birkhoffWeight(0.25), birkhoffWeight(0.75));
  for (double s : {0.0, 1.0, -0.5, 1.5, std::nan("")}) EXPECT_EQ(birkhoffWeight(s), 0.0) << s;
  const BirkhoffWeights w = birkhoffWeights(1000);
  ASSERT_EQ(w.g.size(), 1000u);
  EXPECT_EQ(w.g[0], 0.0);
  EXPECT_EQ(w.g[500], std::exp(-4.0));
  // Σ g(n/T) ≈ T ∫ g = 0.00702985… · T (the integral of the bump, by a long double midpoint rule here).
  long double integral = 0;
  constexpr int kSteps = 1'000'000;
  for (int i = 0; i < kSteps; ++i) {
    const long double s = (i + 0.5L) / kSteps;
    integral += std::exp(-1 / (s * (1 - s))) / kSteps;
  }
  EXPECT_NEAR(w.sum / 1000, static_cast<double>(integral), 1e-15);
  EXPECT_THROW((void)birkhoffWeights(kMinIterations - 1), std::invalid_argument);
  EXPECT_THROW((void)birkhoffWeights(kMaxIterations + 1), std::invalid_argument);
}

TEST(BirkhoffAverage, ConvergesFasterThanAnyPowerOnAQuasiPeriodicSequence) {
  // f_n = cos(2π(nω + φ)) with ω the golden mean's fraction: a rotation on a circle, average exactly 0.  The
  // plain average errs by O(1/T); the weighted one reaches rounding level (compensated sums: ~10⁻¹⁶).
  const double omega = (std::sqrt(5.0) - 1) / 2;
  for (std::size_t T : {1000u, 10000u}) {
    std::vector<double> f(T);
    double plain = 0;
    for (std::size_t n = 0; n < T; ++n) {
      f[n] = std::cos(2 * std::numbers::pi * (static_cast<double>(n) * omega + 0.1));
      plain += f[n] / static_cast<double>(T);
    }
    const double weighted = weightedBirkhoffAverage(f);
    EXPECT_LT(std::fabs(weighted), T == 1000 ? 1e-11 : 1e-14) << T;
    EXPECT_GT(std::fabs(plain), 1e-6 / static_cast<double>(T) * 100) << T;  // the plain average is ~1/T off
  }
}

TEST(BirkhoffAverage, DigitsAreCappedAndNaNAware) {
  EXPECT_EQ(convergenceDigits(1.0, 1.0), kMaxDigits);
  EXPECT_EQ(convergenceDigits(0.0, 1e-20), kMaxDigits);
  EXPECT_DOUBLE_EQ(convergenceDigits(0.5, 0.5 + 1e-3), 3.0);
  EXPECT_TRUE(std::isnan(convergenceDigits(std::nan(""), 1)));
  EXPECT_LT(convergenceDigits(0, 100), 0);  // a difference above 1: negative digits, not clamped at 0
}

}  // namespace
}  // namespace archipelago
