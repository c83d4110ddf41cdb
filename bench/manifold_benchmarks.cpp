// Speed of core/manifolds (issue 28): drawing a branch with adaptive refinement (the hot loop of a zoomed portrait,
// which refines the visible part of the manifolds at every zoom) and computing a flux.  Each benchmark reports
// "points_per_second" (refined points of the branch per second of wall time) or the time of one flux.
//
//   cmake --build build-bench --target manifold_benchmarks && build-bench/bench/manifold_benchmarks
//
// Names: branch/<what>: computeManifoldCurve of the fixed point's inner unstable branch at K = 0.1 — plane (the
// loop and its lobes, escaping), box (Q* in the paper's box, cut at the wraps), view (a zoomed view 0.01 wide at the
// tip of the loop, refined to 1e−5 there), six (the period-6 chain's outer branch); flux/<what>: computeTurnstileFlux
// (fixed point at K = 0.1, the period-6 and the 138-chain).
#include <benchmark/benchmark.h>

#include "core/manifolds/ManifoldCurve.hpp"
#include "core/manifolds/TurnstileFlux.hpp"
#include "core/periodic/HyperbolicPartner.hpp"

namespace archipelago {
namespace {

PeriodicOrbit chain(int period, PhysicalPoint near, long double radius) {
  PeriodicOrbitSearch s;
  s.period = period;
  s.near = near;
  s.searchRadius = radius;
  return findHyperbolicOrbit(0.1L, s);
}

void branch(benchmark::State& state, ManifoldCurveRequest request) {
  std::size_t points = 0;
  for (auto _ : state) {
    const ManifoldCurve c = computeManifoldCurve(request);
    points += c.points;
    benchmark::DoNotOptimize(c.length);
  }
  state.counters["points_per_second"] = benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate);
  state.counters["points_per_iteration"] = benchmark::Counter(static_cast<double>(points), benchmark::Counter::kAvgIterations);
}

ManifoldCurveRequest plane() {
  ManifoldCurveRequest r;
  r.K = 0.1L;
  r.length = 20;
  return r;
}

void flux(benchmark::State& state, TurnstileRequest request) {
  for (auto _ : state) benchmark::DoNotOptimize(computeTurnstileFlux(request).lobeArea);
}

void registerAll() {
  benchmark::RegisterBenchmark("branch/plane", branch, plane())->Unit(benchmark::kMillisecond);
  ManifoldCurveRequest box = plane();
  box.box = MapParameters{0.1, -0.8, 0.5};
  benchmark::RegisterBenchmark("branch/box", branch, box)->Unit(benchmark::kMillisecond);
  ManifoldCurveRequest view = plane();
  view.view = PhysicalRect{-0.69L, -0.68L, -0.37L, -0.36L};
  view.maxSpacing = 1e-5L;
  benchmark::RegisterBenchmark("branch/view", branch, view)->Unit(benchmark::kMillisecond);
  ManifoldCurveRequest six = plane();
  six.orbit = chain(6, {0.0157L, 0}, 0.01L);
  six.side = BranchSide::Outward;
  six.length = 4;
  benchmark::RegisterBenchmark("branch/six", branch, six)->Unit(benchmark::kMillisecond);
  TurnstileRequest fixed;
  fixed.K = 0.1L;
  benchmark::RegisterBenchmark("flux/fixed_point", flux, fixed)->Unit(benchmark::kMillisecond);
  TurnstileRequest sixFlux = fixed;
  sixFlux.orbit = six.orbit;
  sixFlux.side = BranchSide::Outward;
  benchmark::RegisterBenchmark("flux/six", flux, sixFlux)->Unit(benchmark::kMillisecond);
  TurnstileRequest long138 = sixFlux;
  long138.orbit = chain(138, {0.0358L, 0.034L}, 0.005L);
  benchmark::RegisterBenchmark("flux/138", flux, long138)->Unit(benchmark::kMillisecond)->Iterations(1);
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
