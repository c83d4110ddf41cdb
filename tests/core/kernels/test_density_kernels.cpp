// The density-binning kernels (VectorKernels.hpp, DensityKernel) of every path give the same orbit states as
// the orbit kernels and the same counts, carries and totals as binning the scalar trace with RasterGrid::pixelOf.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "tests/core/kernels/KernelsUnderTest.hpp"

namespace archipelago {
namespace {

struct Binned {
  std::vector<UnitState> orbits;
  std::vector<std::uint64_t> counts;  // 8-bit counts plus 256 per carry
  std::uint64_t total = 0;
};

Binned runDensity(DensityKernel kernel, const MapCoefficients& c, std::vector<UnitState> orbits,
                  std::uint64_t steps, const RasterGrid& grid, int calls) {
  std::vector<std::uint8_t> counts(static_cast<std::size_t>(grid.iw * grid.ih), 0);
  std::vector<std::uint32_t> carries;
  Binned out;
  for (int i = 0; i < calls; ++i) out.total += kernel(c, orbits, steps, grid, counts.data(), carries);
  out.orbits = std::move(orbits);
  out.counts.assign(counts.begin(), counts.end());
  for (std::uint32_t p : carries) out.counts[p] += 256;
  return out;
}

// The reference: scalar orbit iteration with a trace, every traced point binned with pixelOf.
Binned reference(const MapCoefficients& c, std::vector<UnitState> orbits, std::uint64_t steps,
                 const RasterGrid& grid, int calls) {
  Binned out;
  out.counts.assign(static_cast<std::size_t>(grid.iw * grid.ih), 0);
  std::vector<UnitState> trace(steps * orbits.size());
  for (int i = 0; i < calls; ++i) {
    iterateOrbitsScalar(c, MapDirection::forward, orbits, steps, trace.data());
    for (const UnitState& z : trace) {
      const std::int64_t p = grid.pixelOf(z);
      if (p < 0) continue;
      out.counts[static_cast<std::size_t>(p)] += 1;
      out.total += 1;
    }
  }
  out.orbits = std::move(orbits);
  return out;
}

TEST(DensityKernels, MatchScalarTraceBinning) {
  const MapCoefficients c = computeCoefficients({0.1, -0.8, 0.5});
  std::mt19937_64 rng(42);
  // A whole-box grid (every point inside), a small zoomed grid (most points outside, some pixels hit more
  // than 256 times so that carries occur) and a non-square one off-centre.
  const std::uint64_t one = fixedpoint::kOne;
  const std::vector<RasterGrid> grids = {
      {one / 2, one / 2, 64.0 / static_cast<double>(one), 48.0 / static_cast<double>(one), 32, 24, 64, 48, 64, 48},
      {one / 3, one / 5, 4.0 / (static_cast<double>(one) / 8), 4.0 / (static_cast<double>(one) / 8), 2, 2, 4, 4, 4, 4},
      {one / 10, one - 5, 7.0 / (static_cast<double>(one) / 3), 5.0 / (static_cast<double>(one) / 2), 3.5, 2.5, 7, 5,
       7, 5},
  };
  for (const auto& kernel : kerneltests::kernelsUnderTest()) {
    for (std::size_t g = 0; g < grids.size(); ++g) {
      std::uint64_t pointsInGrid = 0;  // the comparison means something only when points land in the grid
      for (const std::size_t n : {1u, 5u, 8u, 13u, 32u, 45u}) {
        std::vector<UnitState> orbits(n);
        for (auto& z : orbits) z = {rng() >> 12, rng() >> 12};
        const Binned want = reference(c, orbits, 300, grids[g], 3);
        const Binned got = runDensity(kernel.density, c, orbits, 300, grids[g], 3);
        SCOPED_TRACE(std::string(kernel.name) + " grid " + std::to_string(g) + " n " + std::to_string(n));
        ASSERT_EQ(got.orbits, want.orbits);
        ASSERT_EQ(got.total, want.total);
        ASSERT_EQ(got.counts, want.counts);
        pointsInGrid += want.total;
      }
      EXPECT_GT(pointsInGrid, 100u) << "grid " << g;
    }
  }
}

// The carries path: a 1 × 1 grid over the whole box counts every point, so its 8-bit count wraps many times.
TEST(DensityKernels, CarriesCountEveryWrap) {
  const MapCoefficients c = computeCoefficients({0.1, -0.8, 0.5});
  const std::uint64_t one = fixedpoint::kOne;
  const RasterGrid whole{one / 2, one / 2, 1.0 / static_cast<double>(one), 1.0 / static_cast<double>(one),
                         0.5, 0.5, 1, 1, 1, 1};
  for (const auto& kernel : kerneltests::kernelsUnderTest()) {
    std::vector<UnitState> orbits(9, UnitState{12345, 678});
    for (std::size_t i = 0; i < orbits.size(); ++i) orbits[i].X += i * 1000;
    const Binned got = runDensity(kernel.density, c, orbits, 1000, whole, 1);
    EXPECT_EQ(got.total, 9000u) << kernel.name;
    EXPECT_EQ(got.counts[0], 9000u) << kernel.name;
  }
}

}  // namespace
}  // namespace archipelago
