// Run files: exact round trip, atomic writes, and a clear error for every kind of bad file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "runfile/RunFile.hpp"

namespace archipelago {
namespace {

TrappingState sampleRun(std::uint64_t stopAfterBlocks = 0) {
  TrappingParameters p;
  p.q = 4;
  p.T = 5000;
  p.M = 20;
  p.subsets = 5;
  p.longestKept = 7;
  p.seed = 99;
  TrappingRunOptions o;
  if (stopAfterBlocks == 0) return runTrapping(startTrapping(p), o);
  o.maxChunkBlocks = stopAfterBlocks;
  std::stop_source stop;
  return runTrapping(startTrapping(p), o, [&](const TrappingState&, const TrappingProgress&) { stop.request_stop(); },
                     stop.get_token());
}

void expectEqualStates(const TrappingState& a, const TrappingState& b) {
  EXPECT_TRUE(a.params == b.params);
  EXPECT_TRUE(a.coefficients == b.coefficients);
  EXPECT_EQ(a.orbitBegin, b.orbitBegin);
  EXPECT_EQ(a.orbitEnd, b.orbitEnd);
  EXPECT_EQ(a.blocksDone, b.blocksDone);
  EXPECT_TRUE(a.orbits == b.orbits);
  EXPECT_TRUE(a.subsets == b.subsets);
  EXPECT_TRUE(a.longest == b.longest);
  EXPECT_EQ(a.elapsedSeconds, b.elapsedSeconds);
  EXPECT_EQ(a.kernel, b.kernel);
}

TEST(RunFile, RoundTripIsExact) {
  const TrappingState s = sampleRun();
  expectEqualStates(s, parseRunFile(runFileText(s)));
  const TrappingState partial = sampleRun(16);
  expectEqualStates(partial, parseRunFile(runFileText(partial)));
}

TEST(RunFile, ResumingFromAFileEqualsAnUninterruptedRun) {
  const TrappingState whole = sampleRun();
  const auto path = std::filesystem::temp_directory_path() / "archipelago-test-resume.json";
  saveRunFile(path, sampleRun(16));
  TrappingState resumed = runTrapping(loadRunFile(path), TrappingRunOptions{});
  std::filesystem::remove(path);
  EXPECT_TRUE(resumed.subsets == whole.subsets);
  EXPECT_TRUE(resumed.longest == whole.longest);
  EXPECT_TRUE(resumed.orbits == whole.orbits);
}

TEST(RunFile, SaveIsAtomicAndLeavesNoTemporaryFiles) {
  const auto dir = std::filesystem::temp_directory_path() / "archipelago-test-atomic";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const TrappingState s = sampleRun();
  saveRunFile(dir / "run.json", s);
  saveRunFile(dir / "run.json", s);  // overwrite
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1);
  expectEqualStates(s, loadRunFile(dir / "run.json"));
  EXPECT_THROW(saveRunFile(dir / "no-such-folder" / "run.json", s), std::runtime_error);
  std::filesystem::remove_all(dir);
}

void expectRejected(const std::string& text, const std::string& mention) {
  try {
    (void)parseRunFile(text);
    ADD_FAILURE() << "accepted: " << mention;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "errors are one line";
  }
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(RunFile, BadFilesGiveClearErrors) {
  const std::string good = runFileText(sampleRun());
  expectRejected("", "corrupt or truncated");
  expectRejected(good.substr(0, good.size() / 2), "corrupt or truncated");
  expectRejected("[1, 2, 3]", "not an Archipelago run file");
  expectRejected(R"({"format": "something-else"})", "not an Archipelago run file");
  expectRejected(replaced(good, "\"version\": 1", "\"version\": 99"), "version 99 is not supported");
  expectRejected(replaced(good, "\"T\": 5000", "\"T\": -5"), "T = -5 must be a whole number");  // one codec: run spec
  expectRejected(replaced(good, "\"K\": 0.1", "\"K\": 0.9"), "invalid parameters: xmin");
  expectRejected(replaced(good, "\"subsets\": 5", "\"subsets\": 4"), "one histogram per subset");
  expectRejected(replaced(good, "\"A\": ", "\"A\": 1"), "coefficients (A, B, C, m) differ");
  expectRejected(replaced(good, "\"blocksDone\": 5000", "\"blocksDone\": 4999"), "block count differs");
  expectRejected(replaced(good, "\"orbits\"", "\"orbitz\""), "missing field 'orbits'");
}

TEST(RunFile, UnreadableFileNamesThePath) {
  try {
    (void)loadRunFile("/nonexistent/archipelago/run.json");
    ADD_FAILURE();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/archipelago/run.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace archipelago
