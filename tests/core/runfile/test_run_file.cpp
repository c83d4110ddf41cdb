// Run files: exact round trip, atomic writes, and a clear error for every kind of bad file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "core/runfile/RunFile.hpp"

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

// Content errors are checked with allowModified: an edited file is first of all a modified one (its checksum
// says so), and these tests are about what the whole-file validation finds behind that.
void expectRejected(const std::string& text, const std::string& mention) {
  try {
    (void)parseRunFile(text, {.allowModified = true, .allowModifiedName = {}});
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
  expectRejected(replaced(good, "\"version\": 2", "\"version\": 99"), "version 99 is not supported");
  expectRejected(replaced(good, "\"T\": 5000", "\"T\": -5"), "T = -5 must be a whole number");  // one codec: run spec
  expectRejected(replaced(good, "\"K\": 0.1", "\"K\": 0.9"), "invalid parameters: xmin");
  expectRejected(replaced(good, "\"subsets\": 5", "\"subsets\": 4"), "one histogram per subset");
  expectRejected(replaced(good, "\"A\": ", "\"A\": 1"), "coefficients (A, B, C, m) differ");
  expectRejected(replaced(good, "\"blocksDone\": 5000", "\"blocksDone\": 4999"), "block count differs");
  expectRejected(replaced(good, "\"orbits\"", "\"orbitz\""), "the run file has no 'orbits'");
}

// --- issue 12, finding 4: run files that were accepted with wrong results ----------------------------------

using nlohmann::json;

/// The sample run's JSON with an edit applied (the checksum is left as it was).
std::string edited(const std::function<void(json&)>& edit) {
  json j = json::parse(runFileText(sampleRun()));
  edit(j);
  return j.dump(1);
}

TEST(RunFile, AnyEditIsDetectedByTheChecksum) {
  const std::string good = runFileText(sampleRun());
  EXPECT_NO_THROW((void)parseRunFile(good));
  // Change one digit of a count deep inside the histograms: a plausible file, silently wrong before.
  json j = json::parse(good);
  j["subsets"][0][0][1] = j["subsets"][0][0][1].get<std::uint64_t>() + 1;
  const std::string text = j.dump(1);
  try {
    (void)parseRunFile(text);
    ADD_FAILURE() << "an edited file was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("modified after it was written"), std::string::npos) << e.what();
  }
  // Forensic reading: allowed on request, still validated (this edit breaks the bin's length sum).
  EXPECT_THROW((void)parseRunFile(text, {.allowModified = true, .allowModifiedName = {}}), std::runtime_error);
  // Re-indenting is not an edit of the content.
  EXPECT_NO_THROW((void)parseRunFile(json::parse(good).dump(4)));
}

// Issue #23, finding 4: deleting the checksum and declaring "version": 1 bypassed it, and `run --resume`
// then laundered the edit into a version-2 file with a fresh, valid checksum.
TEST(RunFile, VersionDowngrade_Issue23_IsRefusedWithoutOptIn) {
  json j = json::parse(runFileText(sampleRun()));
  j.erase("checksum");
  j["version"] = 1;
  j["parameters"]["seed"] = 100;  // an edit a version-1 file cannot reveal
  const std::string text = j.dump(1);
  try {
    (void)parseRunFile(text, {.allowModifiedName = "--allow-modified"});
    ADD_FAILURE() << "a version-1 file was read without --allow-modified";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("version 1 has no checksum"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("; --allow-modified reads it anyway"), std::string::npos) << e.what();
  }
  // A front end without the setting (the GUI, a resume) is told of none (issue 51: the CLI's flag reached them all).
  try {
    (void)parseRunFile(text);
    ADD_FAILURE() << "a version-1 file was read without allowModified";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()).find("anyway"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
  }
  // Inspection on request: read, validated, and marked unverified.
  const TrappingState read = parseRunFile(text, {.allowModified = true, .allowModifiedName = {}});
  EXPECT_TRUE(read.unverified);
  EXPECT_EQ(read.params.seed, 100u);
  EXPECT_FALSE(parseRunFile(runFileText(sampleRun())).unverified);
}

TEST(RunFile, UnverifiedState_Issue23_IsNeverWrittenAsAVerifiedFile) {
  json j = json::parse(runFileText(sampleRun(16)));
  j["elapsedSeconds"] = 1e9;  // an edit the consistency checks cannot see: only the checksum can
  TrappingState s = parseRunFile(j.dump(1), {.allowModified = true, .allowModifiedName = {}});
  ASSERT_TRUE(s.unverified);
  EXPECT_THROW((void)runFileText(s), std::runtime_error);
  const auto path = std::filesystem::temp_directory_path() / "archipelago-test-launder.json";
  EXPECT_THROW(saveRunFile(path, s), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(path));
  // Resuming it keeps the mark (the run goes on from an edited state), and so does a merge with a verified part.
  TrappingRunOptions o;
  o.untilBlocks = 32;
  const TrappingState resumed = runTrapping(std::move(s), o);
  EXPECT_TRUE(resumed.unverified);
  EXPECT_THROW((void)runFileText(resumed), std::runtime_error);
}

TEST(RunFile, DeepJson_Issue23_IsACleanError) {
  json j = json::parse(runFileText(sampleRun()));
  std::string text = j.dump(1);
  text.insert(1, "\"zzz\": " + std::string(60000, '[') + std::string(60000, ']') + ",");
  try {
    (void)parseRunFile(text);
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("nested deeper than"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)parseRunFile(text, {.allowModified = true, .allowModifiedName = {}}), std::runtime_error);
}

TEST(RunFile, CountsWhoseSumPassesTwoToTheSixtyFourAreRejected) {
  // 2^63 segments of length 1 in two subsets: Σ counts wraps to 0 in 64 bits (gave Σ t f_t = 0.94).
  expectRejected(edited([](json& j) {
                   j["subsets"][0] = json::array({json::array({1, 1ull << 63, 1ull << 63})});
                   j["subsets"][1] = json::array({json::array({1, 1ull << 63, 1ull << 63})});
                 }),
                 "add up to more blocks than its orbits have done");
}

TEST(RunFile, ExactBinWithInconsistentLengthSumIsRejected) {
  expectRejected(edited([](json& j) { j["subsets"][0] = json::array({json::array({3, 2, 7})}); }),  // 2 × 3 ≠ 7
                 "do not fit the bin");
}

TEST(RunFile, DuplicateBinsOrKeysAreRejected) {
  expectRejected(edited([](json& j) {
                   j["subsets"][0] = json::array({json::array({3, 1, 3}), json::array({3, 2, 6})});
                 }),
                 "listed once each");
  std::string text = runFileText(sampleRun());
  text.insert(text.find("\"blocksDone\""), "\"blocksDone\": 0, ");
  expectRejected(text, "appears twice");
}

TEST(RunFile, LongestSegmentOutsideTheBlocksDoneIsRejected) {
  // Length 2^63 (shown as 0 steps: length × q overflowed), start block 0 (never recorded), start past T.
  expectRejected(edited([](json& j) { j["longest"][0]["length"] = 1ull << 63; }), "longest segment 0");
  expectRejected(edited([](json& j) { j["longest"][0]["start"]["block"] = 0; }), "inside the blocks done");
  expectRejected(edited([](json& j) { j["longest"][0]["start"]["block"] = 6000; }), "inside the blocks done");
  expectRejected(edited([](json& j) { j["longest"][1]["length"] = j["longest"][0]["length"].get<std::uint64_t>() + 1; }),
                 "not ranked");
}

TEST(RunFile, OpenSegmentLongerThanTheBlocksDoneIsRejected) {
  expectRejected(edited([](json& j) { j["orbits"][0][4] = 6000; }), "does not end at blocksDone");
  expectRejected(edited([](json& j) { j["orbits"][0][3] = 6000; }), "more random draws than blocks");
}

TEST(RunFile, NoBlocksDoneWithNonEmptyHistogramsIsRejected) {
  // blocksDone = 0 with the histograms of a finished run: resuming it counted every segment twice.
  expectRejected(edited([](json& j) {
                   j["blocksDone"] = 0;
                   j["finished"] = false;
                   for (auto& o : j["orbits"]) o[2] = o[3] = o[4] = o[7] = o[8] = 0;  // orbits at their start
                 }),
                 "segments longer than the 0 blocks done");
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
