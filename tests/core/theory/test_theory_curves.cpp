// Which small-K theory curves apply to a run (Karney 1983, §4), and their fitted amplitudes.  Reference
// values come from the paper (t_max = 5.1454 |K|^−1/4, F ≈ 3.024 (Tmax − T)^−1/2 near the cutoff,
// ½ log λ ≈ K^¼) or are computed here from the formulas, never from this code's earlier output.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "core/runspec/RunSpec.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/theory/SmallKTheory.hpp"
#include "core/theory/TheoryCurves.hpp"

namespace archipelago {
namespace {

TrappingParameters withK(double K) {
  TrappingParameters p;
  p.map.K = K;
  p.map.xmin = -0.05;
  p.map.xmax = 0.05;
  return p;
}

Series sampled(double from, double to, double step, const std::function<double(double)>& f) {
  Series s;
  for (double t = from; t <= to; t += step) {
    s.x.push_back(t);
    s.value.push_back(f(t));
    s.error.push_back(0);
  }
  return s;
}

std::vector<const TheoryCurve*> curvesOf(const std::vector<TheoryCurve>& all, Statistic s, TheoryCurve::Kind kind) {
  std::vector<const TheoryCurve*> out;
  for (const TheoryCurve& c : all)
    if (c.statistic == s && c.kind == kind) out.push_back(&c);
  return out;
}

TEST(TheoryCurves, RegimeFollowsTheSignOfKUpToTheSmallKLimit) {
  EXPECT_EQ(smallKRegime(-1e-4), SmallKRegime::negative);
  EXPECT_EQ(smallKRegime(-0.02), SmallKRegime::negative);
  EXPECT_EQ(smallKRegime(0.0), SmallKRegime::zero);
  EXPECT_EQ(smallKRegime(-0.0), SmallKRegime::zero);
  EXPECT_EQ(smallKRegime(1e-4), SmallKRegime::positive);
  EXPECT_EQ(smallKRegime(0.02), SmallKRegime::positive);
  // §4, last paragraph: at K = 0.1 "the foregoing analysis does not apply".
  EXPECT_EQ(smallKRegime(0.1), SmallKRegime::none);
  EXPECT_EQ(smallKRegime(0.021), SmallKRegime::none);
  EXPECT_EQ(smallKRegime(-0.5), SmallKRegime::none);
  EXPECT_EQ(smallKRegime(std::nan("")), SmallKRegime::none);
}

TEST(TheoryCurves, NoneForKPointOneOrWithoutData) {
  TrappingStatistics s;
  s.f = sampled(1, 1000, 1, [](double t) { return std::pow(t, -2.5); });
  s.C = sampled(0, 2000, 1, [](double t) { return 1 / (1 + t); });
  s.P = s.C;
  EXPECT_TRUE(theoryCurves(withK(0.1), s).empty());
  EXPECT_TRUE(theoryCurves(withK(0.05), s).empty());
  EXPECT_TRUE(theoryCurves(withK(-1e-4), TrappingStatistics{}).empty());  // no segment yet
}

// K < 0: the cutoff at t_max = 5.1454 |K|^−1/4 on f_t, P_t and C_τ (paper: t_max ≈ 51.454 at K = −10⁻⁴),
// F(|K|^¼ t) fitted to f_t and C(|K|^¼ τ) to C_τ over 0.4 … 0.85 t_max.
TEST(TheoryCurves, NegativeKHasTheCutoffAndTheFittedShapes) {
  const double K = -1e-4;
  const double a = 7.25e-3;
  TrappingStatistics s;
  s.f = sampled(1, 60, 1, [&](double t) { return a * smallk::negativeKSegmentShape(t, K); });
  for (auto& v : s.f.value)
    if (!std::isfinite(v)) v = 0;  // beyond t_max: f = 0
  s.C = sampled(0, 120, 1, [](double t) { return t < 50 ? std::pow(1 - t / 51.454, 1.5) : 0.0; });
  s.P = s.C;
  const auto all = theoryCurves(withK(K), s);

  const double paperTmax = 5.1454 * std::pow(1e-4, -0.25);  // 51.454
  for (Statistic st : {Statistic::f, Statistic::P, Statistic::C}) {
    const auto lines = curvesOf(all, st, TheoryCurve::Kind::verticalLine);
    ASSERT_EQ(lines.size(), 1u) << statisticInfo(st).key;
    EXPECT_NEAR(lines[0]->at, paperTmax, 1e-5 * paperTmax);  // the paper gives 5 digits
    EXPECT_EQ(lines[0]->label, "t_max = 5.1454 |K|^-1/4");
    EXPECT_TRUE(lines[0]->curve.x.empty());
  }
  EXPECT_TRUE(curvesOf(all, Statistic::P, TheoryCurve::Kind::series).empty());
  EXPECT_TRUE(curvesOf(all, Statistic::S, TheoryCurve::Kind::series).empty());
  EXPECT_TRUE(curvesOf(all, Statistic::Dt, TheoryCurve::Kind::verticalLine).empty());

  const auto f = curvesOf(all, Statistic::f, TheoryCurve::Kind::series);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0]->label, "F(|K|^1/4 t)");
  EXPECT_NEAR(f[0]->amplitude, a, 1e-12 * a);  // data are exactly a·F: the fit returns a
  EXPECT_NEAR(f[0]->fitFrom, 0.4 * paperTmax, 1e-5 * paperTmax);
  EXPECT_NEAR(f[0]->fitTo, 0.85 * paperTmax, 1e-5 * paperTmax);
  EXPECT_EQ(f[0]->fitPoints, 23u);  // t = 21 … 43 lie in [20.58, 43.74]
  ASSERT_GE(f[0]->curve.x.size(), 10u);
  // Near the cutoff the paper gives F(T) ≈ 3.024 (Tmax − T)^−1/2 (T = |K|^¼ t): the last drawn point is
  // within 10⁻⁶ t_max of it.
  const double tLast = f[0]->curve.x.back();
  const double T = 0.1 * tLast, Tmax = 0.1 * f[0]->curve.x.back() / (1 - 1e-6);
  EXPECT_NEAR(tLast, paperTmax * (1 - 1e-6), 1e-5 * paperTmax);
  EXPECT_NEAR(f[0]->curve.value.back() / a, 3.024 / std::sqrt(Tmax - T), 2e-3 * 3.024 / std::sqrt(Tmax - T));

