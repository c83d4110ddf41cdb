#pragma once
/// \file TheoryOverlay.hpp
/// \brief Which small-K theory curves (Karney 1983, §4) are drawn over which plot.
///
/// The curves and the fits of their amplitudes to the data come from core/theory; this file only decides
/// where each one is drawn: for K < 0 the cutoff t_max = 5.1454 |K|^−1/4 as a vertical line and F(|K|^¼ t)
/// on f_t; for K = 0 the algebraic decay t^−7 on f_t; for small K > 0 the exponential exp(−K^¼ t) on f_t.
/// Called on the worker thread.

#include <vector>

#include "RunSnapshot.hpp"

namespace archipelago::ui {

[[nodiscard]] std::vector<TheoryCurve> theoryCurves(const TrappingParameters& params,
                                                    const TrappingStatistics& statistics);

}  // namespace archipelago::ui
