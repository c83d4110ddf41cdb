#pragma once
/// \file ScanCsv.hpp
/// \brief The summary files of a K scan (§5; theory/KScan.hpp) and the box-invariant file of a run with a
/// known b₂ (eq. A3; stats/StochasticAreaQuantities.hpp).  Same conventions as StatisticsCsv.hpp: "# " comment
/// lines, one header row, 17 significant digits without the locale (K and the box: the shortest text that reads
/// back exactly), '\n' line ends; empty cells where a value is undefined.
///
///   scan_f_t.csv              K,t,f_t,f_t_error               f_t of every K, long format (t in steps)
///   scan_local_exponent.csv   tau,<K₁>,<K₂>,…                 −d log C_τ/d log τ (fig. 6d) over τ (rows) and K
///                                                             (columns, headed by the K); empty where undefined
///   scan_summary.csv          K,xmin,xmax,blocks_done,T,segments,D,D_error,longest_steps,
///                             time_fraction_ge_1e4,b2_area,b2_fraction,b2_D,b2_D_error
///                             (the b₂ cells empty for a K whose b₂ was not computed)
///   box_invariant.csv         quantity,value,error            b₂ (area, fraction, L²), b₂·D and the §6 figures
///   b2_f_t.csv                t,b2_f_t,b2_f_t_error           b₂·f_t, the same in every box for large t (eq. A3)

#include <cmath>
#include <string>
#include <vector>

#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/theory/KScan.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago {

inline constexpr const char* scanFtCsvFileName = "scan_f_t.csv";
inline constexpr const char* scanLocalExponentCsvFileName = "scan_local_exponent.csv";
inline constexpr const char* scanSummaryCsvFileName = "scan_summary.csv";
inline constexpr const char* boxInvariantCsvFileName = "box_invariant.csv";
inline constexpr const char* boxInvariantFtCsvFileName = "b2_f_t.csv";

/// One K of a scan: its parameters (the box of scanBox(K) and the scan's common settings), the scan point and
/// the statistics.
struct ScanRunSummary {
  TrappingParameters params;
  ScanPoint point;
  TrappingStatistics statistics;
};

/// The local exponent over τ and K: value[row · K.size() + column] at tau[row], K[column]; NaN where undefined.
/// tau is the sorted union of the runs' grids.
struct ScanHeatMap {
  std::vector<double> K;
  std::vector<double> tau;
  std::vector<double> value;
};
[[nodiscard]] ScanHeatMap localExponentHeatMap(const std::vector<ScanRunSummary>& runs);

[[nodiscard]] std::string scanFtCsv(const std::vector<ScanRunSummary>& runs);
[[nodiscard]] std::string scanLocalExponentCsv(const std::vector<ScanRunSummary>& runs);
[[nodiscard]] std::string scanSummaryCsv(const std::vector<ScanRunSummary>& runs);

/// box_invariant.csv of a run (its statistics) whose box has stochastic area `b2`; `DError` is D's error as
/// supportedDError() gives it (TailAnalysis.hpp), NaN (an empty cell) when the tail dominates D.
[[nodiscard]] std::string boxInvariantCsv(const TrappingState& state, const TrappingStatistics& statistics,
                                          const StochasticAreaValue& b2, double DError);
/// b2_f_t.csv: b₂ (the area) times f_t and its error, at the abscissae of f_t.
[[nodiscard]] std::string boxInvariantFtCsv(const TrappingState& state, const TrappingStatistics& statistics,
                                            const StochasticAreaValue& b2);

}  // namespace archipelago
