// Speed of the map kernels and of the trapping pipeline (issue 4).  Every benchmark reports a counter
// "steps_per_second" (steps of N or N⁻¹ per second of wall time) and "steps_per_iteration"; bench/run-benchmarks.sh
// runs each several times (--benchmark_repetitions, randomly interleaved) and turns the medians into ratios.
// Multi-threaded CPU times are of the whole process (all threads).  Names: bare_step/<kernel>,
// bare_step/<kernel>/threads:2, naive_double, pipeline/<kernel>/q:<q>/threads:<t>, measure/<kind>/<kernel> (the
// orbit measures of issue 27: iterate N and accumulate, one thread), indicator/<kind>/<kernel> (a whole indicator
// map, issue 27), rotation/profile/<kernel> and rotation/number/scalar (rotation numbers: a profile along a segment,
// one chain-identification measurement), tail/<what>/<kernel> (the tail sampler, issue 29), manifold/branch_<what>
// (manifold refinement, issue 28: "steps" there are refined points of the branch), and the paired ratios
// paired/<what>, which report a counter "ratio" (see pairedRatio).  The JSON's context names the CPU (cpu_model,
// cpu_flags: see main), so that a kept result names the machine it was measured on.
//
// Each repetition is kept short (a few tenths of a second): on a shared machine the speed changes over
// minutes, and many short interleaved repetitions let slow periods hit every benchmark alike.
#include <benchmark/benchmark.h>

#include <omp.h>

#include <time.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/manifolds/ManifoldCurve.hpp"
#include "core/measures/IndicatorMap.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/measures/RotationNumber.hpp"
#include "core/measures/RotationProfile.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/tail/TailSampler.hpp"

