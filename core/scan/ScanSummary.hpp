#pragma once
/// \file ScanSummary.hpp
/// \brief What a K scan (§5; ScanBox.hpp) reports per K (ScanRunSummary.hpp), and its summary files.  Same conventions as
/// export/StatisticsCsv.hpp: "# " comment
/// lines, one header row, 17 significant digits without the locale (K and the box: the shortest text that reads
/// back exactly), '\n' line ends; empty cells where a value is undefined.
///
///   scan_f_t.csv              K,t,f_t,f_t_error               f_t of every K, long format (t in steps)
///   scan_local_exponent.csv   tau,<K₁>,<K₂>,…                 −d log C_τ/d log τ (fig. 6d) over τ (rows) and K
///                                                             (columns, headed by the K); empty where undefined
///   scan_summary.csv          K,xmin,xmax,blocks_done,T,segments,D,D_error,longest_steps,
///                             time_fraction_ge_1e4,b2_area,b2_fraction,b2_D,b2_D_error
///                             (the b₂ cells empty for a K whose b₂ was not computed)

#include <cmath>
#include <string>
#include <vector>

#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/scan/ScanRunSummary.hpp"

namespace archipelago {

inline constexpr const char* scanFtCsvFileName = "scan_f_t.csv";
inline constexpr const char* scanLocalExponentCsvFileName = "scan_local_exponent.csv";
inline constexpr const char* scanSummaryCsvFileName = "scan_summary.csv";

[[nodiscard]] std::string scanFtCsv(const std::vector<ScanRunSummary>& runs);
[[nodiscard]] std::string scanLocalExponentCsv(const std::vector<ScanRunSummary>& runs);
[[nodiscard]] std::string scanSummaryCsv(const std::vector<ScanRunSummary>& runs);

}  // namespace archipelago
