#pragma once
/// \file StochasticAreaQuantities.hpp
/// \brief b₂ as an area, the box-invariant products of eq. (A3) and the application figures of §6 — the one
/// definition that the CLI (`stochastic-area`, `stats --b2`, `scan`), the GUI's b₂ dialog and the CSV files use.
///
/// Karney (1983), appendix A: "The total area of phase space in Q* is b₀ = L²" and "b₂ [is] the area of the
/// stochastic component of Q*".  b₂ is therefore an area in the (x, y) plane, not the occupied fraction of the
/// box that the box counting of §5 measures: b₂ = fraction · L², L = xmax − xmin.  (Issue #14: two boxes at
/// K = 0.1, (−0.8, 0.5) and (−0.65, 0.35), give f_A/f_B ≈ 0.52–0.55 for 10⁴ ≲ t ≲ 10⁵; eq. (A3) predicts 0.524
/// with b₂ as an area and 0.886 with b₂ as a fraction.)
///
/// Eq. (A3): for large t the trapping statistics of two boxes obey b₂′ f_t′ = b₂ f_t, so b₂ f_t and b₂ D (D is
/// a moment of f_t dominated by long segments, eq. ddef) do not depend on the box.  The paper's b₂ = 0.693,
/// D = 6400 give b₂ D ≈ 4.4·10³.
///
/// §6, the first-order accelerator modes of the standard map at k = 2πn: h = ±2πn, γ = (2/πn)², A₁ = (2π)²,
/// two islands, so the factor between the island's contribution and Q*'s statistics is
/// 2h²(γ/A₁) b₂ = (8/π²) b₂ (the paper: ≈ 0.56 for b₂ = 0.693), and the island's diffusion coefficient over
/// the quasi-linear one 𝒟_ql = (πn)² is (8/π²) b₂ D / (πn)² (the paper: "at least 360/n²" for D ≥ 6400).

#include <optional>
#include <string>

#include "core/map/MapParameters.hpp"
#include "core/paper/PaperTable.hpp"

namespace archipelago {

/// The paper's numbers at K = 0.1 (§5): b₂ (an area, in the box of the caption of fig. 6, which our copy lacks)
/// and D = 6400 ± 800.
inline constexpr double kPaperStochasticArea = paper::kStochasticArea;  // core/paper holds the paper's numbers
inline constexpr double kPaperDiffusion = paper::kDiffusion;
inline constexpr double kPaperDiffusionError = paper::kDiffusionError;
inline constexpr double kPaperK = paper::kK;

/// b₂ of one box: the occupied fraction that the box counting measures, and the area it stands for.
struct StochasticAreaValue {
  double fraction = 0;  ///< occupied fraction of the box, 0 … 1
  double boxArea = 0;   ///< b₀ = L², L = xmax − xmin
  double area = 0;      ///< b₂ = fraction · L² (appendix A)
};

/// b₂ of the box of `map` from its occupied fraction.  NaN fields for a fraction outside [0, 1] or an invalid box.
[[nodiscard]] StochasticAreaValue stochasticAreaOf(const MapParameters& map, double fraction) noexcept;

/// The rules of b₂ given back to a front end (`stats --b2 AREA`, Python's box_invariant and scan b2 fraction):
/// "<name> = <area> must be an area in (0, L^2 = <L²>] of the run's box (stochastic-area prints it)";
/// "<name> = <fraction> must lie in [0, 1] (the visited fraction stochastic_area gives)"; or nothing.
[[nodiscard]] std::optional<std::string> stochasticAreaError(std::string_view name, const MapParameters& map,
                                                             double area);
[[nodiscard]] std::optional<std::string> visitedFractionError(std::string_view name, double fraction);

/// The factor 2h²(γ/A₁) b₂ = (8/π²) b₂ of §6 for the first-order accelerator modes of the standard map (any n).
[[nodiscard]] double acceleratorModeFactor(double b2Area) noexcept;

/// The island's diffusion coefficient over the quasi-linear value, (8/π²) b₂ D / (πn)², for the modes at k = 2πn
/// (§6).  NaN unless n ≥ 1.
[[nodiscard]] double acceleratorModeEnhancement(double b2Area, double D, int n) noexcept;

/// The box-invariant quantities of a run whose box has stochastic area b₂ (eq. A3): b₂·D with its error
/// (b₂'s own error is not included: it is a count, converged to ~0.1 % at 2²⁷ steps), and the §6 figures.
struct BoxInvariantQuantities {
  StochasticAreaValue b2;
  double b2D = 0, b2DError = 0;       ///< b₂ · D and b₂ · δD
  double acceleratorFactor = 0;       ///< (8/π²) b₂
  double enhancementN1 = 0;           ///< (8/π²) b₂ D / π²: the enhancement for n = 1 (divide by n² for n)
};
[[nodiscard]] BoxInvariantQuantities boxInvariantQuantities(const StochasticAreaValue& b2, double D, double DError) noexcept;

/// The rule of the D and its error given to boxInvariantQuantities by a front end: "D and D_error must be finite", or
/// nothing.
[[nodiscard]] std::optional<std::string> diffusionInputError(double D, double DError);

/// One line describing b₂ for people: "b2 = 1.3706 (area; fraction 0.81100 of the box L^2 = 1.69 for
/// xmin = -0.8, xmax = 0.5)".  Plain ASCII, for the CLI and the GUI alike.
[[nodiscard]] std::string stochasticAreaText(const MapParameters& map, const StochasticAreaValue& b2);

/// The comparison with the paper's b₂ = 0.693, only for K = 0.1 (nothing otherwise: the paper gives b₂ for no
/// other K), saying which box: the paper's box is that of its fig. 6 caption, which our copy lacks, so the
/// areas agree only if the boxes do.
[[nodiscard]] std::optional<std::string> paperStochasticAreaComparison(const MapParameters& map,
                                                                       const StochasticAreaValue& b2);

}  // namespace archipelago
