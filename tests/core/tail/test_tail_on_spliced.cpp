// Issue #29 in the GUI and the report: the tail sampler's P_t drawn on the statistics a user sees.  The sampler
// counts segments of whole blocks of q steps (the run's process); statistics spliced with a q = 1 companion count
// the q = 1 process's segments, many more and shorter.  reliableSurvivalIn() scales by α_shown/α_run; the test
// compares the scaled levels with the spliced P_t of an independent pair of runs (its own seeds), level by level.
#include <gtest/gtest.h>

#include <cmath>

#include "core/report/ReportRuns.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/tail/TailResult.hpp"

namespace archipelago {
namespace {

// P of `s` at t, linearly interpolated in log-log between grid points; NaN outside.
double pAt(const Series& s, double t, double* error) {
  for (std::size_t i = 0; i + 1 < s.x.size(); ++i) {
    if (s.x[i] <= t && t <= s.x[i + 1] && s.value[i] > 0 && s.value[i + 1] > 0) {
      const double w = std::log(t / s.x[i]) / std::log(s.x[i + 1] / s.x[i]);
      *error = s.error[i] + w * (s.error[i + 1] - s.error[i]);
      return std::exp(std::log(s.value[i]) + w * std::log(s.value[i + 1] / s.value[i]));
    }
  }
  return NAN;
}

TEST(TailOnSplicedStatistics, ScaledLevelsLieOnTheSplicedPt_Issue29) {
  TrappingParameters p = report::k01Run(report::ReportSize::quick).params;  // K = 0.1, q = 16
  p.seed = 77;
  const TrappingState run = runTrapping(startTrapping(p), TrappingRunOptions{});
  const TrappingState companion = runTrapping(startTrapping(companionParameters(p, 0.1)), TrappingRunOptions{});
  const TrappingStatistics spliced = splicedStatisticsOf(run, companion);
  TailRequest r;
  r.run = p;
  r.run.seed = 78;  // the sampler's own random numbers
  r.population = 100;
  r.replicas = 8;
  r.maxSteps = 100'000;
  TailRunOptions o;
  o.threads = 2;
  const TailResult tail = tailResult(runTail(startTail(r), o));

  double factor = 0;
  const Series scaled = reliableSurvivalIn(tail, run, spliced, &factor);
  EXPECT_NEAR(factor, spliced.alpha / statisticsOf(run).alpha, 1e-12);
  EXPECT_LT(factor, 0.5);  // q = 1 segments are several times more numerous than blocks of 16 steps
  double own = 0;
  const Series unscaled = reliableSurvivalIn(tail, run, statisticsOf(run), &own);
  EXPECT_EQ(own, 1.0);
  ASSERT_EQ(unscaled.x.size(), scaled.x.size());

  int compared = 0;
  for (std::size_t i = 0; i < scaled.x.size(); ++i) {
    if (scaled.x[i] > 3e4) break;  // where the quick run has many segments beyond t
    double e = 0;
    const double P = pAt(spliced.P, scaled.x[i], &e);
    ASSERT_TRUE(std::isfinite(P)) << "t = " << scaled.x[i];
    ++compared;
    // 4σ of the two errors, plus 2 % for the log-log interpolation of the spliced P_t between its grid points.
    EXPECT_LT(std::abs(scaled.value[i] - P), 4 * std::hypot(scaled.error[i], e) + 0.02 * P)
        << "t = " << scaled.x[i] << ": scaled " << scaled.value[i] << ", spliced P_t " << P;
    // Unscaled, the sampler's P_t is that of the blocks' segments: several times the spliced curve.
    EXPECT_GT(unscaled.value[i], 2 * P) << "t = " << scaled.x[i];
  }
  EXPECT_GE(compared, 4);
}

}  // namespace
}  // namespace archipelago
