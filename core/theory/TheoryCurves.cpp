#include "core/theory/TheoryCurves.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/theory/SmallKTheory.hpp"

namespace archipelago {

namespace {

/// Samples a·shape(t) on a logarithmic grid over [tLow, tHigh] (points where shape is not finite and > 0 are
/// left out).
Series sampled(double a, double tLow, double tHigh, const std::function<double(double)>& shape) {
  Series s;
  if (!(tLow > 0) || !(tHigh > tLow)) return s;
  const double ratio = std::log(tHigh / tLow);
  for (int i = 0; i <= theoryCurveSamples; ++i) {
    const double t = tLow * std::exp(ratio * i / theoryCurveSamples);
    const double v = shape(t);
    if (!std::isfinite(v) || v <= 0) continue;
    s.x.push_back(t);
    s.value.push_back(a * v);
    s.error.push_back(0);
  }
  return s;
}

/// Fits the amplitude of `shape` to the data of `statistic` over [tLow, tHigh] and samples it over
/// [drawLow, drawHigh].  Nothing when no data point lies in the window.
void addFitted(std::vector<TheoryCurve>& out, const TrappingStatistics& stats, Statistic statistic,
               const char* label, const char* labelRich, double tLow, double tHigh, double drawLow, double drawHigh,
               const std::function<double(double)>& shape) {
  const Series& data = seriesOf(stats, statistic);
  if (data.x.empty()) return;
  const smallk::AmplitudeFit fit = smallk::fitAmplitude(data.x, data.value, tLow, tHigh, shape);
  if (!fit.valid() || !std::isfinite(fit.amplitude)) return;
  TheoryCurve c;
  c.statistic = statistic;
  c.kind = TheoryCurve::Kind::series;
  c.label = label;
  c.labelRich = labelRich;
  c.curve = sampled(fit.amplitude, drawLow, drawHigh, shape);
  c.amplitude = fit.amplitude;
  c.fitFrom = tLow;
  c.fitTo = tHigh;
  c.fitPoints = fit.points;
  c.rmsLogResidual = fit.rmsLogResidual;
  if (!c.curve.x.empty()) out.push_back(std::move(c));
}

double lastX(const Series& s) { return s.x.empty() ? 0 : s.x.back(); }
double firstX(const Series& s) { return s.x.empty() ? 0 : s.x.front(); }

}  // namespace

SmallKRegime smallKRegime(double K) noexcept {
  if (!(std::abs(K) <= smallKLimit)) return SmallKRegime::none;  // NaN included
  if (K < 0) return SmallKRegime::negative;
  if (K == 0) return SmallKRegime::zero;
  return SmallKRegime::positive;
}

std::vector<TheoryCurve> theoryCurves(const TrappingParameters& params, const TrappingStatistics& stats) {
  std::vector<TheoryCurve> out;
  const double K = params.map.K;
  const SmallKRegime regime = smallKRegime(K);
  if (regime == SmallKRegime::none || stats.f.x.empty()) return out;
  const double tEnd = std::max(lastX(stats.f), lastX(stats.C));
  const double tStart = std::max(1.0, std::min(firstX(stats.f), firstX(stats.C)));
  constexpr double inf = std::numeric_limits<double>::infinity();

  switch (regime) {
    case SmallKRegime::negative: {
      // The cutoff t_max = 5.1454 |K|^−1/4 (§4) bounds f_t, P_t and C_τ alike.
      const double tmax = smallk::negativeKMaximumTime(K);
      for (Statistic s : {Statistic::f, Statistic::P, Statistic::C}) {
        TheoryCurve line;
        line.statistic = s;
        line.kind = TheoryCurve::Kind::verticalLine;
        line.label = "t_max = 5.1454 |K|^-1/4";
        line.labelRich = "t<sub>max</sub> = 5.1454 |K|<sup>−1/4</sup>";
        line.at = tmax;
        out.push_back(line);
      }
      // F(|K|^¼ t) (eq. fneg) is singular at t_max: drawn up to just below it.  Fitted over 0.4 … 0.85 t_max:
      // at shorter times the measured f_t decays "somewhat slower (approximately as t^−6) than F(T)" (§4, at
      // |K|^¼ = 0.1 the asymptotic regime is not reached), and a window from 0.2 t_max bent the fit away from
      // the data on both sides.
      addFitted(out, stats, Statistic::f, "F(|K|^1/4 t)", "F(|K|<sup>1/4</sup> t), fitted", kNegativeFitFrom * tmax,
                kNegativeFitTo * tmax, tStart, tmax * (1 - 1e-6),
                [K](double t) { return smallk::negativeKSegmentShape(t, K); });
      addFitted(out, stats, Statistic::C, "C(|K|^1/4 tau)", "C(|K|<sup>1/4</sup> τ), fitted", kNegativeFitFrom * tmax,
                kNegativeFitTo * tmax, tStart, tmax * (1 - 1e-6),
                [K](double t) { return smallk::negativeKCorrelationShape(t, K); });
      break;
    }
    case SmallKRegime::zero: {
      // f_t ∝ t^−7, reached from t ∼ 100 (§4, fig. 3b); C_τ ∝ τ^−5.
      const double from = tEnd > 300 ? 100 : 20;
      addFitted(out, stats, Statistic::f, "t^-7", "t<sup>−7</sup>, fitted", from, inf, from / 3, tEnd,
                [](double t) { return smallk::zeroKSegmentShape(t); });
      addFitted(out, stats, Statistic::C, "tau^-5", "τ<sup>−5</sup>, fitted", from, inf, from / 3, tEnd,
                [](double t) { return smallk::zeroKCorrelationShape(t); });
      break;
    }
    case SmallKRegime::positive: {
      // f_t ∝ exp(−½ log λ t) ≈ exp(−K^¼ t) for t ≫ K^−1/4 (§4); C_τ decays at the same rate.
      const double scale = std::pow(K, -0.25);
      addFitted(out, stats, Statistic::f, "exp(-K^1/4 t)", "exp(−K<sup>1/4</sup> t), fitted", 2 * scale, inf,
                scale, tEnd, [K](double t) { return smallk::positiveKSegmentShape(t, K); });
      addFitted(out, stats, Statistic::C, "exp(-K^1/4 tau)", "exp(−K<sup>1/4</sup> τ), fitted", 2 * scale, inf,
                scale, tEnd, [K](double t) { return smallk::positiveKSegmentShape(t, K); });
      break;
    }
    case SmallKRegime::none: break;
  }
  return out;
}

}  // namespace archipelago
