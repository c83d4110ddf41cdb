#include "core/measures/OrbitMeasures.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/measures/MeasureKernels.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {
// Steps of a group between two checks of the stop token (the cancellation latency: ~1 ms per group with
// AVX-512 IFMA, a few ms with the scalar path).
constexpr std::uint64_t kChunkSteps = std::uint64_t{1} << 14;
}  // namespace

std::string_view toString(OrbitVerdict verdict) noexcept {
  switch (verdict) {
    case OrbitVerdict::NotComputed: return "not computed";
    case OrbitVerdict::Measured: return "measured";
    case OrbitVerdict::Regular: return "regular";
    case OrbitVerdict::Chaotic: return "chaotic";
    case OrbitVerdict::Escaping: return "escaping";
  }
  return "unknown";
}

std::optional<std::string> validationError(const MeasureSettings& s) {
  if (auto e = mapError(s.map)) return e;
  if (auto e = rangeError("iterations", s.iterations, kMinIterations, kMaxIterations)) return e;
  if (auto e = realRangeError("digits threshold", s.digitsThreshold, 0, kMaxDigits)) return e;
  if (s.kind == IndicatorKind::Rotation)
    return realOpenIntervalError("K", s.map.K, 0, 1,
                                 "for rotation numbers: only there is the centre (−√K, 0) elliptic");
  return std::nullopt;
}

std::uint64_t stepsPerOrbit(const MeasureSettings& s) noexcept { return measures::totalSteps(s.kind, s.iterations); }

std::optional<std::string> boxPointError(const std::string& name, const MapParameters& map, PhysicalPoint p) {
  const long double L = static_cast<long double>(map.xmax) - map.xmin;
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return name + " must be two finite numbers x,y";
  if (!(p.x >= map.xmin && p.x < map.xmax && p.y >= -L / 2 && p.y < L / 2)) {
    // Shortest texts (issue 53, finding 18: %.17Lg printed the box as [-0.65000000000000002, 0.65000000000000002)):
    // the point as given, the box's y edges as the map's own L = xmax − xmin (a double, appendix B) gives them.
    const double half = map.width() / 2;
    return name + " = (" + io::shortestText(p.x) + ", " + io::shortestText(p.y) + ") must lie in the box [" +
           shortestDecimal(map.xmin) + ", " + shortestDecimal(map.xmax) + ") x [" + shortestDecimal(-half) + ", " +
           shortestDecimal(half) + ")";
  }
  return std::nullopt;
}

PhysicalPoint rotationCentreUnits(const MapParameters& map) noexcept {
  const long double L = static_cast<long double>(map.xmax) - static_cast<long double>(map.xmin);
  const long double one = static_cast<long double>(FixedPointMap::kOne);
  const long double x = -std::sqrt(static_cast<long double>(map.K));
  return {(x - static_cast<long double>(map.xmin)) / L * one, static_cast<long double>(FixedPointMap::kHalf)};
}

namespace measures {

std::uint64_t totalSteps(IndicatorKind kind, std::uint64_t T) noexcept { return isBirkhoffKind(kind) ? 2 * T : T; }

MeasurePath measurePath(KernelKind kind) noexcept {
  switch (kind) {
    case KernelKind::avx512ifma: return {&measureKernelAvx512Ifma, 32};
    case KernelKind::avx512f:  // the avx2 accumulation on the AVX-512F trace (MeasureSetup::trace): 3 vectors of 8
    case KernelKind::avx2: return {&measureKernelAvx2, 24};
    case KernelKind::scalar: break;
  }
  return {&measureKernelScalar, 8};
}

}  // namespace measures

