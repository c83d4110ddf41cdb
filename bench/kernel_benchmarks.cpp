// Speed of the map kernels and of the trapping pipeline (issue 4).  Every benchmark reports a counter
// "steps_per_second" (steps of N or N⁻¹ per second of wall time); bench/run-benchmarks.sh turns them into
// ratios.  Pipeline CPU times are of the whole process (all threads).  Names: bare_step/<kernel>, naive_double, pipeline/<kernel>/q:<q>/threads:<t>.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "kernels/KernelDispatch.hpp"
#include "trapping/TrappingRun.hpp"

namespace archipelago {
namespace {

const MapParameters kPaperBox{0.1, -0.8, 0.5};  // the paper's K = 0.1 case (§5)

// Steps per wall-clock second, and steps per iteration so that the script can also divide by CPU time (the
// machine may be shared: CPU time then shows what the code does, wall time what the user gets).
void reportSteps(benchmark::State& state, double steps) {
  state.counters["steps_per_second"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["steps_per_iteration"] = benchmark::Counter(steps, benchmark::Counter::kAvgIterations);
}

// The bare map: N⁻¹ on 48 independent orbits (6 vectors of 8 for AVX-512), no bookkeeping.
void bareStep(benchmark::State& state, OrbitKernel kernel) {
  const MapCoefficients coefficients = computeCoefficients(kPaperBox);
  std::vector<UnitState> orbits(48);
  for (std::size_t i = 0; i < orbits.size(); ++i) orbits[i] = {(i + 1) * 0x123456789ABull % fixedpoint::kOne, i};
  constexpr std::uint64_t kSteps = 1 << 16;
  for (auto _ : state) {
    kernel(coefficients, MapDirection::backward, orbits, kSteps, nullptr);
    benchmark::DoNotOptimize(orbits.data());
  }
  reportSteps(state, static_cast<double>(state.iterations()) * kSteps * static_cast<double>(orbits.size()));
}

// What a straightforward port would do: Q* in double precision, one orbit after another, reduced to the box
// by comparisons every step.
void naiveDouble(benchmark::State& state) {
  const double K = kPaperBox.K, xmin = kPaperBox.xmin, L = kPaperBox.width();
  std::vector<double> xs(48), ys(48);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    xs[i] = xmin + L * (static_cast<double>(i) + 0.5) / 48;
    ys[i] = 0.01 * static_cast<double>(i);
  }
  constexpr std::uint64_t kSteps = 1 << 14;
  for (auto _ : state) {
    for (std::size_t i = 0; i < xs.size(); ++i) {
      double x = xs[i], y = ys[i];
      for (std::uint64_t j = 0; j < kSteps; ++j) {
        y += 2 * (x * x - K);
        if (y >= L / 2) y -= L;
        if (y < -L / 2) y += L;
        x += y;
        if (x >= xmin + L) x -= L;
        if (x < xmin) x += L;
      }
      xs[i] = x;
      ys[i] = y;
    }
    benchmark::DoNotOptimize(xs.data());
  }
  reportSteps(state, static_cast<double>(state.iterations()) * kSteps * static_cast<double>(xs.size()));
}

// The whole engine, runTrapping(), on the paper's K = 0.1 box with Xr = 0.02: randomizing zone, q steps of
// N⁻¹ per block, segment bookkeeping, histograms, longest segments, OpenMP over groups of orbits.
void pipeline(benchmark::State& state, BlockKernel kernel, std::uint32_t q, int threads, double stepsPerIteration) {
  TrappingParameters p;
  p.map = kPaperBox;
  p.q = q;
  p.M = 256;
  p.T = static_cast<std::uint64_t>(stepsPerIteration / (static_cast<double>(p.M) * q)) + 1;
  TrappingRunOptions options;
  options.threads = threads;
  options.kernel = kernel;
  options.chunkSeconds = 1.0;
  double steps = 0;
  std::uint64_t segments = 0;
  for (auto _ : state) {
    const TrappingState done = runTrapping(startTrapping(p), options);
    steps += done.stepsDone();
    segments += done.total().segments();
  }
  reportSteps(state, steps);
  state.counters["segments_per_block"] =
      static_cast<double>(segments) / (steps / q);  // how often the bookkeeping runs
}

void registerAll() {
  for (const auto& k : supportedKernels())
    benchmark::RegisterBenchmark(("bare_step/" + std::string(k.name)).c_str(), bareStep, k.orbits)
        ->UseRealTime()
        ->MinTime(0.3);
  benchmark::RegisterBenchmark("naive_double", naiveDouble)->UseRealTime()->MinTime(0.3);
  for (const auto& k : supportedKernels()) {
    // About 0.1–1 s per iteration whatever the path.
    const double steps = k.kind == KernelKind::scalar ? 1.5e8 : k.kind == KernelKind::avx2 ? 3e8 : 1.2e9;
    for (const std::uint32_t q : {1u, 16u, 100u})
      for (const int threads : {1, 2})
        benchmark::RegisterBenchmark(("pipeline/" + std::string(k.name) + "/q:" + std::to_string(q) +
                                      "/threads:" + std::to_string(threads))
                                         .c_str(),
                                     pipeline, k.blocks, q, threads, steps * threads)
            ->UseRealTime()
            ->MeasureProcessCPUTime()
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.5);
  }
}

}  // namespace
}  // namespace archipelago

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  archipelago::registerAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
