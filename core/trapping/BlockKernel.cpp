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

// The lane loops must be unrolled so that the lanes' products interleave (GCC does not at -O2 by itself).
#if defined(__clang__)
#define ARCHIPELAGO_UNROLL_LANES _Pragma("clang loop unroll(full)")
#else
#define ARCHIPELAGO_UNROLL_LANES _Pragma("GCC unroll 8")
#endif

namespace {
// N⁻¹ in the form the scalar kernel computes it: for a, b < 2^52, ⌊a·b/2^52⌋ = ⌊(a·2^12)·b/2^64⌋ is the high
// word of one 64×64-bit product (mul/mulx, no double-word shift), with A·2^12 and B·2^12 precomputed.  The
// same integers as backwardStep() in FixedPointMap.hpp (exact floor divisions of the same products).
struct ScalarStep {
  std::uint64_t A12, B12, C;
  int m;
  explicit ScalarStep(const MapCoefficients& c)
      : A12(static_cast<std::uint64_t>(c.A) << 12), B12(static_cast<std::uint64_t>(c.B) << 12),
        C(static_cast<std::uint64_t>(c.C)), m(c.m) {}
};

inline std::uint64_t mulHigh(std::uint64_t a, std::uint64_t b) noexcept {
  return static_cast<std::uint64_t>((uint128{a} * b) >> 64);
}

/// One step of N⁻¹; ORs into `wrap` a word with a bit ≥ 52 set when the step wrapped.
inline void backwardScalar(const ScalarStep& c, std::uint64_t& X, std::uint64_t& Y, std::uint64_t& wrap) noexcept {
  using namespace fixedpoint;
  const std::uint64_t s = X - Y + kHalf;
  const std::uint64_t x = s & kMask;
  const std::uint64_t x2 = mulHigh(x << 12, x);                          // ⌊x²/2^52⌋
  const std::uint64_t G = (mulHigh(c.A12, x2) - mulHigh(c.B12, x) + c.C) << c.m;  // fixedPointG(x)
  const std::uint64_t u = Y - G;
  X = x;
  Y = u & kMask;
  wrap |= s | u;
}
}  // namespace

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
        for (std::size_t l = 0; l < kLanes; ++l) backwardScalar(c, X[l], Y[l], wrap[l]);
      }
      unsigned ended = zone;
      ARCHIPELAGO_UNROLL_LANES
      for (std::size_t l = 0; l < kLanes; ++l) ended |= (wrap[l] >= fixedpoint::kOne ? 1u : 0u) << l;
      for (unsigned bits = ended; bits; bits &= bits - 1) {  // endSegment(), with SegmentSink::record inlined
        const auto l = static_cast<std::size_t>(__builtin_ctz(bits));
        OrbitState& s = orbits[first + l];
        if (s.start.block != 0) {
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
