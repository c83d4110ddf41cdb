#pragma once
/// \file ViewLayer.hpp
/// \brief The portrait's view: its map, its viewport and history, zoom, pan and crop, the render's settings and the
/// fixed points of the map (one layer of PortraitController, issue 51).
///
/// Viewport maths is core's (Viewport, framedInBox, viewWidthError); this object keeps the history and hands the
/// PortraitView the view to draw.  The render runs on the view's own worker (PortraitWorker): no job channel here.

#include <QObject>
#include <QPointer>
#include <QString>

#include <cstdint>
#include <optional>
#include <vector>

#include "core/colour/ColourMap.hpp"
#include "core/map/MapParameters.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/periodic/SegmentAnalysis.hpp"
#include "core/portrait/PortraitRaster.hpp"
#include "core/view/Viewport.hpp"

namespace archipelago::ui {

class PortraitView;

class ViewLayer : public QObject {
  Q_OBJECT
 public:
  explicit ViewLayer(PortraitView* view);  ///< shows the default map's whole box

  [[nodiscard]] PortraitView* view() const noexcept { return view_; }

  /// A new map: the whole box and a history of one view; nothing is shown or announced until showMap() (the
  /// controller announces the new map once every layer has followed).
  void setMap(const MapParameters& map);
  /// Draws the map's fixed points and shows its view.
  void showMap();
  [[nodiscard]] const MapParameters& map() const noexcept { return map_; }

  /// Shows `view` and records it in the history (a new view drops the forward history, as in a browser).
  void setViewport(const Viewport& view) { show(true, view); }
  [[nodiscard]] const Viewport& viewport() const noexcept { return history_[historyIndex_]; }
  /// Zoom by `factor` (> 1 in) about the point at fractions (fx, fy) of the view (0,0 bottom-left).  A zoom in that
  /// reaches the resolution limit says so, and why (core's deepestZoomNote; issue 53, finding 7).
  void zoomAt(double fx, double fy, double factor);
  /// Move by fractions of the view; a pan that cannot move says so (issue 25, finding 12).
  void panBy(double fx, double fy);
  /// The sub-rectangle [fx0, fx1] × [fy0, fy1] of the view; with equal aspect no thinner than 1:4 (framedInBox).
  /// At the resolution limit it says so, as zoomAt().
  void crop(double fx0, double fx1, double fy0, double fy1);
  /// Frames `region` to the canvas's aspect inside the box and shows it; false when it does not fit this map.
  bool zoomToRegion(const SegmentRegion& region);
  /// The view of centre (x, y) and width `width`; false with the reason (core's viewWidthError, boxPointError).
  bool goTo(long double x, long double y, long double width, QString* error = nullptr);
  /// Re-centres the view on (x, y) when outside it (replacing the current history entry).
  void ensureVisible(long double x, long double y);
  [[nodiscard]] bool shows(long double x, long double y) const noexcept;
  [[nodiscard]] const std::vector<Viewport>& history() const noexcept { return history_; }
  [[nodiscard]] std::size_t historyIndex() const noexcept { return historyIndex_; }
  /// Restores a history and shows views[current]; an empty list or an index past its end is refused.
  bool restoreHistory(std::vector<Viewport> views, std::size_t current);
  [[nodiscard]] bool canGoBack() const noexcept { return historyIndex_ > 0; }
  [[nodiscard]] bool canGoForward() const noexcept { return historyIndex_ + 1 < history_.size(); }
  void back();
  void forward();
  /// The whole box; when the view is already the whole box, renders it again.
  void resetView();

  void setEqualAspect(bool on);
  [[nodiscard]] bool equalAspect() const noexcept;
  void setMode(PortraitMode mode);
  [[nodiscard]] PortraitMode mode() const noexcept;
  void setIndicator(std::optional<IndicatorKind> kind);
  [[nodiscard]] std::optional<IndicatorKind> indicator() const noexcept;
  void setColourMap(ColourMapName colours);
  [[nodiscard]] ColourMapName colourMap() const noexcept;
  void setPointBudget(std::uint64_t points);
  [[nodiscard]] std::uint64_t pointBudget() const noexcept;
  void stopRendering();
  void setRenderPaused(bool paused);

 Q_SIGNALS:
  /// The view changed (zoom, pan, history, reset) — not a new map.
  void viewportChanged();
  /// The mode, colour map, points budget or aspect changed.
  void settingsChanged();
  void statusMessage(const QString& text);

 private:
  void show(bool record, const Viewport& view);
  void cropView(double fx0, double fx1, double fy0, double fy1);
  /// Says that the view is the deepest there is, when it is.
  void noteDeepestZoom();
  void updateFixedPoints();

  QPointer<PortraitView> view_;
  MapParameters map_;
  std::vector<Viewport> history_{Viewport()};
  std::size_t historyIndex_ = 0;
};

}  // namespace archipelago::ui
