// Replayed segments in buffers, where they spent their time, their chains (core/periodic/SegmentAnalysis.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/periodic/SegmentAnalysis.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago {
namespace {

/// A short K = 0.1 run whose longest segments are a few thousand steps long.
const TrappingState& shortRun() {
  static const TrappingState state = [] {
    TrappingParameters p;
    p.M = 16;
    p.T = 20000;
    p.longestKept = 10;
    TrappingRunOptions o;
    o.threads = 1;
    return runTrapping(startTrapping(p), o);
  }();
  return state;
}

struct Visit {
  std::uint64_t step;
  UnitState z;
};

std::vector<Visit> reference(const TrappingState& state, const SegmentRecord& record) {
  std::vector<Visit> visits;
  replaySegment(state.params, record, [&](std::uint64_t step, const UnitState& z) { visits.push_back({step, z}); });
  return visits;
}

TEST(SegmentAnalysis, TraceWithStrideOneIsBitIdenticalToReplaySegment) {
  const TrappingState& state = shortRun();
  ASSERT_GE(state.longest.items().size(), 3u);
  for (std::size_t rank : {0u, 2u}) {
    const SegmentRecord& record = state.longest.items()[rank];
    const std::vector<Visit> visits = reference(state, record);
    const auto trace = traceSegment(state.params, record, visits.size());
    ASSERT_TRUE(trace.has_value());
    EXPECT_EQ(trace->stride, 1u);
    EXPECT_EQ(trace->blocks, record.length);
    EXPECT_EQ(trace->steps, record.length * state.params.q);
    ASSERT_EQ(trace->states.size(), visits.size());
    for (std::size_t i = 0; i < visits.size(); ++i) {
      ASSERT_EQ(trace->stepAt(i), visits[i].step);
      ASSERT_EQ(trace->states[i], visits[i].z) << "step " << i;
    }
    const FixedPointMap map(state.params.map);
    EXPECT_EQ(trace->points[5].x, map.toPhysical(visits[5].z).x);
    EXPECT_EQ(trace->points[5].y, map.toPhysical(visits[5].z).y);
  }
}

TEST(SegmentAnalysis, StridedTraceKeepsExactStatesAndTheLastStep) {
  const TrappingState& state = shortRun();
  const SegmentRecord& record = state.longest.items().front();
  const std::vector<Visit> visits = reference(state, record);
  const std::uint64_t maxPoints = 101;
  const auto trace = traceSegment(state.params, record, maxPoints);
  ASSERT_TRUE(trace.has_value());
  EXPECT_GT(trace->stride, 1u);
  EXPECT_LE(trace->states.size(), maxPoints);
  EXPECT_GE(trace->states.size(), maxPoints / 2);
  for (std::size_t i = 0; i < trace->states.size(); ++i) {
    const std::uint64_t step = trace->stepAt(i);
    ASSERT_LT(step, visits.size());
    ASSERT_EQ(trace->states[i], visits[step].z) << "index " << i << ", step " << step;
  }
  EXPECT_EQ(trace->stepAt(trace->states.size() - 1), visits.back().step);
  EXPECT_EQ(trace->indexNear(0), 0u);
  EXPECT_EQ(trace->indexNear(trace->stride), 1u);
  EXPECT_EQ(trace->indexNear(UINT64_MAX), trace->states.size() - 1);
  EXPECT_THROW((void)traceSegment(state.params, record, 2), std::invalid_argument);
}

TEST(SegmentAnalysis, StoppedReplaysReturnNothing) {
  const TrappingState& state = shortRun();
  std::stop_source stop;
  stop.request_stop();
  const SegmentRecord& record = state.longest.items().front();
  EXPECT_FALSE(traceSegment(state.params, record, 1000, stop.get_token()).has_value());
  EXPECT_FALSE(segmentPrefix(state.params, record, 1000, stop.get_token()).has_value());
  EXPECT_FALSE(identifySegmentChain(state.params, record, 1000, {}, stop.get_token()).has_value());
}

TEST(SegmentAnalysis, PrefixIsTheFirstConsecutivePoints) {
  const TrappingState& state = shortRun();
  const SegmentRecord& record = state.longest.items().front();
  const std::vector<Visit> visits = reference(state, record);
  const FixedPointMap map(state.params.map);
  const auto prefix = segmentPrefix(state.params, record, 100);
  ASSERT_TRUE(prefix.has_value());
  ASSERT_EQ(prefix->size(), 100u);
  for (std::size_t i = 0; i < prefix->size(); ++i) {
    ASSERT_EQ((*prefix)[i].x, map.toPhysical(visits[i].z).x);
    ASSERT_EQ((*prefix)[i].y, map.toPhysical(visits[i].z).y);
  }
  const auto all = segmentPrefix(state.params, record, UINT64_MAX);
  ASSERT_TRUE(all.has_value());
  EXPECT_EQ(all->size(), visits.size());
}

TEST(SegmentAnalysis, ChainOfASegmentIsTheChainOfItsPrefix) {
  const TrappingState& state = shortRun();
  const SegmentRecord& record = state.longest.items().front();
  IslandChainOptions options;
  options.findCentreOrbit = false;
  const auto chain = identifySegmentChain(state.params, record, 4000, options);
  ASSERT_TRUE(chain.has_value());
  const auto prefix = segmentPrefix(state.params, record, 4000);
  const IslandChain direct = identifyIslandChain(state.params.map.K, *prefix, options);
  EXPECT_EQ(chain->chain.period, direct.period);
  EXPECT_EQ(chain->chain.hierarchy, direct.hierarchy);
  EXPECT_EQ(chain->chain.windingTurns, direct.windingTurns);
  const int level = direct.hierarchy.size() > 1 ? direct.hierarchy[1] : 1;
  const SegmentRegion island = islandRegion(*prefix, level);
  EXPECT_EQ(chain->island.x0, island.x0);
  EXPECT_EQ(chain->island.y1, island.y1);
  EXPECT_THROW((void)identifySegmentChain(state.params, record, 10, options), std::invalid_argument);
}

TEST(SegmentAnalysis, DwellRegionIgnoresShortExcursions) {
  // 950 points spread over [0, 1] × [2, 3] and 50 far away on a line: the 90 % region is the square.
  std::vector<PhysicalPoint> points;
  for (int i = 0; i < 950; ++i) points.push_back({(i % 31) / 30.0L, 2 + (i % 29) / 28.0L});
  for (int i = 0; i < 50; ++i) points.push_back({5 + i * 0.1L, -4});
  const SegmentRegion r = dwellRegion(points, 0.9, 64, 0);
  EXPECT_GE(r.fraction, 0.9);
  EXPECT_LE(r.fraction, 0.951);
  EXPECT_GE(r.x0, -1e-12L);
  EXPECT_LT(r.x1, 1.2L);
  EXPECT_GT(r.y0, 1.9L);
  EXPECT_LE(r.y1, 3 + 1e-12L);
  EXPECT_LT(r.x0, 0.2L);
  EXPECT_GT(r.y1, 2.8L);
  const SegmentRegion padded = dwellRegion(points, 0.9, 64, 0.1);
  EXPECT_NEAR(static_cast<double>(padded.width()), 1.2 * static_cast<double>(r.width()), 1e-12);
  const SegmentRegion everything = dwellRegion(points, 1.0, 64, 0);
  EXPECT_EQ(everything.fraction, 1.0);
  EXPECT_THROW((void)dwellRegion({}, 0.9), std::invalid_argument);
  EXPECT_THROW((void)dwellRegion(points, 0.0), std::invalid_argument);
  EXPECT_THROW((void)dwellRegion(points, 0.9, 0), std::invalid_argument);
}

TEST(SegmentAnalysis, IslandRegionFramesEveryLevelthPoint) {
  // Points alternate between two clusters (a chain of period 2): every second point from z_0 stays in the
  // first cluster, so the region frames it alone.
  std::vector<PhysicalPoint> points;
  for (int i = 0; i < 400; ++i) {
    const long double jitter = (i % 7) * 0.01L;
    points.push_back(i % 2 == 0 ? PhysicalPoint{1 + jitter, 1 + jitter} : PhysicalPoint{-1 - jitter, -1});
  }
  const SegmentRegion one = islandRegion(points, 2, 1.0, 0);
  EXPECT_EQ(one.x0, 1.0L);
  EXPECT_EQ(one.y0, 1.0L);
  EXPECT_NEAR(static_cast<double>(one.x1), 1.06, 1e-15);
  const SegmentRegion both = islandRegion(points, 1, 1.0, 0);
  EXPECT_LT(both.x0, -1.0L);
  EXPECT_THROW((void)islandRegion(points, 0), std::invalid_argument);
}

TEST(SegmentAnalysis, FramedInBoxKeepsTheAspectAndStaysInTheBox) {
  const MapParameters map;  // [-0.8, 0.5] × [-0.65, 0.65]
  SegmentRegion r;
  r.x0 = 0.1L, r.x1 = 0.2L, r.y0 = 0.0L, r.y1 = 0.01L;
  const SegmentRegion f = framedInBox(r, map, 1.5, 0);
  EXPECT_NEAR(static_cast<double>(f.width() / f.height()), 1.5, 1e-15);
  EXPECT_NEAR(static_cast<double>(f.width()), 0.1, 1e-15);
  EXPECT_NEAR(static_cast<double>(f.y0 + f.y1), 0.01, 1e-15);  // same centre
  // Near the edge: shifted inside.
  r.x0 = 0.45L, r.x1 = 0.5L, r.y0 = 0.6L, r.y1 = 0.65L;
  const SegmentRegion edge = framedInBox(r, map, 1, 0.2L);
  EXPECT_NEAR(static_cast<double>(edge.width()), 0.2, 1e-15);
  EXPECT_EQ(edge.x1, 0.5L);
  EXPECT_NEAR(static_cast<double>(edge.y1), 0.65, 1e-15);
  // Larger than the box: cut to it.
  r.x0 = -2, r.x1 = 2, r.y0 = -1, r.y1 = 1;
  const SegmentRegion all = framedInBox(r, map, 1, 0);
  EXPECT_NEAR(static_cast<double>(all.x0), -0.8, 1e-15);
  EXPECT_NEAR(static_cast<double>(all.x1), 0.5, 1e-15);
  EXPECT_THROW((void)framedInBox(r, map, 0, 0), std::invalid_argument);
}

TEST(SegmentAnalysis, CsvHasOneLinePerKeptState) {
  const TrappingState& state = shortRun();
  const auto trace = traceSegment(state.params, state.longest.items().front(), 50);
  ASSERT_TRUE(trace.has_value());
  const std::string path = (std::filesystem::temp_directory_path() / "archipelago_segment_test.csv").string();
  writeSegmentCsv(path, *trace);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "step,x,y,X,Y");
  std::size_t lines = 0;
  std::string last;
  while (std::getline(in, line)) {
    ++lines;
    last = line;
  }
  EXPECT_EQ(lines, trace->states.size());
  EXPECT_EQ(last.substr(0, last.find(',')), std::to_string(trace->steps));
  EXPECT_EQ(last.substr(last.rfind(',') + 1), std::to_string(trace->states.back().Y));
  std::filesystem::remove(path);
  EXPECT_THROW(writeSegmentCsv("/nonexistent-dir/x.csv", *trace), std::runtime_error);
}

