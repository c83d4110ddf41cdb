// The tail sampler as a job (core/tail/TailJob.hpp, issue 51): checkpoints on the job's clock, a checkpoint that cannot
// be written warned and retried while the sampler goes on, and a final write that rescues the work and says where;
// the tail command's session on one process and on sliced ranks (core/job/Ranks.hpp).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "core/tail/TailFile.hpp"
#include "core/tail/TailJob.hpp"

namespace archipelago {
namespace {

TailRequest smallRequest() {
  TailRequest r;
  r.population = 16;
  r.replicas = 2;
  r.firstSteps = 20;
  r.maxSteps = 200;
  return r;
}

TEST(TailJob, CheckpointsOnItsClockAndTheResumedFileFinishesAsTheWholeRun) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "archipelago_test_tail_job";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  TailJobOptions o;
  o.checkpoint = dir / "tail.json";
  o.checkpointSeconds = 0;  // at every chunk while unfinished
  o.run.untilLevel = 2;     // stop at a known point, as a test does (TailRunOptions)
  LastCheckpoint last;
  const TailState part = runTailJob(startTail(smallRequest()), o, last);
  ASSERT_FALSE(part.finished());
  EXPECT_EQ(last.path, o.checkpoint.string());
  ASSERT_TRUE(std::filesystem::exists(o.checkpoint));
  EXPECT_FALSE(loadTailFile(o.checkpoint).finished());
  // The checkpoint resumed by the job ends where the uninterrupted run ends, bit for bit.
  TailJobOptions rest;
  LastCheckpoint none;
  const TailState resumed = runTailJob(loadTailFile(o.checkpoint), rest, none);
  const TailState whole = runTail(startTail(smallRequest()), {});
  ASSERT_TRUE(resumed.finished());
  EXPECT_EQ(tailResult(resumed).levels.size(), tailResult(whole).levels.size());
  for (std::size_t i = 0; i < tailResult(whole).levels.size(); ++i)
    EXPECT_EQ(tailResult(resumed).levels[i].P, tailResult(whole).levels[i].P) << i;
  EXPECT_TRUE(none.path.empty());  // no checkpoint file: none written
  std::filesystem::remove_all(dir);
}

TEST(TailJob, AFailedCheckpointIsWarnedAndTheFinalWriteRescuesTheRun) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "archipelago_test_tail_job_folder";
  std::filesystem::create_directories(dir);
  TailJobOptions o;
  o.checkpoint = dir;  // a folder: every checkpoint fails
  o.checkpointSeconds = 0;
  int warnings = 0;
  o.warning = [&](const std::string& reason, double retry) {
    ++warnings;
    EXPECT_FALSE(reason.empty());
    EXPECT_EQ(retry, 0);
  };
  LastCheckpoint last{"resumed.json", 0};
  const TailState s = runTailJob(startTail(smallRequest()), o, last);
  ASSERT_TRUE(s.finished());
  EXPECT_GE(warnings, 1);
  EXPECT_EQ(last.path, "resumed.json");  // still where the work was
  const std::filesystem::path rescued =
      std::filesystem::temp_directory_path() / (dir.filename().string() + ".rescued-" + std::to_string(::getpid()) + ".json");
  try {
    saveTailOrSayWhere(dir, s, last, ": resume with --resume resumed.json");
    ADD_FAILURE() << "writing over a folder succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("the tail run (finished) was saved instead to " + rescued.string()),
              std::string::npos) << e.what();
  }
  ASSERT_TRUE(std::filesystem::exists(rescued));
  EXPECT_EQ(tailFileText(loadTailFile(rescued)), tailFileText(s));
  std::filesystem::remove(rescued);
  std::filesystem::remove_all(dir);
}

TEST(TailJob, TheComparisonCsvHasItsColumnsAndEmptyCellsForNumbersThatAreNot) {
  TailComparison c;
  c.bruteSteps = 1e6;
  c.alpha = 2.5;
  TailComparisonLevel l;
  l.t = 100;
  l.P = 0.25;
  c.levels.push_back(l);
  const std::string csv = tailComparisonCsv(c);
  EXPECT_NE(csv.find("# brute-force steps: 1000000\n# alpha: 2.5\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("t,P,P_error,reliable,brute_P,brute_error,brute_segments,z,tail_steps,brute_steps_same_error,"
                     "measured\n100,0.25,"),
            std::string::npos) << csv;
  EXPECT_NE(csv.find(",,"), std::string::npos) << "a NaN is an empty cell: " << csv;
}

