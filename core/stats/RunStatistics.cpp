#include "core/stats/RunStatistics.hpp"

namespace archipelago {

std::vector<std::uint64_t> orbitsPerSubset(const TrappingState& state) {
  const std::uint64_t n = state.params.subsets;
  std::vector<std::uint64_t> counts(n, 0);
  for (std::uint64_t i = state.orbitBegin; i < state.orbitEnd; ++i) counts[i % n] += 1;
  return counts;
}

TrappingStatistics statisticsOf(const TrappingState& state) {
  return computeStatistics(state.subsets, orbitsPerSubset(state), state.blocksDone, state.params.q);
}

}  // namespace archipelago
