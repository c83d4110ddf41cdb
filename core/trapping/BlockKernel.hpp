#pragma once
/// \file BlockKernel.hpp
/// \brief The trapping block (appendix B, steps 5–9) for a group of orbits, and where ended segments go.
///
/// One block of an orbit: length ← length + 1; if X ≤ ⌊Xr·2^52⌋ then Y ← Y + U (the orbit's next draw) and the
/// segment ends; then N⁻¹ is applied q times and any wrap ends the segment.  When the segment ends it is
/// handed to the SegmentSink with its start state, and the next segment starts from the state after the
/// block.  Kernels (scalar here; vector ones in core/kernels) must produce bit-identical orbit states and
/// identical sink calls, in any order.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/random/CounterRng.hpp"
#include "core/trapping/LongestSegments.hpp"
#include "core/trapping/TrappingHistogram.hpp"
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago {

/// What a kernel needs besides the orbits: plain integers.
struct KernelSettings {
  MapCoefficients coefficients;
  std::uint64_t randomizingX = 0;  ///< ⌊Xr·2^52⌋
  std::uint32_t q = 1;
  std::uint64_t seed = 0;
};

/// The settings of blocks of q steps of N⁻¹ with the randomizing zone 0 ≤ X ≤ Xr (unit X) and random seed
/// `seed`: what trapping runs, replays, Stickiness portraits and b₂ all iterate.
[[nodiscard]] inline KernelSettings blockSettings(const MapCoefficients& coefficients, double Xr, std::uint32_t q,
                                                  std::uint64_t seed) noexcept {
  return {coefficients, randomizingThreshold(Xr), q, seed};
}

/// Whether an ended segment counts: not the one that ends in an orbit's first block (it started on X = 0,
/// inside the randomizing zone), so that every recorded segment starts at a random point (docs/design.md, "Trapping statistics").
[[nodiscard]] inline bool isRecorded(const SegmentStart& start) noexcept { return start.block != 0; }

/// Starts the next segment of `s` at its current state, after a block in which the open one ended.
inline void restartSegment(OrbitState& s) noexcept {
  s.length = 0;
  s.start = {s.z, s.block, s.draws};
}

/// Collects ended segments of one thread: the histogram of each subset and the longest segments.
class SegmentSink {
 public:
  SegmentSink(std::uint32_t subsets, std::size_t longestKept) : subsets_(subsets), longest_(longestKept) {}

  /// Records a segment that ended.  The segment that ends in an orbit's first block (it started on X = 0,
  /// inside the randomizing zone) is not recorded, so every recorded segment starts at a random point.
  void record(std::uint64_t orbit, std::uint64_t length, const SegmentStart& start) {
    if (!isRecorded(start)) return;
    subsets_[orbit % subsets_.size()].add(length);
    if (longest_.mightKeep(length)) longest_.insert({orbit, length, start});
  }

  [[nodiscard]] std::vector<TrappingHistogram>& subsets() noexcept { return subsets_; }
  [[nodiscard]] const std::vector<TrappingHistogram>& subsets() const noexcept { return subsets_; }
  [[nodiscard]] LongestSegments& longest() noexcept { return longest_; }
  [[nodiscard]] const LongestSegments& longest() const noexcept { return longest_; }

 private:
  std::vector<TrappingHistogram> subsets_;
  LongestSegments longest_;
};

/// Advances `orbits` (the orbits with indices firstOrbit, firstOrbit + 1, …) by `blocks` blocks each.
using BlockKernel = void (*)(const KernelSettings& settings, std::span<OrbitState> orbits,
                             std::uint64_t firstOrbit, std::uint64_t blocks, SegmentSink& sink);

/// The portable scalar reference kernel (interleaves kScalarBlockOrbits orbits to hide multiply latency;
/// a remainder of fewer is advanced one orbit at a time).
inline constexpr std::size_t kScalarBlockOrbits = 8;
void advanceBlocksScalar(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                         std::uint64_t blocks, SegmentSink& sink);

/// The start of a block (appendix B, 6.1–6.2): length + 1, and when X ≤ ⌊Xr·2^52⌋ (the randomizing zone)
/// Y ← Y + U, the orbit's next draw, which ends the segment.  Returns true when it did.  The q steps of N⁻¹
/// and block + 1 follow (advanceBlockVisiting; kernels/TracedBlocks.hpp).
inline bool enterBlock(const KernelSettings& k, std::uint64_t orbit, OrbitState& s) noexcept {
  s.length += 1;
  if (s.z.X > k.randomizingX) return false;
  s.draws += 1;
  s.z.Y = (s.z.Y + orbitDraw(orbitKey(k.seed, orbit), s.draws)) & fixedpoint::kMask;
  return true;
}

/// One block of one orbit, the definition every kernel must match: length + 1, the randomizing zone, q steps
/// of N⁻¹ (calling afterStep(z) after each), block + 1.  Returns true when the segment ended; it does not
/// close the segment (advanceOneBlock does; other callers use isRecorded() and restartSegment()).  `orbit` is
/// the orbit's index (it selects its random numbers).  Every visiting caller uses it: replays
/// (replaySegmentUntil) and Stickiness portraits (PortraitRenderer.cpp); give it a local copy of the state, so
/// that stores made by afterStep cannot alias it and it stays in registers.
template <class StepVisitor>
inline bool advanceBlockVisiting(const KernelSettings& k, std::uint64_t orbit, OrbitState& s, StepVisitor&& afterStep) {
  bool ended = enterBlock(k, orbit, s);
  for (std::uint32_t j = 0; j < k.q; ++j) {
    ended |= backwardStep(k.coefficients, s.z);
    afterStep(s.z);
  }
  s.block += 1;
  return ended;
}

/// advanceBlockVisiting() without a visitor, closing the segment when it ended: the sink (if any) records it
/// and the next segment starts at the state after the block.  Returns true when the segment ended.
bool advanceOneBlock(const KernelSettings& settings, std::uint64_t orbit, OrbitState& s, SegmentSink* sink);

}  // namespace archipelago
