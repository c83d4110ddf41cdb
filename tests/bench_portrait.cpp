// Benchmark: 10^8 orbit points of the exact map into a 1024 × 1024 density raster (issue 6's target: <= 1 s
// on two cores).  Prints the rate; run by scripts/bench-portrait.sh, never as a timed test.
#include <benchmark/benchmark.h>

#include <omp.h>

#include "core/portrait/PortraitRenderer.hpp"

namespace {

void densityIntoMegapixel(benchmark::State& state) {
  archipelago::PortraitRequest request;  // the paper's K = 0.1 box, whole view
  request.width = request.height = 1024;
  request.points = static_cast<std::uint64_t>(state.range(0));
  request.passes = 1;
  std::uint64_t points = 0;
  for (auto _ : state) {
    const auto result = archipelago::renderPortrait(request);
    points += result.raster.pointsIterated;
    benchmark::DoNotOptimize(result.raster.counts.data());
  }
  state.counters["points/s"] = benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate);
  state.counters["threads"] = omp_get_max_threads();
}

}  // namespace

BENCHMARK(densityIntoMegapixel)->Arg(100'000'000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK_MAIN();
