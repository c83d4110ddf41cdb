#pragma once
/// \file SegmentResults.hpp
/// \brief What the background jobs of the long-segment table hand to the GUI: immutable values.
///
/// Both are computed by core (periodic/SegmentAnalysis.hpp) as background jobs (ui/jobs) and passed as shared
/// pointers to const, so the GUI can keep and read them without locks.

#include <QMetaType>
#include <QString>

#include <memory>
#include <optional>

#include "core/periodic/SegmentAnalysis.hpp"
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago::ui {

/// A replayed segment with where it spent its time (the view it is drawn in).
struct SegmentReplay {
  TrappingParameters params;
  SegmentTrace trace;
  SegmentRegion region;     ///< dwellRegion(trace.points): the densest 90 %, with a margin
  double seconds = 0;       ///< wall time of the replay (diagnostics)
};
using SegmentReplayPtr = std::shared_ptr<const SegmentReplay>;

/// The island chain of a segment, or why it could not be identified.
struct ChainResult {
  std::optional<IslandChain> chain;
  SegmentRegion island;     ///< SegmentChain::island: one island of the chain with its satellites
  QString error;
  double seconds = 0;
};
using ChainResultPtr = std::shared_ptr<const ChainResult>;

/// A segment's identity within a run: (orbit, first block).
struct SegmentKey {
  std::uint64_t orbit = 0;
  std::uint64_t block = 0;
  [[nodiscard]] static SegmentKey of(const SegmentRecord& r) noexcept { return {r.orbit, r.start.block}; }
  friend auto operator<=>(const SegmentKey&, const SegmentKey&) = default;
};

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::SegmentReplayPtr)
Q_DECLARE_METATYPE(archipelago::ui::ChainResultPtr)
