#include "core/portrait/PortraitRenderer.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/limits/Limits.hpp"
#include "core/kernels/ScalarLanes.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/random/CounterRng.hpp"
#include "core/trapping/BlockKernel.hpp"

// Glossary: an "orbit" is one trajectory of N (Density, Orbits) or of trapping blocks of N⁻¹ (Stickiness);
// a "group" is up to kLanes orbits advanced in lockstep by one thread; a "chunk" is at most chunkSteps points
// of every orbit of a group; a "round" advances every group by one chunk; a "pass" ends at a refinement level.

namespace archipelago {

std::string_view toString(PortraitMode mode) noexcept {
  switch (mode) {
    case PortraitMode::Density: return "density";
    case PortraitMode::Orbits: return "orbits";
    case PortraitMode::Stickiness: return "stickiness";
  }
  return "unknown";
}

std::optional<PortraitMode> parsePortraitMode(std::string_view name) noexcept {
  for (PortraitMode m : {PortraitMode::Density, PortraitMode::Orbits, PortraitMode::Stickiness})
    if (name == toString(m)) return m;
  return std::nullopt;
}

std::vector<double> PortraitRaster::meanSegmentLengths() const {
  std::vector<double> mean(pixelCount(), 0.0);
  for (std::size_t i = 0; i < mean.size(); ++i) mean[i] = meanSegmentLength(i);
  return mean;
}

std::size_t PortraitRaster::nonEmptyPixels() const noexcept {
  return static_cast<std::size_t>(std::count_if(counts.begin(), counts.end(), [](std::uint64_t c) { return c > 0; }));
}

std::uint64_t PortraitRequest::orbitCount() const noexcept {
  return mode == PortraitMode::Orbits ? std::uint64_t{seedColumns} * seedRows : std::uint64_t{orbits};
}

std::uint64_t PortraitRequest::stepsPerOrbit() const noexcept {
  const std::uint64_t n = orbitCount();
  if (n == 0) return 0;
  std::uint64_t steps = (points + n - 1) / n;
  if (mode == PortraitMode::Stickiness && q > 0) steps = (steps + q - 1) / q * q;
  return steps;
}

namespace {
constexpr std::uint64_t kMaxPasses = std::uint64_t{1} << 16;

/// Calls f(end) for every pass end of passSchedule(r), in order; stops early (returning false) once more
/// than `limit` ends were produced.
template <class F>
bool forEachPassEnd(const PortraitRequest& r, std::uint64_t limit, F&& f) {
  const std::uint64_t steps = r.stepsPerOrbit();
  const std::uint64_t unit = r.mode == PortraitMode::Stickiness && r.q > 0 ? r.q : 1;
  const std::uint64_t orbits = std::max<std::uint64_t>(r.orbitCount(), 1);
  const std::uint64_t cap = r.passPoints > 0 ? std::max<std::uint64_t>(r.passPoints / orbits / unit, 1) * unit : 0;
  std::uint64_t prev = 0, count = 0;
  for (std::uint32_t pass = 0; pass < r.passes; ++pass) {
    std::uint64_t end = pass + 1 == r.passes ? steps : (steps >> (r.passes - 1 - pass)) / unit * unit;
    end = std::max(end, prev);
    if (cap > 0 && end - prev > cap) {
      const std::uint64_t units = (end - prev) / unit, parts = (end - prev + cap - 1) / cap;
      if (parts > limit) return false;
      for (std::uint64_t j = 1; j < parts; ++j) {
        if (++count > limit) return false;
        f(prev + ((units / parts) * j + (units % parts) * j / parts) * unit);
      }
    }
    if (++count > limit) return false;
    f(end);
    prev = end;
  }
  return true;
}
}  // namespace

std::optional<std::string> validationError(const PortraitRequest& r) {
  if (auto e = mapError(r.map)) return e;
  std::ostringstream s;
  if (auto e = rasterSizeError(r.width, r.height)) return e;
  if (auto e = lowerBoundError("points", r.points, 1)) return e;
  if (r.points > (std::uint64_t{1} << 50)) return "points must be < 2^50";
  if (r.mode != PortraitMode::Orbits)
    if (auto e = rangeError("orbits", r.orbits, 1, limits::kRasterOrbits)) return e;
  if (r.mode == PortraitMode::Orbits) {
    if (auto e = rangeError("seed grid columns", r.seedColumns, 1, limits::kSeedGridSide)) return e;
    if (auto e = rangeError("seed grid rows", r.seedRows, 1, limits::kSeedGridSide)) return e;
  }
  // Xr and q are checked in every mode (the renderer builds its block settings from them whatever the mode): a
  // value given for a mode that does not use it is still refused, never carried as a silent nonsense.
  if (auto e = randomizingZoneError(r.Xr)) return e;
  if (auto e = rangeError("q", r.q, 1, limits::kRasterQ)) return e;
  if (auto e = rangeError("passes", r.passes, 1, 30)) return e;
  if (auto e = rangeError("chunkSteps", r.chunkSteps, 1, 1u << 20))
    return e;
  if (!forEachPassEnd(r, kMaxPasses, [](std::uint64_t) {})) {
    s << "passPoints = " << r.passPoints << " splits the " << r.points << " points into more than 2^16 passes";
    return s.str();
  }
  return std::nullopt;
}

std::vector<std::uint64_t> passSchedule(const PortraitRequest& r) {
  std::vector<std::uint64_t> ends;
  forEachPassEnd(r, kMaxPasses, [&](std::uint64_t end) { ends.push_back(end); });
  return ends;
}

void setProgressiveSchedule(PortraitRequest& r, std::uint64_t firstPassPoints, std::uint64_t passPoints) {
  firstPassPoints = std::max<std::uint64_t>(firstPassPoints, 1);
  std::uint32_t passes = 1;
  while (passes < 30 && (r.points >> passes) >= firstPassPoints) ++passes;
  r.passes = passes;
  // Splitting adds at most points / passPoints + 1 passes per level; keep well inside kMaxPasses.
  const std::uint64_t most = kMaxPasses / 2;
  if (passPoints > 0 && r.points / passPoints > most) passPoints = r.points / most + 1;
  r.passPoints = passPoints;
}

double seaPointsExpectedIfAllSea(const PortraitRequest& r, std::uint64_t points) noexcept {
  const long double box = static_cast<long double>(FixedPointMap::kOne) * static_cast<long double>(FixedPointMap::kOne);
  return static_cast<double>(static_cast<long double>(points) * (r.view.widthUnits() * r.view.heightUnits() / box));
}

bool viewHoldsNoSea(const PortraitRequest& r, const PortraitRaster& raster) noexcept {
  return r.mode == PortraitMode::Density && raster.pointsBinned == 0 &&
         seaPointsExpectedIfAllSea(r, raster.pointsIterated) >= kNoSeaExpectedPoints;
}

PixelMapping::PixelMapping(const Viewport& view, int width, int height) noexcept
    : grid_{view.centre().X,
            view.centre().Y,
            static_cast<double>(width / view.widthUnits()),
            static_cast<double>(height / view.heightUnits()),
            width / 2.0,
            height / 2.0,
            static_cast<double>(width),
            static_cast<double>(height),
            width,
            height} {}

namespace {

constexpr std::size_t kLanes = kScalarLanes;  // Orbits, Stickiness: orbits per group (ScalarLanes.hpp)
// Density mode iterates and bins groups of kDensityGroup orbits with the selected vector kernel
// (KernelDispatch.hpp, DensityKernel): 32 orbits are four AVX-512 vectors, enough to hide the multiply
// latency, and 256 orbits still make 8 groups to share between threads.
constexpr std::size_t kDensityGroup = 32;
constexpr std::uint32_t kNoLabel = std::numeric_limits<std::uint32_t>::max();
// Per-thread counts are 32-bit; they are flushed into the 64-bit raster before they could overflow.
constexpr std::uint64_t kFlushThreshold = std::uint64_t{1} << 31;
constexpr std::size_t kOpenSegmentBuffer = std::size_t{1} << 16;
constexpr std::size_t kCarriesFlush = std::size_t{1} << 20;

/// A thread's private accumulators.
struct ThreadRaster {
  std::vector<std::uint32_t> counts;
  // Density: 8-bit counts, so that a megapixel raster (1 MB) stays in the core's L2 cache while the points
  // land at random pixels (32-bit counts, 4 MB, made every increment a cache miss); each wrap to 0 appends
  // the pixel to `carries`, worth 256 counts.
  std::vector<std::uint8_t> density;
  std::vector<std::uint32_t> carries;
  std::vector<std::uint32_t> labels;      // Orbits: smallest seed index, kNoLabel when none
  std::vector<std::uint64_t> lengthSums;  // Stickiness
  std::uint64_t binned = 0;               // since the last flush
  std::uint64_t binnedTotal = 0;
};

/// The points of a trapped segment still open: pixel indices, aggregated into (pixel, count) pairs when the
/// buffer fills so that memory stays bounded by the number of distinct pixels however long the segment.
struct OpenSegment {
  std::vector<std::uint32_t> pixels;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> aggregated;

