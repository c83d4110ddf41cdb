#include "core/manifolds/KacCheck.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/limits/Limits.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/random/CounterRng.hpp"

namespace archipelago {

namespace {

/// Samples per unit of parallel work: results are summed per chunk in index order, then over chunks in order, so
/// they do not depend on the number of threads.
constexpr std::uint64_t kChunk = 256;
/// Chunks between two progress reports (and stop checks beyond parallelFor's own).
constexpr std::uint64_t kChunksPerBatch = 64;
/// The zone is re-checked every this many steps (a safety net; see the header).
constexpr std::uint64_t kZoneCheckInterval = 1024;

/// A uniform random point of `region`, by rejection from its bounding box, from the draws of sample `index`.
PhysicalPoint uniformPoint(const PolygonRegion& region, std::uint64_t seed, std::uint64_t index) {
  const std::uint64_t key = orbitKey(seed, index);
  const PhysicalRect& b = region.bounds();
  for (std::uint64_t k = 1;; k += 2) {
    const long double u = std::ldexp(static_cast<long double>(orbitDraw(key, k)), -52);
    const long double v = std::ldexp(static_cast<long double>(orbitDraw(key, k + 1)), -52);
    const PhysicalPoint p{b.x0 + u * (b.x1 - b.x0), b.y0 + v * (b.y1 - b.y0)};
    if (region.contains(p.x, p.y)) return p;
  }
}

struct Step {
  double K;
  void operator()(double& x, double& y) const noexcept {
    y += 2 * (x * x - K);
    x += y;
  }
};

struct ChunkSums {
  double sum = 0, sumSquares = 0;
  std::uint64_t count = 0, capped = 0, longest = 0, inconsistent = 0, steps = 0;
};

template <class Body>
void runChunks(std::uint64_t samples, int threads, std::vector<ChunkSums>& chunks, const Body& body,
               const ManifoldProgressCallback& progress, double fraction0, double fraction1, const char* stage,
               std::stop_token stop) {
  const std::uint64_t total = (samples + kChunk - 1) / kChunk;
  chunks.assign(total, {});
  for (std::uint64_t first = 0; first < total; first += kChunksPerBatch) {
    const std::uint64_t count = std::min(kChunksPerBatch, total - first);
    const bool complete = parallelFor(
        count,
        [&](std::size_t i, int) {
          const std::uint64_t chunk = first + i;
          ChunkSums& s = chunks[chunk];
          const std::uint64_t end = std::min(samples, (chunk + 1) * kChunk);
          for (std::uint64_t sample = chunk * kChunk; sample < end; ++sample) body(sample, s);
        },
        stop, threads);
    if (!complete || stop.stop_requested()) throw std::runtime_error("stopped");
    if (progress)
      progress({fraction0 + (fraction1 - fraction0) * static_cast<double>(first + count) / static_cast<double>(total), stage});
  }
}

/// The regions of the check and the map: orbits run in the zone Z until they enter the exit lobe X, at most T steps.
struct KacRegions {
  const PolygonRegion& zone;
  const PolygonRegion& exit;
  Step step;
  std::uint64_t T;
};

/// Left side: τ of the orbit entering through E at p, capped at T, added to s.
void addEntryResidence(const KacRegions& k, PhysicalPoint p, ChunkSums& s) {
  double x = static_cast<double>(p.x), y = static_cast<double>(p.y);
  k.step(x, y);  // now inside Z
  std::uint64_t tau = 1;
  bool capped = false;
  for (;; ++tau) {
    if (k.exit.contains(x, y)) break;
    if (tau >= k.T) {
      capped = true;
      break;
    }
    if (tau % kZoneCheckInterval == 0 && !k.zone.contains(x, y)) {
      ++s.inconsistent;
      break;
    }
    k.step(x, y);
  }
  const auto t = static_cast<double>(tau);
  s.sum += t;
  s.sumSquares += t * t;
  ++s.count;
  s.capped += capped ? 1 : 0;
  s.longest = std::max(s.longest, tau);
  s.steps += tau;
}

/// Right side: whether the point p of Z leaves within T steps (τ_f ≤ T ⇔ Q^j w ∈ X for some j < T), added to s.
void addZoneTransit(const KacRegions& k, PhysicalPoint p, ChunkSums& s) {
  double x = static_cast<double>(p.x), y = static_cast<double>(p.y);
  std::uint64_t j = 0;
  bool leaves = false;
  for (; j < k.T; ++j) {
    if (k.exit.contains(x, y)) {
      leaves = true;
      break;
    }
    if (j > 0 && j % kZoneCheckInterval == 0 && !k.zone.contains(x, y)) {
      ++s.inconsistent;
      break;
    }
    k.step(x, y);
  }
  s.sum += leaves ? 1 : 0;
  ++s.count;
  s.steps += j + 1;
}

/// The chunks' sums in chunk order.
ChunkSums sumOfChunks(const std::vector<ChunkSums>& chunks) {
  ChunkSums total;
  for (const ChunkSums& c : chunks) {
    total.sum += c.sum;
    total.sumSquares += c.sumSquares;
    total.count += c.count;
    total.capped += c.capped;
    total.longest = std::max(total.longest, c.longest);
    total.inconsistent += c.inconsistent;
    total.steps += c.steps;
  }
  return total;
}

/// The left side of Kac's lemma from the entry orbits' sums: the mean residence and its standard error.
void setMeanResidence(KacResult& out, const ChunkSums& left) {
  const auto n = static_cast<double>(left.count);
  out.entryOrbits = left.count;
  out.meanResidence = left.sum / n;
  const double variance = std::max(0.0, left.sumSquares / n - out.meanResidence * out.meanResidence);
  out.meanResidenceError = left.count > 1 ? std::sqrt(variance / (n - 1)) : 0;
  out.stillInside = left.capped;
  out.longestResidence = left.longest;
}

/// The right side from the zone points' sums: the transit fraction, area, and the residence it predicts.
void setPredictedResidence(KacResult& out, const ChunkSums& right, const TurnstileFlux& flux) {
  const auto m = static_cast<double>(right.count);
  const double p = right.sum / m;
  const double area = static_cast<double>(flux.zoneArea), phi = static_cast<double>(flux.lobeArea);
  out.zonePoints = right.count;
  out.transitFraction = p;
  out.transitFractionError = std::sqrt(p * (1 - p) / m);
  out.transitArea = p * area;
  out.transitAreaError = out.transitFractionError * area;
  out.predictedResidence = out.transitArea / phi;
  out.predictedResidenceError = out.transitAreaError / phi;
  out.islandArea = (1 - p) * area;
}

}  // namespace

std::optional<std::string> validationError(const KacRequest& r) {
  if (auto e = manifoldKError(r.K)) return e;
  if (r.orbit && r.orbit->K != r.K)
    return "the orbit's K = " + shortestDecimal(static_cast<double>(r.orbit->K)) + " differs from K = " +
           shortestDecimal(static_cast<double>(r.K));
  if (auto e = rangeError("entry samples", r.entrySamples, 1, 1'000'000'000)) return e;
  if (auto e = rangeError("zone samples", r.zoneSamples, 1, 1'000'000'000)) return e;
  if (auto e = rangeError("maximum steps", r.maxSteps, 1, 1'000'000'000'000)) return e;
  if (auto e = threadsError(r.threads)) return e;
  return std::nullopt;
}

double KacResult::discrepancy() const noexcept {
  const double sigma = std::hypot(meanResidenceError, predictedResidenceError);
  return sigma > 0 ? (meanResidence - predictedResidence) / sigma : 0;
}

KacResult runKacCheck(const KacRequest& request, const ManifoldProgressCallback& progress, std::stop_token stop) {
  if (auto e = validationError(request)) throw std::invalid_argument(*e);
  const auto started = std::chrono::steady_clock::now();
  if (progress) progress({0, "turnstile"});
  TurnstileRequest turnstile;
  turnstile.K = request.K;
  turnstile.orbit = request.orbit;
  turnstile.side = request.side;
  turnstile.maxVertices = 1 << 10;  // the areas come from the actions here; the polygons only draw the regions
  const TurnstileFlux flux = computeTurnstileFlux(turnstile, {}, stop);
  const PolygonRegion zone(flux.zoneBoundary), exit(flux.exitLobe), entry(flux.entryLobe);
  const KacRegions regions{zone, exit, Step{static_cast<double>(request.K)}, request.maxSteps};

  KacResult out;
  out.flux = flux.lobeArea;
  out.zoneArea = flux.zoneArea;
  out.maxSteps = request.maxSteps;

  std::vector<ChunkSums> chunks;
  runChunks(
      request.entrySamples, request.threads, chunks,
      [&](std::uint64_t sample, ChunkSums& s) {
        addEntryResidence(regions, uniformPoint(entry, request.seed, sample), s);
      },
      progress, 0.05, 0.5, "entry orbits", stop);
  const ChunkSums left = sumOfChunks(chunks);
  setMeanResidence(out, left);
  runChunks(
      request.zoneSamples, request.threads, chunks,
      [&](std::uint64_t sample, ChunkSums& s) {
        // "ZONE": other draws than E's
        addZoneTransit(regions, uniformPoint(zone, request.seed ^ 0x5A4F4E45ULL, sample), s);
      },
      progress, 0.5, 1.0, "zone points", stop);
  const ChunkSums right = sumOfChunks(chunks);
  setPredictedResidence(out, right, flux);
  out.inconsistent = left.inconsistent + right.inconsistent;
  out.steps = left.steps + right.steps;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (progress) progress({1, "done"});
  return out;
}

}  // namespace archipelago
