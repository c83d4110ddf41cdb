// The one CSV writer of a run's statistics (issue #11 items 2 and 3).  Regression: `stats --csv` wrote
// D_t.csv with the header "t,f_t,error" and no record of the run, the GUI D.csv with "curve,x,value,error".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/export/StatisticsCsv.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/stats/RunSummary.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago {
namespace {

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

/// The comment lines ("# …") and the rest.
struct Split {
  std::vector<std::string> comments, rows;
};
Split split(const std::string& text) {
  Split s;
  for (const std::string& l : linesOf(text)) {
    if (s.rows.empty() && l.rfind("# ", 0) == 0) s.comments.push_back(l);
    else s.rows.push_back(l);
  }
  return s;
}

std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::istringstream in(row);
  for (std::string c; std::getline(in, c, ',');) out.push_back(c);
  return out;
}

bool contains(const std::vector<std::string>& lines, const std::string& line) {
  for (const std::string& l : lines)
    if (l == line) return true;
  return false;
}

/// A small finished run (K = 0.1 unless told), computed with the portable kernel.
TrappingState smallRun(double K = 0.1) {
  TrappingParameters p;
  p.map.K = K;
  if (K != 0.1) {
    p.map.xmin = -0.05;  // the small-K box of §4 (tests/core/trapping/test_small_k_trapping.cpp)
    p.map.xmax = 0.05;
  }
  p.q = K == 0.1 ? 4 : 1;
  p.T = 3000;
  p.M = 12;
  p.subsets = 4;
  p.seed = 11;
  return runTrapping(startTrapping(p), TrappingRunOptions{});
}

TEST(StatisticsCsv, MetadataHeaderRecordsTheRun) {
  const TrappingState state = smallRun();
  const std::string header = csvMetadataHeader(state);
  const auto lines = linesOf(header);
  ASSERT_FALSE(lines.empty());
  for (const std::string& l : lines) EXPECT_EQ(l.rfind("# ", 0), 0u) << l;
  EXPECT_EQ(header.back(), '\n');
  // The program, its version and the commit it was built from (issue 42).
  EXPECT_EQ(lines.front().rfind(std::string("# program: archipelago ") + ARCHIPELAGO_VERSION + " (commit ", 0), 0u)
      << lines.front();
  EXPECT_EQ(lines.front(), "# program: " + archipelago::programDescription());
  // The parameters as the run-spec codec writes them: the shortest decimals that read back exactly.
  EXPECT_TRUE(contains(lines, "# K: 0.1"));
  EXPECT_TRUE(contains(lines, "# xmin: -0.8"));
  EXPECT_TRUE(contains(lines, "# longestKept: " + std::to_string(state.params.longestKept)));
  EXPECT_TRUE(contains(lines, "# xmax: 0.5"));
  EXPECT_TRUE(contains(lines, "# Xr: 0.02"));
  EXPECT_TRUE(contains(lines, "# q: 4"));
  EXPECT_TRUE(contains(lines, "# T: 3000"));
  EXPECT_TRUE(contains(lines, "# blocks_done: 3000"));
  EXPECT_TRUE(contains(lines, "# M: 12"));
  EXPECT_TRUE(contains(lines, "# orbits: 0 to 12 (exclusive)"));
  EXPECT_TRUE(contains(lines, "# seed: 11"));
  EXPECT_TRUE(contains(lines, "# subsets: 4"));
  EXPECT_TRUE(contains(lines, "# A: " + std::to_string(state.coefficients.A)));
  EXPECT_TRUE(contains(lines, "# B: " + std::to_string(state.coefficients.B)));
  EXPECT_TRUE(contains(lines, "# C: " + std::to_string(state.coefficients.C)));
  EXPECT_TRUE(contains(lines, "# m: " + std::to_string(state.coefficients.m)));
  ASSERT_FALSE(state.kernel.empty());
  EXPECT_TRUE(contains(lines, "# kernel: " + state.kernel));
  // A run in progress says how far it got.
  TrappingParameters p = state.params;
  const TrappingState fresh = startTrapping(p);
  EXPECT_TRUE(contains(linesOf(csvMetadataHeader(fresh)), "# blocks_done: 0"));
}

