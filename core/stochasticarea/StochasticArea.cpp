#include "core/stochasticarea/StochasticArea.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include "core/limits/Limits.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/kernels/TracedBlocks.hpp"

namespace archipelago {

std::optional<std::string> validationError(const StochasticAreaRequest& r) {
  if (auto e = mapError(r.map)) return e;
  if (auto e = randomizingZoneError(r.Xr)) return e;
  if (auto e = rangeError("q", r.q, 1, limits::kRasterQ)) return e;
  if (auto e = rangeError("orbits", r.orbits, 1, limits::kRasterOrbits)) return e;
  if (auto e = rangeError("gridBits", r.gridBits, 1, 12)) return e;
  if (auto e = rangeError("iterations", r.iterations, 1, 1LL << 50)) return e;
  if (auto e = lowerBoundError("firstCheckpoint", r.firstCheckpoint, 1)) return e;
  return std::nullopt;
}

StochasticAreaResult computeStochasticArea(const StochasticAreaRequest& r, const StochasticAreaObserver& observer,
                                           std::stop_token stop) {
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const KernelSettings settings = blockSettings(computeCoefficients(r.map), r.Xr, r.q, r.seed);
  const int shift = FixedPointMap::kBits - r.gridBits;
  const std::uint64_t boxes = std::uint64_t{1} << (2 * r.gridBits);
  const std::size_t words = static_cast<std::size_t>((boxes + 63) / 64);
  constexpr std::uint64_t kChunkBlocks = std::uint64_t{1} << 12;  // ≤ 2^16 steps at q = 16

  // Blocks per orbit at each checkpoint: total steps doubling from firstCheckpoint, ending at `iterations`.
  auto blocksFor = [&](std::uint64_t totalSteps) {
    const std::uint64_t perOrbit = (totalSteps + r.orbits - 1) / r.orbits;
    return (perOrbit + r.q - 1) / r.q;
  };
  std::vector<std::uint64_t> checkpoints;
  for (std::uint64_t t = std::min(r.firstCheckpoint, r.iterations); t < r.iterations; t *= 2)
    if (checkpoints.empty() || blocksFor(t) > checkpoints.back()) checkpoints.push_back(blocksFor(t));
  if (checkpoints.empty() || blocksFor(r.iterations) > checkpoints.back()) checkpoints.push_back(blocksFor(r.iterations));

  std::vector<OrbitState> orbits(r.orbits);  // from (0, 0), as trapping runs
  const KernelInfo& kernel = kernelOrBest(r.kernel);
  const std::size_t groupSize = orbitsPerTask(kernel, r.orbits, parallelThreads());
  const std::size_t groups = (r.orbits + groupSize - 1) / groupSize;
  std::vector<std::vector<std::uint64_t>> threadBits(static_cast<std::size_t>(parallelThreads()),
                                                     std::vector<std::uint64_t>(words, 0));
  std::vector<std::uint64_t> visited(words, 0);

  StochasticAreaResult result;
  result.boxes = boxes;
  std::uint64_t blocksDone = 0;
  for (const std::uint64_t target : checkpoints) {
    while (blocksDone < target && !stop.stop_requested()) {
      const std::uint64_t blocks = std::min(kChunkBlocks, target - blocksDone);
      const bool complete = parallelFor(
          groups,
          [&](std::size_t g, int thread) {
            std::uint64_t* bits = threadBits[static_cast<std::size_t>(thread)].data();
            const std::size_t first = g * groupSize;
            const std::size_t n = std::min<std::size_t>(groupSize, r.orbits - first);
            advanceBlocksTraced(settings, kernel.orbits, std::span<OrbitState>(orbits.data() + first, n), first, blocks,
                                [&](std::span<const UnitState> trace) {
                                  for (const UnitState& z : trace) {
                                    const std::uint64_t box = ((z.Y >> shift) << r.gridBits) | (z.X >> shift);
                                    bits[box >> 6] |= std::uint64_t{1} << (box & 63);
                                  }
                                });
          },
          stop);
      if (!complete) break;  // orbits at different blocks: this checkpoint is not reached
      blocksDone += blocks;
    }
    if (blocksDone < target) {
      result.cancelled = true;
      break;
    }
    for (const auto& bits : threadBits)
      for (std::size_t w = 0; w < words; ++w) visited[w] |= bits[w];
    std::uint64_t count = 0;
    for (std::uint64_t w : visited) count += static_cast<std::uint64_t>(std::popcount(w));
    StochasticAreaPoint p{blocksDone * r.q * r.orbits, count, static_cast<double>(count) / static_cast<double>(boxes)};
    result.convergence.push_back(p);
    if (observer) observer(p);
  }
  result.visited.resize(static_cast<std::size_t>(boxes));
  for (std::uint64_t b = 0; b < boxes; ++b) result.visited[b] = static_cast<std::uint8_t>((visited[b >> 6] >> (b & 63)) & 1);
  return result;
}

}  // namespace archipelago
