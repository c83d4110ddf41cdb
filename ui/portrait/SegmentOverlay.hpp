#pragma once
/// \file SegmentOverlay.hpp
/// \brief What the portrait's "selected long segment" and "periodic orbits" layers draw.
///
/// The PortraitController owns these layers (PortraitLayer): it keeps the replay, its chain and the step
/// shown, and asks these functions for fresh plot items whenever one of them changes.  The segment is drawn
/// as dots coloured by time (core's viridis map: early dark blue → late yellow), the steps just before the
/// one shown as a white trail ending in a ring, the chain's centre orbit as cyan discs and orbits from the
/// "Find periodic orbit" dialog as magenta diamonds.  All in physical coordinates.

#include <QStringList>

#include <vector>

#include "core/periodic/PeriodicOrbit.hpp"
#include "ui/portrait/SegmentResults.hpp"

class QwtPlotItem;

namespace archipelago::ui {

struct SegmentOverlay {
  /// Steps of the trail drawn behind the step shown (kept states).
  static constexpr std::size_t kTrailStates = 200;

  /// The segment's dots (none without a replay).
  [[nodiscard]] static std::vector<QwtPlotItem*> segmentItems(const SegmentReplayPtr& replay);
  /// The chain's centre orbit (none when unknown).
  [[nodiscard]] static std::vector<QwtPlotItem*> chainItems(const ChainResultPtr& chain);
  /// The kept state `index` of the segment with the trail before it (none without a replay).
  [[nodiscard]] static std::vector<QwtPlotItem*> stepItems(const SegmentReplayPtr& replay, std::size_t index);
  /// A periodic orbit's points.
  [[nodiscard]] static std::vector<QwtPlotItem*> periodicItems(const PeriodicOrbit& orbit);
  /// The legend's lines (rich text) for what is drawn; periodicPeriod 0: no periodic orbit.
  [[nodiscard]] static QStringList legendLines(const SegmentReplayPtr& replay, const ChainResultPtr& chain,
                                               int periodicPeriod);
};

}  // namespace archipelago::ui