TEST(StatisticsCsv, EachStatisticHasDescriptiveColumnsAndExactNumbers) {
  const TrappingState state = smallRun();
  const TrappingStatistics stats = statisticsOf(state);
  const std::string header = csvMetadataHeader(state);
  const std::pair<Statistic, const char*> expected[] = {
      {Statistic::f, "t,f_t,f_t_error"},
      {Statistic::p, "t,p_t,p_t_error"},
      {Statistic::P, "t,P_t,P_t_error"},
      {Statistic::C, "tau,C_tau,C_tau_error"},
      {Statistic::localExponent, "tau,local_exponent,local_exponent_error"},
      {Statistic::S, "t,S_t,S_t_error"},
      {Statistic::Dt, "t,D_t,D_t_error"},
  };
  for (const auto& [statistic, columns] : expected) {
    const std::string text = statisticCsv(state, stats, statistic);
    EXPECT_EQ(text.rfind(header, 0), 0u) << "every file opens with the run's metadata";
    const Split s = split(text);
    ASSERT_FALSE(s.rows.empty());
    // Issue #26: a run of q > 1 marks the rows below 10 q (blocks of q steps, not the q = 1 process).
    const bool marked = stats.blockAffectedBelow > 0;
    EXPECT_EQ(s.rows.front(), std::string(columns) + (marked ? ",blocks_affected" : ""));
    const Series& series = seriesOf(stats, statistic);
    ASSERT_GT(series.x.size(), 0u) << columns;
    ASSERT_EQ(s.rows.size(), series.x.size() + 1) << columns;
    for (std::size_t i = 0; i < series.x.size(); ++i) {
      const auto c = cells(s.rows[i + 1]);
      ASSERT_EQ(c.size(), marked ? 4u : 3u) << s.rows[i + 1];
      if (marked) EXPECT_EQ(c[3], series.x[i] < stats.blockAffectedBelow ? "1" : "0") << s.rows[i + 1];
      // 17 significant digits: every double reads back exactly.
      EXPECT_EQ(std::strtod(c[0].c_str(), nullptr), series.x[i]);
      EXPECT_EQ(std::strtod(c[1].c_str(), nullptr), series.value[i]);
      EXPECT_EQ(std::strtod(c[2].c_str(), nullptr), series.error[i]);
    }
  }
  // C_0 = Σ t f_t ≈ 1 (eq. cdef): the first row of C_tau.
  const auto c0 = cells(split(statisticCsv(state, stats, Statistic::C)).rows.at(1));
  EXPECT_EQ(c0.at(0), "0");
  EXPECT_NEAR(std::strtod(c0.at(1).c_str(), nullptr), 1, 0.05);
}

TEST(StatisticsCsv, SummaryKeepsAlphaDAndTheCounts) {
  const TrappingState state = smallRun();
  const TrappingStatistics stats = statisticsOf(state);
  const RunSummary summary = summarizeRun(state, stats);
  const Split s = split(summaryCsv(state, stats, summary));
  ASSERT_EQ(s.rows.size(), 10u);
  EXPECT_EQ(s.rows[0], "quantity,value,error");
  const char* names[] = {"alpha", "D", "D_error_subsets", "gamma_P", "gamma_P_low", "gamma_P_high",
                         "sum_t_f_t", "segments", "longest_blocks"};
  for (int i = 0; i < 9; ++i) EXPECT_EQ(cells(s.rows[i + 1]).at(0), names[i]);
  EXPECT_EQ(std::strtod(cells(s.rows[1]).at(1).c_str(), nullptr), stats.alpha);
  EXPECT_EQ(std::strtod(cells(s.rows[2]).at(1).c_str(), nullptr), stats.D);
  EXPECT_EQ(std::strtod(cells(s.rows[3]).at(1).c_str(), nullptr), stats.DError);  // the subsets', named as such
  EXPECT_EQ(cells(s.rows[8]).at(1), std::to_string(stats.segments));
}

// Issue 51, item 6: summary.csv's D error is the run summary's — what `stats` and Python's D_error give — never
// the subsets' standard error (once D = 1088 ± 487 in the CSV where `stats` said D has no error).
TEST(StatisticsCsv, SummaryDErrorIsTheRunSummarysAndEmptyWhenThereIsNone) {
  const TrappingState state = smallRun();
  const TrappingStatistics stats = statisticsOf(state);
  const auto dRow = [&](const RunSummary& summary) {
    const Split s = split(summaryCsv(state, stats, summary));
    std::vector<std::string> row = cells(s.rows.at(2));
    EXPECT_EQ(row.at(0), "D");
    return row;
  };
  const auto commentOf = [&](const RunSummary& summary, const std::string& key) {
    for (const std::string& c : split(summaryCsv(state, stats, summary)).comments)
      if (c.rfind("# " + key + ": ", 0) == 0) return c.substr(key.size() + 4);
    return std::string("(missing)");
  };
  RunSummary given = summarizeRun(stats, nullptr, "no tail analysis");
  given.DError = 123.25;  // a value no statistics give: the CSV must take the summary's
  given.DErrorNote = "one sigma of a bootstrap over segments";
  EXPECT_EQ(dRow(given).at(2), "123.25");
  EXPECT_EQ(commentOf(given, "D_error"), given.DErrorNote);
  RunSummary none = given;
  none.DError = kTailUndefined;  // dominated: no error
  none.DErrorNote = "no error: D is dominated by its longest segments";
  const std::vector<std::string> row = dRow(none);
  EXPECT_TRUE(row.size() == 2 || row.at(2).empty()) << "D's error cell must be empty when D has none";
  EXPECT_EQ(commentOf(none, "D_error"), none.DErrorNote);
  // The computed summary of this run: the cell is its DError, whatever the subsets say.
  const RunSummary computed = summarizeRun(state, stats);
  const std::vector<std::string> r = dRow(computed);
  if (std::isfinite(computed.DError)) EXPECT_EQ(std::strtod(r.at(2).c_str(), nullptr), computed.DError);
  else EXPECT_TRUE(r.size() == 2 || r.at(2).empty());
}

