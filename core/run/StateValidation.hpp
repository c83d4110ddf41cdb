#pragma once
/// \file StateValidation.hpp
/// \brief The internal consistency of a TrappingState, checked whole: what a run file, a checkpoint or a
/// merge must satisfy before a single statistic is computed from it (docs/design.md, "no silent wrong answer").
///
/// The rules follow from how runTrapping() builds a state (BlockKernel.hpp, appendix B):
///  - orbits: one state per orbit of [orbitBegin, orbitEnd), each at block blocksDone; the open segment
///    started at start.block and has `length` blocks, so start.block + length = blocksDone; at most one
///    random draw per block, so start.draws ≤ draws ≤ block and start.draws ≤ start.block;
///  - histograms: one per subset; every bin non-empty with its length sum inside the bin's range (exactly
///    count·t for the exact bins); segments of an orbit are disjoint, so the lengths of subset s sum to at
///    most (orbits of s)·blocksDone — which also bounds every count and rules out overflowing sums; no
///    length exceeds blocksDone;
///  - longest segments: at most longestKept, ranked; each was recorded (start.block ≥ 1), lies inside the
///    blocks done (start.block + length ≤ blocksDone), used at most one draw per block, and is counted in
///    the histogram of its orbit's subset.

#include <optional>
#include <string>

#include "core/run/TrappingRun.hpp"

namespace archipelago {

/// The first inconsistency of `state` as one line, or nothing.  Assumes valid parameters.
[[nodiscard]] std::optional<std::string> consistencyError(const TrappingState& state);

}  // namespace archipelago