namespace archipelago {
namespace {

const MapParameters kPaperBox{0.1, -0.8, 0.5};  // the paper's K = 0.1 case (§5)

// Steps per wall-clock second, and steps per iteration so that the script can also divide by CPU time (the
// machine may be shared: CPU time then shows what the code does, wall time what the user gets).
void reportSteps(benchmark::State& state, double steps) {
  state.counters["steps_per_second"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["steps_per_iteration"] = benchmark::Counter(steps, benchmark::Counter::kAvgIterations);
}

// The bare map: N⁻¹ on 48 independent orbits (6 vectors of 8 for AVX-512), no bookkeeping.  With threads > 1,
// each OpenMP thread iterates its own 48 orbits (in its own cache lines) with the same kernel, and the rate
// is the total over the threads: what the hardware itself allows, for the pipeline's 2-thread scaling.  An
// iteration is one parallel region of 2^20 steps per orbit (≈ 13 ms with AVX-512 IFMA), long enough that the
// fork and the barriers cost little; when a co-tenant holds the other vCPU the region waits for the delayed
// thread (run-benchmarks.sh prints the CPUs the process got).  One thread does the same calls without a region.
void bareStep(benchmark::State& state, OrbitKernel kernel, int threads) {
  struct alignas(64) OrbitSet {
    std::array<UnitState, 48> orbits;
  };
  const MapCoefficients coefficients = computeCoefficients(kPaperBox);
  std::vector<OrbitSet> sets(static_cast<std::size_t>(threads));
  for (std::size_t t = 0; t < sets.size(); ++t)
    for (std::size_t i = 0; i < 48; ++i)
      sets[t].orbits[i] = {(48 * t + i + 1) * 0x123456789ABull % fixedpoint::kOne, i};
  constexpr std::uint64_t kSteps = 1 << 20;
  int threadsRun = threads;
  for (auto _ : state) {
    if (threads == 1) {
      kernel(coefficients, MapDirection::backward, sets[0].orbits, kSteps, nullptr);
    } else {
#pragma omp parallel num_threads(threads)
      {
#pragma omp single
        threadsRun = omp_get_num_threads();
        kernel(coefficients, MapDirection::backward, sets[static_cast<std::size_t>(omp_get_thread_num())].orbits,
               kSteps, nullptr);
      }
    }
    benchmark::DoNotOptimize(sets.data());
  }
  if (threadsRun != threads) state.SkipWithError("OpenMP gave fewer threads than asked");
  reportSteps(state, static_cast<double>(state.iterations()) * kSteps * 48.0 * threads);
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
void pipeline(benchmark::State& state, const KernelInfo* kernel, std::uint32_t q, int threads, double stepsPerIteration) {
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

// The orbit measures (core/measures/OrbitMeasures.hpp): 512 orbits on a line across the K = 0.1 box (the central
// island, the six islands, the sea) measured by OrbitMeasurer on one thread, T = 10⁴ (2·10⁴ steps per orbit for
// dig and rotation, 10⁴ for fli, megno and lyapunov).  Steps of N per second, comparable with the bare step.
void measureOrbits(benchmark::State& state, const KernelInfo* kernel, IndicatorKind kind) {
  MeasureSettings settings;
  settings.map = kPaperBox;
  settings.kind = kind;
  settings.iterations = 10000;
  settings.kernel = kernel;
  const OrbitMeasurer measurer(settings);
  const FixedPointMap map(kPaperBox);
  std::vector<UnitState> starts(512);
  for (std::size_t i = 0; i < starts.size(); ++i)
    starts[i] = map.toUnit(-0.7L + 1.1L * static_cast<long double>(i) / 512, 0.05L);
  std::vector<OrbitMeasure> out(starts.size());
  for (auto _ : state) {
    measurer.measure(starts, out, {}, 1);
    benchmark::DoNotOptimize(out.data());
  }
  reportSteps(state, static_cast<double>(state.iterations()) * static_cast<double>(stepsPerOrbit(settings)) *
                         static_cast<double>(starts.size()));
}

// --- Paired ratios -------------------------------------------------------------------------------------------
// A ratio of two rates measured minutes apart carries the machine's drift; here the two sides run alternately,
// a few tens of milliseconds each, A B B A A B …, and every iteration yields one ratio of rates: the counter
// "ratio" is the median over the iterations.  One-thread work is timed by the thread's CPU clock (time the
// guest took the vCPU away does not count), two-thread work by the wall clock.

/// Steps done, the seconds they took, and the CPUs the process got meanwhile (CPU time / wall time; 2-thread work
/// only, else 0).
struct Timed {
  double steps = 0;
  double seconds = 0;
  double cpus = 0;
};
using Work = std::function<Timed()>;

double threadSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
double processSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Work on one thread: the bare step of `kernel` on 48 orbits for `steps` steps each.
Work bareWork(OrbitKernel kernel, std::uint64_t steps) {
  auto orbits = std::make_shared<std::vector<UnitState>>(48);
  for (std::size_t i = 0; i < orbits->size(); ++i) (*orbits)[i] = {(i + 1) * 0x123456789ABull % fixedpoint::kOne, i};
  const MapCoefficients coefficients = computeCoefficients(kPaperBox);
  return [=] {
    const double t0 = threadSeconds();
    kernel(coefficients, MapDirection::backward, *orbits, steps, nullptr);
    benchmark::DoNotOptimize(orbits->data());
    return Timed{static_cast<double>(steps) * 48.0, threadSeconds() - t0};
  };
}

/// Work: runTrapping() on the K = 0.1 box, M = 256 orbits, T blocks of q steps, on `threads` threads, timed by
/// the wall clock when `wall` (always with more than one thread), else by the thread's CPU clock.
Work pipelineWork(const KernelInfo* kernel, std::uint32_t q, int threads, std::uint64_t T, bool wall = false) {
  TrappingParameters p;
  p.map = kPaperBox;
  p.q = q;
  p.M = 256;
  p.T = T;
  TrappingRunOptions options;
  options.threads = threads;
  options.kernel = kernel;
  options.chunkSeconds = 1.0;
  return [=] {
    const TrappingState start = startTrapping(p);
    const bool byWall = wall || threads > 1;
    const double t0 = byWall ? wallSeconds() : threadSeconds(), c0 = processSeconds();
    const TrappingState done = runTrapping(start, options);
    const double t1 = byWall ? wallSeconds() : threadSeconds(), c1 = processSeconds();
    return Timed{done.stepsDone(), t1 - t0, threads > 1 ? (c1 - c0) / (t1 - t0) : 0.0};
  };
}

/// Rate of `numerator` / rate of `denominator`, alternated; the counter "ratio" is the median of the
/// iterations' ratios.  (Two-thread work is wall-timed, and so is the one-thread side it is compared with; the
/// counter "cpus" is then the median of the CPUs the numerator's process got, so that a ratio measured while a
/// co-tenant held a vCPU can be told from one that measures scaling.)
void pairedRatio(benchmark::State& state, const Work& numerator, const Work& denominator) {
  std::vector<double> ratios, cpus;
  bool numeratorFirst = true;
  for (auto _ : state) {
    Timed a, b;
    if (numeratorFirst) {
      a = numerator();
      b = denominator();
    } else {
      b = denominator();
      a = numerator();
    }
    numeratorFirst = !numeratorFirst;
    ratios.push_back((a.steps / a.seconds) / (b.steps / b.seconds));
    cpus.push_back(a.cpus);
  }
  std::sort(ratios.begin(), ratios.end());
  std::sort(cpus.begin(), cpus.end());
  state.counters["ratio"] = ratios.empty() ? 0.0 : ratios[ratios.size() / 2];
  if (!cpus.empty() && cpus.back() > 0) state.counters["cpus"] = cpus[cpus.size() / 2];
}

void registerPaired() {
  // Pointers into the static table (allKernels()): the benchmarks run after this function returns.
  const CpuFeatures cpu = CpuFeatures::detect();
  const auto find = [&](KernelKind kind) -> const KernelInfo* {
    for (const auto& k : allKernels())
      if (k.kind == kind && supports(cpu, kind)) return &k;
    return nullptr;
  };
  const auto add = [](const std::string& name, Work numerator, Work denominator) {
    benchmark::RegisterBenchmark(("paired/" + name).c_str(),
                                 [=](benchmark::State& s) { pairedRatio(s, numerator, denominator); })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.5);
  };
  // Each side ≈ 20–60 ms.  Blocks per pipeline call for ~3·10^7 (scalar), 6·10^7 (avx2), 2·10^8 (avx512ifma)
  // steps on one thread.
  const auto T = [](const KernelInfo& k, std::uint32_t q, int threads) {
    const double steps = k.kind == KernelKind::scalar ? 1.5e7 : k.kind == KernelKind::avx2 ? 4e7 : 1.5e8;
    return static_cast<std::uint64_t>(steps * threads / (256.0 * q)) + 1;
  };
  const auto bareSteps = [](const KernelInfo& k) -> std::uint64_t {
    return k.kind == KernelKind::scalar ? 1u << 18 : k.kind == KernelKind::avx2 ? 1u << 19 : 1u << 21;
  };
  if (const KernelInfo* ifma = find(KernelKind::avx512ifma)) {
    for (const std::uint32_t q : {1u, 16u, 100u}) {
      add("pipeline_vs_bare/avx512ifma/q:" + std::to_string(q), pipelineWork(ifma, q, 1, T(*ifma, q, 1)),
          bareWork(ifma->orbits, bareSteps(*ifma)));
      add("two_threads_vs_one/avx512ifma/q:" + std::to_string(q), pipelineWork(ifma, q, 2, T(*ifma, q, 2)),
          pipelineWork(ifma, q, 1, T(*ifma, q, 1), true));
    }
  }
  const KernelInfo* avx2 = find(KernelKind::avx2);
  const KernelInfo* scalar = find(KernelKind::scalar);
  // Issue 41: the AVX-512F path against the AVX2 one it replaces on CPUs without IFMA (target: 1.5x at q = 16, 100).
  if (const KernelInfo* f = find(KernelKind::avx512f); f && avx2) {
    add("avx512f_vs_avx2/bare", bareWork(f->orbits, bareSteps(*f)), bareWork(avx2->orbits, bareSteps(*avx2)));
    for (const std::uint32_t q : {1u, 16u, 100u})
      add("avx512f_vs_avx2/q:" + std::to_string(q), pipelineWork(f, q, 1, T(*f, q, 1)),
          pipelineWork(avx2, q, 1, T(*avx2, q, 1)));
  }
  if (avx2 && scalar) {
    add("avx2_vs_scalar/bare", bareWork(avx2->orbits, bareSteps(*avx2)), bareWork(scalar->orbits, bareSteps(*scalar)));
    for (const std::uint32_t q : {1u, 16u, 100u})
      add("avx2_vs_scalar/q:" + std::to_string(q), pipelineWork(avx2, q, 1, T(*avx2, q, 1)),
          pipelineWork(scalar, q, 1, T(*scalar, q, 1)));
  }
}

// The tail sampler (core/tail, issue 29) on one thread, K = 0.1 box, q = 16.  tail/splitting/<kernel>: the splitting
// from t = 1008 to 10^6 steps (N = 200, R = 2, perturbed clones), started each iteration from the same population
// (stage 0 done once, outside the timing): walkers advanced in chunks by the block kernel, dead ones dropped at chunk
// boundaries, survivors resampled at each level.  tail/stage0/<kernel>: stage 0 alone (N = 100, R = 1, the first
// level at 1008 steps: a brute-force run of entry orbits, 32 at a time, with its pilot).  Steps of the sampler per
// second (TailState::steps: the map steps it computes), comparable with bare_step/<kernel>.
void tailSplitting(benchmark::State& state, const KernelInfo* kernel) {
  TailRequest r;
  r.population = 200;
  r.replicas = 2;
  r.maxSteps = 1'000'000;
  TailRunOptions options;
  options.threads = 1;
  options.kernel = kernel;
  options.untilLevel = 1;
  const TailState start = runTail(startTail(r), options);
  options.untilLevel = SIZE_MAX;
  double steps = 0;
  for (auto _ : state) {
    const TailState done = runTail(start, options);
    steps += static_cast<double>(done.steps - start.steps);
  }
  reportSteps(state, steps);
}

void tailStageZero(benchmark::State& state, const KernelInfo* kernel) {
  TailRequest r;
  r.population = 100;
  r.replicas = 1;
  r.maxSteps = 1000;
  TailRunOptions options;
  options.threads = 1;
  options.kernel = kernel;
  double steps = 0;
  for (auto _ : state) steps += static_cast<double>(runTail(startTail(r), options).steps);
  reportSteps(state, steps);
}

void registerTail() {
  for (const auto& k : supportedKernels()) {
    benchmark::RegisterBenchmark(("tail/splitting/" + std::string(k.name)).c_str(), tailSplitting,
                                 &kernelByName(k.name))
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.4);
    benchmark::RegisterBenchmark(("tail/stage0/" + std::string(k.name)).c_str(), tailStageZero, &kernelByName(k.name))
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.4);
  }
}

void registerMeasures() {
  for (const auto& k : supportedKernels())
    for (IndicatorKind kind : {IndicatorKind::Dig, IndicatorKind::Rotation, IndicatorKind::Fli, IndicatorKind::Megno,
                               IndicatorKind::Lyapunov})
      benchmark::RegisterBenchmark(("measure/" + std::string(toString(kind)) + "/" + std::string(k.name)).c_str(),
                                   measureOrbits, &kernelByName(k.name), kind)
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond)
          ->MinTime(0.25);
}

// An indicator map (core/measures/IndicatorMap.hpp) of the whole K = 0.1 box, one thread, T = 10⁴, the default 4
// progressive passes: the measure's loop over pixels with the raster's bookkeeping.  Dig: 128 × 128 pixels with
// AVX-512 IFMA, 64 × 64 otherwise; MEGNO (a log per step) half as wide and high (≈ 0.1–0.4 s per iteration).  Steps of N per second (stepsPerOrbit per pixel:
// no orbit stops early), comparable with bare_step/<kernel>.
void indicatorMap(benchmark::State& state, const KernelInfo* kernel, IndicatorKind kind) {
  IndicatorRequest r;
  r.measure.map = kPaperBox;
  r.measure.kind = kind;
  r.measure.iterations = 10000;
  r.measure.kernel = kernel;
  r.width = r.height = (kernel->kind == KernelKind::avx512ifma ? 128 : 64) / (kind == IndicatorKind::Megno ? 2 : 1);
  r.threads = 1;
  double steps = 0;
  for (auto _ : state) {
    const IndicatorResult done = computeIndicatorMap(r);
    steps += static_cast<double>(done.raster.pixelsDone) * static_cast<double>(stepsPerOrbit(r.measure));
    benchmark::DoNotOptimize(done.raster.values.data());
  }
  reportSteps(state, steps);
}

// Rotation numbers.  rotation/profile/<kernel>: computeRotationProfile (RotationProfile.hpp) along the x axis across
// the K = 0.1 box's central island and six islands, 256 points, T = 10⁴, one thread (the Rotation measure, plus the
// rationals).  rotation/number/scalar: measureRotation (RotationNumber.hpp), one chain-identification level: Q⁶
// about the central fixed point from a point of the central island, T = 10⁴ (1.2·10⁵ steps of N, scalar on the
// calling thread whatever the CPU, so it is compared with bare_step/scalar).  Steps of N per second.
void rotationProfile(benchmark::State& state, const KernelInfo* kernel) {
  RotationProfileRequest r;
  r.measure.map = kPaperBox;
  r.measure.kind = IndicatorKind::Rotation;
  r.measure.iterations = 10000;
  r.measure.kernel = kernel;
  r.from = {-0.6L, 0};
  r.to = {0.1L, 0};
  r.points = 256;
  r.threads = 1;
  double steps = 0;
  for (auto _ : state) {
    const RotationProfile done = computeRotationProfile(r);
    steps += static_cast<double>(done.points.size()) * static_cast<double>(stepsPerOrbit(r.measure));
    benchmark::DoNotOptimize(done.points.data());
  }
  reportSteps(state, steps);
}

void rotationNumber(benchmark::State& state) {
  RotationRequest r;
  r.map = kPaperBox;
  r.start = FixedPointMap(kPaperBox).toUnit(-0.4L, 0);
  r.centre = centralFixedPoint(kPaperBox);
  r.power = 6;
  r.iterations = 10000;
  double steps = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(measureRotation(r).rotation);
    steps += 2.0 * static_cast<double>(r.iterations) * static_cast<double>(r.power);
  }
  reportSteps(state, steps);
}

