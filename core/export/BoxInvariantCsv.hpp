#pragma once
/// \file BoxInvariantCsv.hpp
/// \brief The box-invariant files of a run with a known b₂ (eq. A3; stats/StochasticAreaQuantities.hpp): `stats
/// --b2` writes them.  Same conventions as StatisticsCsv.hpp.
///
///   box_invariant.csv   quantity,value,error            b₂ (area, fraction, L²), b₂·D and the §6 figures
///   b2_f_t.csv          t,b2_f_t,b2_f_t_error           b₂·f_t, the same in every box for large t (eq. A3)

#include <string>

#include "core/run/TrappingRun.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

inline constexpr const char* boxInvariantCsvFileName = "box_invariant.csv";
inline constexpr const char* boxInvariantFtCsvFileName = "b2_f_t.csv";

/// box_invariant.csv of a run (its statistics) whose box has stochastic area `b2`; `DError` is D's error as
/// core's run summary gives it (RunSummary::DError), NaN (an empty cell) when the tail dominates D.
[[nodiscard]] std::string boxInvariantCsv(const TrappingState& state, const TrappingStatistics& statistics,
                                          const StochasticAreaValue& b2, double DError);
/// b2_f_t.csv: b₂ (the area) times f_t and its error, at the abscissae of f_t.
[[nodiscard]] std::string boxInvariantFtCsv(const TrappingState& state, const TrappingStatistics& statistics,
                                            const StochasticAreaValue& b2);

}  // namespace archipelago
