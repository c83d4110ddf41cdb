#include "trapping/BlockKernel.hpp"

#include <algorithm>


namespace archipelago {

namespace {
// Ends the open segment of `s` after a block: hand it to the sink, start the next one at the current state.
inline void endSegment(std::uint64_t orbit, OrbitState& s, SegmentSink* sink) {
  if (sink) sink->record(orbit, s.length, s.start);
  s.length = 0;
  s.start = {s.z, s.block, s.draws};
}
}  // namespace

bool advanceOneBlock(const KernelSettings& k, std::uint64_t orbit, OrbitState& s, SegmentSink* sink) {
  const bool ended = advanceBlockVisiting(k, orbit, s, [](const UnitState&) {});
  if (ended) endSegment(orbit, s, sink);
  return ended;
}

void advanceBlocksScalar(const KernelSettings& k, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                         std::uint64_t blocks, SegmentSink& sink) {
  // Lanes of independent orbits advanced in lockstep: the three 128-bit products of a step form a long
  // dependency chain, and interleaving several orbits lets the CPU overlap them.
  constexpr std::size_t kLanes = 8;
  for (std::size_t first = 0; first < orbits.size(); first += kLanes) {
    const std::size_t n = std::min(kLanes, orbits.size() - first);
    if (n < kLanes) {  // a ragged tail: one orbit at a time
      for (std::size_t i = first; i < orbits.size(); ++i)
        for (std::uint64_t b = 0; b < blocks; ++b) advanceOneBlock(k, firstOrbit + i, orbits[i], &sink);
      break;
    }
    UnitState z[kLanes];
    for (std::size_t l = 0; l < kLanes; ++l) z[l] = orbits[first + l].z;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      bool ended[kLanes];
      for (std::size_t l = 0; l < kLanes; ++l) {
        OrbitState& s = orbits[first + l];
        s.length += 1;
        ended[l] = z[l].X <= k.randomizingX;
        if (ended[l]) {
          s.draws += 1;
          z[l].Y = (z[l].Y + orbitDraw(orbitKey(k.seed, firstOrbit + first + l), s.draws)) & fixedpoint::kMask;
        }
      }
      for (std::uint32_t j = 0; j < k.q; ++j)
        for (std::size_t l = 0; l < kLanes; ++l) ended[l] |= backwardStep(k.coefficients, z[l]);
      for (std::size_t l = 0; l < kLanes; ++l) {
        OrbitState& s = orbits[first + l];
        s.block += 1;
        if (ended[l]) {
          s.z = z[l];
          endSegment(firstOrbit + first + l, s, &sink);
        }
      }
    }
    for (std::size_t l = 0; l < kLanes; ++l) orbits[first + l].z = z[l];
  }
}

}  // namespace archipelago
