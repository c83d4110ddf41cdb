#pragma once
/// \file SegmentResults.hpp
/// \brief What the background jobs of the long-segment table hand to the GUI, and the portrait draws:
/// immutable values.
///
/// Both are computed by core (periodic/SegmentAnalysis.hpp) as background jobs (ui/jobs) of the long-segment
/// panel (ui/segments) and passed as shared pointers to const, so the GUI can keep and read them without locks.
/// They live here, in the portrait's folder, because the portrait's segment layers (SegmentOverlay) draw them:
/// the segment panel depends on the portrait, never the other way round.

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

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::SegmentReplayPtr)
Q_DECLARE_METATYPE(archipelago::ui::ChainResultPtr)
