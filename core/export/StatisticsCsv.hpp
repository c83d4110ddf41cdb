#pragma once
/// \file StatisticsCsv.hpp
/// \brief The one CSV writer of a run's statistics and theory curves: `stats --csv`, the GUI's per-plot CSV
/// export and its "Export all" all write through it, so the same run gives the same bytes everywhere.
///
/// Files (names from the statistics table, stats/StatisticsTable.hpp):
///   <stem>.csv         one per statistic: f_t, p_t, P_t, C_tau, local_exponent, S_t, D_t
///   <stem>.theory.csv  the small-K theory curves over that statistic (theory/TheoryCurves.hpp), only when
///                      some apply
///   summary.csv        the run summary (stats/RunSummary.hpp): α, D with the error `stats` gives it, the
///                      subsets' error of D for reference, γ_P and its interval, Σ t f_t, segments, longest segment
///   longest_segments.csv  the longest trapped segments with their start states (longestSegmentsCsv())
/// Format: comment lines starting with "# " (csvMetadataHeader(): program, parameters, map coefficients,
/// kernel; then lines about the file's content), one header row of descriptive column names, then rows.
///   <stem>.csv:         <abscissa>,<key>,<key>_error        e.g. t,f_t,f_t_error  (tau for C_τ)
///   <stem>.theory.csv:  curve,<abscissa>,<key>              one row per sampled point of each curve; a
///                       vertical line (t_max) is a comment line "# vertical_line: <label>; <abscissa> = <v>"
///   summary.csv:        quantity,value,error   (error empty: none can be given; the comment lines say why)
/// Numbers have 17 significant digits (round-trip exact for doubles) and are formatted without the locale
/// (std::to_chars), so a GUI running in a locale with a decimal comma writes the same bytes as the CLI.
/// Lines end with '\n'.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/provenance/Provenance.hpp"
#include "core/stats/RunSummary.hpp"
#include "core/stats/StatisticsTable.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/theory/TheoryCurves.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago {

/// What a run's outputs record of it, in order (one definition: the CSV files' comment lines and the statistics
/// plots' PNG text chunks, issue 54 item 6): program, each parameter of the run spec (K, xmin, xmax, Xr, q, T, M, seed,
/// subsets, longestKept) with the codec's digits, blocks_done, orbits, the map coefficients A, B, C, m, the kernel.
[[nodiscard]] Provenance runProvenance(const TrappingState& state);

/// One line of the run's parameters for a picture of its statistics: "K = 0.1, xmin = -0.8, xmax = 0.5, Xr = 0.02,
/// q = 16, T = 62500, M = 64, seed = 1; 62500 of 62500 blocks".
[[nodiscard]] std::string runParametersLine(const TrappingState& state);

/// The comment lines ("# name: value\n") that open every CSV file of a run (runProvenance()'s fields): program and version, the
/// parameters (K, xmin, xmax, Xr, q, T, blocks done, M, orbit range, seed, subsets), the integer map
/// coefficients (A, B, C, m) that define the map exactly, and the kernel that computed the state last.
[[nodiscard]] std::string csvMetadataHeader(const TrappingState& state);

/// A number as every CSV file writes it: 17 significant digits, shortest form, never the locale's separator.
[[nodiscard]] std::string csvNumber(double v);
/// Appends one metadata line of a CSV header, "# name: value".
void csvMetadataLine(std::string& out, std::string_view name, const std::string& value);

/// The column `blocks_affected` (issue #26), one definition for every CSV file of a series over t (the statistics,
/// b2_f_t.csv, the scan's scan_f_t.csv): present when the statistics of a run of q > 1 were not spliced with a
/// q = 1 companion (TrappingStatistics::blockAffectedBelow > 0); 1 where t < 10 q, else 0.
[[nodiscard]] bool hasBlocksAffectedColumn(const TrappingStatistics& statistics) noexcept;
/// For the `# columns:` line: "; blocks_affected (1: t below 10 q = … steps, …)", or "" without the column.
[[nodiscard]] std::string blocksAffectedColumnNote(const TrappingStatistics& statistics);
/// A row's cell with its leading comma (",1" or ",0"), or "" without the column.
[[nodiscard]] std::string blocksAffectedCell(const TrappingStatistics& statistics, double t);

/// The file name of a statistic's CSV ("f_t.csv") and of its theory curves ("f_t.theory.csv").
[[nodiscard]] std::string statisticCsvFileName(Statistic s);
[[nodiscard]] std::string theoryCsvFileName(Statistic s);
inline constexpr const char* summaryCsvFileName = "summary.csv";
inline constexpr const char* longestSegmentsCsvFileName = "longest_segments.csv";

/// The text of <stem>.csv for one statistic of `statistics` (the statistics of `state`).
[[nodiscard]] std::string statisticCsv(const TrappingState& state, const TrappingStatistics& statistics,
                                       Statistic s);
/// The text of <stem>.theory.csv: the curves of `theory` that belong to `s`; empty when none does.
[[nodiscard]] std::string theoryCsv(const TrappingState& state, const std::vector<TheoryCurve>& theory, Statistic s);
/// The text of summary.csv: `summary` (summarizeRun() of `statistics`, as every front end prints it) with
/// `statistics`' longest bin.
[[nodiscard]] std::string summaryCsv(const TrappingState& state, const TrappingStatistics& statistics,
                                     const RunSummary& summary);

/// The text of longest_segments.csv: the run's longest trapped segments (§6), longest first, with the
/// metadata header and the columns rank, length_steps (q · blocks), length_blocks, orbit, start_block,
/// start_draws, start_X, start_Y (the exact unit state, integers in units of 2⁻⁵²) and start_x, start_y
/// (physical coordinates), enough to replay each segment bit for bit.
[[nodiscard]] std::string longestSegmentsCsv(const TrappingState& state);

/// One file to write: its name in the folder and its content.
struct CsvFile {
  std::string name;
  std::string text;
};
/// Every file of a run, in table order: each statistic's CSV, then its theory CSV when it has one, then
/// summary.csv and longest_segments.csv.
[[nodiscard]] std::vector<CsvFile> statisticsCsvFiles(const TrappingState& state,
                                                      const TrappingStatistics& statistics,
                                                      const std::vector<TheoryCurve>& theory,
                                                      const RunSummary& summary);

/// Writes statisticsCsvFiles() into `dir` (created when missing) and returns the paths written.
/// Throws std::runtime_error naming the file or folder on failure.
std::vector<std::filesystem::path> writeStatisticsCsv(const std::filesystem::path& dir, const TrappingState& state,
                                                      const TrappingStatistics& statistics,
                                                      const std::vector<TheoryCurve>& theory,
                                                      const RunSummary& summary);

/// Writes one statistic to `path` and, when theory curves belong to it, those to the same path with the
/// suffix ".csv" replaced by ".theory.csv" (".theory.csv" appended when the path has another suffix).
/// The contents are those of statisticsCsvFiles().  Returns the paths written; throws std::runtime_error.
std::vector<std::filesystem::path> writeStatisticCsv(const std::filesystem::path& path, const TrappingState& state,
                                                     const TrappingStatistics& statistics,
                                                     const std::vector<TheoryCurve>& theory, Statistic s);

}  // namespace archipelago