/// One rank that slices its job as archipelago-mpi's ranks do (its slice file, then the merge), without MPI.
class OneSlicedRank final : public Ranks {
public:
  [[nodiscard]] int rank() const override { return 0; }
  [[nodiscard]] int size() const override { return 1; }
  [[nodiscard]] bool sliced() const override { return true; }
  void agree(bool ok, const std::string& message) override {
    if (!ok) throw std::runtime_error(message);
  }
  [[nodiscard]] bool all(bool mine) override { return mine; }
  [[nodiscard]] std::vector<std::string> gather(const std::string&) override { return {}; }
};

TailSessionOptions sessionIn(const std::filesystem::path& dir) {
  TailSessionOptions o;
  o.plan.request = smallRequest();
  o.plan.spec = [] {
    RunSpec s;
    s.threads = 1;
    return s;
  };
  o.plan.out = (dir / "tail.json").string();
  o.plan.csv = (dir / "tail.csv").string();
  o.plan.optionName = [](std::string_view role) { return "--" + std::string(role); };
  return o;
}

TEST(TailJob, TheSessionOnOneProcessAndOnSlicedRanksWritesTheWholeRunsFiles) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "archipelago_test_tail_session";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const TailState whole = runTail(startTail(smallRequest()), {});
  OneProcess one;
  const TailSessionOutcome a = runTailSession(sessionIn(dir), one);
  ASSERT_EQ(a.end, TailSessionOutcome::End::finished);
  const TailState written = loadTailFile(dir / "tail.json");
  EXPECT_EQ(tailCsvText(written, tailResult(written)), tailCsvText(whole, tailResult(whole)));
  EXPECT_TRUE(std::filesystem::exists(dir / "tail.csv"));
  EXPECT_EQ(a.report, tailLevelsText(whole, tailResult(whole)));
  EXPECT_EQ(a.report.rfind("# tail: K = 0.1, q = 16, N = 16, R = 2", 0), 0U) << a.report;
  std::filesystem::remove(dir / "tail.json");
  std::filesystem::remove(dir / "tail.csv");
  OneSlicedRank sliced;  // its slice file, then the merge of the one slice: the same tail file, no slice left
  const TailSessionOutcome b = runTailSession(sessionIn(dir), sliced);
  ASSERT_EQ(b.end, TailSessionOutcome::End::finished);
  const TailState merged = loadTailFile(dir / "tail.json");
  EXPECT_EQ(tailCsvText(merged, tailResult(merged)), tailCsvText(whole, tailResult(whole)));
  EXPECT_FALSE(std::filesystem::exists(dir / "tail.slice-0-of-1.json"));
  std::filesystem::remove_all(dir);
}

TEST(TailJob, AStoppedSessionSavesItsCheckpointAndPrintLevelsRunsNothing) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "archipelago_test_tail_session_stop";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::stop_source stop;
  stop.request_stop();
  OneProcess one;
  const TailSessionOutcome r = runTailSession(sessionIn(dir), one, stop.get_token());
  ASSERT_EQ(r.end, TailSessionOutcome::End::interrupted);
  EXPECT_EQ(r.checkpoint, (dir / "tail.json").string());
  EXPECT_FALSE(loadTailFile(dir / "tail.json").finished());
  EXPECT_FALSE(std::filesystem::exists(dir / "tail.csv"));
  TailSessionOptions levels = sessionIn(dir);
  levels.plan.printLevels = true;
  std::filesystem::remove(dir / "tail.json");
  const TailSessionOutcome l = runTailSession(levels, one);
  EXPECT_EQ(l.end, TailSessionOutcome::End::levelsOnly);
  EXPECT_EQ(l.state.levels, startTail(smallRequest()).levels);
  EXPECT_FALSE(std::filesystem::exists(dir / "tail.json"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace archipelago
