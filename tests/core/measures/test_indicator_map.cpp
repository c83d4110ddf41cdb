// Indicator maps (core/measures/IndicatorMap.hpp): progressive passes, threads and stop requests do not change a
// pixel; a pixel is its orbit's measure; and the chaotic share of a whole-box dig map agrees with the stochastic
// area b₂ of stochastic-area (core/stochasticarea/StochasticArea.hpp), an independent count by randomized orbits.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <stop_token>

#include "core/measures/IndicatorMap.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/stochasticarea/StochasticArea.hpp"
#include "tests/core/kernels/KernelsUnderTest.hpp"

namespace archipelago {
namespace {

const MapParameters kBox{0.1, -0.8, 0.5};

IndicatorRequest small(IndicatorKind kind, int width = 40, int height = 30) {
  IndicatorRequest r;
  r.measure.map = kBox;
  r.measure.kind = kind;
  r.measure.iterations = 300;
  r.width = width;
  r.height = height;
  r.roundPixels = 97;  // several rounds per pass
  return r;
}

void expectSameRaster(const IndicatorRaster& a, const IndicatorRaster& b) {
  ASSERT_EQ(a.pixelCount(), b.pixelCount());
  for (std::size_t i = 0; i < a.pixelCount(); ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.values[i]), std::bit_cast<std::uint64_t>(b.values[i])) << i;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a.digits[i]), std::bit_cast<std::uint64_t>(b.digits[i])) << i;
    EXPECT_EQ(a.verdicts[i], b.verdicts[i]) << i;
  }
}

TEST(IndicatorMap, PassesThreadsAndPathsDoNotChangeAPixel) {
  for (IndicatorKind kind : {IndicatorKind::Dig, IndicatorKind::Rotation, IndicatorKind::Fli, IndicatorKind::Megno,
                             IndicatorKind::Lyapunov}) {
    SCOPED_TRACE(std::string(toString(kind)));
    IndicatorRequest one = small(kind);
    one.passes = 1;
    one.threads = 1;
    one.measure.kernel = &kernelByName("scalar");
    const IndicatorResult reference = computeIndicatorMap(one);
    EXPECT_EQ(reference.raster.pixelsDone, reference.raster.pixelCount());
    EXPECT_EQ(reference.raster.count(OrbitVerdict::NotComputed), 0u);
    for (const KernelInfo& k : kerneltests::kernelsUnderTest()) {
      IndicatorRequest many = small(kind);
      many.passes = 4;
      many.threads = 2;
      many.measure.kernel = &k;
      expectSameRaster(computeIndicatorMap(many).raster, reference.raster);
    }
  }
}

TEST(IndicatorMap, APixelIsItsOrbitsMeasureFromTheCentreOfItsCell) {
  const IndicatorRequest r = small(IndicatorKind::Rotation, 7, 5);
  const IndicatorResult result = computeIndicatorMap(r);
  const OrbitMeasurer measurer(r.measure);
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      const UnitState start = indicatorPixelStart(r.view, r.width, r.height, col, row);
      // Row 0 is the top of the view; orbitSeed counts rows up from the bottom.
      EXPECT_EQ(start, orbitSeed(r.view, 7, 5, static_cast<std::uint32_t>(col), static_cast<std::uint32_t>(4 - row)));
      const OrbitMeasure m = measurer.measure(start);
      const std::size_t i = static_cast<std::size_t>(row * r.width + col);
      EXPECT_EQ(result.raster.verdicts[i], m.verdict);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(result.raster.values[i]), std::bit_cast<std::uint64_t>(m.value));
    }
  // The top-left pixel lies at the top of the box (largest y), the bottom-right at the bottom right.
  const PhysicalPoint topLeft = FixedPointMap(kBox).toPhysical(indicatorPixelStart(r.view, 7, 5, 0, 0));
  EXPECT_LT(topLeft.x, -0.6L);
  EXPECT_GT(topLeft.y, 0.5L);
}

TEST(IndicatorMap, ACoarseRasterFirstThenFinerOnes) {
  IndicatorRequest r = small(IndicatorKind::Dig);
  r.passes = 4;
  std::vector<IndicatorRaster> snapshots;
  std::vector<std::uint32_t> strides;
  int finals = 0;
  const IndicatorResult result = computeIndicatorMap(r, [&](const IndicatorProgress& p) {
    EXPECT_EQ(p.pixelsTotal, 1200u);
    if (!p.snapshot) return;
    snapshots.push_back(*p.snapshot);
    strides.push_back(p.stride);
    finals += p.final;
  });
  ASSERT_EQ(snapshots.size(), 4u);
  EXPECT_EQ(strides, (std::vector<std::uint32_t>{8, 4, 2, 1}));
  EXPECT_EQ(finals, 1);
  EXPECT_EQ(result.passesDone, 4u);
  // Pass k computes the pixels whose column and row are multiples of its stride: ⌈40/s⌉·⌈30/s⌉ in all.
  EXPECT_EQ(snapshots[0].pixelsDone, 5u * 4u);
  EXPECT_EQ(snapshots[1].pixelsDone, 10u * 8u);
  EXPECT_EQ(snapshots[2].pixelsDone, 20u * 15u);
  EXPECT_EQ(snapshots[3].pixelsDone, 1200u);
  // The first snapshot, filled: every pixel shows the computed pixel at the top-left corner of its 8 × 8 block.
  const std::vector<double> filled = snapshots[0].filled();
  for (int row = 0; row < 30; ++row)
    for (int col = 0; col < 40; ++col) {
      const std::size_t corner = static_cast<std::size_t>((row - row % 8) * 40 + (col - col % 8));
      EXPECT_EQ(filled[static_cast<std::size_t>(row * 40 + col)], result.raster.values[corner]);
    }
}

