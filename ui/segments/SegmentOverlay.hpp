#pragma once
/// \file SegmentOverlay.hpp
/// \brief Draws a replayed segment, the step shown, and periodic orbits on a PortraitView, and zooms it.
///
/// The segment is drawn as dots coloured by time (core's viridis map: early dark blue → late yellow), the
/// steps just before the one shown as a white trail ending in a ring, the chain's centre orbit as cyan discs
/// and orbits from the "Find periodic orbit" dialog as magenta diamonds.  The items are plain QwtPlotItems
/// attached to the view's plot (physical coordinates); the view keeps rendering the portrait beneath them.
/// Zooming uses the view's own Viewport (core): the region is first framed to the canvas's aspect ratio and
/// the box by core's framedInBox().

#include <QObject>
#include <QPointer>

#include <memory>
#include <vector>

#include "core/periodic/PeriodicOrbit.hpp"
#include "ui/segments/SegmentResults.hpp"

class QwtPlot;
class QwtPlotTextLabel;

namespace archipelago::ui {

class PortraitView;
class PointsItem;

class SegmentOverlay : public QObject {
  Q_OBJECT
 public:
  explicit SegmentOverlay(PortraitView* view, QObject* parent = nullptr);
  ~SegmentOverlay() override;

  /// Draws the segment (replacing the previous one) and zooms to where it spent its time.
  void showReplay(const SegmentReplayPtr& replay);
  /// Draws the chain's centre orbit (or removes it when `chain` has none).
  void showChain(const ChainResultPtr& chain);
  /// Marks the kept state `index` of the segment shown, with a trail of the states before it.
  void showStep(std::size_t index);
  /// Draws a periodic orbit found in the dialog (replacing the previous one).
  void showPeriodicOrbit(const PeriodicOrbit& orbit);
  /// Removes everything drawn.
  void clear();

  /// Zoom to the whole segment's region / to one island of its chain (when known).
  void zoomToSegment();
  void zoomToIsland();

 private:
  void zoomTo(const SegmentRegion& region);
  void replot();
  void updateLegend();
  [[nodiscard]] QwtPlot* plot() const;

  QPointer<PortraitView> view_;
  SegmentReplayPtr replay_;
  ChainResultPtr chain_;
  PointsItem* segment_ = nullptr;
  PointsItem* trail_ = nullptr;
  PointsItem* centre_ = nullptr;
  PointsItem* periodic_ = nullptr;
  QwtPlotTextLabel* legend_ = nullptr;   // what is drawn, top left of the canvas
  int periodicPeriod_ = 0;               // of the dialog's orbit shown (0: none)
};

}  // namespace archipelago::ui