// Issue #12, finding 5: a replay was bounded by T, not by the recorded length: a record whose start lies in an
// island (it never reaches the randomizing zone) replayed for q·T steps (T = 2^58 here: forever).  Every replay
// now stops after record.length blocks and reports the mismatch; a streamed CSV is then not written at all.
TEST(SegmentAnalysis, ReplayNeverEndsWhenARecordsStartLiesInAnIsland) {
  TrappingParameters p;  // the paper's K = 0.1 box
  p.T = std::uint64_t{1} << 58;
  const FixedPointMap map(p.map);
  SegmentRecord stuck;
  stuck.length = 5000;
  stuck.start.z = map.toUnit(-std::sqrt(0.1L) + 0.05L, 0);
  std::uint64_t visits = 0;
  try {
    (void)replaySegment(p, stuck, [&](std::uint64_t, const UnitState&) { ++visits; });
    ADD_FAILURE() << "no replay mismatch";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("replay mismatch"), std::string::npos) << e.what();
  }
  EXPECT_EQ(visits, stuck.length * p.q + 1);  // stopped at the record's end, not at T
  EXPECT_THROW((void)traceSegment(p, stuck, 1000), std::runtime_error);  // the GUI's replay
  const auto path = (std::filesystem::temp_directory_path() / "archipelago-stuck-segment.csv").string();
  std::filesystem::remove(path);
  EXPECT_THROW((void)writeSegmentCsv(path, p, stuck, 1000), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(path));  // nothing half-written
  // Where the record says the run's last block cut it, the replay ends there (the GUI's test of an island
  // segment relies on it); one block earlier in the run it is a mismatch again.
  stuck.start.block = p.T - stuck.length;
  EXPECT_EQ(replaySegment(p, stuck, {}), stuck.length);
  stuck.start.block -= 1;
  EXPECT_THROW((void)replaySegment(p, stuck, {}), std::runtime_error);
  // A record that ends before its recorded length is a mismatch too.
  const TrappingState& state = shortRun();
  SegmentRecord longer = state.longest.items().front();
  longer.length += 1;
  EXPECT_THROW((void)replaySegment(state.params, longer, {}), std::runtime_error);
}