  void add(std::uint32_t pixel) {
    pixels.push_back(pixel);
    if (pixels.size() >= kOpenSegmentBuffer) aggregate();
  }
  void aggregate() {
    std::sort(pixels.begin(), pixels.end());
    std::vector<std::pair<std::uint32_t, std::uint32_t>> runs;
    for (std::size_t i = 0; i < pixels.size();) {
      std::size_t j = i;
      while (j < pixels.size() && pixels[j] == pixels[i]) ++j;
      runs.emplace_back(pixels[i], static_cast<std::uint32_t>(j - i));
      i = j;
    }
    pixels.clear();
    std::vector<std::pair<std::uint32_t, std::uint32_t>> merged;
    merged.reserve(runs.size() + aggregated.size());
    std::size_t a = 0, b = 0;
    while (a < aggregated.size() || b < runs.size()) {
      if (b == runs.size() || (a < aggregated.size() && aggregated[a].first < runs[b].first)) {
        merged.push_back(aggregated[a++]);
      } else if (a == aggregated.size() || runs[b].first < aggregated[a].first) {
        merged.push_back(runs[b++]);
      } else {
        merged.emplace_back(runs[b].first, runs[b].second + aggregated[a].second);
        ++a, ++b;
      }
    }
    aggregated.swap(merged);
  }
  /// Adds the ended segment of length `steps` to the thread's raster (when `record`) and empties it.
  /// (A single segment of more than 2^31 points inside the view could overflow a 32-bit thread count; at
  /// K = 0.1 the longest segments are ~10^9 steps (§5), so this needs budgets far beyond interactive use.)
  void close(bool record, std::uint64_t steps, ThreadRaster& out) {
    if (record) {
      for (std::uint32_t p : pixels) {
        out.counts[p] += 1;
        out.lengthSums[p] += steps;
      }
      for (auto [p, n] : aggregated) {
        out.counts[p] += n;
        out.lengthSums[p] += steps * n;
      }
      out.binned += pixels.size();
      for (auto [p, n] : aggregated) out.binned += n;
    }
    pixels.clear();
    aggregated.clear();
  }
};

/// State of one trapping orbit (Stickiness mode) between chunks: the orbit as trapping runs keep it, and the
/// pixels of its open segment.
struct TrappingOrbit {
  OrbitState orbit;  // from (0, 0), appendix B step 2
  OpenSegment open;
};

class Renderer {
 public:
  Renderer(const PortraitRequest& r, const PortraitObserver& observer, std::stop_token stop)
      : r_(r),
        observer_(observer),
        stop_(std::move(stop)),
        coef_(computeCoefficients(r.map)),
        step_(coef_),
        mapping_(r.view, r.width, r.height),
        orbitCount_(r.orbitCount()),
        steps_(r.stepsPerOrbit()),
        blocks_(blockSettings(coef_, r.Xr, r.q, r.seed)),
        densityKernel_(kernelOrBest(r.kernel).density) {}

