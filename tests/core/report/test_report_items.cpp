// The report's items and marks (core/report/ReportItem.hpp, ReportPlan.hpp; issue #26: "report checks that can
// fail"): every statement's check fails for a wrong value, the marks follow the table (sizes, open questions), the
// plan covers exactly the table, and the theory statements agree with the paper.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "core/paper/PaperTable.hpp"
#include "core/io/NumberText.hpp"
#include "core/report/ReportItem.hpp"
#include "core/report/ReportPlan.hpp"
#include "core/report/ReportWriters.hpp"
#include "core/report/RunStatements.hpp"
#include "core/report/TheoryStatements.hpp"

namespace archipelago::report {
namespace {

/// A value the statement's comparison must refuse: well beyond its tolerance, on the failing side.
double wrongValue(const paper::Statement& s) {
  const double target = *s.paper;
  const double away = 2 * s.tolerance + 0.5 * std::abs(target) + 1;
  return s.comparison == paper::Comparison::atLeast ? target - away : target + away;
}

TEST(ReportItems, EveryStatementsCheckFailsForAWrongValueAndPassesForThePapers) {
  int checked = 0;
  for (const paper::Statement& s : paper::statements()) {
    SCOPED_TRACE(std::string(s.id));
    if (s.comparison == paper::Comparison::openQuestion) {
      // An open question is reported, never judged, whatever the value.
      EXPECT_EQ(makeItem(s.id, 1.0, 0, true, "", "").mark, Mark::reported);
      EXPECT_FALSE(passes(s, 1.0, 0, s.paper));
      continue;
    }
    ASSERT_TRUE(s.paper.has_value()) << "a judged statement needs the paper's value";
    EXPECT_EQ(makeItem(s.id, *s.paper, 0, true, "", "").mark, Mark::agrees);
    EXPECT_EQ(makeItem(s.id, wrongValue(s), 0, true, "", "").mark, Mark::differs);
    // The error widens the check by 3 σ, no more.
    const double w = wrongValue(s);
    const double gap = std::abs(w - *s.paper) - s.tolerance;
    EXPECT_EQ(makeItem(s.id, w, gap / 2.9, true, "", "").mark, Mark::agrees);
    EXPECT_EQ(makeItem(s.id, w, gap / 3.1, true, "", "").mark, Mark::differs);
    ++checked;
  }
  EXPECT_GE(checked, 30);
}

TEST(ReportItems, OneSidedComparisonsFailOnTheirSideOnly) {
  for (const paper::Statement& s : paper::statements()) {
    if (s.comparison != paper::Comparison::atLeast && s.comparison != paper::Comparison::atMost) continue;
    SCOPED_TRACE(std::string(s.id));
    const double far = 10 * (s.tolerance + std::abs(*s.paper) + 1);
    const bool atLeast = s.comparison == paper::Comparison::atLeast;
    EXPECT_EQ(makeItem(s.id, *s.paper + (atLeast ? far : -far), 0, true, "", "").mark, Mark::agrees);
    EXPECT_EQ(makeItem(s.id, *s.paper + (atLeast ? -far : far), 0, true, "", "").mark, Mark::differs);
  }
}

// Issue 39: S-superdiffusive is two-sided against the independent 1.652 ± 0.002 (the report passes it as the reference).
// It passes the report's full-size value (1.664 ± 0.005, docs/statistics.md) and fails the q = 16 run without its
// companion (1.576 ± 0.005, issue 39), which the paper's one-sided "> 3/2" passed; the smallest deviation it detects
// is 3 × 0.002 + 3 σ of ours (0.021 at σ = 0.005).
TEST(ReportItems, SuperdiffusiveSlopeIsTwoSidedAgainstTheIndependentValue) {
  const double ref = paper::kSuperdiffusiveSlope;
  EXPECT_EQ(makeItem("S-superdiffusive", 1.664, 0.005, true, "", "", ref).mark, Mark::agrees);
  EXPECT_EQ(makeItem("S-superdiffusive", ref, 0.005, true, "", "", ref).mark, Mark::agrees);
  EXPECT_EQ(makeItem("S-superdiffusive", 1.576, 0.005, true, "", "", ref).mark, Mark::differs);
  EXPECT_EQ(makeItem("S-superdiffusive", 1.75, 0.005, true, "", "", ref).mark, Mark::differs);  // too fast, too
  EXPECT_EQ(makeItem("S-superdiffusive", ref + 0.0209, 0.005, true, "", "", ref).mark, Mark::agrees);
  EXPECT_EQ(makeItem("S-superdiffusive", ref + 0.0211, 0.005, true, "", "", ref).mark, Mark::differs);
  EXPECT_GT(1.576, 1.5) << "the paper's words alone (> 3/2) pass the artefact";
}

TEST(ReportItems, MarksFollowTheTable) {
  for (const paper::Statement& s : paper::statements()) {
    SCOPED_TRACE(std::string(s.id));
    if (s.comparison == paper::Comparison::openQuestion) continue;
    // No value, or a value that is not a number: not computed, never "agrees".
    EXPECT_EQ(makeItem(s.id, std::nullopt, 0, true, "", "").mark, Mark::notComputed);
    EXPECT_EQ(makeItem(s.id, std::numeric_limits<double>::quiet_NaN(), 0, true, "", "").mark, Mark::notComputed);
    EXPECT_EQ(makeItem(s.id, std::numeric_limits<double>::infinity(), 0, true, "", "").mark, Mark::notComputed);
    // A NaN error does not widen the check.
    EXPECT_EQ(makeItem(s.id, wrongValue(s), std::numeric_limits<double>::quiet_NaN(), true, "", "").mark,
              Mark::differs);
    // A quick report does not judge what needs the paper's size.
    EXPECT_EQ(makeItem(s.id, wrongValue(s), 0, false, "", "").mark,
              s.needsFullSize ? Mark::notAtThisSize : Mark::differs);
  }
  EXPECT_THROW((void)makeItem("no-such-statement", 1.0, 0, true, "", ""), std::out_of_range);
}

TEST(ReportItems, AReferenceReplacesThePapersValue) {
  const paper::Statement& s = paper::statement("tmax-measured");
  // The longest segment in the run's finite box is compared with the box's prediction, not the infinite box's.
  EXPECT_EQ(makeItem(s.id, *s.paper - 6, 0, true, "", "", *s.paper - 6).mark, Mark::agrees);
  EXPECT_EQ(makeItem(s.id, *s.paper, 0, true, "", "", *s.paper - 6).mark, Mark::differs);
}

TEST(ReportItems, OnlyADifferenceIsExplained) {
  ReportItem agrees = makeItem("t7", 7.0, 0, true, "", "fit");
  explainDifference(agrees, "a reason");
  EXPECT_EQ(agrees.mark, Mark::agrees);
  EXPECT_EQ(agrees.note, "fit");
  ReportItem differs = makeItem("t7", 20.0, 0, true, "", "fit");
  explainDifference(differs, "a reason");
  EXPECT_EQ(differs.mark, Mark::differsExplained);
  EXPECT_EQ(differs.note, "fit; a reason");
}

// markov-tree (issue 40): a reported comparison, never a verdict — ours is the comparison's reach, the note carries
// every level's ratio (one far below the smallest double too, as the exponential tail of a finite tree gives) and the
// level that holds the model's survivors; no level, no value.
TEST(ReportItems, TheMarkovTreeItemReportsTheReachWithEveryRatio) {
  MarkovTree tree;
  tree.states.resize(3);
  tree.lumped.resize(2);
  MarkovTreeComparison c;
  c.weight = 0.0531L;
  c.factor = 3;
  c.reach = 21744;
  const long double ratios[] = {1.12L, 0.437L, 1e-989L};
  const double ts[] = {1008, 21744, 1e9};
  for (int k = 0; k < 3; ++k) {
    MarkovTreeLevelComparison m;
    m.t = ts[k];
    m.measured = 1e-6;
    m.ratio = ratios[k];
    m.holdingLevel = 1;
    m.holdingShare = 0.97;
    c.levels.push_back(m);
  }
  const ReportItem it = markovTreeStatement(c, tree, 1, 18.9242, 1.37005, "archipelago-cli markov-tree");
  EXPECT_EQ(it.mark, Mark::reported);
  ASSERT_TRUE(it.ours.has_value());
  EXPECT_EQ(*it.ours, 21744);
  for (const char* part : {"depth-1 atlas", "3 states, 2 chains lumped", "b₂ = 1.37005", "at t = 2.174e+04 steps last",
                           "1.01e+03: 1.12 (1, 97 %)", "2.17e+04: 0.437", "1e+09: 1e-989"}) {
    EXPECT_NE(it.note.find(part), std::string::npos) << part << " not in: " << it.note;
  }
  c.levels.clear();
  const ReportItem none = markovTreeStatement(c, tree, 1, 18.9242, 1.37005, "archipelago-cli markov-tree");
  EXPECT_FALSE(none.ours.has_value());
  EXPECT_NE(none.note.find("no reliable level"), std::string::npos) << none.note;
}

// tail-gamma-K (issue 55): the exponent over 10⁴–10⁶ averaged over K against Cristadoro & Ketzmerick's 1.57, within
// 2√(error² + s²/n).  Per-K exponents about 1.57 agree and a set centred on 1.0 differs; the factor is 2, not the 3 σ
// of the other items; a K that does not reach 10⁶ (γ NaN) is left out and named; fewer than two K, none, or an
// unknown error give no value, never a pass; a quick report does not judge it.
std::vector<TailExponent> perK(const std::vector<double>& gammas, double error) {
  std::vector<TailExponent> out;
  for (const double g : gammas) out.push_back({kTailGammaKFrom, kTailGammaKTo, 1e5, 30, g, error});
  return out;
}

/// 2√(error² + s²/n) of finite γ with one error each, by hand.
double ruleTolerance(const std::vector<double>& g, double error) {
  const double n = static_cast<double>(g.size());
  double mean = 0, squares = 0;
  for (const double x : g) mean += x / n;
  for (const double x : g) squares += (x - mean) * (x - mean);
  const double meanError = std::sqrt(n * error * error) / n;
  return 2 * std::sqrt(meanError * meanError + squares / (n - 1) / n);
}

TEST(ReportItems, TheKAveragedTailExponentAgreesAbout157AndDiffersAbout1) {
  const std::vector<double> K{0.1, 0.15, 0.2, 0.25}, about157{1.50, 1.62, 1.55, 1.64}, about1{0.95, 1.05, 0.98, 1.02};
  const ReportItem near = tailGammaKStatement(K, perK(about157, 0.02), true, "archipelago-cli tail-scan");
  EXPECT_EQ(near.mark, Mark::agrees) << near.note;
  ASSERT_TRUE(near.ours && near.tolerance);
  EXPECT_NEAR(*near.ours, 1.5775, 1e-12);
  EXPECT_NEAR(near.error, 0.01, 1e-12) << "√(Σσ²)/n";
  EXPECT_NEAR(*near.tolerance, ruleTolerance(about157, 0.02), 1e-12);
  EXPECT_NE(itemsCsv({near}).find(io::formatC(",%.3g,\"agrees\",", *near.tolerance)), std::string::npos)
      << "items.csv gives the tolerance checked against: " << itemsCsv({near});
  for (const std::string part : {"at 4 of 4 K", "left out, not reaching 1e+06 reliably: none", "s²/n) = ",
                                 "agrees when |γ̄ − 1.57| ≤ ", "0.25: 1.640 ± 0.020", "finite window",
                                 "asymptotic"})
    EXPECT_NE(near.note.find(part), std::string::npos) << part << " not in: " << near.note;
  const ReportItem far = tailGammaKStatement(K, perK(about1, 0.02), true, "");
  EXPECT_EQ(far.mark, Mark::differs) << far.note;
  EXPECT_NEAR(*far.ours, 1.0, 1e-12);
}

TEST(ReportItems, TheKAveragedTailExponentIsCheckedAtTwoOfItsTolerancesSigmaNotThree) {
  // Four equal γ: s = 0, so the tolerance is 2 × the error 0.01.  At 2.5 errors from 1.57 the makeItem rule
  // (tolerance 0 + 3 σ) would pass; the item's rule does not.
  const std::vector<double> K{0.1, 0.15, 0.2, 0.25};
  const double g = paper::kGammaCristadoroKetzmerick + 0.025;
  const ReportItem it = tailGammaKStatement(K, perK({g, g, g, g}, 0.02), true, "");
  EXPECT_NEAR(*it.tolerance, 0.02, 1e-12);
  EXPECT_EQ(it.mark, Mark::differs) << it.note;
  EXPECT_EQ(makeItem("tail-gamma-K", g, 0.01, true, "", "").mark, Mark::agrees);
  const double inside = paper::kGammaCristadoroKetzmerick + 0.019;
  EXPECT_EQ(tailGammaKStatement(K, perK({inside, inside, inside, inside}, 0.02), true, "").mark, Mark::agrees);
}

TEST(ReportItems, TheKAveragedTailExponentLeavesOutTheKThatDoNotReachAndNeedsTwo) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> K{0.1, 0.15, 0.2, 0.25};
  const ReportItem some = tailGammaKStatement(K, perK({1.55, nan, 1.6, nan}, 0.02), true, "");
  EXPECT_EQ(some.mark, Mark::agrees) << some.note;
  EXPECT_NEAR(*some.ours, 1.575, 1e-12);
  EXPECT_NE(some.note.find("at 2 of 4 K (left out, not reaching 1e+06 reliably: 0.15, 0.25)"), std::string::npos)
      << some.note;
  for (const ReportItem& none : {tailGammaKStatement(K, perK({1.57, nan, nan, nan}, 0.02), true, ""),
                                 tailGammaKStatement(K, perK({nan, nan, nan, nan}, 0.02), true, ""),
                                 tailGammaKStatement({}, {}, true, ""),
                                 tailGammaKStatement(K, perK({1.5, 1.6, 1.55, 1.6}, nan), true, "")}) {
    EXPECT_EQ(none.mark, Mark::notComputed) << none.note;
    EXPECT_FALSE(none.ours.has_value());
    EXPECT_NE(none.note.find("no average"), std::string::npos) << none.note;
  }
  const ReportItem quick = tailGammaKStatement(K, perK({0.95, 1.05, 0.98, 1.02}, 0.02), false, "");
  EXPECT_EQ(quick.mark, Mark::notAtThisSize);
  EXPECT_TRUE(quick.ours.has_value()) << "the value is given at any size";
}

TEST(ReportPlan, EveryStatementHasExactlyOneNeedAndNoOtherIdHasOne) {
  std::set<Need> used;
  for (const paper::Statement& s : paper::statements()) used.insert(needOf(s.id));
  EXPECT_EQ(used, allNeeds()) << "every part of a report serves some statement";
  EXPECT_THROW((void)needOf("no-such-statement"), std::out_of_range);
  EXPECT_THROW((void)needOf(""), std::out_of_range);
}

// §2, §4's closed forms, §7's orbit and appendix C: computations of ours against the paper's printed numbers.
TEST(TheoryStatements, AgreeWithThePaper) {
  const auto items = theoryStatements();
  std::set<std::string> ids;
  for (const ReportItem& it : items) {
    SCOPED_TRACE(std::string(it.id()) + ": ours " + (it.ours ? std::to_string(*it.ours) : "none") + "; " + it.note);
    ids.insert(std::string(it.id()));
    EXPECT_EQ(it.mark, Mark::agrees);
    EXPECT_EQ(needOf(it.id()), Need::theory);
    EXPECT_FALSE(it.command.empty()) << "every item names a command that reproduces it";
  }
  for (const paper::Statement& s : paper::statements()) {
    if (needOf(s.id) == Need::theory) {
      EXPECT_EQ(ids.count(std::string(s.id)), 1u) << s.id;
    }
  }
}

}  // namespace
}  // namespace archipelago::report
