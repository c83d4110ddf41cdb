#include "core/trapping/BlockKernel.hpp"

#include <algorithm>

#include "core/map/ScalarStep.hpp"


namespace archipelago {

namespace {
// Ends the open segment of `s` after a block: hand it to the sink, start the next one at the current state.
inline void endSegment(std::uint64_t orbit, OrbitState& s, SegmentSink* sink) {
  if (sink) sink->record(orbit, s.length, s.start);
  restartSegment(s);
}
}  // namespace

bool advanceOneBlock(const KernelSettings& k, std::uint64_t orbit, OrbitState& s, SegmentSink* sink) {
  const bool ended = advanceBlockVisiting(k, orbit, s, [](const UnitState&) {});
  if (ended) endSegment(orbit, s, sink);
  return ended;
}



void advanceBlocksScalar(const KernelSettings& k, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                         std::uint64_t blocks, SegmentSink& sink) {
  // Lanes of independent orbits advanced in lockstep: the three products of a step form a long dependency
  // chain, and interleaving several orbits lets the CPU overlap them.
  constexpr std::size_t kLanes = kScalarBlockOrbits;
  const ScalarStep c(k.coefficients);
  for (std::size_t first = 0; first < orbits.size(); first += kLanes) {
    const std::size_t n = std::min(kLanes, orbits.size() - first);
    if (n < kLanes) {  // a ragged tail: one orbit at a time
      for (std::size_t i = first; i < orbits.size(); ++i)
        for (std::uint64_t b = 0; b < blocks; ++b) advanceOneBlock(k, firstOrbit + i, orbits[i], &sink);
      break;
    }
    // Per-lane counters and the lane's subset histogram live here, not in OrbitState: a block touches only
    // these, and an ended segment goes straight to its histogram (SegmentSink::record without the division).
    std::uint64_t X[kLanes], Y[kLanes], length[kLanes], block0[kLanes];
    TrappingHistogram* subset[kLanes];
    for (std::size_t l = 0; l < kLanes; ++l) {
      const OrbitState& s = orbits[first + l];
      X[l] = s.z.X;
      Y[l] = s.z.Y;
      length[l] = s.length;
      block0[l] = s.block;
      subset[l] = &sink.subsets()[(firstOrbit + first + l) % sink.subsets().size()];
    }
    LongestSegments& longest = sink.longest();
    for (std::uint64_t b = 0; b < blocks; ++b) {
      std::uint64_t wrap[kLanes] = {};
      unsigned zone = 0;
      ARCHIPELAGO_UNROLL_LANES
      for (std::size_t l = 0; l < kLanes; ++l) {
        length[l] += 1;
        zone |= (X[l] <= k.randomizingX ? 1u : 0u) << l;
      }
      for (unsigned bits = zone; bits; bits &= bits - 1) {  // appendix B, 6.1–6.2
        const auto l = static_cast<std::size_t>(__builtin_ctz(bits));
        OrbitState& s = orbits[first + l];
        s.draws += 1;
        Y[l] = (Y[l] + orbitDraw(orbitKey(k.seed, firstOrbit + first + l), s.draws)) & fixedpoint::kMask;
      }
      for (std::uint32_t j = 0; j < k.q; ++j) {
        ARCHIPELAGO_UNROLL_LANES
        for (std::size_t l = 0; l < kLanes; ++l) c.backward(X[l], Y[l], wrap[l]);
      }
      unsigned ended = zone;
      ARCHIPELAGO_UNROLL_LANES
      for (std::size_t l = 0; l < kLanes; ++l) ended |= (wrap[l] >= fixedpoint::kOne ? 1u : 0u) << l;
      for (unsigned bits = ended; bits; bits &= bits - 1) {  // endSegment(), with SegmentSink::record inlined
        const auto l = static_cast<std::size_t>(__builtin_ctz(bits));
        OrbitState& s = orbits[first + l];
        if (isRecorded(s.start)) {
          subset[l]->add(length[l]);
          if (longest.mightKeep(length[l])) longest.insert({firstOrbit + first + l, length[l], s.start});
        }
        length[l] = 0;
        s.start = {{X[l], Y[l]}, block0[l] + b + 1, s.draws};
      }
    }
    for (std::size_t l = 0; l < kLanes; ++l) {
      OrbitState& s = orbits[first + l];
      s.length = length[l];
      s.block = block0[l] + blocks;
    }
    for (std::size_t l = 0; l < kLanes; ++l) orbits[first + l].z = {X[l], Y[l]};
  }
}

}  // namespace archipelago
