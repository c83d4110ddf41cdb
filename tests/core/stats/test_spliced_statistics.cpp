// Composite statistics (issue #26; docs/design.md, "Blocks of q steps"): a run of q = 16 spliced with its q = 1
// companion must give the statistics of the paper's q = 1 process.  The reference is an independent q = 1 run
// (another seed, as many steps as the q = 16 run): over the overlap the spliced C_τ and S_t agree with it within
// errors, while the q = 16 run alone does not at τ < 10 q (the block artefact the splice removes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <tuple>

#include "core/report/ReportRuns.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/stats/RunStatistics.hpp"

namespace archipelago {
namespace {

// The value and error of `s` at abscissa x, linearly interpolated between its neighbouring grid points (the grids
// are integers up to a few hundred, then 30 points a decade: a linear step is far below the errors compared);
// NaN outside s's range.
struct Point {
  double value = NAN, error = NAN;
};
Point at(const Series& s, double x) {
  for (std::size_t i = 0; i + 1 < s.x.size(); ++i) {
    if (s.x[i] <= x && x <= s.x[i + 1]) {
      const double w = s.x[i + 1] == s.x[i] ? 0 : (x - s.x[i]) / (s.x[i + 1] - s.x[i]);
      return {s.value[i] + w * (s.value[i + 1] - s.value[i]), s.error[i] + w * (s.error[i + 1] - s.error[i])};
    }
  }
  return {};
}

// Counts the abscissae x in [from, to] of `reference` where `s` differs from it by more than `sigmas` combined
// standard errors, and those compared.
struct Agreement {
  int compared = 0, outside = 0;
};
Agreement compare(const Series& s, const Series& reference, double from, double to, double sigmas) {
  Agreement a;
  for (std::size_t i = 0; i < reference.x.size(); ++i) {
    const double x = reference.x[i];
    if (x < from || x > to) continue;
    const Point p = at(s, x);
    if (!std::isfinite(p.value)) continue;
    ++a.compared;
    const double tol = sigmas * std::hypot(p.error, reference.error[i]);
    if (std::abs(p.value - reference.value[i]) > tol) ++a.outside;
  }
  return a;
}

TEST(SplicedStatistics, EqualAnIndependentQ1RunOverTheOverlap_Issue26) {
  TrappingParameters p = report::k01Run(report::ReportSize::quick).params;  // K = 0.1, fig. 6's box
  p.q = 16;
  p.T = 40'000;  // 64 orbits × 6.4·10⁵ steps: under a second
  const TrappingState run = runTrapping(startTrapping(p), TrappingRunOptions{});
  const TrappingState companion = runTrapping(startTrapping(companionParameters(p, 0.25)), TrappingRunOptions{});
  TrappingParameters ref = p;  // the paper's process at q = 1, its own random numbers
  ref.q = 1;
  ref.T = p.T * p.q;
  ref.seed = p.seed + 1000;
  const TrappingState reference = runTrapping(startTrapping(ref), TrappingRunOptions{});

  const TrappingStatistics spliced = splicedStatisticsOf(run, companion);
  const TrappingStatistics alone = statisticsOf(run);
  const TrappingStatistics q1 = statisticsOf(reference);
  ASSERT_GE(spliced.splicedAt, 10.0 * p.q);
  EXPECT_EQ(alone.blockAffectedBelow, 10.0 * p.q);
  EXPECT_EQ(spliced.blockAffectedBelow, 0.0);

  // 3σ of the two subset errors: with some 30–60 grid points compared, one outside is allowed for chance
  // (P(|z| > 3) = 0.27 % a point; the points are correlated, so not much more than that).
  const double end = 1e3;  // well inside both runs' data (their longest segments reach 10⁴–10⁵ steps)
  for (const auto& [name, ours, theirs] : {std::tuple{"C", &spliced.C, &q1.C}, std::tuple{"S", &spliced.S, &q1.S}}) {
    const Agreement a = compare(*ours, *theirs, 1, end, 3);
    SCOPED_TRACE(name);
    EXPECT_GE(a.compared, 20);
    EXPECT_LE(a.outside, 1) << a.outside << " of " << a.compared << " points differ by more than 3 σ";
  }
  // The q = 16 run alone is off below q (C_τ ≈ 1 − τ/q there: most of its segments are one block, a point mass at
  // q steps): the same comparison must see it at every point.
  const Agreement blocks = compare(alone.C, q1.C, 2, p.q - 1, 3);
  EXPECT_GE(blocks.compared, 10);
  EXPECT_EQ(blocks.outside, blocks.compared) << "the block artefact is visible in C_τ of the q = 16 run alone";
}

}  // namespace
}  // namespace archipelago