TEST(StatisticsCsv, FileNamesForKPointOneHaveNoTheory) {
  const TrappingState state = smallRun();
  const TrappingStatistics stats = statisticsOf(state);
  const auto theory = theoryCurves(state.params, stats);
  EXPECT_TRUE(theory.empty());
  std::vector<std::string> names;
  for (const CsvFile& f : statisticsCsvFiles(state, stats, theory, summarizeRun(state, stats))) names.push_back(f.name);
  EXPECT_EQ(names, (std::vector<std::string>{"f_t.csv", "p_t_probability.csv", "P_t.csv", "C_tau.csv",
                                             "local_exponent.csv", "S_t.csv", "S_t_compensated.csv", "D_t.csv", "summary.csv",
                                             "longest_segments.csv"}));
  EXPECT_TRUE(theoryCsv(state, theory, Statistic::f).empty());
}

// K < 0 (§4): t_max on f_t, P_t and C_τ, fitted curves on f_t and C_τ, each in <stem>.theory.csv.
TEST(StatisticsCsv, NegativeKWritesTheTheoryNextToItsStatistic) {
  const TrappingState state = smallRun(-1e-4);
  const TrappingStatistics stats = statisticsOf(state);
  const auto theory = theoryCurves(state.params, stats);
  std::set<std::string> names;
  for (const CsvFile& f : statisticsCsvFiles(state, stats, theory, summarizeRun(state, stats))) names.insert(f.name);
  for (const char* n : {"f_t.theory.csv", "P_t.theory.csv", "C_tau.theory.csv"}) EXPECT_EQ(names.count(n), 1u) << n;
  EXPECT_EQ(names.count("S_t.theory.csv"), 0u);
  EXPECT_EQ(names.size(), 13u);

  const Split f = split(theoryCsv(state, theory, Statistic::f));
  const double tmax = 5.1454 * std::pow(1e-4, -0.25);
  double line = 0;
  for (const std::string& c : f.comments) {
    const std::string prefix = "# vertical_line: t_max = 5.1454 |K|^-1/4; t = ";
    if (c.rfind(prefix, 0) == 0) line = std::strtod(c.c_str() + prefix.size(), nullptr);
  }
  EXPECT_NEAR(line, tmax, 1e-5 * tmax);  // the paper gives 5 digits
  ASSERT_GT(f.rows.size(), 1u);
  EXPECT_EQ(f.rows.front(), "curve,t,f_t");
  for (std::size_t i = 1; i < f.rows.size(); ++i) {
    const auto c = cells(f.rows[i]);
    ASSERT_EQ(c.size(), 3u) << f.rows[i];
    EXPECT_EQ(c[0], "F(|K|^1/4 t)");
    EXPECT_LT(std::strtod(c[1].c_str(), nullptr), line);  // F is drawn up to the singularity at t_max
  }
  EXPECT_EQ(split(theoryCsv(state, theory, Statistic::C)).rows.front(), "curve,tau,C_tau");
  // P_t has the cutoff line only: a header and no rows.
  const Split P = split(theoryCsv(state, theory, Statistic::P));
  EXPECT_EQ(P.rows, (std::vector<std::string>{"curve,t,P_t"}));
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(StatisticsCsv, WritersWriteExactlyTheTexts) {
  const TrappingState state = smallRun(-1e-4);
  const TrappingStatistics stats = statisticsOf(state);
  const auto theory = theoryCurves(state.params, stats);
  const auto dir = std::filesystem::temp_directory_path() / "archipelago_statistics_csv_test";
  std::filesystem::remove_all(dir);
  const auto written = writeStatisticsCsv(dir / "all", state, stats, theory, summarizeRun(state, stats));
  const auto files = statisticsCsvFiles(state, stats, theory, summarizeRun(state, stats));
  ASSERT_EQ(written.size(), files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    EXPECT_EQ(written[i], dir / "all" / files[i].name);
    EXPECT_EQ(slurp(written[i]), files[i].text) << files[i].name;
  }
  // One statistic to a path of the user's choice: its theory goes next to it.
  const auto one = writeStatisticCsv(dir / "mine.csv", state, stats, theory, Statistic::C);
  ASSERT_EQ(one.size(), 2u);
  EXPECT_EQ(one[1], dir / "mine.theory.csv");
  EXPECT_EQ(slurp(dir / "mine.csv"), slurp(dir / "all" / "C_tau.csv"));
  EXPECT_EQ(slurp(dir / "mine.theory.csv"), slurp(dir / "all" / "C_tau.theory.csv"));
  EXPECT_EQ(writeStatisticCsv(dir / "S.csv", state, stats, theory, Statistic::S).size(), 1u);
  EXPECT_THROW((void)writeStatisticsCsv("/proc/archipelago-no-such-folder/x", state, stats, theory, RunSummary{}),
               std::runtime_error);
  EXPECT_THROW((void)writeStatisticCsv("/nonexistent-folder/x.csv", state, stats, theory, Statistic::f),
               std::runtime_error);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace archipelago
