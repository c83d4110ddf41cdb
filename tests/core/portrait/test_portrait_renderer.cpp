// Portrait rendering: pixels of a known orbit, a deep zoom into the chain of six islands, refinement,
// cancellation and determinism (Karney 1983, §5 and fig. 2).
#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <array>
#include <set>
#include <atomic>
#include <thread>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/portrait/PortraitColours.hpp"
#include "core/portrait/MapOverlays.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/random/CounterRng.hpp"
#include "core/run/TrappingRun.hpp"
#include "tests/core/kernels/KernelsUnderTest.hpp"

namespace archipelago {
namespace {

const MapParameters kPaper{0.1, -0.8, 0.5};  // §5

// The pixel of a physical point, computed independently of PixelMapping, in long double.
long double columnOf(const PhysicalRect& r, int width, long double x) { return (x - r.x0) / (r.x1 - r.x0) * width; }
long double rowOf(const PhysicalRect& r, int height, long double y) { return (r.y1 - y) / (r.y1 - r.y0) * height; }

TEST(PortraitRenderer, KnownOrbitLandsInTheRightPixels) {
  PortraitRequest req;
  req.map = kPaper;
  req.view = Viewport::fromPhysical(kPaper, {-0.7L, 0.2L, -0.45L, 0.35L});
  req.width = 180;
  req.height = 160;
  req.mode = PortraitMode::Orbits;
  req.seedColumns = req.seedRows = 1;  // one seed, at the centre of the view
  req.points = 20000;
  req.passes = 3;
  req.chunkSteps = 999;
  const PortraitResult res = renderPortrait(req);
  ASSERT_FALSE(res.cancelled);
  EXPECT_EQ(res.raster.pointsIterated, 20000u);

  // The same orbit by hand: N from the seed, binned by its physical coordinates.
  const FixedPointMap N(kPaper);
  UnitState z = orbitSeed(req.view, 1, 1, 0, 0);
  EXPECT_EQ(z, req.view.centre());
  const PhysicalRect r = req.view.physical(kPaper);
  std::vector<std::uint64_t> expected(static_cast<std::size_t>(req.width * req.height), 0);
  std::uint64_t inside = 0;
  for (int i = 0; i < 20000; ++i) {
    N.forward(z);
    const PhysicalPoint p = N.toPhysical(z);
    const long double c = columnOf(r, req.width, p.x), w = rowOf(r, req.height, p.y);
    if (c < 0 || c >= req.width || w < 0 || w >= req.height) continue;
    expected[static_cast<std::size_t>(w) * static_cast<std::size_t>(req.width) + static_cast<std::size_t>(c)] += 1;
    ++inside;
  }
  ASSERT_GT(inside, 1000u);  // the seed lies in the central island: its orbit stays in view
  EXPECT_EQ(res.raster.pointsBinned, inside);
  EXPECT_EQ(res.raster.counts, expected);
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(res.raster.labels[i], expected[i] ? 1u : 0u);
}

// Newton's method for the period-6 orbit of Q (eq. qu) in long double: returns a point of the elliptic
// orbit at the centres of the chain of six islands around the central island at K = 0.1.
PhysicalPoint periodSixIslandCentre() {
  const long double K = 0.1L;
  long double x = -0.33959L, y = 0.26244L;  // from a scan of Q^6 along the symmetry line 2y = g(x − y)
  for (int it = 0; it < 20; ++it) {
    long double X = x, Y = y, j11 = 1, j12 = 0, j21 = 0, j22 = 1;
    for (int s = 0; s < 6; ++s) {
      const long double g1 = 4 * X;  // g'(x)
      Y += 2 * (X * X - K);
      X += Y;
      // Jacobian of one step: [[1 + g', 1], [g', 1]]
      const long double a11 = 1 + g1, a12 = 1, a21 = g1, a22 = 1;
      const long double n11 = a11 * j11 + a12 * j21, n12 = a11 * j12 + a12 * j22;
      const long double n21 = a21 * j11 + a22 * j21, n22 = a21 * j12 + a22 * j22;
      j11 = n11, j12 = n12, j21 = n21, j22 = n22;
    }
    const long double fx = X - x, fy = Y - y, a = j11 - 1, b = j12, c = j21, d = j22 - 1, det = a * d - b * c;
    x -= (d * fx - b * fy) / det;
    y -= (-c * fx + a * fy) / det;
  }
  return {x, y};
}

TEST(PortraitRenderer, DeepZoomIntoTheSixIslandChainShowsItsCentre) {
  const PhysicalPoint centre = periodSixIslandCentre();
  EXPECT_NEAR(static_cast<double>(centre.x), -0.33958976097517, 1e-12);
  EXPECT_NEAR(static_cast<double>(centre.y), 0.26244081789623, 1e-12);
  const long double half = 0.5e-9L;  // a view of width 10^-9
  PortraitRequest req;
  req.map = kPaper;
  req.view = Viewport::fromPhysical(kPaper, {centre.x - half, centre.x + half, centre.y - half, centre.y + half});
  req.width = req.height = 128;
  req.mode = PortraitMode::Orbits;
  req.seedColumns = req.seedRows = 6;
  req.points = 36 * 12000;
  const PortraitResult res = renderPortrait(req);
  const PortraitRaster& ras = res.raster;
  // Seeds near an elliptic period-6 point stay on small invariant curves around it: 1 point in 6 returns
  // to the view, except along the arcs of the outer (elongated) curves that leave the square view.
  EXPECT_GT(ras.pointsBinned, req.points / 6 / 4);
  EXPECT_LE(ras.pointsBinned, req.points / 6 + 36);
  EXPECT_GT(ras.nonEmptyPixels(), 2000u);
  // Correct placement: the content surrounds the centre of the view (the island centre) symmetrically,
  // and the pixel at the centre (the periodic point itself) stays empty: no invariant curve passes there.
  double sx = 0, sy = 0, n = 0;
  int quadrants[2][2] = {{0, 0}, {0, 0}};
  for (int row = 0; row < ras.height; ++row)
    for (int col = 0; col < ras.width; ++col) {
      const auto c = static_cast<double>(ras.counts[ras.index(col, row)]);
      if (c == 0) continue;
      sx += c * (col + 0.5), sy += c * (row + 0.5), n += c;
      quadrants[row < ras.height / 2][col < ras.width / 2] += 1;
    }
  EXPECT_NEAR(sx / n, ras.width / 2.0, ras.width * 0.05);
  EXPECT_NEAR(sy / n, ras.height / 2.0, ras.height * 0.05);
  for (auto& q : quadrants)
    for (int count : q) EXPECT_GT(count, 200);
  EXPECT_EQ(ras.counts[ras.index(ras.width / 2, ras.height / 2)], 0u);
  // Each seed's orbit keeps its own label; inner curves do not cross outer ones, so many labels survive.
  std::vector<std::uint32_t> labels(ras.labels.begin(), ras.labels.end());
  std::sort(labels.begin(), labels.end());
  EXPECT_GT(std::unique(labels.begin(), labels.end()) - labels.begin(), 10);
}

TEST(PortraitRenderer, DensityLeavesTheIslandsEmpty) {
  PortraitRequest req;
  req.map = kPaper;
  req.width = req.height = 130;  // pixels of 0.01 in x and y
  req.points = 4'000'000;
  const PortraitResult res = renderPortrait(req);
  const PortraitRaster& ras = res.raster;
  EXPECT_EQ(res.passesDone, req.passes);
  EXPECT_EQ(ras.pointsBinned, ras.pointsIterated);  // the whole box is in view
  // The elliptic fixed point (−√K, 0), the centre of the central island: column (x + 0.8)/0.01, row (0.65 − y)/0.01.
  const auto col = static_cast<int>((-std::sqrt(0.1) + 0.8) / 0.01), row = 65;
  for (int dr = -3; dr <= 3; ++dr)
    for (int dc = -3; dc <= 3; ++dc) EXPECT_EQ(ras.counts[ras.index(col + dc, row + dr)], 0u);
  const double filled = static_cast<double>(ras.nonEmptyPixels()) / static_cast<double>(ras.pixelCount());
  EXPECT_GT(filled, 0.7);   // the sea (b2 ≈ 0.81 of the box, see test_stochastic_area.cpp)
  EXPECT_LT(filled, 0.9);   // … but not the islands
}

TEST(PortraitRenderer, ResultDoesNotDependOnTheThreadCount) {
  for (PortraitMode mode : {PortraitMode::Density, PortraitMode::Orbits, PortraitMode::Stickiness}) {
    PortraitRequest req;
    req.map = kPaper;
    req.width = 64;
    req.height = 48;
    req.mode = mode;
    req.points = 300'000;
    req.orbits = 37;  // not a multiple of the lanes
    req.seedColumns = 5;
    req.seedRows = 3;
    const int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    const PortraitRaster one = renderPortrait(req).raster;
    omp_set_num_threads(3);
    const PortraitRaster three = renderPortrait(req).raster;
    omp_set_num_threads(saved);
    EXPECT_EQ(one.counts, three.counts) << toString(mode);
    EXPECT_EQ(one.labels, three.labels) << toString(mode);
    EXPECT_EQ(one.lengthSums, three.lengthSums) << toString(mode);
    EXPECT_EQ(one.pointsBinned, three.pointsBinned) << toString(mode);
    EXPECT_GT(one.nonEmptyPixels(), 0u) << toString(mode);
  }
}

TEST(PortraitRenderer, RefinementDeliversOneSnapshotPerPass) {
  PortraitRequest req;
  req.map = kPaper;
  req.width = req.height = 64;
  req.points = 1 << 20;
  req.orbits = 16;
  req.passes = 5;
  req.chunkSteps = 1000;
  std::vector<std::uint64_t> snapshotPoints;
  std::vector<std::uint64_t> snapshotBinned;
  std::uint64_t last = 0;
  bool monotone = true, sawFinal = false;
  const PortraitResult res = renderPortrait(req, [&](const PortraitProgress& p) {
    monotone = monotone && p.pointsDone >= last;
    last = p.pointsDone;
    EXPECT_EQ(p.pointsTotal, req.points);
    if (p.snapshot) {
      snapshotPoints.push_back(p.snapshot->pointsIterated);
      snapshotBinned.push_back(p.snapshot->pointsBinned);
      sawFinal = p.final;
    }
  });
  EXPECT_TRUE(monotone);
  EXPECT_TRUE(sawFinal);
  // Passes end at 1/16, 1/8, 1/4, 1/2 and all of the 2^16 steps per orbit: coarse first, then finer.
  EXPECT_EQ(snapshotPoints, (std::vector<std::uint64_t>{1 << 16, 1 << 17, 1 << 18, 1 << 19, 1 << 20}));
  EXPECT_EQ(snapshotBinned, snapshotPoints);  // whole box in view
  EXPECT_EQ(res.raster.pointsIterated, std::uint64_t{1} << 20);
}

// The explorer accumulates a large budget in passes of bounded size: splitting the doubling levels gives a
// snapshot every passPoints points and does not change the raster (the same orbits, continued).
TEST(PortraitRenderer, SplitPassesAccumulateTheSameRaster) {
  PortraitRequest req;
  req.map = kPaper;
  req.view = Viewport::fromPhysical(kPaper, {-0.5L, 0.1L, -0.3L, 0.3L});
  req.width = req.height = 48;
  req.points = 1 << 20;
  req.orbits = 16;  // 2^16 steps per orbit
  req.passes = 3;   // levels end at 2^14, 2^15, 2^16 steps per orbit
  req.passPoints = 1 << 17;  // 2^13 steps per orbit per pass
  req.chunkSteps = 3000;
  std::vector<std::uint64_t> expectedEnds;
  for (std::uint64_t k = 1; k <= 8; ++k) expectedEnds.push_back(k << 13);
  EXPECT_EQ(passSchedule(req), expectedEnds);
  std::vector<std::uint64_t> snapshotPoints;
  std::uint32_t reportedPasses = 0;
  const PortraitResult split = renderPortrait(req, [&](const PortraitProgress& p) {
    reportedPasses = p.passes;
    if (p.snapshot) snapshotPoints.push_back(p.snapshot->pointsIterated);
  });
  EXPECT_EQ(reportedPasses, 8u);
  EXPECT_EQ(split.passesDone, 8u);
  std::vector<std::uint64_t> expectedPoints;
  for (std::uint64_t k = 1; k <= 8; ++k) expectedPoints.push_back(k << 17);
  EXPECT_EQ(snapshotPoints, expectedPoints);  // points so far grow by passPoints every pass
  PortraitRequest once = req;
  once.passes = 1;
  once.passPoints = 0;
  const PortraitResult whole = renderPortrait(once);
  EXPECT_EQ(split.raster.counts, whole.raster.counts);
  EXPECT_EQ(split.raster.pointsBinned, whole.raster.pointsBinned);
  EXPECT_GT(whole.raster.pointsBinned, 0u);

  // Stickiness splits whole blocks of q.
  req.mode = PortraitMode::Stickiness;
  req.q = 16;
  req.passPoints = 100'000;  // 6250 steps per orbit: 390 blocks
  const auto ends = passSchedule(req);
  std::uint64_t prev = 0;
  for (std::uint64_t e : ends) {
    EXPECT_EQ(e % 16, 0u);
    EXPECT_GT(e, prev);
    EXPECT_LE(e - prev, 6240u);
    prev = e;
  }
  EXPECT_EQ(ends.back(), req.stepsPerOrbit());
}

TEST(PortraitRenderer, ProgressiveScheduleStartsSmallAndCapsEveryPass) {
  PortraitRequest req;
  req.points = 10'000'000'000;  // 10^10: the explorer's largest budget
  setProgressiveSchedule(req, 1 << 20, 1 << 26);
  ASSERT_FALSE(validationError(req)) << *validationError(req);
  const auto ends = passSchedule(req);
  const std::uint64_t n = req.orbitCount();
  EXPECT_GE(ends.front() * n, std::uint64_t{1} << 20);  // the first snapshot comes after about 2^20 points
  EXPECT_LT(ends.front() * n, std::uint64_t{1} << 22);
  std::uint64_t prev = 0;
  for (std::uint64_t e : ends) {
    EXPECT_LE((e - prev) * n, std::uint64_t{1} << 26);
    prev = e;
  }
  EXPECT_EQ(ends.back(), req.stepsPerOrbit());
  EXPECT_GE(ends.back() * n, req.points);
  // A pass size too small for the budget is raised so that the schedule stays within 2^16 passes …
  req.points = std::uint64_t{1} << 45;
  setProgressiveSchedule(req, 1 << 20, 1000);
  EXPECT_FALSE(validationError(req));
  EXPECT_LE(passSchedule(req).size(), std::size_t{1} << 16);
  // … and a request that asks for more passes is refused with a clear message.
  req.passPoints = 1000;
  ASSERT_TRUE(validationError(req));
  EXPECT_NE(validationError(req)->find("more than 2^16 passes"), std::string::npos) << *validationError(req);
}

// An empty Density view is declared free of sea only once an all-sea view would have had 64 points:
// inside the central island (about the elliptic fixed point) that verdict comes; a view of the same size in
// the sea next to xmax gets points; and a 7·10⁻⁴-wide view in the sea is not empty after 10^8 points.
TEST(PortraitRenderer, SaysWhenAViewHoldsNoChaoticPoints) {
  PortraitRequest req;
  req.map = kPaper;
  // Expected points of an all-sea view: points · (view area / L²), computed here from the physical sizes.
  req.view = Viewport::fromPhysical(kPaper, {-0.3212L, -0.3112L, -0.005L, 0.005L});
  const double fraction = 0.01 * 0.01 / (1.3 * 1.3);
  EXPECT_NEAR(seaPointsExpectedIfAllSea(req, 1'000'000), 1e6 * fraction, 1e-6 * 1e6 * fraction);
  EXPECT_DOUBLE_EQ(seaPointsExpectedIfAllSea(PortraitRequest{}, 12345), 12345.0);  // the whole box

  req.width = req.height = 40;
  req.points = static_cast<std::uint64_t>(2 * kNoSeaExpectedPoints / fraction);
  const PortraitRaster island = renderPortrait(req).raster;
  EXPECT_EQ(island.pointsBinned, 0u);
  EXPECT_TRUE(viewHoldsNoSea(req, island));
  // Too few points for a verdict: an empty view says nothing yet.
  PortraitRequest early = req;
  early.points = static_cast<std::uint64_t>(kNoSeaExpectedPoints / fraction / 4);
  const PortraitRaster few = renderPortrait(early).raster;
  EXPECT_EQ(few.pointsBinned, 0u);
  EXPECT_FALSE(viewHoldsNoSea(early, few));
  // Other modes never give the verdict.
  PortraitRequest orbits = early;
  orbits.mode = PortraitMode::Orbits;
  EXPECT_FALSE(viewHoldsNoSea(orbits, few));

  PortraitRequest sea = req;
  sea.view = Viewport::fromPhysical(kPaper, {0.44L, 0.45L, 0.295L, 0.305L});
  const PortraitRaster seaRaster = renderPortrait(sea).raster;
  EXPECT_GT(seaRaster.pointsBinned, 0u);
  EXPECT_FALSE(viewHoldsNoSea(sea, seaRaster));

  PortraitRequest deep = sea;
  deep.view = Viewport::fromPhysical(kPaper, {0.44965L, 0.45035L, 0.29965L, 0.30035L});
  deep.points = 100'000'000;
  const PortraitRaster deepRaster = renderPortrait(deep).raster;
  EXPECT_GT(deepRaster.nonEmptyPixels(), 0u);
  EXPECT_FALSE(viewHoldsNoSea(deep, deepRaster));
}

TEST(PortraitRenderer, CancellationStopsWithinOneChunk) {
  PortraitRequest req;
  req.map = kPaper;
  req.width = req.height = 64;
  req.points = std::uint64_t{1} << 30;  // minutes of work if it were not stopped
  req.orbits = 32;
  req.chunkSteps = 4096;
  std::stop_source source;
  std::uint64_t atStop = 0;
  int calls = 0;
  const PortraitResult res = renderPortrait(
      req,
      [&](const PortraitProgress& p) {
        if (++calls == 3) {  // after three rounds of one chunk per orbit
          atStop = p.pointsDone;
          source.request_stop();
        }
      },
      source.get_token());
  EXPECT_TRUE(res.cancelled);
  EXPECT_EQ(atStop, 3u * 32u * 4096u);
  EXPECT_EQ(res.raster.pointsIterated, atStop);  // no chunk started after the request
  EXPECT_EQ(res.raster.pointsBinned, atStop);    // and what was done is in the raster

  // A request from another thread while the work runs: the round in progress finishes at most the chunk
  // each orbit is in, and no further round starts.
  std::stop_source other;
  std::atomic<std::uint64_t> lastReported{0};
  std::atomic<int> rounds{0};
  PortraitResult concurrent;
  std::thread worker([&] {
    concurrent = renderPortrait(req, [&](const PortraitProgress& p) {
      lastReported = p.pointsDone;
      ++rounds;
    }, other.get_token());
  });
  while (rounds.load() < 2) std::this_thread::yield();
  other.request_stop();
  worker.join();
  EXPECT_TRUE(concurrent.cancelled);
  EXPECT_LE(concurrent.raster.pointsIterated, lastReported.load() + std::uint64_t{32} * 4096);
  EXPECT_LT(concurrent.raster.pointsIterated, req.points / 100);

  std::stop_source before;
  before.request_stop();
  EXPECT_EQ(renderPortrait(req, {}, before.get_token()).raster.pointsIterated, 0u);  // not a single chunk
}

TEST(PortraitRenderer, StickinessMeansAreWholeBlocksAndLongestNearTheIslands) {
  PortraitRequest req;
  req.map = kPaper;
  req.width = req.height = 65;  // pixels of 0.02
  req.mode = PortraitMode::Stickiness;
  req.points = 6'000'000;
  req.orbits = 64;
  const PortraitRaster ras = renderPortrait(req).raster;
  ASSERT_GT(ras.nonEmptyPixels(), ras.pixelCount() / 2);
  double nearIslands = 0, farAway = 0;
  int nNear = 0, nFar = 0;
  for (int row = 0; row < ras.height; ++row)
    for (int col = 0; col < ras.width; ++col) {
      const std::size_t i = ras.index(col, row);
      if (ras.counts[i] == 0) continue;
      EXPECT_GE(ras.meanSegmentLength(i), req.q);  // every segment is at least one block of q steps
      const double x = -0.8 + 0.02 * (col + 0.5), y = 0.65 - 0.02 * (row + 0.5);
      const double r = std::hypot(x + 0.2, y);  // distance from the middle of the island chain
      if (r < 0.35) nearIslands += std::log(ras.meanSegmentLength(i)), ++nNear;
      if (x > 0.35) farAway += std::log(ras.meanSegmentLength(i)), ++nFar;
    }
  ASSERT_GT(nNear, 10);
  ASSERT_GT(nFar, 10);
  // Segments passing close to the islands are longer (the stickiness, §5) than those near the box edge.
  EXPECT_GT(nearIslands / nNear, farAway / nFar + std::log(2.0));
}

// Xr and q are refused in every mode: in density mode the renderer still builds its block settings from them, and an
// Xr of 1e308 reached an undefined float-to-integer conversion (clang's UBSan, cli.hostile's `portrait --Xr 1e308`).
TEST(PortraitRenderer, XrAndQAreCheckedInEveryMode) {
  for (PortraitMode mode : {PortraitMode::Density, PortraitMode::Orbits, PortraitMode::Stickiness}) {
    PortraitRequest req;
    req.mode = mode;
    EXPECT_FALSE(validationError(req));
    for (double Xr : {1e308, -1.0, std::numeric_limits<double>::quiet_NaN(), 1.0}) {
      req.Xr = Xr;
      ASSERT_TRUE(validationError(req)) << Xr;
      EXPECT_EQ(validationError(req)->rfind("Xr = ", 0), 0u) << *validationError(req);
    }
    req = {};
    req.mode = mode;
    req.q = 0;
    ASSERT_TRUE(validationError(req));
    EXPECT_NE(validationError(req)->find("q"), std::string::npos) << *validationError(req);
  }
}

TEST(PortraitRenderer, BadRequestsGiveClearErrors) {
  PortraitRequest req;
  req.width = 0;
  EXPECT_NE(validationError(req)->find("raster size = 0x512"), std::string::npos);
  req = {};
  req.points = 0;
  EXPECT_NE(validationError(req)->find("points"), std::string::npos);
  req = {};
  req.map.xmin = 0.0;
  EXPECT_NE(validationError(req)->find("xmin"), std::string::npos);
  req = {};
  req.chunkSteps = 0;
  EXPECT_THROW((void)renderPortrait(req), std::invalid_argument);
  EXPECT_EQ(*validationError(req), "chunkSteps = 0 must lie in [1, 1048576]");
  req = {};
  req.passes = 31;
  EXPECT_EQ(*validationError(req), "passes = 31 must lie in [1, 30]");
  EXPECT_FALSE(validationError(PortraitRequest{}));
}

// Issue #11, item 6: the kernel is part of the request (never read from $ARCHIPELAGO_KERNEL inside core), and
// every path the CPU supports, passed explicitly, gives the scalar path's raster in every mode.
TEST(PortraitRenderer, EveryKernelPassedInTheRequestGivesTheSameRaster) {
  for (PortraitMode mode : {PortraitMode::Density, PortraitMode::Orbits, PortraitMode::Stickiness}) {
    PortraitRequest req;
    req.map = kPaper;
    req.view = Viewport::fromPhysical(kPaper, {-0.6L, 0.1L, -0.4L, 0.3L});
    req.width = 70;
    req.height = 50;
    req.mode = mode;
    req.points = 400'000;
    req.orbits = 45;  // a ragged last group in every vector width
    req.seedColumns = 7;
    req.seedRows = 5;
    req.kernel = &kernelByName("scalar");
    const PortraitRaster scalar = renderPortrait(req).raster;
    ASSERT_GT(scalar.nonEmptyPixels(), 0u) << toString(mode);
    for (const auto& kernel : kerneltests::kernelsUnderTest()) {
      req.kernel = &kernel;
      const PortraitRaster raster = renderPortrait(req).raster;
      SCOPED_TRACE(std::string(toString(mode)) + " " + std::string(kernel.name));
      EXPECT_EQ(raster.counts, scalar.counts);
      EXPECT_EQ(raster.labels, scalar.labels);
      EXPECT_EQ(raster.lengthSums, scalar.lengthSums);
      EXPECT_EQ(raster.orbitWrapped, scalar.orbitWrapped);
      EXPECT_EQ(raster.pointsBinned, scalar.pointsBinned);
    }
  }
}

// Issue #11, item 4: Stickiness portraits iterate the trapping block of runs (BlockKernel.hpp), so with the
// whole box in view the points binned are q times the summed lengths of the segments runTrapping() records
// for the same orbits, seed, Xr, q and number of blocks (first and open segments dropped by both).
TEST(PortraitRenderer, StickinessSegmentsAreThoseOfTrappingRuns) {
  PortraitRequest req;
  req.map = kPaper;
  req.width = req.height = 32;
  req.mode = PortraitMode::Stickiness;
  req.orbits = 13;
  req.q = 8;
  req.Xr = 0.05;
  req.seed = 7;
  req.points = 13 * 8 * 5000;
  const PortraitRaster raster = renderPortrait(req).raster;
  TrappingParameters p;
  p.map = kPaper;
  p.M = req.orbits;
  p.q = req.q;
  p.Xr = req.Xr;
  p.seed = req.seed;
  p.T = req.stepsPerOrbit() / req.q;
  p.subsets = 1;
  TrappingRunOptions o;
  o.kernel = &kernelByName("scalar");
  const TrappingState run = runTrapping(startTrapping(p), o);
  ASSERT_GT(run.total().segments(), 100u);
  EXPECT_EQ(raster.pointsBinned, run.total().totalLength() * req.q);
  std::uint64_t counted = 0;
  for (std::uint64_t c : raster.counts) counted += c;
  EXPECT_EQ(counted, raster.pointsBinned);
}

// The Orbits mode's lane loop (kernels/ScalarLanes.hpp) flags a seed's orbit as wrapped exactly when one of
// its steps of N wraps, as forwardStep() reports it one step at a time.
TEST(PortraitRenderer, OrbitsModeFlagsTheSeedsThatWrap) {
  PortraitRequest req;
  req.map = kPaper;
  req.width = req.height = 40;
  req.mode = PortraitMode::Orbits;
  req.seedColumns = 9;  // one group of eight lanes and a remainder of one, per row
  req.seedRows = 4;
  req.points = 36 * 3000;
  req.passes = 2;
  req.chunkSteps = 700;
  const PortraitRaster raster = renderPortrait(req).raster;
  const MapCoefficients c = computeCoefficients(kPaper);
  ASSERT_EQ(raster.orbitWrapped.size(), 36u);
  int wrapped = 0;
  for (std::uint32_t j = 0; j < req.seedRows; ++j)
    for (std::uint32_t i = 0; i < req.seedColumns; ++i) {
      UnitState z = orbitSeed(req.view, req.seedColumns, req.seedRows, i, j);
      bool expected = false;
      for (std::uint64_t s = 0; s < req.stepsPerOrbit(); ++s) expected |= forwardStep(c, z);
      EXPECT_EQ(raster.orbitWrapped[j * req.seedColumns + i] != 0, expected) << i << ", " << j;
      wrapped += expected ? 1 : 0;
    }
  EXPECT_FALSE(raster.allOrbitsWrapped());
  EXPECT_GT(wrapped, 0);   // seeds in the sea wrap …
  EXPECT_LT(wrapped, 36);  // … seeds on KAM curves around the islands do not
}

// Issue 53 finding 22: the seeds' orbits leave a view 10⁻⁶ wide about the hyperbolic fixed point (the GUI advised a
// larger budget there, and an indicator map is what shows it); they stay in the whole box.
TEST(PortraitRenderer, OrbitsLeaveADeepViewAndStayInTheBox) {
  PortraitRequest req;
  req.map = kPaper;
  req.width = req.height = 40;
  req.mode = PortraitMode::Orbits;
  req.points = 100'000;
  const long double x = 0.316227766L, half = 5e-7L;
  req.view = Viewport::fromPhysical(kPaper, {x - half, x + half, -half, half});
  const PortraitRaster deep = renderPortrait(req).raster;
  EXPECT_TRUE(deep.orbitsLeaveView()) << deep.pointsBinned << " of " << deep.pointsIterated;
  req.view = Viewport::fromPhysical(kPaper, {-0.8L, 0.5L, -0.65L, 0.65L});
  const PortraitRaster box = renderPortrait(req).raster;
  EXPECT_FALSE(box.orbitsLeaveView()) << box.pointsBinned << " of " << box.pointsIterated;
  req.mode = PortraitMode::Density;  // an Orbits-mode rule
  EXPECT_FALSE(renderPortrait(req).raster.orbitsLeaveView());
}

// Issue 53 finding 14: a launched orbit's colour stands apart from every orbit colour of the portrait (they were the
// same palette: orbit 1 had label 1's colour).
TEST(ColourMap, LaunchedOrbitsStandApartFromThePortraitsOrbits) {
  for (std::uint32_t id = 1; id <= 1000; ++id)
    for (std::uint32_t label = 1; label <= 1000; ++label) {
      const Rgb a = launchedOrbitColour(id), b = orbitColour(label);
      const int apart = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
      ASSERT_GE(apart, 102) << id << ", " << label;
    }
  EXPECT_NE(launchedOrbitColour(1), launchedOrbitColour(2));
}

TEST(MapOverlays, FixedPointsOfThePaperBox) {
  const auto points = fixedPoints(kPaper);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_DOUBLE_EQ(static_cast<double>(points[0].position.x), -std::sqrt(0.1));
  EXPECT_TRUE(points[0].elliptic);
  EXPECT_DOUBLE_EQ(static_cast<double>(points[1].position.x), std::sqrt(0.1));
  EXPECT_FALSE(points[1].elliptic);
  const auto orbit = traceOrbit(kPaper, points[0].position.x, 0, 100);
  ASSERT_EQ(orbit.size(), 101u);
  EXPECT_NEAR(static_cast<double>(orbit.back().x), -std::sqrt(0.1), 1e-12);  // a fixed point stays put
}

TEST(ColourMap, EndsAndOrbitColours) {
  const ColourMap inferno(ColourMapName::Inferno);
  EXPECT_LE(inferno.at(0).r + inferno.at(0).g + inferno.at(0).b, 10);    // black
  EXPECT_GE(inferno.at(1).r, 245);                                        // pale yellow
  EXPECT_GE(inferno.at(1).g, 245);
  EXPECT_NE(orbitColour(1), orbitColour(2));
  EXPECT_EQ(parseColourMap("viridis"), ColourMapName::Viridis);
  EXPECT_FALSE(parseColourMap("jet"));
  PortraitRaster r;
  r.width = 2, r.height = 1, r.counts = {0, 5};
  const RasterImage image = colourize(r, ColourMapName::Grey);
  ASSERT_EQ(image.rgb.size(), 6u);
  EXPECT_EQ(image.rgb[0], 255);  // empty: white, as the paper's figures
  EXPECT_EQ(image.rgb[3], 0);    // the most visited pixel: black
}

// Issue 25, finding 14: Density was almost all saturated yellow (the scale between the 0.5% and 99.9% quantiles
// put the nearly uniform sea at its top).  Centred on the median, the bulk of the sea sits mid-scale.
TEST(ColourMap, DensityCentresTheSeaOnTheScale_Issue25Finding14) {
  PortraitRequest req;  // the paper's box, K = 0.1
  req.width = req.height = 160;
  req.mode = PortraitMode::Density;
  req.points = 20'000'000;
  const PortraitRaster raster = renderPortrait(req).raster;
  const RasterImage image = colourize(raster, ColourMapName::Grey);
  // Grey runs from white (t = 0) to black (t = 1): the pixels in the top tenth of the scale are a minority.
  std::size_t visited = 0, top = 0, middle = 0;
  for (std::size_t i = 0; i < raster.pixelCount(); ++i) {
    if (raster.counts[i] == 0) continue;
    ++visited;
    const double t = 1 - image.rgb[3 * i] / 255.0;
    top += t > 0.92;
    middle += t > 0.3 && t < 0.8;
  }
  ASSERT_GT(visited, raster.pixelCount() / 2);
  EXPECT_LT(top, visited / 10);
  EXPECT_GT(middle, visited / 2);
  EXPECT_LT(image.scaleMin, image.scaleMax);
}

// K = 0 (fig. 3b): Q has no island, every seed of the Orbits mode wraps around the torus.  The sea used to be
// painted one grey, so the portrait was blank; it is now shaded by its visits through the colour map, and
// the colour map changes the picture.
TEST(ColourMap, OrbitsModeShadesTheSeaThroughTheColourMap) {
  PortraitRequest req;
  req.map = MapParameters{0.0, -0.05, 0.05};
  req.width = req.height = 100;
  req.mode = PortraitMode::Orbits;
  req.points = 1'000'000;
  const PortraitRaster raster = renderPortrait(req).raster;
  std::size_t wrapped = 0;
  for (std::uint8_t w : raster.orbitWrapped) wrapped += w;
  EXPECT_EQ(wrapped, raster.orbitWrapped.size());  // every seed is in the sea
  EXPECT_TRUE(raster.allOrbitsWrapped());
  const RasterImage inferno = colourize(raster, ColourMapName::Inferno);
  const RasterImage viridis = colourize(raster, ColourMapName::Viridis);
  std::set<std::array<std::uint8_t, 3>> colours;
  for (std::size_t i = 0; i < raster.pixelCount(); ++i)
    colours.insert({inferno.rgb[3 * i], inferno.rgb[3 * i + 1], inferno.rgb[3 * i + 2]});
  EXPECT_GT(colours.size(), 20u);  // not one flat grey
  EXPECT_NE(inferno.rgb, viridis.rgb);
  // Every sea colour comes from the dim part of the map; island orbits keep their hues.
  const ColourMap map(ColourMapName::Inferno);
  std::set<std::array<std::uint8_t, 3>> allowed;
  for (int k = 0; k <= 255; ++k) {
    const double t = k / 255.0;
    if (t < kSeaLowest - 1.0 / 255 || t > kSeaHighest + 1.0 / 255) continue;
    const Rgb c = map.at(t);
    allowed.insert({c.r, c.g, c.b});
  }
  for (const auto& c : colours) EXPECT_TRUE(allowed.count(c) || c == (std::array<std::uint8_t, 3>{16, 16, 24}));

  PortraitRaster islands;
  islands.width = 2, islands.height = 1, islands.mode = PortraitMode::Orbits;
  islands.counts = {3, 3};
  islands.labels = {1, 2};
  islands.orbitWrapped = {0, 1};
  const RasterImage image = colourize(islands, ColourMapName::Viridis);
  EXPECT_EQ((Rgb{image.rgb[0], image.rgb[1], image.rgb[2]}), orbitColour(1));
  // A lone sea pixel is its own median: the scale runs from a decade below it to half a decade above, so
  // it sits at t = 1/1.5 of the sea's part of the map.
  EXPECT_EQ((Rgb{image.rgb[3], image.rgb[4], image.rgb[5]}),
            ColourMap(ColourMapName::Viridis).at(kSeaLowest + (kSeaHighest - kSeaLowest) / 1.5));
}

}  // namespace
}  // namespace archipelago
