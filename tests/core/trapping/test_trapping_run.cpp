// The trapping engine: exactness and independence of threads, chunks, interruptions and orbit ranges.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <stop_token>

#include "core/run/TrappingRun.hpp"

namespace archipelago {
namespace {

TrappingParameters smallRun() {
  TrappingParameters p;  // the paper's K = 0.1 box, short
  p.q = 16;
  p.T = 20000;
  p.M = 37;  // not a multiple of the kernel's lanes: exercises ragged groups
  p.subsets = 4;
  p.longestKept = 20;
  p.seed = 12345;
  return p;
}

TrappingState runWith(const TrappingParameters& p, int threads, std::uint64_t maxChunk) {
  TrappingRunOptions o;
  o.threads = threads;
  o.maxChunkBlocks = maxChunk;
  return runTrapping(startTrapping(p), o);
}

void expectSameResult(const TrappingState& a, const TrappingState& b) {
  ASSERT_EQ(a.subsets.size(), b.subsets.size());
  for (std::size_t i = 0; i < a.subsets.size(); ++i) EXPECT_TRUE(a.subsets[i] == b.subsets[i]) << "subset " << i;
  EXPECT_TRUE(a.longest == b.longest);
  EXPECT_TRUE(a.orbits == b.orbits);
  EXPECT_EQ(a.blocksDone, b.blocksDone);
}

TEST(TrappingRun, ResultDoesNotDependOnThreadsOrChunks) {
  const TrappingParameters p = smallRun();
  const TrappingState reference = runWith(p, 1, 0);
  EXPECT_TRUE(reference.finished());
  EXPECT_GT(reference.total().segments(), 1000u);
  expectSameResult(reference, runWith(p, 2, 0));
  expectSameResult(reference, runWith(p, 2, 1));
  expectSameResult(reference, runWith(p, 1, 777));
}

// The reference definition: one orbit at a time through advanceOneBlock, segments collected in a list.
TEST(TrappingRun, InterleavedScalarKernelMatchesOneBlockDefinition) {
  const TrappingParameters p = smallRun();
  const TrappingState engine = runWith(p, 2, 0);
  const KernelSettings k{computeCoefficients(p.map), randomizingThreshold(p.Xr), p.q, p.seed};
  SegmentSink sink(p.subsets, p.longestKept);
  for (std::uint64_t orbit = 0; orbit < p.M; ++orbit) {
    OrbitState s;
    for (std::uint64_t b = 0; b < p.T; ++b) advanceOneBlock(k, orbit, s, &sink);
    EXPECT_EQ(s, engine.orbits[orbit]) << "orbit " << orbit;
  }
  for (std::size_t i = 0; i < p.subsets; ++i) EXPECT_TRUE(sink.subsets()[i] == engine.subsets[i]);
  EXPECT_TRUE(sink.longest() == engine.longest);
}

TEST(TrappingRun, StopAndResumeEqualsUninterruptedRun) {
  const TrappingParameters p = smallRun();
  const TrappingState reference = runWith(p, 2, 0);
  std::stop_source stopper;
  int chunks = 0;
  TrappingRunOptions o;
  o.maxChunkBlocks = 1000;
  TrappingState partial = runTrapping(
      startTrapping(p), o, [&](const TrappingState&, const TrappingProgress&) {
        if (++chunks == 3) stopper.request_stop();
      },
      stopper.get_token());
  EXPECT_EQ(chunks, 3);
  EXPECT_GT(partial.blocksDone, 0u);
  EXPECT_FALSE(partial.finished());
  o.maxChunkBlocks = 0;
  expectSameResult(reference, runTrapping(std::move(partial), o));
}

TEST(TrappingRun, OrbitRangesRunAloneAndMergeExactly) {
  const TrappingParameters p = smallRun();
  const TrappingState whole = runWith(p, 2, 0);
  TrappingRunOptions o;
  const TrappingState low = runTrapping(startTrapping(p, 0, 10), o);
  const TrappingState mid = runTrapping(startTrapping(p, 10, 11), o);
  const TrappingState high = runTrapping(startTrapping(p, 11, p.M), o);
  expectSameResult(whole, mergeTrapping(mergeTrapping(high, mid), low));
  expectSameResult(whole, mergeTrapping(low, mergeTrapping(mid, high)));
  EXPECT_THROW((void)mergeTrapping(low, high), std::invalid_argument);  // not adjacent
}

// Issue 35: a range beyond M was cut to M silently by core (the CLI and Python refused it with their own words);
// core's one rule refuses it, with one message.
TEST(TrappingRun, OrbitRangeBeyondMIsRefusedNotCut) {
  const TrappingParameters p = smallRun();
  EXPECT_EQ(orbitRangeError(p.M, 0, p.M), std::nullopt);
  EXPECT_EQ(orbitRangeError(64, 0, 65), "orbits [0, 65) must satisfy begin < end ≤ M = 64");
  EXPECT_EQ(orbitRangeError(64, 3, 3), "orbits [3, 3) must satisfy begin < end ≤ M = 64");
  EXPECT_THROW((void)startTrapping(p, 0, p.M + 1), std::invalid_argument);
  EXPECT_THROW((void)startTrapping(p, 5, 2), std::invalid_argument);
  EXPECT_EQ(startTrapping(p).orbitEnd, p.M);  // kAllOrbits: all of them
}

TEST(TrappingRun, LongestSegmentsReplayBitForBit) {
  const TrappingParameters p = smallRun();
  const TrappingState run = runWith(p, 2, 0);
  ASSERT_EQ(run.longest.items().size(), p.longestKept);
  const FixedPointMap map(p.map);
  for (const SegmentRecord& rec : run.longest.items()) {
    // Replay, and independently iterate the orbit from its start with N⁻¹: the points must agree exactly.
    UnitState independent = rec.start.z;
    std::uint64_t mismatches = 0, points = 0;
    const std::uint64_t length = replaySegment(p, rec, [&](std::uint64_t step, const UnitState& z) {
      ++points;
      if (step > 0 && (step - 1) % p.q == 0 && independent.X <= randomizingThreshold(p.Xr)) {
        mismatches += (step - 1 != (rec.length - 1) * p.q);  // a draw is only allowed in the last block
        independent = z;  // the randomized last block: adopt the replayed state
        return;
      }
      if (step > 0) map.backward(independent);
      mismatches += !(z == independent);
    });
    EXPECT_EQ(length, rec.length);
    EXPECT_EQ(points, rec.length * p.q + 1);
    EXPECT_EQ(mismatches, 0u) << "orbit " << rec.orbit << " block " << rec.start.block;
  }
  // Ranked: longest first.
  for (std::size_t i = 1; i < run.longest.items().size(); ++i)
    EXPECT_GE(run.longest.items()[i - 1].length, run.longest.items()[i].length);
}

TEST(TrappingRun, FirstSegmentIsNotRecordedAndPartialSegmentsAreDropped) {
  TrappingParameters p = smallRun();
  p.M = 8;
  p.subsets = 1;
  const TrappingState run = runWith(p, 1, 0);
  // Every block belongs to exactly one of: the unrecorded first segment (block 0), a recorded segment, or the
  // open segment at the end.
  std::uint64_t open = 0;
  for (const auto& o : run.orbits) open += o.length;
  EXPECT_EQ(run.total().totalLength() + p.M /* the first block of each orbit */ + open, p.M * p.T);
}

TEST(TrappingRun, InvalidParametersAreRejectedWithTheirRule) {
  TrappingParameters p = smallRun();
  p.q = 0;
  EXPECT_THROW((void)startTrapping(p), std::invalid_argument);
  p = smallRun();
  p.subsets = 100;
  try {
    (void)startTrapping(p);
    ADD_FAILURE();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("subsets = 100 must be ≤ M = 37"), std::string::npos);
  }
  p = smallRun();
  p.Xr = 1.5;
  EXPECT_TRUE(validationError(p).has_value());
  p = smallRun();
  p.map.xmin = 0;
  EXPECT_NE(validationError(p)->find("xmin"), std::string::npos);
}

TEST(TrappingHistogram, BinsAreContiguousExactThenThirtyPerDecade) {
  for (int i = 1; i + 1 < TrappingHistogram::kBins; ++i) {
    ASSERT_EQ(TrappingHistogram::binUpper(i), TrappingHistogram::binLower(i + 1));
    ASSERT_LT(TrappingHistogram::binLower(i), TrappingHistogram::binUpper(i));
  }
  for (std::uint64_t t = 1; t <= 50; ++t) EXPECT_EQ(TrappingHistogram::binOf(t), static_cast<int>(t));
  EXPECT_EQ(TrappingHistogram::binOf(51), 51);  // ⌈10^(51/30)⌉ = 51
  EXPECT_EQ(TrappingHistogram::binLower(60), 100u);
  EXPECT_EQ(TrappingHistogram::binLower(90), 1000u);
  EXPECT_EQ(TrappingHistogram::binOf(999), 89);
  EXPECT_EQ(TrappingHistogram::binOf(1000), 90);
  EXPECT_EQ(TrappingHistogram::binOf(UINT64_MAX), TrappingHistogram::kBins - 1);
  // The paper's b(t) = ⌊30 log10 t⌋ away from edges.
  for (std::uint64_t t : {77ull, 1234ull, 98765ull, 31415926ull})
    EXPECT_EQ(TrappingHistogram::binOf(t), static_cast<int>(std::floor(30 * std::log10(static_cast<double>(t)))));
  for (std::uint64_t t = 51; t < 200000; t = t * 11 / 10 + 1) {
    const int i = TrappingHistogram::binOf(t);
    EXPECT_LE(TrappingHistogram::binLower(i), t);
    EXPECT_GT(TrappingHistogram::binUpper(i), t);
  }
}

TEST(LongestSegments, KeptSetDoesNotDependOnInsertionOrder) {
  std::vector<SegmentRecord> all;
  for (std::uint64_t i = 0; i < 200; ++i) all.push_back({i % 7, (i * 37) % 23 + 1, {{i, i}, i, 0}});
  LongestSegments forward(10), backward(10), halves(10), other(10);
  for (const auto& r : all) forward.insert(r);
  for (auto it = all.rbegin(); it != all.rend(); ++it) backward.insert(*it);
  for (std::size_t i = 0; i < all.size(); ++i) (i % 2 ? halves : other).insert(all[i]);
  halves.merge(other);
  EXPECT_TRUE(forward == backward);
  EXPECT_TRUE(forward == halves);
  EXPECT_EQ(forward.items().size(), 10u);
  EXPECT_EQ(forward.items().front().length, 23u);
}


// Issue 13, finding 11: every violated rule of a run's parameters is reported at once, each naming its field and
// stating the range of parameterRules(); a broken map does not hide a broken integer.
TEST(TrappingRun, EveryViolatedParameterRuleIsReported) {
  TrappingParameters p;
  p.map.xmin = -0.2;  // > −√0.1
  p.Xr = 2;
  p.q = 0;
  p.M = 0;
  const std::vector<ParameterError> errors = validationErrors(p);
  std::vector<std::string> first;
  for (const ParameterError& e : errors) first.push_back(e.fields.front());
  EXPECT_EQ(first, (std::vector<std::string>{"xmin", "Xr", "q", "M"}));
  EXPECT_EQ(errors[3].message, "M = 0 must lie in [1, 2³²] (and the memory they need)");
  EXPECT_EQ(errors[1].message.substr(0, 9), "Xr = 2 mu");
  EXPECT_EQ(validationError(p), errors.front().message);
  p = TrappingParameters{};
  p.q = 4;
  p.T = std::uint64_t{1} << 61;
  const std::vector<ParameterError> steps = validationErrors(p);
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(steps[0].fields, (std::vector<std::string>{"T", "q"}));
  EXPECT_NE(steps[0].message.find("≤ 2⁶²"), std::string::npos) << steps[0].message;
}
}  // namespace
// ⌊Xr·2^52⌋ for a valid Xr, and defined (no undefined float-to-integer conversion) for every other double.
TEST(RandomizingThreshold, IsFloorOfXrTimesTheUnitAndDefinedForEveryDouble) {
  EXPECT_EQ(randomizingThreshold(0.02), 90071992547409u);  // python3 -c "print(int(0.02*2**52))"
  EXPECT_EQ(randomizingThreshold(0.0), 0u);
  const std::uint64_t unit = 4503599627370496u;  // 2^52
  for (double Xr : {-1.0, -1e308, -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()})
    EXPECT_EQ(randomizingThreshold(Xr), 0u) << Xr;
  for (double Xr : {1.0, 5.0, 1e308, std::numeric_limits<double>::infinity()})
    EXPECT_EQ(randomizingThreshold(Xr), unit) << Xr;
}

}  // namespace archipelago
