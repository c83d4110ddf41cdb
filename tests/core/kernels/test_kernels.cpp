// Every instruction-set path gives bit-identical results to the scalar reference (issue 4; docs/design.md,
// "Arithmetic contract"): orbit states, wrap-ended segments, histograms and longest segments.
#include <gtest/gtest.h>

#include <cfenv>
#include <random>
#include <string>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/run/TrappingRun.hpp"
#include "tests/core/kernels/KernelsUnderTest.hpp"

namespace archipelago {
namespace {

// The parameter sets of tests/core/map/test_fixed_point_map.cpp: the paper's K = 0.1 box, the small-K boxes of
// §4, and larger K and boxes (m from 0 to 4).
const std::vector<MapParameters> kParameterSets = {
    {0.1, -0.8, 0.5}, {0.0, -0.05, 0.05}, {-1e-4, -0.05, 0.05}, {1e-4, -0.05, 0.05}, {0.5, -1.5, 1.5},
    {1.0, -2.0, 0.25},
};
const std::vector<std::uint32_t> kPowers = {1, 2, 16, 100};
// Odd counts leave ragged tails in every vector width; 32 and 64 fill whole groups.
const std::vector<std::size_t> kOrbitCounts = {1, 3, 7, 13, 32, 45, 64};

std::vector<KernelInfo> vectorKernels() {
  std::vector<KernelInfo> v;
  for (const auto& k : kerneltests::kernelsUnderTest())
    if (k.kind != KernelKind::scalar) v.push_back(k);
  return v;
}

// A random but consistent orbit state in the middle of a run: an open segment of some length that began at
// some random state, and arbitrary block and draw counters.  Some states start at the torus' edges, where
// steps wrap, and some inside the randomizing zone.
OrbitState randomOrbit(std::mt19937_64& rng, std::uint64_t Xr) {
  OrbitState s;
  s.z = {rng() >> 12, rng() >> 12};
  switch (rng() % 6) {
    case 0: s.z.X = rng() % (Xr + 1); break;
    case 1: s.z.Y = fixedpoint::kMask - rng() % 4096; break;
    case 2: s.z.X = fixedpoint::kMask - rng() % 4096; break;
    default: break;
  }
  s.block = rng() % 100'000;
  s.length = rng() % 3 == 0 ? 0 : rng() % (s.block + 1);
  s.draws = rng() % 1000;
  s.start = {{rng() >> 12, rng() >> 12}, s.block - s.length, s.draws - std::min(s.draws, rng() % 10)};
  return s;
}

struct Outcome {
  std::vector<OrbitState> orbits;
  SegmentSink sink;
};

Outcome runKernel(BlockKernel kernel, const KernelSettings& k, std::vector<OrbitState> orbits,
                  std::uint64_t firstOrbit, std::uint64_t blocks, std::uint64_t calls) {
  Outcome out{std::move(orbits), SegmentSink(7, 20)};
  for (std::uint64_t c = 0; c < calls; ++c) kernel(k, out.orbits, firstOrbit, blocks, out.sink);
  return out;
}

void expectSame(const Outcome& expected, const Outcome& actual) {
  ASSERT_EQ(expected.orbits.size(), actual.orbits.size());
  for (std::size_t i = 0; i < expected.orbits.size(); ++i)
    ASSERT_EQ(expected.orbits[i], actual.orbits[i]) << "orbit " << i;
  EXPECT_EQ(expected.sink.subsets(), actual.sink.subsets());
  EXPECT_EQ(expected.sink.longest(), actual.sink.longest());
}

TEST(VectorKernels, BlockKernelsMatchScalarOnRandomStates) {
  const auto kernels = vectorKernels();
  if (kernels.empty()) GTEST_SKIP() << "this CPU has no vector path";
  std::uint64_t segments = 0;
  for (std::size_t set = 0; set < kParameterSets.size(); ++set) {
    for (const std::uint32_t q : kPowers) {
      for (const std::size_t n : kOrbitCounts) {
        std::mt19937_64 rng(1000 * set + 10 * q + n);
        // Alternate a narrow and a wide randomizing zone, so that both wraps and draws end segments.
        const double Xr = (n % 2) ? 0.02 : 0.3;
        const KernelSettings k{computeCoefficients(kParameterSets[set]), randomizingThreshold(Xr), q,
                               rng() % 1000};
        std::vector<OrbitState> orbits(n);
        for (auto& s : orbits) s = randomOrbit(rng, k.randomizingX);
        const std::uint64_t firstOrbit = rng() % 10'000;
        const std::uint64_t blocks = 4000 / q + 1;
        const Outcome expected = runKernel(&advanceBlocksScalar, k, orbits, firstOrbit, blocks, 2);
        segments += expected.sink.longest().items().size();
        for (const auto& kernel : kernels) {
          SCOPED_TRACE(testing::Message() << kernel.name << " set " << set << " q=" << q << " n=" << n);
          expectSame(expected, runKernel(kernel.blocks, k, orbits, firstOrbit, blocks, 2));
        }
      }
    }
  }
  EXPECT_GT(segments, 1000u);  // segments did end, so the bookkeeping was exercised
}

// Fresh orbits start at X = 0, inside the zone: the first segment is not recorded (SegmentSink::record).
TEST(VectorKernels, BlockKernelsMatchScalarFromFreshOrbits) {
  for (const auto& kernel : vectorKernels()) {
    for (const std::uint32_t q : {1u, 16u}) {
      const KernelSettings k{computeCoefficients({0.1, -0.8, 0.5}), randomizingThreshold(0.02), q, 5};
      const std::vector<OrbitState> orbits(29);
      const Outcome expected = runKernel(&advanceBlocksScalar, k, orbits, 3, 500, 3);
      SCOPED_TRACE(testing::Message() << kernel.name << " q=" << q);
      expectSame(expected, runKernel(kernel.blocks, k, orbits, 3, 500, 3));
      EXPECT_GT(expected.sink.subsets()[0].segments(), 0u);
    }
  }
}

// A short longest list over a long call: its threshold soon exceeds the 64 blocks over which the vector
// paths look ahead for candidate lanes (SimdDriver.inl), so segments born during the call must still be
// found when they grow past it.
TEST(VectorKernels, LongestSegmentsBornDuringALongCallAreKept) {
  const auto kernels = vectorKernels();
  if (kernels.empty()) GTEST_SKIP() << "this CPU has no vector path";
  const KernelSettings k{computeCoefficients({0.1, -0.8, 0.5}), randomizingThreshold(0.02), 1, 11};
  const std::vector<OrbitState> orbits(64);
  const auto run = [&](BlockKernel kernel) {
    Outcome out{orbits, SegmentSink(3, 300)};
    kernel(k, out.orbits, 0, 60'000, out.sink);
    return out;
  };
  const Outcome expected = run(&advanceBlocksScalar);
  ASSERT_EQ(expected.sink.longest().items().size(), 300u);
  EXPECT_GT(expected.sink.longest().items().back().length, 2u * 64);  // well past the look-ahead
  for (const auto& kernel : kernels) {
    SCOPED_TRACE(kernel.name);
    expectSame(expected, run(kernel.blocks));
  }
}

TEST(VectorKernels, OrbitIterationMatchesScalarWithTrace) {
  for (const auto& kernel : kerneltests::kernelsUnderTest()) {
    for (std::size_t set = 0; set < kParameterSets.size(); ++set) {
      const MapCoefficients coefficients = computeCoefficients(kParameterSets[set]);
      for (const auto direction : {MapDirection::forward, MapDirection::backward}) {
        for (const std::size_t n : {1ul, 5ul, 13ul, 50ul}) {
          std::mt19937_64 rng(set * 100 + n);
          std::vector<UnitState> start(n);
          for (auto& z : start) z = {rng() >> 12, rng() >> 12};
          constexpr std::uint64_t kSteps = 300;
          // The definition: FixedPointMap.hpp's steps, one orbit at a time.
          std::vector<UnitState> expectedTrace(kSteps * n);
          std::vector<UnitState> expected = start;
          for (std::size_t i = 0; i < n; ++i)
            for (std::uint64_t j = 0; j < kSteps; ++j) {
              direction == MapDirection::forward ? forwardStep(coefficients, expected[i])
                                                 : backwardStep(coefficients, expected[i]);
              expectedTrace[j * n + i] = expected[i];
            }
          std::vector<UnitState> withTrace = start, withoutTrace = start;
          std::vector<UnitState> trace(kSteps * n);
          kernel.orbits(coefficients, direction, withTrace, kSteps, trace.data());
          kernel.orbits(coefficients, direction, withoutTrace, kSteps, nullptr);
          SCOPED_TRACE(testing::Message() << kernel.name << " set " << set << " n=" << n);
          EXPECT_EQ(withTrace, expected);
          EXPECT_EQ(withoutTrace, expected);
          EXPECT_EQ(trace, expectedTrace);
        }
      }
    }
  }
}

// States at the edges of the arithmetic, where the AVX2 path's floors (doubles rounded down) and reductions
// are closest to going wrong: X − Y + 2^51 at 0 and 2^52 exactly, G(X) at multiples of 2^52, X and Y at 0
// (which the double path may hold as −0.0) and at 2^52 − 1, in boxes with m from 0 to 9.  Each step is
// compared with FixedPointMap.hpp's, and the block kernels at q = 1 with the scalar one (wraps end segments).
TEST(VectorKernels, EdgeStatesMatchScalarStepByStep) {
  using fixedpoint::kHalf;
  using fixedpoint::kMask;
  const std::vector<std::uint64_t> special = {0, 1, 2, kHalf - 1, kHalf, kHalf + 1, kMask - 1, kMask,
                                              0x000FFFFF00000000ull, 0x0008000000000001ull};
  std::vector<MapParameters> boxes = kParameterSets;
  boxes.push_back({1.0, -100.0, 100.0});  // m = 9, the largest shift FixedPointMap allows
  for (const auto& box : boxes) {
    const MapCoefficients c = computeCoefficients(box);
    std::vector<UnitState> start;
    for (const std::uint64_t X : special)
      for (const std::uint64_t Y : special) start.push_back({X, Y});
    // Y chosen so that X − Y + 2^51 is exactly 0 or 2^52, and Y = G(X) mod 2^52 (u = 0 after the step).
    for (const std::uint64_t X : special) {
      start.push_back({X, (X + kHalf) & kMask});
      const std::uint64_t Xn = (X - X + kHalf) & kMask;  // the X after a step from (X, X)
      start.push_back({X, static_cast<std::uint64_t>(fixedPointG(c, Xn)) & kMask});
    }
    for (const auto direction : {MapDirection::forward, MapDirection::backward}) {
      constexpr std::uint64_t kSteps = 40;
      std::vector<UnitState> expectedTrace(kSteps * start.size());
      for (std::size_t i = 0; i < start.size(); ++i) {
        UnitState z = start[i];
        for (std::uint64_t j = 0; j < kSteps; ++j) {
          direction == MapDirection::forward ? forwardStep(c, z) : backwardStep(c, z);
          expectedTrace[j * start.size() + i] = z;
        }
      }
      for (const auto& kernel : vectorKernels()) {
        std::vector<UnitState> orbits = start;
        std::vector<UnitState> trace(kSteps * start.size());
        kernel.orbits(c, direction, orbits, kSteps, trace.data());
        SCOPED_TRACE(testing::Message() << kernel.name << " m=" << c.m);
        EXPECT_EQ(trace, expectedTrace);
      }
    }
    const KernelSettings k{c, randomizingThreshold(0.02), 1, 9};
    std::vector<OrbitState> orbits(start.size());
    for (std::size_t i = 0; i < start.size(); ++i) {
      orbits[i].z = start[i];
      orbits[i].start = {start[i], 1, 0};
      orbits[i].block = 1;
    }
    const Outcome expected = runKernel(&advanceBlocksScalar, k, orbits, 0, 30, 1);
    EXPECT_GT(expected.sink.longest().items().size(), 0u);
    for (const auto& kernel : vectorKernels()) {
      SCOPED_TRACE(testing::Message() << kernel.name << " blocks, m=" << c.m);
      expectSame(expected, runKernel(kernel.blocks, k, orbits, 0, 30, 1));
    }
  }
}

// The paths that change the floating-point environment (AVX2: rounding down) restore the caller's.
TEST(VectorKernels, KernelsLeaveTheRoundingModeAsTheyFoundIt) {
  const MapCoefficients c = computeCoefficients({0.1, -0.8, 0.5});
  for (const int mode : {FE_TONEAREST, FE_UPWARD}) {
    ASSERT_EQ(std::fesetround(mode), 0);
    for (const auto& kernel : kerneltests::kernelsUnderTest()) {
      std::vector<UnitState> orbits = {{123, 456}, {fixedpoint::kMask, 0}};
      kernel.orbits(c, MapDirection::backward, orbits, 10, nullptr);
      SegmentSink sink(1, 1);
      std::vector<OrbitState> states(3);
      kernel.blocks({c, randomizingThreshold(0.02), 1, 1}, states, 0, 10, sink);
      EXPECT_EQ(std::fegetround(), mode) << kernel.name;
    }
  }
  std::fesetround(FE_TONEAREST);
}

#if defined(__GLIBC__)
// A caller that traps floating-point exceptions (here inexact results, which nearly every AVX2 step has) still
// gets its results: the AVX2 path masks them while it runs, and the traps are back afterwards.
TEST(VectorKernels, KernelsRunUnderTrappedFloatingPointExceptions) {
  const MapCoefficients c = computeCoefficients({0.1, -0.8, 0.5});
  const auto kernels = kerneltests::kernelsUnderTest();
  std::vector<UnitState> orbits = {{123, 456}, {fixedpoint::kMask, 0}};
  std::vector<UnitState> expected = orbits;
  iterateOrbitsScalar(c, MapDirection::backward, expected, 50, nullptr);
  for (const auto& kernel : kernels) {
    std::vector<UnitState> z = orbits;
    std::feclearexcept(FE_ALL_EXCEPT);  // a flag raised earlier (x87 keeps them pending) would trap at once
    feenableexcept(FE_INEXACT | FE_UNDERFLOW | FE_INVALID);
    kernel.orbits(c, MapDirection::backward, z, 50, nullptr);
    const int traps = fegetexcept();
    fedisableexcept(FE_ALL_EXCEPT);
    EXPECT_EQ(traps, FE_INEXACT | FE_UNDERFLOW | FE_INVALID) << kernel.name;
    EXPECT_EQ(z, expected) << kernel.name;
  }
}
#endif

// The whole engine: chunks, threads and groups, with each path.
TEST(VectorKernels, RunTrappingMatchesScalar) {
  TrappingParameters p;
  p.q = 16;
  p.T = 3000;
  p.M = 75;  // an odd count: the last group is ragged
  p.seed = 42;
  p.subsets = 5;
  p.longestKept = 30;
  TrappingRunOptions scalar;
  scalar.kernel = &kernelByName("scalar");
  scalar.threads = 2;
  scalar.maxChunkBlocks = 700;
  const TrappingState expected = runTrapping(startTrapping(p), scalar);
  ASSERT_GT(expected.total().segments(), 1000u);
  for (const auto& kernel : vectorKernels()) {
    for (const int threads : {1, 2}) {
      TrappingRunOptions options = scalar;
      options.threads = threads;
      options.kernel = &kernel;
      const TrappingState actual = runTrapping(startTrapping(p), options);
      SCOPED_TRACE(testing::Message() << kernel.name << " threads=" << threads);
      EXPECT_EQ(actual.orbits, expected.orbits);
      EXPECT_EQ(actual.subsets, expected.subsets);
      EXPECT_EQ(actual.longest, expected.longest);
      EXPECT_EQ(actual.kernel, kernel.name);
    }
  }
}

}  // namespace
}  // namespace archipelago
