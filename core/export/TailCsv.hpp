#pragma once
/// \file TailCsv.hpp
/// \brief CSV files of D's honest error and of the tail (stats/TailAnalysis.hpp; issue #14, items 2 and 7), and
/// the note that marks every CSV file of a seed ensemble.  Written by `stats --tail-csv DIR` (a folder of their own, so
/// that `stats --csv` stays the GUI's "Export all" set), in the format of StatisticsCsv.hpp (csvMetadataHeader(), then "# " lines on the content, a header row,
/// rows; 17 significant digits, no locale):
///   D_vs_steps.csv        steps,orbits,segments,D,gamma_P_tail,longest   D of the first k subsets (then the
///                         next seed's), γ_P over the tail fit's window, the longest segment so far (steps)
///   tail_fit.csv          from,to,points,gamma_P,gamma_P_lo,gamma_P_hi,exponent_C,exponent_C_lo,exponent_C_hi,
///                         segments_beyond_from,segments_beyond_to   one row per window, the tail fit first
///   segments_beyond.csv   t,P_t,segments                             segments longer than t, on P's grid
///   P_t.reference.csv     curve,t,P_t                                the reference slopes (referenceSlopes())
///   tail_summary.csv      quantity,value,lo,hi                       D and its errors, the shares, the seeds,
///                         the verdict (0/1 flags), the steps-to-decide estimate; undefined values are "nan"
/// An interval's lo and hi are the bootstrap's percentile interval at the confidence written in the file; D's
/// interval and errors are "nan" when the verdict says its longest segments dominate it.

#include <string>
#include <vector>

#include "core/export/StatisticsCsv.hpp"
#include "core/stats/TailAnalysis.hpp"

namespace archipelago {

/// "# ensemble: N runs pooled, seeds s1 s2 …\n" for several seeds, empty for one: the line every CSV file of
/// an ensemble carries after csvMetadataHeader() (whose seed is the first run's).
[[nodiscard]] std::string ensembleNote(const TailAnalysis& analysis);

/// `files` (from statisticsCsvFiles() for `state`) with `note` inserted after each one's metadata header.
[[nodiscard]] std::vector<CsvFile> withNote(std::vector<CsvFile> files, const TrappingState& state,
                                            const std::string& note);

/// The five files above, in that order; `state` is the (first) run, for the metadata header.
[[nodiscard]] std::vector<CsvFile> tailCsvFiles(const TrappingState& state, const TailAnalysis& analysis,
                                                const Series& P);

}  // namespace archipelago
