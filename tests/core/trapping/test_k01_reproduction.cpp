// Karney (1983) §5, fig. 6d and fig. 7: at K = 0.1 the correlation decays as C_τ ~ τ^(−1/4) for τ ≲ 10^4, and
// the spread S_t grows faster than linearly (D_t = S_t/2t increases).  A short run (5·10^8 steps) of the
// paper's box (xmin = −0.8, xmax = 0.5, Xr = 0.02, q = 16) resolves the τ^(−1/4) range.
#include <gtest/gtest.h>

#include "core/stats/RunStatistics.hpp"

namespace archipelago {
namespace {

TEST(K01Reproduction, CorrelationDecaysAsTauToTheMinusOneQuarter) {
  TrappingParameters p;  // defaults: K = 0.1, xmin = −0.8, xmax = 0.5, Xr = 0.02, q = 16
  p.M = 64;
  p.T = 500'000;
  p.seed = 1983;
  const TrappingStatistics s = statisticsOf(runTrapping(startTrapping(p), TrappingRunOptions{}));

  double sum = 0, weights = 0;
  for (std::size_t i = 0; i < s.localExponent.x.size(); ++i) {
    const double tau = s.localExponent.x[i];
    if (tau < 300 || tau > 3000) continue;
    sum += s.localExponent.value[i];
    weights += 1;
  }
  ASSERT_GT(weights, 20);
  EXPECT_NEAR(sum / weights, 0.25, 0.06) << "mean of -dlogC/dlogtau over 300 <= tau <= 3000";

  // Superdiffusive spreading: D_t grows from t = 100 to t = 10^4.
  double d100 = 0, d10000 = 0;
  for (std::size_t i = 0; i < s.Dt.x.size(); ++i) {
    if (d100 == 0 && s.Dt.x[i] >= 100) d100 = s.Dt.value[i];
    if (d10000 == 0 && s.Dt.x[i] >= 10000) d10000 = s.Dt.value[i];
  }
  EXPECT_GT(d10000, 2 * d100);
  EXPECT_NEAR(s.sumTf, 1.0, 1e-3);  // Σ t f_t = C_0 = 1 (appendix A estimator)
}

}  // namespace
}  // namespace archipelago