  PortraitResult run() {
    PortraitResult result;
    PortraitRaster& raster = result.raster;
    raster.width = r_.width;
    raster.height = r_.height;
    raster.mode = r_.mode;
    const std::size_t pixels = raster.pixelCount();
    raster.counts.assign(pixels, 0);
    if (r_.mode == PortraitMode::Orbits) raster.labels.assign(pixels, 0);
    if (r_.mode == PortraitMode::Stickiness) raster.lengthSums.assign(pixels, 0);

    initOrbits();
    if (r_.mode == PortraitMode::Orbits) wrapped_.assign(orbitCount_, 0);
    threads_.resize(static_cast<std::size_t>(parallelThreads()));
    for (ThreadRaster& t : threads_) {
      if (r_.mode == PortraitMode::Density) {
        t.density.assign(pixels, 0);
      } else {
        t.counts.assign(pixels, 0);
      }
      if (r_.mode == PortraitMode::Orbits) t.labels.assign(pixels, kNoLabel);
      if (r_.mode == PortraitMode::Stickiness) t.lengthSums.assign(pixels, 0);
    }

    std::uint64_t done = 0;  // steps per orbit done by every orbit
    const std::vector<std::uint64_t> ends = passSchedule(r_);
    passes_ = static_cast<std::uint32_t>(ends.size());
    for (std::uint32_t pass = 0; pass < passes_; ++pass) {
      const std::uint64_t passEnd = ends[pass];
      while (done < passEnd) {
        const std::uint64_t chunk = std::min<std::uint64_t>(passEnd - done, chunkSteps());
        runRound(done, chunk);
        if (stop_.stop_requested()) break;
        done += chunk;
        flushIfNeeded(raster, false);
        notify(pass, nullptr, false);
      }
      if (stop_.stop_requested()) {
        result.cancelled = true;
        break;
      }
      flushIfNeeded(raster, true);
      result.passesDone = pass + 1;
      notify(pass, &raster, pass + 1 == passes_);
    }
    flushIfNeeded(raster, true);
    raster.pointsIterated = pointsDone_.load();
    return result;
  }

