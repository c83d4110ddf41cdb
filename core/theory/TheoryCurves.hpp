#pragma once
/// \file TheoryCurves.hpp
/// \brief Which curves of the small-K theory (Karney 1983, §4) apply to a run, fitted to its statistics.
///
/// The shapes come from SmallKTheory.hpp; this file decides which apply and where, and fits their amplitudes
/// (the theory gives f_t and C_τ only up to a constant):
///  - K < 0:       the cutoff t_max = 5.1454 |K|^−1/4 as a vertical line on f_t, P_t and C_τ; F(|K|^¼ t)
///                 (eq. fneg) on f_t and C(|K|^¼ τ) on C_τ, fitted over 0.4 t_max … 0.85 t_max (near t_max the
///                 measured singularity sits slightly off, and at shorter times f_t decays as t^−6 rather
///                 than t^−7, §4);
///  - K = 0:       t^−7 on f_t and τ^−5 on C_τ, fitted from t = 100 (where fig. 3b reaches the law; from
///                 t = 20 when the data end before t = 300);
///  - 0 < K:       exp(−½ log λ t) ≈ exp(−K^¼ t) on f_t and C_τ, fitted from t = 2 K^−1/4;
/// all for |K| ≤ 0.02 only: the theory is asymptotic in |K| → 0, the paper checks it up to |K| = 10⁻², and
/// at K = 0.1 "the foregoing analysis does not apply" (§4, last paragraph).
///
/// Pure functions of their arguments (thread-safe): the GUI's run worker calls them on its thread and the
/// CLI calls them for `stats --csv`, so both draw and write the same curves.

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "core/stats/StatisticsTable.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago {

/// Which part of §4 applies to a map parameter K.
enum class SmallKRegime {
  none,      ///< |K| > smallKLimit (or K not finite): no theory curve
  negative,  ///< −smallKLimit ≤ K < 0: eqs. (hama), (tneg), (fneg)
  zero,      ///< K = 0: eq. (ham)
  positive,  ///< 0 < K ≤ smallKLimit: eq. (hamb), the hyperbolic fixed point
};

/// The fit window of the K < 0 shapes, as fractions of t_max.
inline constexpr double kNegativeFitFrom = 0.4;
inline constexpr double kNegativeFitTo = 0.85;

/// |K| up to which theory curves are drawn.
inline constexpr double smallKLimit = 0.02;

[[nodiscard]] SmallKRegime smallKRegime(double K) noexcept;

/// One theory curve, drawn over the plot of `statistic`.
struct TheoryCurve {
  enum class Kind { series, verticalLine };
  Statistic statistic = Statistic::f;  ///< the statistic it belongs to (its key is statisticInfo(...).key)
  Kind kind = Kind::series;
  std::string label;      ///< plain text for files, e.g. "t^-7"
  std::string labelRich;  ///< rich text for legends, e.g. "t<sup>−7</sup>, fitted"
  Series curve;           ///< sampled a·shape(t) on a logarithmic grid (error 0); empty for a vertical line
  double at = 0;          ///< abscissa of a vertical line (steps); 0 for a series
  /// The fit (series only): amplitude a of a·shape, over the data points with fitFrom ≤ t ≤ fitTo
  /// (smallk::fitAmplitude, least squares in log space).
  double amplitude = std::numeric_limits<double>::quiet_NaN();
  double fitFrom = 0, fitTo = 0;
  std::size_t fitPoints = 0;
  double rmsLogResidual = std::numeric_limits<double>::quiet_NaN();
};

/// Points per sampled curve (a logarithmic grid, ends included, minus points where the shape is not > 0).
inline constexpr int theoryCurveSamples = 80;

/// The curves that apply to a run with these parameters and statistics (see the file comment), in a fixed
/// order: vertical lines first, then f_t's curve, then C_τ's.  Nothing when the regime is none or f_t is
/// empty; a series is left out when no data point lies in its fit window.
[[nodiscard]] std::vector<TheoryCurve> theoryCurves(const TrappingParameters& params,
                                                    const TrappingStatistics& statistics);

}  // namespace archipelago