TEST(IndicatorMap, AStopRequestReturnsThePassesDone) {
  IndicatorRequest r = small(IndicatorKind::Megno);
  r.passes = 3;
  std::stop_source stopper;
  const IndicatorResult result = computeIndicatorMap(
      r, [&](const IndicatorProgress& p) {
        if (p.snapshot) stopper.request_stop();
      },
      stopper.get_token());
  EXPECT_TRUE(result.cancelled);
  EXPECT_EQ(result.passesDone, 1u);
  // Three passes: the first one computes every 4th column of every 4th row.
  EXPECT_EQ(result.raster.pixelsDone, 10u * 8u);
  EXPECT_EQ(result.raster.count(OrbitVerdict::NotComputed), 1200u - 80u);
  EXPECT_TRUE(std::isnan(result.raster.values[1]));  // column 1: not a multiple of 4
  EXPECT_FALSE(std::isnan(result.raster.values[4]));
}

TEST(IndicatorMap, RejectsInvalidRequests) {
  IndicatorRequest r = small(IndicatorKind::Dig);
  r.width = 0;
  EXPECT_TRUE(validationError(r));
  r.width = 16384;
  r.height = 16384;  // 2^28 pixels
  EXPECT_TRUE(validationError(r));
  r.height = 10;
  r.passes = 0;
  EXPECT_TRUE(validationError(r));
  r.passes = 13;
  EXPECT_TRUE(validationError(r));
  r.passes = 2;
  r.measure.kind = IndicatorKind::Rotation;
  r.measure.map = {1.5, -1.5, 0.5};  // no elliptic centre
  EXPECT_TRUE(validationError(r));
  EXPECT_THROW((void)computeIndicatorMap(r), std::invalid_argument);
  r.measure.map = kBox;
  r.measure.iterations = kMaxIterations + 1;
  EXPECT_TRUE(validationError(r));
}

TEST(IndicatorMap, ChaoticShareOfTheWholeBoxAgreesWithTheStochasticArea) {
  // b₂ (§5): the fraction of the 1024 × 1024 boxes of the torus visited by randomized trapping orbits (2^26 steps:
  // 0.8097; it grows by 0.0014 more up to 2^30).  The dig map: 128 × 128 pixels, T = 2·10⁴.
  StochasticAreaRequest area;
  area.map = kBox;
  area.iterations = std::uint64_t{1} << 26;
  area.firstCheckpoint = area.iterations;
  const StochasticAreaResult b2 = computeStochasticArea(area);
  IndicatorRequest r;
  r.measure.map = kBox;
  r.measure.kind = IndicatorKind::Dig;
  r.measure.iterations = 20000;
  r.width = r.height = 128;
  r.passes = 1;
  const IndicatorRaster raster = computeIndicatorMap(r).raster;
  double chaotic = 0, escapingVisited = 0, chaoticUnvisited = 0, regularVisited = 0;
  for (int row = 0; row < 128; ++row)
    for (int col = 0; col < 128; ++col) {
      const UnitState z = indicatorPixelStart(r.view, 128, 128, col, row);
      const bool visited = b2.visited[(z.Y >> 42) * 1024 + (z.X >> 42)] != 0;
      const OrbitVerdict v = raster.verdicts[static_cast<std::size_t>(row * 128 + col)];
      chaotic += v == OrbitVerdict::Chaotic;
      escapingVisited += v == OrbitVerdict::Escaping && visited;
      chaoticUnvisited += v == OrbitVerdict::Chaotic && !visited;
      regularVisited += v == OrbitVerdict::Regular && visited;
    }
  const double n = 128.0 * 128.0;
  // b₂'s orbits are randomized (Y ← Y + U) in the strip X ≤ Xr: some land in accelerator-mode islands of Q*, which
  // the dig map calls Escaping (regular on the torus, not orbits of Q), so b₂ counts those too.  The sea as b₂ sees
  // it is then the chaotic pixels plus the escaping ones in boxes it visited.  Tolerance 0.015: three standard
  // deviations of a share of 16384 sampled points (3·√(0.81·0.19/16384) = 0.009), plus the layer of boxes that
  // b₂ counts at island edges (regular pixels in visited boxes, measured 0.35 %), plus regular orbits that have
  // not converged to 9 digits at T = 2·10⁴ (chaotic pixels in boxes no sea orbit reached, measured 0.5 %), plus
  // what b₂ still lacks at 2^26 steps (0.14 %).
  EXPECT_NEAR((chaotic + escapingVisited) / n, b2.fraction(), 0.015);
  // Pixel by pixel, the two agree but for those thin layers.
  EXPECT_LT(chaoticUnvisited / n, 0.01);
  EXPECT_LT(regularVisited / n, 0.01);
  // Without the accelerator islands the chaotic share is smaller than b₂ (by 0.015 here).
  EXPECT_LT(chaotic / n, b2.fraction());
  EXPECT_GT(escapingVisited / n, 0.005);
}

}  // namespace
}  // namespace archipelago
