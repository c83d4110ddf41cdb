#include "TheoryOverlay.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "theory/SmallKTheory.hpp"

namespace archipelago::ui {

namespace {
// The theory of §4 is asymptotic in |K| → 0; the paper checks it at |K| ≤ 10⁻², and at K = 0.1 "the
// foregoing analysis does not apply" (§4, last paragraph).
constexpr double kSmallK = 0.02;
constexpr int kSamples = 80;

/// Samples a·shape(t) on a logarithmic grid over [tLow, tHigh] (points where shape is not finite and > 0 are
/// left out).
Series sampled(double a, double tLow, double tHigh, const std::function<double(double)>& shape) {
  Series s;
  if (!(tLow > 0) || !(tHigh > tLow)) return s;
  const double ratio = std::log(tHigh / tLow);
  for (int i = 0; i <= kSamples; ++i) {
    const double t = tLow * std::exp(ratio * i / kSamples);
    const double v = shape(t);
    if (!std::isfinite(v) || v <= 0) continue;
    s.x.push_back(t);
    s.value.push_back(a * v);
    s.error.push_back(0);
  }
  return s;
}

/// Fits the amplitude of `shape` to `data` over [tLow, tHigh] (core's log-space fit) and draws it over
/// [drawLow, drawHigh].  Nothing when no data point lies in the window.
void addFitted(std::vector<TheoryCurve>& out, PlotKind plot, const std::string& label, const std::string& legend,
               const Series& data,
               double tLow, double tHigh, double drawLow, double drawHigh,
               const std::function<double(double)>& shape) {
  if (data.x.empty()) return;
  const smallk::AmplitudeFit fit = smallk::fitAmplitude(data.x, data.value, tLow, tHigh, shape);
  if (!fit.valid() || !std::isfinite(fit.amplitude)) return;
  TheoryCurve c;
  c.plot = plot;
  c.label = label;
  c.legend = legend;
  c.curve = sampled(fit.amplitude, drawLow, drawHigh, shape);
  if (!c.curve.x.empty()) out.push_back(std::move(c));
}

double lastX(const Series& s) { return s.x.empty() ? 0 : s.x.back(); }
double firstX(const Series& s) { return s.x.empty() ? 0 : s.x.front(); }
}  // namespace

std::vector<TheoryCurve> theoryCurves(const TrappingParameters& params, const TrappingStatistics& stats) {
  std::vector<TheoryCurve> out;
  const double K = params.map.K;
  if (!(std::abs(K) <= kSmallK) || stats.f.x.empty()) return out;
  const double tEnd = std::max(lastX(stats.f), lastX(stats.C));
  const double tStart = std::max(1.0, std::min(firstX(stats.f), firstX(stats.C)));
  constexpr double inf = std::numeric_limits<double>::infinity();

  if (K < 0) {
    // The cutoff t_max = 5.1454 |K|^−1/4 and F(|K|^¼ t) (eq. fneg); C(|K|^¼ τ) on C_τ.  F is fitted over
    // the middle of its range: near t_max the measured singularity sits slightly off (§4).
    const double tmax = smallk::negativeKMaximumTime(K);
    for (PlotKind plot : {PlotKind::f, PlotKind::P, PlotKind::C}) {
      TheoryCurve line;
      line.plot = plot;
      line.label = "t_max = 5.1454 |K|^-1/4";
      line.legend = "t<sub>max</sub> = 5.1454 |K|<sup>−1/4</sup>";
      line.verticalAt = tmax;
      out.push_back(line);
    }
    addFitted(out, PlotKind::f, "F(|K|^1/4 t)", "F(|K|<sup>1/4</sup> t), fitted", stats.f, 0.2 * tmax, 0.8 * tmax, tStart, tmax * (1 - 1e-6),
              [K](double t) { return smallk::negativeKSegmentShape(t, K); });
    addFitted(out, PlotKind::C, "C(|K|^1/4 tau)", "C(|K|<sup>1/4</sup> τ), fitted", stats.C, 0.2 * tmax, 0.8 * tmax, tStart, tmax * (1 - 1e-6),
              [K](double t) { return smallk::negativeKCorrelationShape(t, K); });
  } else if (K == 0) {
    // f_t ∝ t^−7, reached from t ∼ 100 (§4); C_τ ∝ τ^−5.
    const double from = tEnd > 300 ? 100 : 20;
    addFitted(out, PlotKind::f, "t^-7", "t<sup>−7</sup>, fitted", stats.f, from, inf, from / 3, tEnd,
              [](double t) { return smallk::zeroKSegmentShape(t); });
    addFitted(out, PlotKind::C, "tau^-5", "τ<sup>−5</sup>, fitted", stats.C, from, inf, from / 3, tEnd,
              [](double t) { return smallk::zeroKCorrelationShape(t); });
  } else {
    // f_t ∝ exp(−½ log λ t) ≈ exp(−K^¼ t) for t ≫ K^−1/4 (§4); C_τ decays at the same rate.
    const double scale = std::pow(K, -0.25);
    addFitted(out, PlotKind::f, "exp(-K^1/4 t)", "exp(−K<sup>1/4</sup> t), fitted", stats.f, 2 * scale, inf, scale, tEnd,
              [K](double t) { return smallk::positiveKSegmentShape(t, K); });
    addFitted(out, PlotKind::C, "exp(-K^1/4 tau)", "exp(−K<sup>1/4</sup> τ), fitted", stats.C, 2 * scale, inf, scale, tEnd,
              [K](double t) { return smallk::positiveKSegmentShape(t, K); });
  }
  return out;
}

}  // namespace archipelago::ui
