// core/stats/LogFits: fits with equal weight per unit of log t (issue #26, finding 4: fits over the statistics' grid,
// dense in integers, weighted q-dependent parts of t differently).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

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

/// The fit as written before it read only the window: every usable point's logarithms, then the grid (the reference
/// for the windowed reading, which must give the same numbers to the last bit).
SlopeFit wholeSeriesFit(const Series& s, double from, double to, int perDecade) {
  using Real = long double;
  struct P {
    Real u, v, sigma;
  };
  std::vector<P> p;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!(s.x[i] > 0 && s.value[i] > 0) || !std::isfinite(s.value[i])) continue;
    const Real e = std::isfinite(s.error[i]) ? s.error[i] : 0;
    p.push_back({std::log(Real(s.x[i])), std::log(Real(s.value[i])), e / Real(s.value[i])});
  }
  SlopeFit fit;
  if (p.size() < 2 || !(from > 0) || !(to > from)) return fit;
  const Real ln10 = std::log(Real(10));
  const Real first = std::max(std::log(Real(from)), p.front().u), last = std::min(std::log(Real(to)), p.back().u);
  std::vector<P> g;
  std::size_t j = 0;
  for (long k = static_cast<long>(std::ceil(first / ln10 * perDecade - 1e-9));
       k <= static_cast<long>(std::floor(last / ln10 * perDecade + 1e-9)); ++k) {
    const Real u = std::min(std::max(ln10 * k / perDecade, p.front().u), p.back().u);
    while (j + 2 < p.size() && p[j + 1].u < u) ++j;
    const P &a = p[j], &b = p[j + 1];
    const Real w = b.u > a.u ? std::min(std::max((u - a.u) / (b.u - a.u), Real(0)), Real(1)) : 0;
    g.push_back({u, a.v + w * (b.v - a.v), a.sigma + w * (b.sigma - a.sigma)});
  }
  fit.points = g.size();
  if (g.size() < 3) return fit;
  Real su = 0, sv = 0;
  for (const P& q : g) su += q.u, sv += q.v;
  const Real n = Real(g.size()), ub = su / n, vb = sv / n;
  Real suu = 0, suv = 0;
  for (const P& q : g) suu += (q.u - ub) * (q.u - ub), suv += (q.u - ub) * (q.v - vb);
  if (!(suu > 0)) return fit;
  Real var = 0;
  for (const P& q : g) var += (q.u - ub) * (q.u - ub) / (suu * suu) * q.sigma * q.sigma;
  fit.slope = static_cast<double>(suv / suu);
  fit.error = static_cast<double>(std::sqrt(var));
  fit.from = static_cast<double>(std::exp(g.front().u));
  fit.to = static_cast<double>(std::exp(g.back().u));
  return fit;
}

TEST(LogFits, AWindowReadsOnlyItsPointsAndGivesTheWholeSeriesFitToTheLastBit) {
  // Series on log grids (as the statistics give them) and on irregular ones, with holes (zeros, negative and NaN
  // values), repeated abscissae, windows inside, across either end, beyond the series and between two points.
  std::mt19937_64 random(20261128);
  std::uniform_real_distribution<double> unit(0, 1);
  int compared = 0, valid = 0;
  for (int series = 0; series < 60; ++series) {
    Series s;
    double t = 1 + 10 * unit(random);
    const int n = 5 + static_cast<int>(400 * unit(random));
    for (int i = 0; i < n; ++i) {
      t *= series % 3 == 0 ? std::pow(10.0, 1.0 / 25) : 1 + (unit(random) < 0.05 ? 0 : 2 * unit(random));
      const double r = unit(random);
      s.x.push_back(t);
      s.value.push_back(r < 0.05 ? 0 : r < 0.08 ? -1 : r < 0.1 ? std::nan("") : std::pow(t, -1.3) * (1 + 0.3 * unit(random)));
      s.error.push_back(unit(random) < 0.1 ? std::nan("") : 0.1 * std::fabs(s.value.back()));
    }
    for (int w = 0; w < 40; ++w) {
      const double a = std::exp(std::log(s.x.front()) - 2 + (std::log(s.x.back()) - std::log(s.x.front()) + 4) * unit(random));
      const double b = w % 4 == 0 ? a * (1 + 1e-3 * unit(random)) : a * std::exp(6 * unit(random));
      const double from = w % 7 == 0 ? s.x[static_cast<std::size_t>(unit(random) * n)] : a;  // on a point
      const int perDecade = 1 + static_cast<int>(40 * unit(random));
      const SlopeFit expected = wholeSeriesFit(s, from, b, perDecade), got = logLogSlope(s, from, b, perDecade);
      const SlopeFit once = logLogSlope(LogSeries(s), from, b, perDecade);  // the logarithms taken once
      EXPECT_EQ(once.points, expected.points);
      EXPECT_TRUE(!expected.valid() || (once.slope == expected.slope && once.error == expected.error));
      const SlopeFit ranged = logLogSlope(LogSeries(s, from / (1 + unit(random)), b * (1 + unit(random))), from, b,
                                          perDecade);  // the logarithms of a range holding the window
      EXPECT_EQ(ranged.points, expected.points);
      EXPECT_TRUE(!expected.valid() || (ranged.slope == expected.slope && ranged.error == expected.error));
      ++compared;
      valid += expected.valid() ? 1 : 0;
      ASSERT_EQ(got.points, expected.points) << series << " " << w;
      ASSERT_EQ(got.valid(), expected.valid());
      if (!expected.valid()) continue;
      EXPECT_EQ(got.slope, expected.slope) << series << " " << w;
      EXPECT_EQ(got.error, expected.error);
      EXPECT_EQ(got.from, expected.from);
      EXPECT_EQ(got.to, expected.to);
    }
  }
  EXPECT_EQ(compared, 2400);
  EXPECT_GT(valid, 1000);  // most windows fit (the comparison is not of empty fits)
}

}  // namespace
}  // namespace archipelago
