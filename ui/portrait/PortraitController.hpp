#pragma once
/// \file PortraitController.hpp
/// \brief The one owner of the phase portrait: its view, its map, its view history and its overlay layers.
///
/// Everything that changes the portrait asks this object: the main window sets the map from the parameter
/// panel, the long-segment panel draws a segment and zooms to it, the periodic-orbit dialog's orbit is
/// drawn here, and the portrait panel's buttons navigate.  The PortraitView only draws and renders what this
/// controller hands it (its setters are private to it) and turns mouse and keys into requests that come back
/// here.  The layers (PortraitLayers.hpp) are: fixed points, launched orbits, the selected long segment (with
/// its chain's centre orbit and the step shown) and periodic orbits.  Viewport maths is core's (Viewport,
/// framedInBox); no maths here.

#include <QObject>
#include <QPointer>

#include <cstdint>
#include <optional>
#include <vector>

#include "core/map/MapParameters.hpp"
#include "core/periodic/PeriodicOrbit.hpp"
#include "core/portrait/ColourMap.hpp"
#include "core/portrait/PortraitRaster.hpp"
#include "core/portrait/Viewport.hpp"
#include "core/session/SessionFile.hpp"
#include "ui/portrait/PortraitView.hpp"
#include "ui/portrait/SegmentResults.hpp"

class QWidget;

namespace archipelago::ui {

class PortraitController : public QObject {
  Q_OBJECT
 public:
  /// Creates the view as a child of `viewParent` (which also parents the controller).
  explicit PortraitController(QWidget* viewParent);
  ~PortraitController() override;

  [[nodiscard]] PortraitView* view() const noexcept { return view_; }

  // --- The map -----------------------------------------------------------------------------------------
  /// Shows the portrait of this map (and randomizing zone Xr, for the b₂ dialog).  A new map shows the whole
  /// box, clears the history, the launched orbits and the segment; the same map and Xr change nothing (the
  /// zoom stays).  Invalid parameters are refused: returns false, statusMessage says why.  While the view is
  /// hidden its render waits and starts when it is shown, at its real size.
  bool setMap(const MapParameters& map, double Xr);
  [[nodiscard]] const MapParameters& map() const noexcept { return map_; }
  [[nodiscard]] double Xr() const noexcept { return Xr_; }

  // --- The view ----------------------------------------------------------------------------------------
  /// Shows `view` and records it in the history (a new view drops the forward history, as in a browser).
  void setViewport(const Viewport& view);
  [[nodiscard]] const Viewport& viewport() const noexcept { return history_[historyIndex_]; }
  /// Zoom by `factor` (> 1 in) about the point at fractions (fx, fy) of the view (0,0 bottom-left).
  void zoomAt(double fx, double fy, double factor);
  /// Move by fractions of the view.
  void panBy(double fx, double fy);
  /// The sub-rectangle [fx0, fx1] × [fy0, fy1] of the view, in fractions.
  void crop(double fx0, double fx1, double fy0, double fy1);
  /// Frames `region` to the canvas's aspect ratio inside the box (core's framedInBox) and shows it.
  /// False when the region does not fit this map (the view is left alone).
  bool zoomToRegion(const SegmentRegion& region);
  /// Re-centres the view on (x, y) when that point lies outside it (the zoom stays; the move replaces the
  /// current history entry, so that following a moving point does not fill the history).
  void ensureVisible(long double x, long double y);
  /// True when the physical point (x, y) lies inside the view.
  [[nodiscard]] bool shows(long double x, long double y) const noexcept;
  /// The view history, oldest first, and the index of the view shown (session files keep them).
  [[nodiscard]] const std::vector<Viewport>& history() const noexcept { return history_; }
  [[nodiscard]] std::size_t historyIndex() const noexcept { return historyIndex_; }
  /// Restores a history (e.g. from a session file) and shows views[current].  An empty list or an index past
  /// its end is refused (returns false, nothing changes).
  bool restoreHistory(std::vector<Viewport> views, std::size_t current);
  [[nodiscard]] bool canGoBack() const noexcept { return historyIndex_ > 0; }
  [[nodiscard]] bool canGoForward() const noexcept { return historyIndex_ + 1 < history_.size(); }

  // --- Rendering ---------------------------------------------------------------------------------------
  void setMode(PortraitMode mode);
  [[nodiscard]] PortraitMode mode() const noexcept;
  void setColourMap(ColourMapName colours);
  [[nodiscard]] ColourMapName colourMap() const noexcept;
  /// The points budget of a view: the render accumulates until it has done this many map steps.
  void setPointBudget(std::uint64_t points);
  [[nodiscard]] std::uint64_t pointBudget() const noexcept;
  /// Stops accumulating; the portrait so far stays.
  void stopRendering();

  // --- Layers ------------------------------------------------------------------------------------------
  /// Launch an orbit of N from the physical point (x, y), `steps` long, drawn in its own colour.
  void launchOrbit(double x, double y, int steps = 20000);
  [[nodiscard]] int orbitCount() const noexcept { return static_cast<int>(orbits_.size()); }
  /// The physical start points of the launched orbits, in launch order.
  [[nodiscard]] std::vector<PhysicalPoint> launchedOrbitStarts() const;
  /// The selected long segment (null: none); its chain's centre orbit; the kept state shown.
  void showSegment(const SegmentReplayPtr& replay);
  void showSegmentChain(const ChainResultPtr& chain);
  void showSegmentStep(std::size_t index);
  /// A periodic orbit from the dialog (replacing the previous one).
  void showPeriodicOrbit(const PeriodicOrbit& orbit);
  /// Removes the segment, its chain, its step and the periodic orbit.
  void clearSegment();

  // --- Sessions (core/session) -------------------------------------------------------------------------
  /// The portrait's part of a session: the view history and its current entry, mode, colour map, points
  /// budget, the start points of launched orbits and the periodic-orbit overlay.
  [[nodiscard]] SessionPortrait sessionState() const;
  /// Shows `state` for this map: the map first (a new map clears), then the views, orbits and overlay.
  void restoreSession(const SessionPortrait& state, const MapParameters& map, double Xr);

 public Q_SLOTS:
  void back();
  void forward();
  /// The whole box; when the view is already the whole box, renders it again.
  void resetView();
  void clearOrbits();
  void zoomIn() { zoomAt(0.5, 0.5, 2.0); }
  void zoomOut() { zoomAt(0.5, 0.5, 0.5); }

 Q_SIGNALS:
  /// A new map is shown (setMap with other parameters).
  void mapChanged();
  /// The view changed (zoom, pan, history, reset, map).
  void viewportChanged();
  /// The mode, colour map or points budget changed (the panel's controls follow).
  void settingsChanged();
  void statusMessage(const QString& text);

 private:
  void show(bool record, const Viewport& view);
  void updateFixedPoints();
  void updateLegend();

  QPointer<PortraitView> view_;
  MapParameters map_;
  double Xr_ = 0.02;
  std::vector<Viewport> history_{Viewport()};
  std::size_t historyIndex_ = 0;
  std::vector<std::vector<PhysicalPoint>> orbits_;  // launched orbits (their items live in the view's layer)
  SegmentReplayPtr replay_;
  ChainResultPtr chain_;
  int periodicPeriod_ = 0;
  std::optional<PeriodicOrbit> periodic_;           // the overlay from the periodic-orbit dialog
};

}  // namespace archipelago::ui
