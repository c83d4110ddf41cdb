#pragma once
/// \file LongOrbit.hpp
/// \brief Fig. 8 of the report (Karney 1983, §7): "the longest orbit segment seen for K = 0.1 … spends most of
/// its time around such a chain of islands whose order is 6 × 23 = 138".  The run's longest segment, replayed
/// exactly and zoomed to where it stuck, with its chain identified; and, when that segment sticks elsewhere, the
/// longest of the run's next few segments that sticks to the 138-chain.  Every step is core/periodic's
/// (traceSegment, identifySegmentChain, framedInBox): the GUI's long-segment table does the same for one row.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/periodic/SegmentAnalysis.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago::report {

/// One recorded segment, replayed and identified.
struct LongOrbitView {
  std::size_t rank = 0;               ///< in the run's longest-segment list (0: the longest)
  SegmentRecord record;
  std::uint64_t steps = 0;            ///< q · record.length
  SegmentChain chain;                 ///< from its first kChainIdentificationPoints points
  std::vector<PhysicalPoint> points;  ///< the exact replay, every stride-th state (at most maxPoints)
  SegmentRegion view;                 ///< chain.island framed to a square inside the box
  std::string command;                ///< the archipelago-cli replay command that identifies it alone
};

/// Whether `chain` is the paper's 138 = 6 × 23 chain (its period, or a level of its hierarchy, is 138).
[[nodiscard]] bool isChain138(const IslandChain& chain) noexcept;

struct LongOrbitFigures {
  std::optional<LongOrbitView> longest;   ///< rank 0; none when the run recorded no identifiable segment
  std::optional<LongOrbitView> chain138;  ///< the first of ranks 0 … examined−1 on the 138-chain, if any
  std::size_t examined = 0;               ///< ranks identified in the search for the 138-chain
};

/// Replays and identifies the run's longest segment, then ranks 1, 2, … up to `candidates` − 1 (fewer when the
/// run kept fewer) until one sticks to the 138-chain.  `maxPoints` ≥ 3 states are kept of each replay drawn.
/// `runFile` names the run in the commands.  Segments too short to identify are skipped.
[[nodiscard]] LongOrbitFigures longOrbitFigures(const TrappingState& run, std::size_t candidates,
                                                std::uint64_t maxPoints, const std::string& runFile);

/// Where a replayed segment's figure came from (its PNG's text): the run's map (K, the box), the view (the frame
/// drawn, `v.view`), the image, the orbit, the segment's steps and the replay's command.
[[nodiscard]] Provenance longOrbitProvenance(const TrappingState& run, const LongOrbitView& v);

}  // namespace archipelago::report