// Issue #11 item 8: `archipelago-cli replay --identify` kept every point of the segment (up to 2·10⁷ long-double
// points, ~640 MB) and took its own path.  It now takes the GUI's, identifySegmentChain(), which holds at most
// maxPoints points however long the segment: here one that never ends (an orbit on a KAM curve of the central
// island never reaches the randomizing zone; T allows 1.6·10¹³ steps).
TEST(SegmentAnalysis, ChainIdentificationHoldsAtMostItsCapWhateverTheSegmentLength) {
  TrappingParameters p;  // the paper's K = 0.1 box
  p.T = 1'000'000'000'000;
  const FixedPointMap map(p.map);
  SegmentRecord endless;
  endless.length = p.T;
  endless.start.z = map.toUnit(-std::sqrt(0.1L) + 0.05L, 0);
  for (std::uint64_t cap : {std::uint64_t{1000}, std::uint64_t{20'000}}) {
    const auto prefix = segmentPrefix(p, endless, cap);
    ASSERT_TRUE(prefix.has_value());
    EXPECT_EQ(prefix->size(), cap);
    EXPECT_LE(prefix->capacity(), cap);  // reserved for the cap, never for the segment's length
    const auto found = identifySegmentChain(p, endless, cap);
    ASSERT_TRUE(found.has_value());
    EXPECT_EQ(found->points, cap);
    EXPECT_EQ(found->chain.period, 1);  // it circles the central island
  }
  // A short segment is used whole, and the count says so.
  const TrappingState& state = shortRun();
  const SegmentRecord& record = state.longest.items().front();
  const auto whole = identifySegmentChain(state.params, record, UINT64_MAX);
  ASSERT_TRUE(whole.has_value());
  EXPECT_EQ(whole->points, record.length * state.params.q + 1);
  EXPECT_GE(kChainIdentificationPoints, 1'000'000u);  // the default the GUI and the CLI share
}

TEST(SegmentAnalysis, StreamedCsvEqualsTheTraceCsv) {
  const TrappingState& state = shortRun();
  const SegmentRecord& record = state.longest.items().front();
  const auto dir = std::filesystem::temp_directory_path();
  const std::string traced = (dir / "archipelago_segment_traced.csv").string();
  const std::string streamed = (dir / "archipelago_segment_streamed.csv").string();
  const auto trace = traceSegment(state.params, record, UINT64_MAX);
  ASSERT_TRUE(trace.has_value());
  writeSegmentCsv(traced, *trace);
  EXPECT_EQ(writeSegmentCsv(streamed, state.params, record, 1), record.length);
  auto text = [](const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(text(streamed), text(traced));
  // Every 7th step, and always the last one.
  const std::uint64_t last = record.length * state.params.q;
  writeSegmentCsv(streamed, state.params, record, 7);
  std::ifstream in(streamed);
  std::string line, previous;
  std::uint64_t lines = 0;
  while (std::getline(in, line)) {
    ++lines;
    previous = line;
  }
  EXPECT_EQ(lines, 1 + last / 7 + 1 + (last % 7 != 0 ? 1 : 0));
  EXPECT_EQ(previous.substr(0, previous.find(',')), std::to_string(last));
  EXPECT_THROW((void)writeSegmentCsv(streamed, state.params, record, 0), std::invalid_argument);
  EXPECT_THROW((void)writeSegmentCsv("/nonexistent-dir/x.csv", state.params, record, 1), std::runtime_error);
  std::filesystem::remove(traced);
  std::filesystem::remove(streamed);
}

}  // namespace
}  // namespace archipelago
