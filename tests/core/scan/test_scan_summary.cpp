// The summary files of a K scan and box_invariant.csv (core/scan/ScanSummary.hpp, core/export/BoxInvariantCsv.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/export/BoxInvariantCsv.hpp"
#include "core/scan/ScanHeatMap.hpp"
#include "core/scan/ScanSummary.hpp"
#include "core/stats/TailAnalysis.hpp"
#include "core/stats/RunStatistics.hpp"

namespace archipelago {
namespace {

std::vector<std::string> dataLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.starts_with("#")) lines.push_back(line);
  return lines;
}

ScanRunSummary summaryOf(double K, std::optional<double> fraction) {
  TrappingParameters p;
  p.map = scanBox(K);
  p.M = 4;
  p.T = 3000;
  p.subsets = 2;
  const TrappingState s = runTrapping(startTrapping(p), TrappingRunOptions{});
  const TrappingStatistics st = statisticsOf(s);
  std::optional<StochasticAreaValue> b2;
  if (fraction) b2 = stochasticAreaOf(p.map, *fraction);
  return {p, scanPointOf(s, st, b2), st};
}

TEST(ScanCsv, FilesHoldEveryKInTheirLayout) {
  const std::vector<ScanRunSummary> runs{summaryOf(0.05, std::nullopt), summaryOf(0.1, 0.8)};
  const auto ft = dataLines(scanFtCsv(runs));
  // q = 16: the rows below 10 q = 160 steps describe blocks of q steps (issue #26), marked as in f_t.csv.
  EXPECT_EQ(ft.front(), "K,t,f_t,f_t_error,blocks_affected");
  EXPECT_EQ(ft.size(), 1 + runs[0].statistics.f.x.size() + runs[1].statistics.f.x.size());
  EXPECT_TRUE(ft[1].starts_with("0.05,")) << ft[1];
  EXPECT_TRUE(ft[1].ends_with(",1")) << ft[1];
  EXPECT_TRUE(ft.back().starts_with("0.1,")) << ft.back();
  EXPECT_TRUE(ft.back().ends_with(",0")) << ft.back();

  const ScanHeatMap map = localExponentHeatMap(runs);
  const auto heat = dataLines(scanLocalExponentCsv(runs));
  EXPECT_EQ(heat.front(), "tau,0.05,0.1");
  EXPECT_EQ(heat.size(), 1 + map.tau.size());
  // Every value of every run is in its cell; a τ one run lacks is an empty cell.
  for (std::size_t c = 0; c < runs.size(); ++c) {
    const Series& e = runs[c].statistics.localExponent;
    for (std::size_t i = 0; i < e.x.size(); ++i) {
      const auto row = static_cast<std::size_t>(std::find(map.tau.begin(), map.tau.end(), e.x[i]) - map.tau.begin());
      ASSERT_LT(row, map.tau.size());
      EXPECT_EQ(map.value[row * 2 + c], e.value[i]);
    }
  }
  std::size_t emptyCells = 0;
  for (std::size_t i = 1; i < heat.size(); ++i) {
    const std::string& line = heat[i];
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 2) << line;  // τ and one cell per K, even when empty
    emptyCells += (line.find(",,") != std::string::npos) + line.ends_with(",");
  }
  std::size_t nan = 0;
  for (const double v : map.value) nan += std::isnan(v);
  EXPECT_EQ(emptyCells, nan);  // NaN (undefined) is an empty cell, never "nan"

  const auto summary = dataLines(scanSummaryCsv(runs));
  ASSERT_EQ(summary.size(), 3u);
  EXPECT_EQ(summary[0], "K,xmin,xmax,blocks_done,T,segments,D,D_error,longest_steps,time_fraction_ge_1e4,b2_area,"
                        "b2_fraction,b2_D,b2_D_error");
  EXPECT_TRUE(summary[1].starts_with("0.05,")) << summary[1];
  EXPECT_TRUE(summary[1].ends_with(",,,,")) << summary[1];  // no b₂ for K = 0.05
  // With b₂: b2_D carries D's error exactly when D has one (supportedDError: none where the tail dominates).
  const std::vector<std::string> cells = [&] {
    std::vector<std::string> c;
    std::stringstream in(summary[2]);
    for (std::string cell; std::getline(in, cell, ',');) c.push_back(cell);
    if (summary[2].ends_with(",")) c.emplace_back();
    return c;
  }();
  ASSERT_EQ(cells.size(), 14u) << summary[2];
  EXPECT_FALSE(cells[12].empty()) << summary[2];                  // b2_D
  EXPECT_EQ(cells[7].empty(), cells[13].empty()) << summary[2];   // D_error and b2_D_error
}

TEST(ScanCsv, BoxInvariantFileHoldsAreaProductAndFactors) {
  TrappingParameters p;
  p.M = 4;
  p.T = 3000;
  p.subsets = 2;
  const TrappingState s = runTrapping(startTrapping(p), TrappingRunOptions{});
  const TrappingStatistics st = statisticsOf(s);
  const std::string text = boxInvariantCsv(s, st, stochasticAreaOf(p.map, 0.811), 12.5);
  const auto lines = dataLines(text);
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines[0], "quantity,value,error");
  EXPECT_TRUE(lines[1].starts_with("b2_area,1.3705")) << lines[1];
  EXPECT_TRUE(lines[2].starts_with("b2_fraction,0.811")) << lines[2];
  EXPECT_TRUE(lines[5].starts_with("b2_D,")) << lines[5];
  EXPECT_NE(text.find("# K: 0.1"), std::string::npos);  // the run's metadata opens the file
  EXPECT_TRUE(lines[4].starts_with("D,") && lines[4].ends_with(",12.5")) << lines[4];  // the error given, not the subsets'
  // No error where the tail dominates D: an empty cell for D, b₂·D and the enhancement, never a number.
  const auto none = dataLines(boxInvariantCsv(s, st, stochasticAreaOf(p.map, 0.811), kTailUndefined));
  EXPECT_TRUE(none[4].starts_with("D,") && none[4].ends_with(",")) << none[4];
  EXPECT_TRUE(none[5].starts_with("b2_D,") && none[5].ends_with(",")) << none[5];
  EXPECT_TRUE(none[7].ends_with(",")) << none[7];
}

}  // namespace
}  // namespace archipelago