// Manifold refinement (core/manifolds/ManifoldCurve.hpp, issue 28): the fixed point's inner unstable branch at
// K = 0.1, arc length 20, in the paper's box (manifold/branch_box) and in a zoomed view 0.01 wide at the tip of the
// loop refined to 10⁻⁵ there (manifold/branch_view: a zoomed portrait's hot loop); one thread, long double.  The
// "steps" reported are refined points of the branch (each the local series iterated d·stepsPerDomain steps of Q in
// long double, d its domain), so the ratio to the bare step is points per second over steps per second: its
// inverse is what one point costs, in steps of the bare kernel.  bench/manifold_benchmarks.cpp has more cases.
void manifoldBranch(benchmark::State& state, ManifoldCurveRequest request) {
  double points = 0;
  for (auto _ : state) {
    const ManifoldCurve c = computeManifoldCurve(request);
    points += static_cast<double>(c.points);
    benchmark::DoNotOptimize(c.length);
  }
  reportSteps(state, points);
}

void registerInstruments() {
  for (const auto& k : supportedKernels()) {
    for (IndicatorKind kind : {IndicatorKind::Dig, IndicatorKind::Megno})
      benchmark::RegisterBenchmark(("indicator/" + std::string(toString(kind)) + "/" + std::string(k.name)).c_str(),
                                   indicatorMap, &kernelByName(k.name), kind)
          ->UseRealTime()
          ->Unit(benchmark::kMillisecond)
          ->MinTime(0.25);
    benchmark::RegisterBenchmark(("rotation/profile/" + std::string(k.name)).c_str(), rotationProfile,
                                 &kernelByName(k.name))
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.25);
  }
  benchmark::RegisterBenchmark("rotation/number/scalar", rotationNumber)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond)
      ->MinTime(0.25);
  ManifoldCurveRequest box;
  box.K = 0.1L;
  box.length = 20;
  box.box = kPaperBox;
  benchmark::RegisterBenchmark("manifold/branch_box", manifoldBranch, box)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond)
      ->MinTime(0.25);
  ManifoldCurveRequest view;
  view.K = 0.1L;
  view.length = 20;
  view.view = PhysicalRect{-0.69L, -0.68L, -0.37L, -0.36L};
  view.maxSpacing = 1e-5L;
  benchmark::RegisterBenchmark("manifold/branch_view", manifoldBranch, view)
      ->UseRealTime()
      ->Unit(benchmark::kMillisecond)
      ->MinTime(0.25);
}

