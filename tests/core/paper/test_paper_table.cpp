// core/paper/PaperTable: the one table of the paper's figures and statements (issue #24).  Its own consistency:
// every statement names a figure panel the paper has, every panel that plots a statistic names one the statistics
// table has, ids are unique, every tolerance says why.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/paper/PaperTable.hpp"
#include "core/stats/StatisticsTable.hpp"

namespace archipelago::paper {
namespace {

TEST(PaperTable, FiguresAreNumberedByFirstCitation) {
  const char* labels[] = {"exam", "exa", "fsmall", "level", "txzero", "expense", "spread", "long"};
  ASSERT_EQ(figures().size(), 8u);
  for (int n = 1; n <= 8; ++n) {
    EXPECT_EQ(figure(n).number, n);
    EXPECT_EQ(figure(n).label, labels[n - 1]);
  }
  EXPECT_THROW((void)figure(9), std::out_of_range);
  // Fig. 7 has three panels (§5: "fig. spread(a)", "fig. spread(b)", "fig. spread(c)").
  ASSERT_EQ(figure(7).panels.size(), 3u);
  EXPECT_EQ(panelName(figure(7), figure(7).panels[1]), "7b");
  EXPECT_EQ(figure(6).panels.size(), 4u);
  EXPECT_EQ(figure(4).panels.size(), 2u);  // level(a): K = 0; level(b): K > 0 (§4)
}

TEST(PaperTable, PanelsNameStatisticsThatExist) {
  for (const Figure& f : figures())
    for (const FigurePanel& p : f.panels)
      if (!p.statisticKey.empty())
        EXPECT_TRUE(statisticWithKey(p.statisticKey).has_value()) << panelName(f, p) << ": " << p.statisticKey;
}

TEST(PaperTable, StatementsAreWholeAndUnique) {
  std::set<std::string> ids, panels;
  for (const Figure& f : figures())
    for (const FigurePanel& p : f.panels) panels.insert(panelName(f, p));
  for (const Statement& s : statements()) {
    EXPECT_TRUE(ids.insert(std::string(s.id)).second) << "id twice: " << s.id;
    EXPECT_FALSE(s.section.empty()) << s.id;
    EXPECT_FALSE(s.words.empty()) << s.id;
    EXPECT_FALSE(s.paperText.empty()) << s.id;
    EXPECT_FALSE(s.method.empty()) << s.id;
    EXPECT_FALSE(s.toleranceWhy.empty()) << s.id;
    if (!s.panel.empty()) EXPECT_TRUE(panels.count(std::string(s.panel))) << s.id << ": panel " << s.panel;
    if ((s.comparison == Comparison::value || s.comparison == Comparison::range) && !s.toleranceFromData)
      EXPECT_GT(s.tolerance, 0) << s.id << ": a value compared needs a tolerance";
    if (s.toleranceFromData) EXPECT_EQ(s.tolerance, 0) << s.id << ": the report computes it";
    if (s.comparison != Comparison::openQuestion) EXPECT_TRUE(s.paper.has_value()) << s.id;
    EXPECT_EQ(findStatement(s.id), &s);
  }
  EXPECT_EQ(findStatement("no-such-statement"), nullptr);
  EXPECT_THROW((void)statement("no-such-statement"), std::out_of_range);
}

TEST(PaperTable, MarkdownTableHasARowPerStatement) {
  const std::string md = markdownTable();
  std::size_t rows = 0;
  for (std::size_t at = 0; (at = md.find("\n| ", at)) != std::string::npos; ++at) ++rows;
  EXPECT_EQ(rows, statements().size());  // a row per statement after the header and separator lines
  EXPECT_NE(md.find("| chain138-x |"), std::string::npos);
}

}  // namespace
}  // namespace archipelago::paper