  const auto c = curvesOf(all, Statistic::C, TheoryCurve::Kind::series);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0]->label, "C(|K|^1/4 tau)");
  EXPECT_GT(c[0]->amplitude, 0);
}

// K = 0: f_t ∝ t^−7 and C_τ ∝ τ^−5 (§4), fitted from t = 100 when the data reach beyond t = 300.
TEST(TheoryCurves, ZeroKHasAlgebraicDecays) {
  TrappingStatistics s;
  s.f = sampled(1, 1000, 1, [](double t) { return 5e3 * std::pow(t, -7); });
  s.C = sampled(0, 1000, 1, [](double t) { return t > 0 ? 2e2 * std::pow(t, -5) : 1.0; });
  s.P = s.C;
  const auto all = theoryCurves(withK(0), s);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_TRUE(curvesOf(all, Statistic::f, TheoryCurve::Kind::verticalLine).empty());
  const auto f = curvesOf(all, Statistic::f, TheoryCurve::Kind::series);
  const auto c = curvesOf(all, Statistic::C, TheoryCurve::Kind::series);
  ASSERT_EQ(f.size(), 1u);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(f[0]->label, "t^-7");
  EXPECT_EQ(c[0]->label, "tau^-5");
  EXPECT_EQ(f[0]->fitFrom, 100);
  EXPECT_EQ(f[0]->fitPoints, 901u);  // t = 100 … 1000
  EXPECT_EQ(static_cast<int>(f[0]->curve.x.size()), theoryCurveSamples + 1);
  EXPECT_NEAR(f[0]->curve.x.front(), 100.0 / 3, 1e-9);
  EXPECT_NEAR(f[0]->curve.x.back(), 1000, 1e-9);
  for (std::size_t i = 0; i < f[0]->curve.x.size(); ++i) {
    const double t = f[0]->curve.x[i];
    EXPECT_NEAR(f[0]->curve.value[i], 5e3 * std::pow(t, -7), 1e-12 * 5e3 * std::pow(t, -7)) << t;
  }
  for (std::size_t i = 0; i < c[0]->curve.x.size(); ++i) {
    const double t = c[0]->curve.x[i];
    EXPECT_NEAR(c[0]->curve.value[i], 2e2 * std::pow(t, -5), 1e-12 * 2e2 * std::pow(t, -5)) << t;
  }
}

