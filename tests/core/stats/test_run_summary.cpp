// One run summary (issue 35, item 3): D's error and its source are decided once, in core.  The bug it guards:
// Python's Run.statistics(short=…) paired the spliced D with the bootstrap error of the run alone, while
// `stats --short` gave the spliced statistics' subsets' error.  Hand-made statistics and tail analyses, so that each
// rule is seen to choose the value it names (the numbers differ on purpose: a wrong choice shows).
#include <gtest/gtest.h>

#include <cmath>

#include "core/stats/RunSummary.hpp"

namespace archipelago {
namespace {

TrappingStatistics statistics(double D, double subsetsError, double splicedAt) {
  TrappingStatistics s;
  s.D = D;
  s.DError = subsetsError;
  s.splicedAt = splicedAt;
  s.segments = 1000;
  s.alpha = 12.5;
  s.alphaError = 0.25;
  return s;
}

TailAnalysis tail(double D, double bootstrapError, bool dominated) {
  TailAnalysis a;
  a.D = D;
  a.DBootstrapError = bootstrapError;
  a.DSubsetError = 1;
  a.shareDominates = dominated;
  a.shares = {{1, dominated ? 0.6 : 0.05, 1e6}};  // as analyseTail makes it: the longest segment's share first
  a.tailFit.gammaP = 1.57;
  return a;
}

TEST(RunSummary, RunAloneTakesTheBootstrapNeverTheSubsets) {
  const TailAnalysis t = tail(6400, 900, false);
  const RunSummary r = summarizeRun(statistics(6400, 80, 0), &t);
  EXPECT_FALSE(r.spliced);
  EXPECT_EQ(r.D, 6400);
  EXPECT_EQ(r.DError, 900);
  EXPECT_EQ(r.errorSource, DErrorSource::bootstrap);
  EXPECT_EQ(r.DSubsetsError, 80);
  EXPECT_EQ(r.runD, 6400);
  EXPECT_EQ(r.runDError, 900);
  EXPECT_EQ(r.gammaP, 1.57);
  EXPECT_EQ(toString(r.errorSource), "bootstrap over segments");
  EXPECT_EQ(keyOf(r.errorSource), "bootstrap");
}

TEST(RunSummary, SplicedTakesTheSplicedSubsetsErrorAndKeepsTheRunAlone) {
  // The spliced D (7000) with the spliced statistics' subsets' error (70), as `stats --short` prints it; the run's
  // own D (6400) keeps its bootstrap error (900).  The bug paired 7000 with 900.
  const TailAnalysis t = tail(6400, 900, false);
  const RunSummary r = summarizeRun(statistics(7000, 70, 160), &t);
  EXPECT_TRUE(r.spliced);
  EXPECT_EQ(r.splicedAt, 160);
  EXPECT_EQ(r.D, 7000);
  EXPECT_EQ(r.DError, 70);
  EXPECT_EQ(r.errorSource, DErrorSource::subsets);
  EXPECT_EQ(r.runD, 6400);
  EXPECT_EQ(r.runDError, 900);
  EXPECT_NE(r.DErrorNote.find("spliced"), std::string::npos);
}

TEST(RunSummary, DominatedHasNoErrorAndSaysWhy) {
  for (const double splicedAt : {0.0, 160.0}) {
    const TailAnalysis t = tail(6400, 900, true);
    const RunSummary r = summarizeRun(statistics(6400, 80, splicedAt), &t);
    EXPECT_TRUE(r.dominated);
    EXPECT_TRUE(std::isnan(r.DError));
    EXPECT_TRUE(std::isnan(r.runDError));
    EXPECT_EQ(r.errorSource, DErrorSource::none);
    EXPECT_FALSE(r.verdict.empty());
    EXPECT_EQ(r.DErrorNote, "no error: " + r.verdict);
  }
}

TEST(RunSummary, NotJudgedHasNoErrorAndSaysWhy) {
  const RunSummary r = summarizeRun(statistics(6400, 80, 0), nullptr, "its error is judged when the run pauses");
  EXPECT_FALSE(r.judged);
  EXPECT_TRUE(std::isnan(r.DError));
  EXPECT_EQ(r.errorSource, DErrorSource::none);
  EXPECT_EQ(r.DErrorNote, "no error: its error is judged when the run pauses");
  EXPECT_EQ(r.runD, 6400);
}

TEST(RunSummary, BootstrapThatCouldNotBeDoneGivesNoError) {
  const TailAnalysis t = tail(6400, kTailUndefined, false);
  const RunSummary r = summarizeRun(statistics(6400, 80, 0), &t);
  EXPECT_TRUE(std::isnan(r.DError));
  EXPECT_EQ(r.errorSource, DErrorSource::none);
}

// Issue 37, finding 19: γ_P and the verdict in `stats`' words, from the summary (the GUI shows these strings).
TEST(RunSummary, GammaPAndTheVerdictInTheCliWords) {
  TailAnalysis t = tail(6400, 900, false);
  t.tailFit.from = 1000;
  t.tailFit.to = 12345;
  t.tailFit.gammaPInterval = {1.41, 1.7333};
  t.windows = {t.tailFit};
  const RunSummary r = summarizeRun(statistics(6400, 80, 0), &t);
  EXPECT_EQ(r.gammaPText, "1.57 [1.41, 1.733] over 1000 <= t <= 1.234e+04");
  EXPECT_EQ(r.tailVerdict, "the tail does not dominate D: its bootstrap error stands");
  const TailAnalysis d = tail(6400, 900, true);  // no windows: no fit
  const RunSummary rd = summarizeRun(statistics(6400, 80, 0), &d);
  EXPECT_EQ(rd.gammaPText, kNoTailFit);
  EXPECT_EQ(rd.tailVerdict, dominanceMessage(d));
  EXPECT_NE(rd.tailVerdict.find("dominated"), std::string::npos);
  EXPECT_TRUE(summarizeRun(statistics(6400, 80, 0), nullptr).gammaPText.empty());
}

}  // namespace
}  // namespace archipelago