namespace {

measures::MeasureSetup makeSetup(const MeasureSettings& s, const MapCoefficients& k, const BirkhoffWeights& w) {
  measures::MeasureSetup setup;
  setup.kind = s.kind;
  setup.coefficients = k;
  setup.T = s.iterations;
  setup.weights = w.g.empty() ? nullptr : w.g.data();
  setup.xmin = s.map.xmin;
  setup.unit = std::ldexp(s.map.width(), -FixedPointMap::kBits);
  setup.K = s.map.K;
  setup.trace = kernelOrBest(s.kernel).orbits;
  if (s.kind == IndicatorKind::Rotation) {
    const PhysicalPoint c = rotationCentreUnits(s.map);
    const long double ix = std::floor(c.x), iy = std::floor(c.y);
    setup.centreX = static_cast<double>(ix);
    setup.centreY = static_cast<double>(iy);
    setup.centreFracX = static_cast<double>(c.x - ix);
    setup.centreFracY = static_cast<double>(c.y - iy);
  }
  return setup;
}

measures::MeasureLane startLane(UnitState z) {
  measures::MeasureLane lane;
  lane.X = z.X & FixedPointMap::kMask;
  lane.Y = z.Y & FixedPointMap::kMask;
  return lane;
}

/// The result of a lane that ran every step (MeasureKernels.hpp defines the sums).
OrbitMeasure finish(const MeasureSettings& s, double weightSum, const measures::MeasureLane& m) {
  OrbitMeasure r;
  const auto T = static_cast<double>(s.iterations);
  constexpr double ln2 = std::numbers::ln2;
  switch (s.kind) {
    case IndicatorKind::Dig: {
      const double unit = std::ldexp(s.map.width(), -FixedPointMap::kBits);
      // Physical x = xmin + unit·X; the digits are of the physical averages' difference.
      r.digits = convergenceDigits(unit * (m.firstBlock / weightSum), unit * ((m.hi + m.lo) / weightSum));
      r.value = r.digits;
      if (!(r.digits >= s.digitsThreshold)) r.verdict = OrbitVerdict::Chaotic;
      else r.verdict = m.wrapped ? OrbitVerdict::Escaping : OrbitVerdict::Regular;  // an accelerator mode of Q*
      break;
    }
    case IndicatorKind::Rotation: {
      constexpr double turn = 2 * std::numbers::pi;
      const double a = m.firstBlock / weightSum / turn, b = (m.hi + m.lo) / weightSum / turn;
      r.digits = convergenceDigits(a, b);
      if (m.wrapped) r.verdict = OrbitVerdict::Escaping;
      else if (!(r.digits >= s.digitsThreshold)) r.verdict = OrbitVerdict::Chaotic;
      else r.verdict = OrbitVerdict::Regular;
      if (r.verdict == OrbitVerdict::Regular) r.value = (a + b) / 2;
      break;
    }
    case IndicatorKind::Fli:
      r.value = m.rescale * ln2 + 0.5 * std::log(m.maxNormSq);
      r.verdict = OrbitVerdict::Measured;
      break;
    case IndicatorKind::Megno:
      r.value = m.sumY / T;
      r.verdict = OrbitVerdict::Measured;
      break;
    case IndicatorKind::Lyapunov:
      r.value = (m.rescale * ln2 + 0.5 * std::log(m.vx * m.vx + m.vy * m.vy)) / T;
      r.verdict = OrbitVerdict::Measured;
      break;
  }
  return r;
}

}  // namespace

OrbitMeasurer::OrbitMeasurer(const MeasureSettings& s) : settings_(s) {
  if (auto e = validationError(s)) throw std::invalid_argument(*e);
  coefficients_ = computeCoefficients(s.map);
  if (isBirkhoffKind(s.kind)) weights_ = birkhoffWeights(s.iterations);
}

OrbitMeasure OrbitMeasurer::measure(UnitState start) const {
  const measures::MeasureSetup setup = makeSetup(settings_, coefficients_, weights_);
  const measures::MeasurePath path = measures::measurePath(kernelOrBest(settings_.kernel).kind);
  measures::MeasureLane lane = startLane(start);
  path.kernel(setup, std::span<measures::MeasureLane>(&lane, 1), 0, stepsPerOrbit(settings_));
  return finish(settings_, weights_.sum, lane);
}

bool OrbitMeasurer::measure(std::span<const UnitState> starts, std::span<OrbitMeasure> out, std::stop_token stop,
                            int threads) const {
  if (out.size() != starts.size()) throw std::invalid_argument("measure: starts and results differ in size");
  const measures::MeasureSetup setup = makeSetup(settings_, coefficients_, weights_);
  const measures::MeasurePath path = measures::measurePath(kernelOrBest(settings_.kernel).kind);
  const std::uint64_t total = stepsPerOrbit(settings_);
  const std::size_t group = path.groupOrbits;
  const std::size_t groups = (starts.size() + group - 1) / group;
  std::atomic<bool> stopped{false};
  const bool complete = parallelFor(
      groups,
      [&](std::size_t g, int) {
        const std::size_t begin = g * group, n = std::min(group, starts.size() - begin);
        measures::MeasureLane lanes[64];
        for (std::size_t i = 0; i < n; ++i) lanes[i] = startLane(starts[begin + i]);
        for (std::uint64_t done = 0; done < total; done += kChunkSteps) {
          if (stop.stop_requested()) {
            stopped.store(true, std::memory_order_relaxed);
            return;
          }
          path.kernel(setup, std::span<measures::MeasureLane>(lanes, n), done, std::min(kChunkSteps, total - done));
        }
        for (std::size_t i = 0; i < n; ++i) out[begin + i] = finish(settings_, weights_.sum, lanes[i]);
      },
      stop, threads);
  return complete && !stopped.load();
}

}  // namespace archipelago
