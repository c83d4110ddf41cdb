#include "core/run/TrappingRun.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/io/NumberText.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/limits/Limits.hpp"
#include "core/parallel/ParallelFor.hpp"


namespace archipelago {

TrappingHistogram TrappingState::total() const {
  TrappingHistogram h;
  for (const auto& s : subsets) h.merge(s);
  return h;
}

double TrappingState::stepsDone() const noexcept {
  return static_cast<double>(orbitEnd - orbitBegin) * static_cast<double>(blocksDone) * params.q;
}

std::optional<std::string> orbitRangeError(std::uint64_t M, std::uint64_t begin, std::uint64_t end) {
  if (begin < end && end <= M) return std::nullopt;
  return "orbits [" + std::to_string(begin) + ", " + std::to_string(end) + ") must satisfy begin < end ≤ M = " +
         std::to_string(M);
}

std::optional<std::string> orbitPartsError(std::uint64_t count, std::uint64_t M, std::string_view parts) {
  if (count <= M) return std::nullopt;
  return std::to_string(count) + " " + std::string(parts) + " for M = " + std::to_string(M) + " orbits: use at most M " +
         std::string(parts);
}

TrappingState startTrapping(const TrappingParameters& params, std::uint64_t orbitBegin, std::uint64_t orbitEnd) {
  validate(params);
  if (orbitEnd == kAllOrbits) orbitEnd = params.M;
  if (auto e = orbitRangeError(params.M, orbitBegin, orbitEnd)) throw std::invalid_argument(*e);
  TrappingState s;
  s.params = params;
  s.coefficients = computeCoefficients(params.map);
  s.orbitBegin = orbitBegin;
  s.orbitEnd = orbitEnd;
  s.orbits.resize(orbitEnd - orbitBegin);  // every orbit starts at (X, Y) = (0, 0), appendix B step 2
  s.subsets.resize(params.subsets);
  s.longest = LongestSegments(params.longestKept);
  return s;
}

namespace {
void checkMergeable(const TrappingState& a, const TrappingState& b) {
  if (!(a.params == b.params) || !(a.coefficients == b.coefficients))
    throw std::invalid_argument("cannot merge runs with different parameters");
  if (a.blocksDone != b.blocksDone)
    throw std::invalid_argument("cannot merge runs at different progress (blocks done differ)");
}
}  // namespace

void appendTrappingRange(TrappingState& lo, const TrappingState& hi) {
  checkMergeable(lo, hi);
  if (lo.orbitEnd != hi.orbitBegin) throw std::invalid_argument("cannot merge runs over non-adjacent orbit ranges");
  lo.orbitEnd = hi.orbitEnd;
  lo.orbits.insert(lo.orbits.end(), hi.orbits.begin(), hi.orbits.end());
  for (std::size_t i = 0; i < lo.subsets.size(); ++i) lo.subsets[i].merge(hi.subsets[i]);
  lo.longest.merge(hi.longest);
  lo.elapsedSeconds += hi.elapsedSeconds;
  lo.unverified = lo.unverified || hi.unverified;  // a merge of an unverified part is unverified
}

TrappingState mergeTrapping(const TrappingState& a, const TrappingState& b) {
  checkMergeable(a, b);
  TrappingState m = a.orbitBegin <= b.orbitBegin ? a : b;
  appendTrappingRange(m, a.orbitBegin <= b.orbitBegin ? b : a);
  return m;
}

namespace {
using Clock = std::chrono::steady_clock;

KernelSettings kernelSettings(const TrappingState& s) {
  return blockSettings(s.coefficients, s.params.Xr, s.params.q, s.params.seed);
}
}  // namespace

TrappingState runTrapping(TrappingState state, const TrappingRunOptions& options, const TrappingObserver& observer,
                          std::stop_token stop) {
  const KernelSettings settings = kernelSettings(state);
  const int threads = parallelThreads(options.threads);
  const std::size_t orbitCount = state.orbits.size();
  const KernelInfo& kernel = kernelOrBest(options.kernel);
  state.kernel = std::string(kernel.name);
  const std::size_t groupSize = orbitsPerTask(kernel, orbitCount, threads);
  const std::size_t groups = (orbitCount + groupSize - 1) / groupSize;

  const auto sessionStart = Clock::now();
  const double stepsPerBlock = static_cast<double>(orbitCount) * state.params.q;
  std::uint64_t chunk = 16;  // blocks per chunk; adapted to options.chunkSeconds as the rate is measured
  std::uint64_t sessionBlocks = 0;

  const std::uint64_t endBlocks =
      options.untilBlocks == 0 ? state.params.T : std::min(options.untilBlocks, state.params.T);
  while (state.blocksDone < endBlocks && !stop.stop_requested()) {
    std::uint64_t blocks = std::min(chunk, endBlocks - state.blocksDone);
    if (options.maxChunkBlocks) blocks = std::min(blocks, options.maxChunkBlocks);
    std::vector<SegmentSink> sinks(static_cast<std::size_t>(threads),
                                   SegmentSink(state.params.subsets, state.params.longestKept));
    const auto chunkStart = Clock::now();
    // No stop token here: a chunk must complete, or orbits would stand at different blocks.
    parallelFor(
        groups,
        [&](std::size_t g, int thread) {
          const std::size_t first = g * groupSize;
          const std::size_t n = std::min(groupSize, orbitCount - first);
          kernel.blocks(settings, std::span<OrbitState>(state.orbits.data() + first, n), state.orbitBegin + first,
                        blocks, sinks[static_cast<std::size_t>(thread)]);
        },
        {}, threads);
    for (const auto& sink : sinks) {
      for (std::size_t i = 0; i < state.subsets.size(); ++i) state.subsets[i].merge(sink.subsets()[i]);
      state.longest.merge(sink.longest());
    }
    state.blocksDone += blocks;
    sessionBlocks += blocks;
    const auto now = Clock::now();
    const double chunkSeconds = std::chrono::duration<double>(now - chunkStart).count();
    const double sessionSeconds = std::chrono::duration<double>(now - sessionStart).count();
    state.elapsedSeconds += chunkSeconds;
    // Aim the next chunk at options.chunkSeconds, growing at most 4× at a time.
    const double perBlock = chunkSeconds / static_cast<double>(blocks);
    if (perBlock > 0) {
      const double target = options.chunkSeconds / perBlock;
      chunk = static_cast<std::uint64_t>(std::clamp(target, 1.0, 4.0 * static_cast<double>(blocks)));
    } else {
      chunk = 4 * blocks;
    }
    if (observer) {
      TrappingProgress p;
      p.blocksDone = state.blocksDone;
      p.blocksTotal = state.params.T;
      p.fraction = static_cast<double>(state.blocksDone) / static_cast<double>(state.params.T);
      p.sessionSeconds = sessionSeconds;
      p.stepsPerSecond = sessionSeconds > 0 ? static_cast<double>(sessionBlocks) * stepsPerBlock / sessionSeconds : 0;
      p.etaSeconds = p.stepsPerSecond > 0
                         ? static_cast<double>(state.params.T - state.blocksDone) * stepsPerBlock / p.stepsPerSecond
                         : 0;
      observer(state, p);
    }
  }
  return state;
}

std::optional<std::uint64_t> replaySegmentUntil(const TrappingParameters& params, const SegmentRecord& record,
                                                const std::function<bool(std::uint64_t, const UnitState&)>& visit,
                                                std::stop_token stop) {
  constexpr std::uint64_t kBlocksBetweenStopChecks = 4096;  // a few ms of work at q = 16
  validate(params);
  const KernelSettings k = blockSettings(computeCoefficients(params.map), params.Xr, params.q, params.seed);
  OrbitState s;
  s.z = record.start.z;
  s.block = record.start.block;
  s.draws = record.start.draws;
  s.start = record.start;
  std::uint64_t step = 0;
  bool more = visit(step, s.z);
  // Bounded by the record, never by T: a record whose start lies in an island (an edited or foreign run file)
  // would otherwise replay for up to q·T steps (issue #12, finding 5).
  while (more) {
    if (s.length % kBlocksBetweenStopChecks == 0 && stop.stop_requested()) return std::nullopt;
    const bool ended = advanceBlockVisiting(k, record.orbit, s, [&](const UnitState& z) {
      ++step;
      if (more) more = visit(step, z);
    });
    if (ended && s.length != record.length)
      throw std::runtime_error("replay mismatch: the segment ended after " + std::to_string(s.length) +
                               " blocks, the run recorded " + std::to_string(record.length));
    if (ended) break;
    if (s.length >= record.length) {
      if (s.block >= params.T) break;  // cut by the run's last block, where the record says
      throw std::runtime_error("replay mismatch: the segment did not end after the " + std::to_string(record.length) +
                               " blocks the run recorded");
    }
    if (s.block >= params.T)
      throw std::runtime_error("replay mismatch: the run's last block came after " + std::to_string(s.length) +
                               " blocks, the run recorded " + std::to_string(record.length));
  }
  return s.length;
}

std::uint64_t replaySegment(const TrappingParameters& params, const SegmentRecord& record,
                            const std::function<void(std::uint64_t, const UnitState&)>& visit) {
  return *replaySegmentUntil(params, record, [&](std::uint64_t step, const UnitState& z) {
    if (visit) visit(step, z);
    return true;
  });
}

std::optional<std::string> chunkSecondsError(double chunkSeconds) {
  return realIntervalError("chunk_seconds", chunkSeconds, 0, true, 3600);
}

std::optional<std::string> subsetIndexError(std::uint64_t index, std::uint64_t count) {
  if (index < count) return std::nullopt;
  return rangeError("subset", index, 0, static_cast<long long>(count) - 1);
}

}  // namespace archipelago
