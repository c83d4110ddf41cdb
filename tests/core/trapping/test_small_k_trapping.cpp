// The paper's small-K results (§4, fig. 3), reproduced by short runs of the engine.
// Runs: q = 1, box xmin = −0.05, xmax = 0.05 (about 5√|K|, wide enough to hold the islands of §4).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/run/TrappingRun.hpp"

namespace archipelago {
namespace {

TrappingState smallKRun(double K, std::uint64_t T) {
  TrappingParameters p;
  p.map = {K, -0.05, 0.05};
  p.q = 1;
  p.M = 64;
  p.T = T;
  p.seed = 2026;
  return runTrapping(startTrapping(p), TrappingRunOptions{});
}

struct Point {
  double t, logf, weight;
};

// f_t per bin (appendix A estimator, divided by the bin width), at the bin's mean length.
std::vector<Point> densities(const TrappingState& s, double tmin, double tmax) {
  const TrappingHistogram h = s.total();
  std::vector<Point> out;
  for (int i = 1; i < TrappingHistogram::kBins; ++i) {
    if (h.count(i) < 5) continue;  // too few segments to take a logarithm of
    const double t = static_cast<double>(h.lengthSum(i)) / static_cast<double>(h.count(i));
    if (t < tmin || t > tmax) continue;
    const double width = static_cast<double>(TrappingHistogram::binUpper(i) - TrappingHistogram::binLower(i));
    const double f = static_cast<double>(h.count(i)) /
                     (static_cast<double>(s.params.M) * (static_cast<double>(s.params.T) + 1 - t)) / width;
    out.push_back({t, std::log(f), static_cast<double>(h.count(i))});
  }
  return out;
}

// Weighted least-squares slope of logf against x(t), weights = counts (Poisson).
template <class X>
double slope(const std::vector<Point>& pts, X x) {
  double w = 0, mx = 0, my = 0;
  for (const auto& p : pts) w += p.weight, mx += p.weight * x(p.t), my += p.weight * p.logf;
  mx /= w, my /= w;
  double sxy = 0, sxx = 0;
  for (const auto& p : pts) sxy += p.weight * (x(p.t) - mx) * (p.logf - my), sxx += p.weight * (x(p.t) - mx) * (x(p.t) - mx);
  return sxy / sxx;
}

// K < 0: no periodic orbits; no segment is longer than t_max = 5.1454 |K|^(−1/4) = 51.45 (lower in a finite
// box, §4), and f_t piles up just below the cut-off (the (Tmax − T)^(−1/2) singularity of F(T), fig. 3a).
TEST(SmallKTrapping, NegativeKHasACutoffBelowTmax) {
  const TrappingState s = smallKRun(-1e-4, 2'000'000);
  const TrappingHistogram h = s.total();
  const int last = h.lastUsedBin();
  const double tmax = 5.1454 * std::pow(1e-4, -0.25);
  EXPECT_LE(static_cast<double>(last), tmax);
  EXPECT_GE(static_cast<double>(last), 0.6 * tmax);
  // The pile-up: f_t falls with t, reaches a minimum, then rises again just below the cut-off.
  int lowest = last - 10;
  for (int i = last - 10; i < last; ++i)
    if (h.count(i) < h.count(lowest)) lowest = i;
  std::uint64_t peak = 0;
  for (int i = lowest; i <= last; ++i) peak = std::max(peak, h.count(i));
  EXPECT_GT(lowest, last - 10) << "no minimum before the cut-off";
  EXPECT_GT(static_cast<double>(peak), 1.25 * static_cast<double>(h.count(lowest)))
      << "no singular pile-up below the cut-off";
}

// K = 0: f_t ~ t^−7 for large t (Zisook; §4) — reached only beyond t ≈ 100 (fig. 3b), steeper than t^−6 before.
TEST(SmallKTrapping, ZeroKDecaysAsTToTheMinusSeven) {
  const TrappingState s = smallKRun(0, 12'000'000);
  const auto logt = [](double t) { return std::log(t); };
  const double early = slope(densities(s, 40, 200), logt);
  const double late = slope(densities(s, 100, 400), logt);
  EXPECT_LT(late, early) << "the decay must steepen towards t^-7";
  EXPECT_NEAR(late, -7.0, 1.0) << "local exponent of f_t for 100 <= t <= 400";
  EXPECT_GT(late, -8.0);
}

// K > 0 small: f_t ~ exp(−½ log λ · t) ≈ exp(−K^¼ t) = exp(−0.1 t) at K = 1e−4 (fig. 3c); rate within 15 %.
TEST(SmallKTrapping, SmallPositiveKDecaysExponentially) {
  const TrappingState s = smallKRun(1e-4, 4'000'000);
  const auto linear = [](double t) { return t; };
  const double rate = -slope(densities(s, 60, 250), linear);
  EXPECT_NEAR(rate, 0.1, 0.015);
}

}  // namespace
}  // namespace archipelago