// 0 < K small: f_t ∝ exp(−½ log λ t), λ = 1 + 2√K + 2√(√K + K) (§4), fitted from t = 2 K^−1/4.
TEST(TheoryCurves, SmallPositiveKHasTheExponentialDecay) {
  const double K = 1e-4;
  const double rate = 0.5 * std::log(1 + 2 * std::sqrt(K) + 2 * std::sqrt(std::sqrt(K) + K));
  EXPECT_NEAR(rate, std::pow(K, 0.25), 0.01 * std::pow(K, 0.25));  // the paper's ≈ K^¼ = 0.1
  TrappingStatistics s;
  s.f = sampled(1, 300, 1, [&](double t) { return 0.3 * std::exp(-rate * t); });
  s.C = sampled(0, 300, 1, [&](double t) { return std::exp(-rate * t); });
  const auto all = theoryCurves(withK(K), s);
  ASSERT_EQ(all.size(), 2u);
  const auto f = curvesOf(all, Statistic::f, TheoryCurve::Kind::series);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0]->label, "exp(-K^1/4 t)");
  EXPECT_NEAR(f[0]->fitFrom, 20, 1e-9);  // 2 K^−1/4
  EXPECT_NEAR(f[0]->amplitude, 0.3, 1e-12);
  for (std::size_t i = 0; i < f[0]->curve.x.size(); ++i) {
    const double t = f[0]->curve.x[i];
    EXPECT_NEAR(f[0]->curve.value[i], 0.3 * std::exp(-rate * t), 1e-12 * 0.3 * std::exp(-rate * t)) << t;
  }
  const auto c = curvesOf(all, Statistic::C, TheoryCurve::Kind::series);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_NEAR(c[0]->amplitude, 1.0, 1e-12);
}

// A series is left out when no data point lies in its fit window (K = 0, data ending before t = 20).
TEST(TheoryCurves, NoCurveWithoutDataInTheFitWindow) {
  TrappingStatistics s;
  s.f = sampled(1, 15, 1, [](double t) { return std::pow(t, -7); });
  s.C = sampled(0, 15, 1, [](double t) { return std::pow(1 + t, -5); });
  EXPECT_TRUE(theoryCurves(withK(0), s).empty());
}

// Issue 13, finding 9: over the fig. 3a preset the fitted F(|K|^¼ t) did not pass through the data.  F is the
// paper's (the tests above), but the preset's box |x| < 0.05 cut every trapped segment short (an orbit leaving
// x = 0.05 still needs about six steps to escape), so f_t ended at t = 37 instead of near t_max = 51.45 (the
// paper's fig. 3a: "a cutoff distribution f_t = 0 for t > t_max ≈ 50"), and the fit window from 0.2 t_max
// took in the t^−6 decay that §4 says differs from F.  A shorter run of the preset (T = 2·10⁶ instead of 2·10⁷).
TEST(TheoryCurves, SmallKNegativePresetReachesTheCutoffAndFollowsF) {
  const Preset* preset = findPreset("small-k-negative");
  ASSERT_NE(preset, nullptr);
  TrappingParameters p = preset->spec.parameters;
  p.T = 2'000'000;
  const TrappingStatistics s = statisticsOf(runTrapping(startTrapping(p), TrappingRunOptions{}));
  const double tmax = 5.1454 * std::pow(-p.map.K, -0.25);
  double last = 0;
  for (std::size_t i = 0; i < s.f.x.size(); ++i)
    if (s.f.value[i] > 0) last = s.f.x[i];
  EXPECT_GT(last, 0.85 * tmax);  // the paper's cutoff "≈ 50"
  EXPECT_LT(last, 1.05 * tmax);  // no segment is much longer than the longest trapping
  const auto all = theoryCurves(p, s);
  const auto f = curvesOf(all, Statistic::f, TheoryCurve::Kind::series);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_GE(f[0]->fitPoints, 15u);
  EXPECT_LT(f[0]->rmsLogResidual, 0.3);  // within ~30 % of the data over the window (it was 2.4 in log)
}

}  // namespace
}  // namespace archipelago
