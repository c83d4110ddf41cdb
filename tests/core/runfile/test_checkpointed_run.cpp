// core/runfile/CheckpointedRun: the one checkpoint loop of `run`, the K scan and the report.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "core/runfile/CheckpointedRun.hpp"
#include "core/runfile/RunFile.hpp"

namespace archipelago {
namespace {

namespace fs = std::filesystem;

TrappingParameters smallRun() {
  TrappingParameters p;
  p.q = 4;
  p.M = 8;
  p.subsets = 4;
  p.T = 20'000;
  return p;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("checkpointed-run-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

TEST(CheckpointedRun, WritesCheckpointsAndFinishesAsAPlainRun) {
  const fs::path file = scratch("ck.json");
  CheckpointedRunOptions o;
  o.run.maxChunkBlocks = 1000;  // 20 chunks
  o.checkpoint = file;
  o.checkpointSeconds = 0;      // a checkpoint at every chunk but the last
  LastCheckpoint last;
  int chunks = 0;
  std::uint64_t lastUnfinished = 0;  // chunks are adaptive (at most 1000 blocks): note where each ended
  const TrappingState s = runWithCheckpoints(startTrapping(smallRun()), o, last,
                                             [&](const TrappingState& st, const TrappingProgress&) {
                                               ++chunks;
                                               if (!st.finished()) lastUnfinished = st.blocksDone;
                                             });
  EXPECT_TRUE(s.finished());
  EXPECT_GE(chunks, 20);
  EXPECT_EQ(last.path, file.string());
  EXPECT_GT(lastUnfinished, 0u);
  EXPECT_EQ(last.blocks, lastUnfinished);  // the last chunk before the end: none is written once finished
  EXPECT_EQ(loadRunFile(file).blocksDone, lastUnfinished);
  // The same result as the run without checkpoints (checkpoints do not change the computation).
  const TrappingState plain = runTrapping(startTrapping(smallRun()), TrappingRunOptions{});
  EXPECT_EQ(s.subsets, plain.subsets);
  EXPECT_EQ(s.orbits, plain.orbits);
  EXPECT_EQ(s.longest.items(), plain.longest.items());
  fs::remove_all(file.parent_path());
}

TEST(CheckpointedRun, StopsWhenAskedAndTheStopTokenToo) {
  CheckpointedRunOptions o;
  o.run.maxChunkBlocks = 1000;
  o.checkpoint = scratch("never.json");
  o.checkpointSeconds = 1e9;
  int polls = 0;
  o.stopRequested = [&] { return ++polls >= 3; };
  LastCheckpoint last;
  TrappingState s = runWithCheckpoints(startTrapping(smallRun()), o, last);
  EXPECT_FALSE(s.finished());
  EXPECT_GT(s.blocksDone, 0u);
  EXPECT_LE(s.blocksDone, 3000u);  // stopped at the third chunk (each at most 1000 blocks)
  EXPECT_TRUE(last.path.empty());      // no checkpoint was due
  o.stopRequested = {};
  std::stop_source stop;
  stop.request_stop();
  const std::uint64_t before = s.blocksDone;
  s = runWithCheckpoints(std::move(s), o, last, {}, stop.get_token());
  EXPECT_LE(s.blocksDone, before + 1000);
  fs::remove_all(o.checkpoint.parent_path());
}

TEST(CheckpointedRun, AFailedCheckpointWarnsAndTheRunGoesOn) {
  const fs::path dir = scratch("a-folder");
  fs::create_directories(dir);  // a folder where the checkpoint should go: every write fails
  CheckpointedRunOptions o;
  o.run.maxChunkBlocks = 5000;
  o.checkpoint = dir;
  o.checkpointSeconds = 0;
  int warnings = 0;
  std::string reason;
  o.warning = [&](const std::string& r, double retry) {
    ++warnings;
    reason = r;
    EXPECT_EQ(retry, 0);
  };
  LastCheckpoint last{"resumed.json", 7};
  const TrappingState s = runWithCheckpoints(startTrapping(smallRun()), o, last);
  EXPECT_TRUE(s.finished());
  EXPECT_GE(warnings, 3);
  EXPECT_FALSE(reason.empty());
  EXPECT_EQ(last.path, "resumed.json");  // still where the work was
  // The final write fails: the run is not lost (issue #23: "no checkpoint was written" once lost it), it goes to
  // the temporary folder and the error says where.
  try {
    saveRunFileOrSayWhere(dir, s, last, ": resume with --resume resumed.json");
    ADD_FAILURE() << "writing over a folder succeeded";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    const fs::path rescued = fs::temp_directory_path() / (dir.filename().string() + ".rescued-" +
                                                          std::to_string(::getpid()) + ".json");
    EXPECT_NE(what.find("the run (20000 of 20000 blocks) was saved instead to " + rescued.string()), std::string::npos)
        << what;
    ASSERT_TRUE(fs::exists(rescued));
    EXPECT_TRUE(loadRunFile(rescued).subsets == s.subsets);
    fs::remove(rescued);
  }
  // Nowhere to rescue it either: the error says where the last good copy is, and how to resume it.
  const std::string tmpdir = std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "";
  const std::string home = std::getenv("HOME") ? std::getenv("HOME") : "";
  ::setenv("TMPDIR", "/nonexistent-archipelago-tmp", 1);
  ::setenv("HOME", "/nonexistent-archipelago-home", 1);
  try {
    saveRunFileOrSayWhere(dir, s, last, ": resume with --resume resumed.json");
    ADD_FAILURE() << "writing over a folder succeeded";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the last checkpoint (7 of 20000 blocks) is in resumed.json: resume with --resume resumed.json"),
              std::string::npos) << what;
  }
  try {
    saveRunFileOrSayWhere(dir, s, LastCheckpoint{});
    ADD_FAILURE() << "writing over a folder succeeded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no checkpoint was written and the run could not be saved in "
                                         "/nonexistent-archipelago-tmp, /nonexistent-archipelago-home"),
              std::string::npos) << e.what();
  }
  if (tmpdir.empty()) ::unsetenv("TMPDIR");
  else ::setenv("TMPDIR", tmpdir.c_str(), 1);
  if (home.empty()) ::unsetenv("HOME");
  else ::setenv("HOME", home.c_str(), 1);
  fs::remove_all(dir.parent_path());
}

// runOrResumeFile()'s plan, alone: start without a file, resume an unfinished run of the parameters, reuse a
// finished one, and refuse a run of others (whatever its progress) with the one wording.
TEST(RunFileAction, StartsResumesReusesOrRefuses) {
  const TrappingParameters wanted = smallRun();
  const fs::path file = "runs/a.json";
  EXPECT_EQ(runFileAction(file, nullptr, wanted), RunFileAction::start);
  const TrappingState fresh = startTrapping(wanted);
  ASSERT_FALSE(fresh.finished());
  EXPECT_EQ(runFileAction(file, &fresh, wanted), RunFileAction::resume);
  const TrappingState done = runTrapping(fresh, TrappingRunOptions{});
  ASSERT_TRUE(done.finished());
  EXPECT_EQ(runFileAction(file, &done, wanted), RunFileAction::reuse);
  TrappingParameters other = wanted;
  other.seed += 1;
  for (const TrappingState* held : {&fresh, &done}) {
    try {
      (void)runFileAction(file, held, other);
      ADD_FAILURE() << "a run of other parameters was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_STREQ(e.what(), "runs/a.json holds a run of other parameters");
    }
  }
}

}  // namespace
}  // namespace archipelago