 private:
  std::uint64_t chunkSteps() const noexcept {
    std::uint64_t c = r_.chunkSteps;
    if (r_.mode == PortraitMode::Stickiness) c = std::max<std::uint64_t>(c / r_.q, 1) * r_.q;
    return c;
  }

  void initOrbits() {
    states_.resize(orbitCount_);
    for (std::uint64_t i = 0; i < orbitCount_; ++i) {
      switch (r_.mode) {
        case PortraitMode::Density: {
          // A random point of the strip 0.98 ≤ X/2^52 < 1: beyond the hyperbolic fixed point, in the sea.
          const std::uint64_t key = orbitKey(r_.seed, i);
          const std::uint64_t strip = FixedPointMap::kOne / 50;
          states_[i] = {FixedPointMap::kOne - 1 - orbitDraw(key, 1) % strip, orbitDraw(key, 2)};
          break;
        }
        case PortraitMode::Orbits:
          states_[i] = orbitSeed(r_.view, r_.seedColumns, r_.seedRows, static_cast<std::uint32_t>(i % r_.seedColumns),
                                 static_cast<std::uint32_t>(i / r_.seedColumns));
          break;
        case PortraitMode::Stickiness:  // trapping_ holds these orbits (from (0, 0))
          break;
      }
    }
    if (r_.mode == PortraitMode::Stickiness) trapping_.assign(orbitCount_, TrappingOrbit{});
  }

  std::size_t groupSize() const noexcept { return r_.mode == PortraitMode::Density ? kDensityGroup : kLanes; }

  void runRound(std::uint64_t done, std::uint64_t chunk) {
    const std::size_t lanes = groupSize();
    const std::size_t groups = (orbitCount_ + lanes - 1) / lanes;
    parallelFor(
        groups,
        [&](std::size_t g, int thread) {
          ThreadRaster& out = threads_[static_cast<std::size_t>(thread)];
          const std::uint64_t first = std::uint64_t{g} * lanes;
          const std::uint64_t n = std::min<std::uint64_t>(lanes, orbitCount_ - first);
          switch (r_.mode) {
            case PortraitMode::Density: advanceDensityOrbits(first, n, chunk, out); break;
            case PortraitMode::Orbits: advanceMapOrbits(first, n, chunk, out); break;
            case PortraitMode::Stickiness: advanceTrappingOrbits(first, n, done, chunk, out); break;
          }
          pointsDone_.fetch_add(n * chunk, std::memory_order_relaxed);
        },
        stop_);  // checked before every chunk
  }

  // Orbits (b): the scalar lane loop (ScalarLanes.hpp) with every point binned and labelled.
  void advanceMapOrbits(std::uint64_t first, std::uint64_t n, std::uint64_t chunk, ThreadRaster& out) {
    stepAllLanes(step_, MapDirection::forward, std::span<UnitState>(states_.data() + first, n), chunk,
                 wrapped_.data() + first,
                 [&](std::size_t lane0, std::size_t lanes, std::uint64_t, const std::uint64_t* X, const std::uint64_t* Y) {
                   for (std::size_t l = 0; l < lanes; ++l) bin({X[l], Y[l]}, first + lane0 + l, out);
                 });
  }

  // Density (a): the vector orbit kernel writes kTraceSteps states of every orbit into a small trace, which
  // is then binned; the same states and pixels as advanceMapOrbits<false>, only computed faster.
  void advanceDensityOrbits(std::uint64_t first, std::uint64_t n, std::uint64_t chunk, ThreadRaster& out) {
    out.binned += densityKernel_(coef_, std::span<UnitState>(states_.data() + first, n), chunk, mapping_.grid(),
                                 out.density.data(), out.carries);
  }

  void bin(const UnitState& z, std::uint64_t orbit, ThreadRaster& out) const noexcept {
    const std::int64_t p = mapping_.pixelOf(z);
    if (p < 0) return;
    const auto i = static_cast<std::size_t>(p);
    out.counts[i] += 1;
    out.binned += 1;
    out.labels[i] = std::min(out.labels[i], static_cast<std::uint32_t>(orbit));
  }

