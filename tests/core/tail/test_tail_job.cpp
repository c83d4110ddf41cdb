// The tail sampler as a job (core/tail/TailJob.hpp, issue 51): checkpoints on the job's clock, a checkpoint that cannot
// be written warned and retried while the sampler goes on, and a final write that rescues the work and says where.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>

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

}  // namespace
}  // namespace archipelago