void registerAll() {
  // Bare steps: ≈ 13–130 ms per iteration (avx512ifma–scalar), ≈ 0.25–0.4 s per repetition.
  for (const auto& k : supportedKernels())
    for (const int threads : {1, 2}) {
      const std::string name = "bare_step/" + std::string(k.name) + (threads > 1 ? "/threads:2" : "");
      auto* b = benchmark::RegisterBenchmark(name.c_str(), bareStep, k.orbits, threads)->UseRealTime()->MinTime(0.25);
      if (threads > 1) b->MeasureProcessCPUTime();
    }
  benchmark::RegisterBenchmark("naive_double", naiveDouble)->UseRealTime()->MinTime(0.25);
  for (const auto& k : supportedKernels()) {
    // Steps per iteration per thread: about 0.1 s (q = 100) to 0.3 s (q = 1) on an idle core, whatever the
    // path; with MinTime(0.4) a repetition is 2–4 iterations.
    const double steps = k.kind == KernelKind::scalar ? 4e7 : k.kind == KernelKind::avx2 ? 6e7 : 3e8;
    for (const std::uint32_t q : {1u, 16u, 100u})
      for (const int threads : {1, 2})
        benchmark::RegisterBenchmark(("pipeline/" + std::string(k.name) + "/q:" + std::to_string(q) +
                                      "/threads:" + std::to_string(threads))
                                         .c_str(),
                                     pipeline, &kernelByName(k.name), q, threads, steps * threads)
            ->UseRealTime()
            ->MeasureProcessCPUTime()
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.4);
  }
}

