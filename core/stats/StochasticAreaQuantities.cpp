#include "core/stats/StochasticAreaQuantities.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// 2h²γ/A₁ with h² = (2πn)², γ = (2/πn)², A₁ = (2π)²: 2 · 4π²n² · 4/(π²n²) / (4π²) = 8/π² (§6).
constexpr double kAcceleratorFactorPerArea = 8 / (std::numbers::pi * std::numbers::pi);
}  // namespace

StochasticAreaValue stochasticAreaOf(const MapParameters& map, double fraction) noexcept {
  const double L = map.width();
  if (!(fraction >= 0 && fraction <= 1) || !(L > 0) || !std::isfinite(L)) return {kNaN, kNaN, kNaN};
  return {fraction, L * L, fraction * (L * L)};
}

double acceleratorModeFactor(double b2Area) noexcept { return kAcceleratorFactorPerArea * b2Area; }

double acceleratorModeEnhancement(double b2Area, double D, int n) noexcept {
  if (n < 1) return kNaN;
  const double quasiLinear = std::numbers::pi * n * std::numbers::pi * n;  // 𝒟_ql = (πn)²
  return acceleratorModeFactor(b2Area) * D / quasiLinear;
}

BoxInvariantQuantities boxInvariantQuantities(const StochasticAreaValue& b2, double D, double DError) noexcept {
  BoxInvariantQuantities q;
  q.b2 = b2;
  q.b2D = b2.area * D;
  q.b2DError = b2.area * DError;
  q.acceleratorFactor = acceleratorModeFactor(b2.area);
  q.enhancementN1 = acceleratorModeEnhancement(b2.area, D, 1);
  return q;
}

std::string stochasticAreaText(const MapParameters& map, const StochasticAreaValue& b2) {
  const std::string text = io::formatC("b2 = %.4f (area; fraction %.5f of the box L^2 = %.4g for xmin = %.6g, xmax = %.6g)",
                                       b2.area, b2.fraction, b2.boxArea, map.xmin, map.xmax);
  return text;
}

std::optional<std::string> paperStochasticAreaComparison(const MapParameters& map, const StochasticAreaValue& b2) {
  if (map.K != kPaperK) return std::nullopt;
  const std::string text = io::formatC(
                "the paper (sec. 5, K = 0.1): b2 = %.3f in the box of its fig. 6 caption (not in our copy); this box "
                "(xmin = %.6g, xmax = %.6g) gives %.4f, ratio %.3f; compare b2*D instead (eq. A3: the paper's "
                "%.3g x %.4g = %.3g)",
                kPaperStochasticArea, map.xmin, map.xmax, b2.area, b2.area / kPaperStochasticArea,
                kPaperStochasticArea, kPaperDiffusion, kPaperStochasticArea * kPaperDiffusion);
  return std::string(text);
}

std::optional<std::string> stochasticAreaError(std::string_view name, const MapParameters& map, double area) {
  const double boxArea = map.width() * map.width();
  if (area > 0 && area <= boxArea) return std::nullopt;
  return std::string(name) + " = " + io::shortestText(area) + " must be an area in (0, L^2 = " +
         io::shortestText(boxArea) + "] of the run's box (stochastic-area prints it)";
}

std::optional<std::string> visitedFractionError(std::string_view name, double fraction) {
  return realRangeError(name, fraction, 0, 1, "the visited fraction stochastic_area gives");
}

std::optional<std::string> diffusionInputError(double D, double DError) {
  if (std::isfinite(D) && std::isfinite(DError)) return std::nullopt;
  return std::string("D and D_error must be finite");
}

}  // namespace archipelago
