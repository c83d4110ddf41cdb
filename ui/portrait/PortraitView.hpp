#pragma once
// PortraitView: the phase-portrait explorer widget (Qwt plot of a raster rendered by core on a worker thread).
//
// Interaction: drag with the left button to zoom into a rectangle; click to launch an orbit (drawn in its own
// colour); wheel to zoom about the cursor; drag with the middle button (or the arrow keys) to pan;
// Back/Forward walk the zoom history; Home resets to the whole box.  The cursor is reported in physical and
// unit coordinates.  Every zoom and pan is core's Viewport maths (exact centre); this widget only maps mouse
// positions to fractions of the view.  Stale frames (of a view already left) are dropped by request id.

#include <QImage>
#include <QPointer>
#include <QWidget>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/map/MapParameters.hpp"
#include "core/portrait/ColourMap.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/portrait/Viewport.hpp"

class QwtPlot;
class QwtPlotMarker;
class QwtPlotPicker;
class QwtPlotPanner;
class QTimer;

namespace archipelago::ui {

class PortraitWorker;
class PortraitImageItem;
class OrbitItem;
class PrecisionScaleDraw;
struct PortraitFrame;

class PortraitView : public QWidget {
  Q_OBJECT
 public:
  explicit PortraitView(QWidget* parent = nullptr);
  ~PortraitView() override;

  /// The map; resets the view to the whole box, clears the orbits and the history.  Invalid parameters are
  /// refused (returns false, statusMessage explains).
  bool setParameters(const MapParameters& parameters);
  [[nodiscard]] const MapParameters& parameters() const noexcept { return parameters_; }

  void setMode(PortraitMode mode);
  [[nodiscard]] PortraitMode mode() const noexcept { return mode_; }
  void setColourMap(ColourMapName colours);
  [[nodiscard]] ColourMapName colourMap() const noexcept { return colours_; }
  /// Map steps per render (all orbits together).
  void setPointBudget(std::uint64_t points);
  [[nodiscard]] std::uint64_t pointBudget() const noexcept { return points_; }

  /// Shows `view` and records it in the history.
  void setViewport(const Viewport& view);
  [[nodiscard]] const Viewport& viewport() const noexcept { return history_[historyIndex_]; }

  /// Zoom by `factor` (> 1 in) about the point at fractions (fx, fy) of the view (0,0 bottom-left).
  void zoomAt(double fx, double fy, double factor);
  /// Move by fractions of the view.
  void panBy(double fx, double fy);
  [[nodiscard]] bool canGoBack() const noexcept { return historyIndex_ > 0; }
  [[nodiscard]] bool canGoForward() const noexcept { return historyIndex_ + 1 < history_.size(); }

  /// Launch an orbit of N from the physical point (x, y), `steps` long, drawn in its own colour.
  void launchOrbit(double x, double y, int steps = 20000);
  [[nodiscard]] int orbitCount() const noexcept { return static_cast<int>(orbits_.size()); }

  /// The plot with axes, title and colour bar, rendered to PNG by QwtPlotRenderer.  False on failure.
  bool exportPng(const QString& path, const QSize& size = QSize(1200, 1000));
  /// The current raster as .npy plus its JSON sidecar.  False when there is none yet or writing failed.
  bool exportNpy(const QString& path);

  /// The last frame shown (null before the first one).
  [[nodiscard]] const PortraitFrame* currentFrame() const noexcept { return frame_.get(); }
  /// True while the worker still refines the current view.
  [[nodiscard]] bool isRendering() const noexcept { return rendering_; }
  [[nodiscard]] QwtPlot* plot() const noexcept { return plot_; }

 public Q_SLOTS:
  void back();
  void forward();
  void resetView();
  void clearOrbits();
  void zoomIn() { zoomAt(0.5, 0.5, 2.0); }
  void zoomOut() { zoomAt(0.5, 0.5, 0.5); }

 Q_SIGNALS:
  /// One line for a status bar: render progress, errors, what was exported.
  void statusMessage(const QString& text);
  /// The cursor in physical and unit coordinates.
  void cursorMoved(const QString& text);
  /// The view changed (zoom, pan, history, reset, parameters).
  void viewportChanged();
  /// The final frame of the current view arrived.
  void renderFinished();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  void showViewport(bool record, const Viewport& view);
  void scheduleRender();
  void startRender();
  void onFrame(const PortraitFrame& frame);
  void onRectangleSelected(const QRectF& rect);
  void updateAxes();
  void updateColourBar();
  void updateFixedPoints();
  [[nodiscard]] QString cursorText(const QPointF& canvasPos) const;

  MapParameters parameters_;
  PortraitMode mode_ = PortraitMode::Orbits;
  ColourMapName colours_ = ColourMapName::Inferno;
  std::uint64_t points_ = 12'000'000;
  std::vector<Viewport> history_{Viewport()};
  std::size_t historyIndex_ = 0;

  QwtPlot* plot_ = nullptr;
  PortraitImageItem* image_ = nullptr;
  PrecisionScaleDraw* xScale_ = nullptr;
  PrecisionScaleDraw* yScale_ = nullptr;
  QwtPlotPicker* picker_ = nullptr;
  QwtPlotPanner* panner_ = nullptr;
  QTimer* renderTimer_ = nullptr;
  std::vector<OrbitItem*> orbits_;
  std::vector<QwtPlotMarker*> fixedPointMarkers_;
  PortraitWorker* worker_ = nullptr;
  quint64 currentRequest_ = 0;
  bool rendering_ = false;
  std::unique_ptr<PortraitFrame> frame_;
};

}  // namespace archipelago::ui