/// The CPU, from /proc/cpuinfo (Linux; empty elsewhere): "model name", family/model/stepping, and which of the flags
/// that decide the paths (and their speed) it has.  Stored in the JSON's context by main.
std::pair<std::string, std::string> cpuDescription() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model, family, number, stepping, flags;
  const auto value = [&] { return line.substr(std::min(line.size(), line.find(':') + 2)); };
  while (std::getline(in, line) && (model.empty() || flags.empty() || family.empty())) {
    if (line.rfind("model name", 0) == 0) model = value();
    else if (line.rfind("cpu family", 0) == 0) family = value();
    else if (line.rfind("model\t", 0) == 0) number = value();
    else if (line.rfind("stepping", 0) == 0) stepping = value();
    else if (line.rfind("flags", 0) == 0) flags = " " + value() + " ";
  }
  if (!family.empty()) model += " (family " + family + ", model " + number + ", stepping " + stepping + ")";
  std::string has, lacks;
  for (const std::string f : {"avx2", "fma", "bmi2", "adx", "avx512f", "avx512dq", "avx512vl", "avx512ifma",
                              "avx512vbmi", "hypervisor"})
    (flags.find(" " + f + " ") != std::string::npos ? has : lacks) += " " + f;
  return {model, (has.empty() ? "" : has.substr(1)) + (lacks.empty() ? "" : "; lacks" + lacks)};
}

}  // namespace
}  // namespace archipelago

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  const auto [model, flags] = archipelago::cpuDescription();
  benchmark::AddCustomContext("cpu_model", model);
  benchmark::AddCustomContext("cpu_flags", flags);
  benchmark::AddCustomContext("best_kernel", std::string(archipelago::bestKernel().name));
  archipelago::registerAll();
  archipelago::registerMeasures();
  archipelago::registerInstruments();
  archipelago::registerTail();
  archipelago::registerPaired();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