  // Trapping blocks (appendix B, steps 5–9), BlockKernel.hpp's definition, one orbit at a time: Stickiness
  // is not the throughput mode, and the per-point bookkeeping dominates anyway.
  void advanceTrappingOrbits(std::uint64_t first, std::uint64_t n, std::uint64_t /*done*/, std::uint64_t chunk,
                             ThreadRaster& out) {
    const std::uint64_t blocks = chunk / r_.q;
    for (std::uint64_t o = first; o < first + n; ++o) {
      TrappingOrbit& t = trapping_[o];
      OrbitState s = t.orbit;  // a local copy, so that the pixel stores below cannot alias it
      const auto visit = [&](const UnitState& z) {
        const std::int64_t p = mapping_.pixelOf(z);
        if (p >= 0) t.open.add(static_cast<std::uint32_t>(p));
      };
      for (std::uint64_t b = 0; b < blocks; ++b) {
        if (!advanceBlockVisiting(blocks_, o, s, visit)) continue;
        t.open.close(isRecorded(s.start), s.length * r_.q, out);
        restartSegment(s);
      }
      t.orbit = s;
    }
  }

  /// Adds the threads' rasters into `raster` when forced or when a 32-bit count could overflow next round.
  void flushIfNeeded(PortraitRaster& raster, bool force) {
    bool needed = force;
    for (const ThreadRaster& t : threads_)
      needed = needed || t.binned >= kFlushThreshold || t.carries.size() >= kCarriesFlush;
    if (!needed) return;
    const std::size_t pixels = raster.pixelCount();
    for (ThreadRaster& t : threads_) {
      if (!t.counts.empty()) {
        for (std::size_t i = 0; i < pixels; ++i) raster.counts[i] += t.counts[i];
        std::fill(t.counts.begin(), t.counts.end(), 0);
      }
      if (!t.density.empty()) {
        for (std::size_t i = 0; i < pixels; ++i) raster.counts[i] += t.density[i];
        std::fill(t.density.begin(), t.density.end(), 0);
        for (std::uint32_t p : t.carries) raster.counts[p] += 256;
        t.carries.clear();
      }
      if (!t.labels.empty()) {
        for (std::size_t i = 0; i < pixels; ++i)
          if (t.labels[i] != kNoLabel && (raster.labels[i] == 0 || t.labels[i] + 1 < raster.labels[i]))
            raster.labels[i] = t.labels[i] + 1;
        // labels are a minimum: keeping them is harmless and saves a pass
      }
      if (!t.lengthSums.empty()) {
        for (std::size_t i = 0; i < pixels; ++i) raster.lengthSums[i] += t.lengthSums[i];
        std::fill(t.lengthSums.begin(), t.lengthSums.end(), 0);
      }
      raster.pointsBinned += t.binned;
      t.binned = 0;
    }
    raster.orbitWrapped = wrapped_;
    raster.pointsIterated = pointsDone_.load();
  }

  void notify(std::uint32_t pass, const PortraitRaster* snapshot, bool final) {
    if (!observer_) return;
    PortraitProgress p;
    p.pointsDone = pointsDone_.load();
    p.pointsTotal = orbitCount_ * steps_;
    p.pass = pass;
    p.passes = passes_;
    p.snapshot = snapshot;
    p.final = final;
    observer_(p);
  }

  const PortraitRequest& r_;
  const PortraitObserver& observer_;
  std::stop_token stop_;
  MapCoefficients coef_;
  ScalarStep step_;
  PixelMapping mapping_;
  std::uint64_t orbitCount_;
  std::uint64_t steps_;
  KernelSettings blocks_;  // Stickiness
  DensityKernel densityKernel_;
  std::vector<UnitState> states_;
  std::vector<TrappingOrbit> trapping_;
  std::vector<std::uint8_t> wrapped_;  // Orbits mode, per seed (each written by the one thread owning its group)
  std::vector<ThreadRaster> threads_;
  std::atomic<std::uint64_t> pointsDone_{0};
  std::uint32_t passes_ = 0;  // of passSchedule()
};

}  // namespace

PortraitResult renderPortrait(const PortraitRequest& request, const PortraitObserver& observer, std::stop_token stop) {
  if (auto e = validationError(request)) throw std::invalid_argument(*e);
  return Renderer(request, observer, std::move(stop)).run();
}

}  // namespace archipelago
