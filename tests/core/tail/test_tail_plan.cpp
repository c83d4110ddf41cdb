// The plan of a tail command (TailPlan.hpp): one call that returns the ready run or throws one error, with the
// wording every front end shows.
#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/tail/TailFile.hpp"
#include "core/tail/TailPlan.hpp"

namespace archipelago {
namespace {

std::string refusal(const TailPlanOptions& o) {
  try {
    (void)planTail(o);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TailPlanOptions newRun() {
  TailPlanOptions o;
  o.spec = [] {
    RunSpec s;
    s.threads = 3;
    s.kernel = "scalar";
    return s;
  };
  o.out = (std::filesystem::temp_directory_path() / "archipelago_test_tail_plan.json").string();
  o.optionName = [](std::string_view role) { return "--" + std::string(role); };  // archipelago-cli's names
  return o;
}

TEST(TailPlan, ANewRunIsStartedWithTheSpecsSettings) {
  TailPlanOptions o = newRun();
  o.clones = "metropolis";
  const TailPlan plan = planTail(o);
  EXPECT_FALSE(plan.printLevelsOnly);
  EXPECT_EQ(plan.threads, 3);
  EXPECT_EQ(plan.kernel, "scalar");
  EXPECT_EQ(plan.state.request.clones, CloneRule::metropolis);
  EXPECT_EQ(plan.state.request.run, RunSpec{}.parameters);
  EXPECT_EQ(plan.state.replicas.size(), o.request.replicas);
  EXPECT_TRUE(plan.runs.empty());
}

TEST(TailPlan, PrintLevelsStopsBeforeTheFilesAndASliceIsStarted) {
  TailPlanOptions o = newRun();
  o.printLevels = true;
  o.csv = o.out;  // an output over another: not checked for --print-levels, which writes nothing
  o.slice = replicaSlice(o.request.replicas, 1, 2);
  const TailPlan plan = planTail(o);
  EXPECT_TRUE(plan.printLevelsOnly);
  EXPECT_FALSE(plan.state.levels.empty());
  EXPECT_EQ(plan.state.firstReplica, o.slice->first);
  EXPECT_EQ(plan.state.replicas.size(), o.slice->count);
}

TEST(TailPlan, TheSpecIsResolvedOnlyForANewRunAfterTheEarlierChecks) {
  TailPlanOptions o = newRun();
  bool asked = false;
  o.spec = [&asked]() -> RunSpec {
    asked = true;
    throw std::invalid_argument("the front end's spec error");
  };
  o.checkpointSeconds = -1;
  EXPECT_EQ(refusal(o), "--checkpoint-interval = -1 must be a number of seconds >= 0");
  EXPECT_FALSE(asked);
  o.checkpointSeconds = 60;
  EXPECT_EQ(refusal(o), "the front end's spec error");
  EXPECT_TRUE(asked);
}

TEST(TailPlan, EachRefusalHasItsOneWording) {
  {
    TailPlanOptions o = newRun();
    o.resume = "old.json";
    o.givenSpec = {"--K", "--q"};
    EXPECT_EQ(refusal(o), "--resume takes the spec from the tail file; do not also give --K");
    o.givenSpec.clear();
    o.givenSampler = {"--population"};
    EXPECT_EQ(refusal(o), "--resume takes the sampler's settings from the tail file; do not also give --population");
    o.givenSampler.clear();
    o.printLevels = true;
    EXPECT_EQ(refusal(o), "--print-levels prints a new run's levels; do not give --resume");
  }
  {
    TailPlanOptions o = newRun();
    o.threads = -1;
    EXPECT_NE(refusal(o).find("threads"), std::string::npos) << refusal(o);
  }
  {
    TailPlanOptions o = newRun();
    o.clones = "magic";
    EXPECT_EQ(refusal(o), "--clones 'magic' must be perturb or metropolis");
    EXPECT_THROW((void)parseCloneRule("x", "clones"), std::invalid_argument);
    EXPECT_EQ(parseCloneRule("perturb"), CloneRule::perturb);
  }
  {
    TailPlanOptions o = newRun();
    o.request.population = 1;
    EXPECT_NE(refusal(o).find("population"), std::string::npos) << refusal(o);
  }
  {
    TailPlanOptions o = newRun();
    o.compareCsv = "c.csv";
    EXPECT_EQ(refusal(o), "--compare-csv needs --compare RUN.json");
  }
  {
    TailPlanOptions o = newRun();
    o.csv = o.out;  // an output over another
    EXPECT_NE(refusal(o).find("--csv"), std::string::npos) << refusal(o);
  }
}

// Issue 51: core names each setting by its role and the front end by its own name; without a name the role itself
// stands (Python's keywords), never a flag of another front end.
TEST(TailPlan, TheFrontEndNamesItsOwnSettings) {
  TailPlanOptions o = newRun();
  o.optionName = {};
  o.checkpointSeconds = -1;
  EXPECT_EQ(refusal(o), "checkpoint-interval = -1 must be a number of seconds >= 0");
  o.checkpointSeconds = 60;
  o.compareCsv = "c.csv";
  EXPECT_EQ(refusal(o), "compare-csv needs compare RUN.json");
  o.optionName = [](std::string_view role) {
    std::string keyword(role);
    for (char& c : keyword) c = c == '-' ? '_' : c;
    return "keyword " + keyword;
  };
  EXPECT_EQ(refusal(o), "keyword compare_csv needs keyword compare RUN.json");
  o.compareCsv.clear();
  o.clones = "magic";
  EXPECT_EQ(refusal(o), "keyword clones 'magic' must be perturb or metropolis");
}

TEST(TailPlan, AFinishedFileIsNotResumedButARanksSliceIs) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "archipelago_test_tail_plan_done.json";
  TailRequest r;
  r.population = 16;
  r.replicas = 2;
  r.firstSteps = 20;
  r.maxSteps = 40;
  TailState s = runTail(startTail(r), {});
  ASSERT_TRUE(s.finished());
  saveTailFile(path, s);
  TailPlanOptions o;
  o.resume = path.string();
  o.out = o.resume;
  EXPECT_EQ(refusal(o), path.string() + " is already finished");
  o.resumeFile = path.string();  // archipelago-mpi: a rank's slice, finished or not
  const TailPlan plan = planTail(o);
  EXPECT_TRUE(plan.state.finished());
  EXPECT_EQ(plan.threads, 0);
  EXPECT_EQ(plan.kernel, "");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace archipelago
