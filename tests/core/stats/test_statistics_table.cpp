// The one table of the statistics (issue #11 item 2).  Regression: the CLI wrote D_t.csv with the header
// "t,f_t,error" while the GUI wrote D.csv with "curve,x,value,error", because three tables described the same
// six series.  Now one table; these tests check that it is complete and consistent.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>

#include "core/stats/StatisticsTable.hpp"

namespace archipelago {
namespace {

// Every series member of TrappingStatistics, tagged with a distinct abscissa so that a row's member pointer
// can be recognised.  Written out here by name, independently of the table.
TrappingStatistics tagged() {
  TrappingStatistics s;
  s.f.x = {1};
  s.p.x = {2};
  s.P.x = {3};
  s.C.x = {4};
  s.localExponent.x = {5};
  s.S.x = {6};
  s.Scompensated.x = {8};
  s.Dt.x = {7};
  return s;
}

TEST(StatisticsTable, EverySeriesMemberAppearsExactlyOnce) {
  const TrappingStatistics s = tagged();
  std::multiset<double> seen;
  for (const StatisticInfo& row : statisticsTable()) {
    ASSERT_NE(row.member, nullptr) << row.key;
    ASSERT_EQ((s.*row.member).x.size(), 1u) << row.key;
    seen.insert((s.*row.member).x[0]);
  }
  EXPECT_EQ(seen, (std::multiset<double>{1, 2, 3, 4, 5, 6, 7, 8}));
}

// A tripwire: TrappingStatistics holds 8 series and 7 doubles and 2 counters.  A new member changes its size;
// if it is a Series, add it to the table (and to tagged() above), then update this count.
TEST(StatisticsTable, TrappingStatisticsHasNoSeriesTheTableMisses) {
  EXPECT_EQ(sizeof(TrappingStatistics), 8 * sizeof(Series) + 7 * sizeof(double) + 2 * sizeof(std::uint64_t));
  EXPECT_EQ(statisticsTable().size(), 8u);
}

TEST(StatisticsTable, RowsFollowTheEnumAndLookUpsAgree) {
  const TrappingStatistics s = tagged();
  std::size_t i = 0;
  for (const StatisticInfo& row : statisticsTable()) {
    EXPECT_EQ(static_cast<std::size_t>(row.statistic), i) << row.key;
    EXPECT_EQ(&statisticInfo(row.statistic), &row);
    EXPECT_EQ(statisticWithKey(row.key), row.statistic);
    EXPECT_EQ(&seriesOf(s, row.statistic), &(s.*row.member));
    ++i;
  }
  EXPECT_FALSE(statisticWithKey("f").has_value());
  EXPECT_FALSE(statisticWithKey("").has_value());
}

TEST(StatisticsTable, KeysAndFileStemsAreUniqueDescriptiveAndSafe) {
  std::set<std::string_view> keys, stems;
  for (const StatisticInfo& row : statisticsTable()) {
    EXPECT_TRUE(keys.insert(row.key).second) << row.key;
    EXPECT_TRUE(stems.insert(row.fileStem).second) << row.fileStem;
    EXPECT_GE(row.fileStem.size(), 3u) << "not a single letter: " << row.fileStem;
    for (const char c : row.fileStem)
      EXPECT_TRUE((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')
          << row.fileStem;
    for (const char c : row.key) EXPECT_NE(c, ',') << row.key;  // the key is a CSV column name
  }
  EXPECT_EQ(stems, (std::set<std::string_view>{"f_t", "p_t_probability", "P_t", "C_tau", "local_exponent", "S_t",
                                                "S_t_compensated", "D_t"}));
}

// Regression: stems "p" and "P" (then "p_t" and "P_t") name the same file on a case-insensitive file system
// (macOS, Windows), where P_t.csv silently replaced p_t.csv.
TEST(StatisticsTable, FileStemsDifferEvenWithoutCase) {
  std::set<std::string> folded;
  for (const StatisticInfo& row : statisticsTable()) {
    std::string stem(row.fileStem);
    for (char& c : stem) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_TRUE(folded.insert(stem).second) << row.fileStem;
  }
}

TEST(StatisticsTable, AbscissaeLabelsAndScales) {
  for (const StatisticInfo& row : statisticsTable()) {
    const bool tau = row.statistic == Statistic::C || row.statistic == Statistic::localExponent;
    EXPECT_EQ(row.abscissa, tau ? "tau" : "t") << row.key;
    EXPECT_NE(row.abscissaLabel.find("(steps)"), std::string_view::npos) << row.key;
    EXPECT_NE(row.abscissaLabelRich.find("(steps)"), std::string_view::npos) << row.key;
    EXPECT_EQ(row.abscissaLabelRich.find(tau ? "τ" : "t"), 0u) << row.key;
    EXPECT_FALSE(row.symbol.empty());
    EXPECT_FALSE(row.symbolRich.empty());
    EXPECT_FALSE(row.valueLabel.empty());
    EXPECT_FALSE(row.valueLabelRich.empty());
    EXPECT_FALSE(row.description.empty());
    EXPECT_NE(row.error.find("subsets"), std::string_view::npos) << row.key;
    EXPECT_EQ(row.abscissaScale, AxisScale::logarithmic) << row.key;
    // Fig. 6(d) draws the local exponent on a linear axis; every other statistic is log-log.
    EXPECT_EQ(row.valueScale, row.statistic == Statistic::localExponent ? AxisScale::linear : AxisScale::logarithmic)
        << row.key;
    // The GUI has a plot for each series of figs. 6 and 7 but p_t = α f_t and fig. 7b's S_t/t^{3/2} (S_t's plot
    // shows the t^{3/2} slope).  Figure panels come from the paper's table: every plotted series is in a figure.
    EXPECT_EQ(row.plotted, row.statistic != Statistic::p && row.statistic != Statistic::Scompensated) << row.key;
    EXPECT_EQ(!figurePanelsOf(row.statistic).empty(), row.statistic != Statistic::p) << row.key;
  }
  // Issue #24: fig. 7 has three panels, (a) S_t, (b) S_t against t^{3/2}, (c) D_t (the report once drew two and
  // labelled D_t "7b"); f_t is drawn in figs. 3 and 6a.
  EXPECT_EQ(figurePanelsOf(Statistic::S), "7a");
  EXPECT_EQ(figurePanelsOf(Statistic::Scompensated), "7b");
  EXPECT_EQ(figurePanelsOf(Statistic::Dt), "7c");
  EXPECT_EQ(figurePanelsOf(Statistic::f), "3abc, 6a");
  EXPECT_EQ(figurePanelsOf(Statistic::localExponent), "6d");
  // Densities per step (appendix B).
  EXPECT_NE(statisticInfo(Statistic::f).valueLabel.find("per step"), std::string_view::npos);
  EXPECT_EQ(statisticInfo(Statistic::f).symbolRich, "f<sub>t</sub>");
  EXPECT_EQ(statisticInfo(Statistic::C).symbolRich, "C<sub>τ</sub>");
}

}  // namespace
}  // namespace archipelago
