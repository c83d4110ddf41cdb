#pragma once
// PortraitView: the phase-portrait widget (Qwt plot of a raster rendered by core on a worker thread).
//
// The view draws; the PortraitController decides.  The map, the view rectangle, the render settings and the
// overlay layers are set only by the controller's layers (the setters are private, the layers are friends).
// Mouse and keys become requests (zoomRequested, …) that the controller turns into views.  A middle-drag
// moves a picture of the canvas while dragging (QwtPanner) and then asks the controller for the pan: the axes
// only ever show the controller's view (issue 25, finding 2: QwtPlotPanner used to move them past the box).
//
// Rendering: the render of the current view accumulates passes into one raster until the points budget is
// reached, the view/mode/map changes, or stopRender(); the render state and the points so far are readable
// (renderState(), pointsSoFar()) and announced by renderStateChanged().  A Density view with no sea ends as
// RenderState::noSea.  While the widget is hidden a render request stays pending and starts at the real size
// when it is shown, and a render in progress pauses (it keeps its orbits and goes on when shown again); a
// resize of the canvas renders again (debounced).  Stale frames (of a request already replaced) are dropped by
// request id.  Instead of the mode's raster the view can show a chaos-indicator map (core/measures), computed
// progressively the same way, with a titled colour bar.
//
// Equal aspect (the default): the plot is laid out inside the widget so that its canvas has the view's own
// aspect ratio — a unit of x as long on screen as a unit of y — with the rest of the widget left empty.

#include <QImage>
#include <QWidget>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "core/map/MapParameters.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/colour/ColourMap.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/view/Viewport.hpp"
#include "ui/portrait/PortraitLayers.hpp"

class QwtPlot;
class QwtPlotItem;
class QwtPlotPicker;
class QwtPanner;
class QwtPlotTextLabel;
class QTimer;

namespace archipelago {
struct AxisLabels;
struct IndicatorRequest;
struct PixelSize;
}  // namespace archipelago

namespace archipelago::ui {

class PauseGate;
class PortraitController;
class PortraitWorker;
class PortraitImageItem;
class PrecisionScaleDraw;
struct PortraitFrame;

/// Where the render of the current view stands.
enum class RenderState {
  idle,          ///< nothing requested yet
  pending,       ///< requested, waiting to be shown (hidden) or for the debounce timer
  accumulating,  ///< passes are being added
  done,          ///< the points budget was reached
  stopped,       ///< stopped by the user
  noSea,         ///< Density: no chaotic point entered the view although an all-sea view would have had 64
  failed,        ///< the request was refused (statusMessage says why)
};

/// A finished render covering less than this fraction of its pixels is sparse: the readout suggests a larger
/// points budget (issue 25, finding 8).
inline constexpr double kSparseFraction = 0.25;

class PortraitView : public QWidget {
  Q_OBJECT
 public:
  explicit PortraitView(QWidget* parent = nullptr);
  ~PortraitView() override;

  [[nodiscard]] const MapParameters& parameters() const noexcept { return map_; }
  [[nodiscard]] const Viewport& viewport() const noexcept { return view_; }
  [[nodiscard]] PortraitMode mode() const noexcept { return mode_; }
  [[nodiscard]] std::optional<IndicatorKind> indicator() const noexcept { return indicator_; }
  [[nodiscard]] ColourMapName colourMap() const noexcept { return colours_; }
  [[nodiscard]] std::uint64_t pointBudget() const noexcept { return points_; }
  [[nodiscard]] bool equalAspect() const noexcept { return equalAspect_; }
  [[nodiscard]] bool renderPaused() const noexcept;
  /// True once a paused render has finished its pass in flight and waits: its points so far are final until resumed.
  [[nodiscard]] bool renderHeld() const;

  [[nodiscard]] RenderState renderState() const noexcept { return state_; }
  /// True while the worker still adds passes to the current view (or is about to).
  [[nodiscard]] bool isRendering() const noexcept {
    return state_ == RenderState::accumulating || state_ == RenderState::pending;
  }
  /// Map steps done so far for the current view (all orbits); pixels of an indicator map.
  [[nodiscard]] std::uint64_t pointsSoFar() const noexcept { return pointsSoFar_; }
  /// One line for the panel's readout: points so far, pixels visited, and the state in words.
  [[nodiscard]] QString readout() const;
  /// True when the render ended with fewer than kSparseFraction of its pixels visited (a larger budget helps, unless
  /// the seeds' orbits leave the view: PortraitRaster::orbitsLeaveView).
  [[nodiscard]] bool sparse() const;
  /// The raster size a render of the current canvas asks for (canvas size × device pixel ratio, clamped).
  [[nodiscard]] QSize rasterSize() const;

  /// The plot with axes, title and colour bar as a PNG of `size` pixels, its raster rendered anew at the size
  /// its canvas has in that image (not the screen's raster scaled, issue 25, finding 9), with as many points
  /// per pixel as the screen's so far.  Waits for that render (a progress dialog appears after half a second,
  /// Cancel stops it).  False on failure or cancel.
  bool exportPng(const QString& path, const QSize& size = QSize(1200, 1000));
  /// The raster size of the last exportPng() (tests: the export's own pixels, not the screen's).
  [[nodiscard]] QSize lastExportRasterSize() const noexcept { return lastExportRaster_; }
  /// The current raster as .npy plus its JSON sidecar.  False when there is none yet or writing failed.
  bool exportNpy(const QString& path);

  /// The last frame shown (null before the first one of the current map).
  [[nodiscard]] const PortraitFrame* currentFrame() const noexcept { return frame_.get(); }
  /// The items of a layer (tests).
  [[nodiscard]] const std::vector<QwtPlotItem*>& layerItems(PortraitLayer layer) const;
  /// True when the layer shows something in the view: a point of one of its items inside it (an item of another
  /// kind, e.g. a marker, counts as shown).
  [[nodiscard]] bool layerInView(PortraitLayer layer) const;
  /// The legend's text as set (rich text; empty: no legend).
  [[nodiscard]] QString legendText() const;
  /// The canvas (tests send it mouse events); the plot itself stays private to the view.
  [[nodiscard]] QWidget* canvas() const;
  /// The x and y axis ranges shown (tests).
  [[nodiscard]] std::pair<double, double> xAxisRange() const;
  [[nodiscard]] std::pair<double, double> yAxisRange() const;
  /// The physical point under a canvas position (the rotation-profile tool).
  [[nodiscard]] PhysicalPoint physicalAt(const QPointF& canvasPos) const;
  /// A drag on the canvas draws a line and reports it (lineSelected) instead of zooming (the profile tool).
  void setLineTool(bool on);
  [[nodiscard]] bool lineTool() const noexcept { return lineTool_; }

 Q_SIGNALS:
  /// One line for a status bar: errors, what was exported.
  void statusMessage(const QString& text);
  /// The cursor in physical and unit coordinates.
  void cursorMoved(const QString& text);
  /// The render state or the points so far changed (readout()).
  void renderStateChanged();
  /// The render of the current view ended by itself: budget reached, or no sea in the view.
  void renderFinished();
  /// A frame of the current view arrived.
  void frameShown();

  // Requests from the mouse and keys, for the controller.
  void zoomRequested(double fx, double fy, double factor);
  void cropRequested(double fx0, double fx1, double fy0, double fy1);
  void panRequested(double fx, double fy);
  void clicked(long double x, long double y);
  /// A Shift+click: find the periodic orbit there (issue 37, finding 16).
  void periodicOrbitRequested(long double x, long double y);
  void backRequested();
  void forwardRequested();
  void resetRequested();
  /// The line tool: a segment dragged on the canvas, physical coordinates.
  void lineSelected(archipelago::PhysicalPoint from, archipelago::PhysicalPoint to);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;
  void showEvent(QShowEvent* event) override;
  void hideEvent(QHideEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;

 private:
  /// The done frame's share of pixels visited, in %.
  [[nodiscard]] double visitedPercent() const;
  // The portrait's layers set what it draws (PortraitController.hpp).
  friend class PortraitController;
  friend class ViewLayer;
  friend class LaunchedOrbitsLayer;
  friend class ManifoldsLayer;
  friend class AtlasIslandLayer;
  friend class OverlayLayer;

  /// Shows this map and view (axes at once) and renders it.
  void display(const MapParameters& map, const Viewport& view);
  void setMode(PortraitMode mode, std::optional<IndicatorKind> indicator);
  void setColourMap(ColourMapName colours);
  void setPointBudget(std::uint64_t points);
  void setEqualAspect(bool on);
  void setRenderPaused(bool paused);
  /// Renders the current view again from nothing.
  void rerender();
  /// Stops the render in progress; the raster so far stays.
  void stopRender();
  /// Replaces the items of `layer` (the view takes ownership) and replots.
  void setLayer(PortraitLayer layer, std::vector<QwtPlotItem*> items);
  /// Adds one item to `layer` / removes (and deletes) one, and replots.
  void addLayerItem(PortraitLayer layer, QwtPlotItem* item);
  void removeLayerItem(PortraitLayer layer, QwtPlotItem* item);
  /// Rich text shown at the top left of the canvas (empty: none).
  void setLegend(const QString& html);
  /// The aspect (width/height) a view should have to fill the room the canvas has (zoom to a region).
  [[nodiscard]] double targetAspect() const;

  void scheduleRender();
  void startRender();
  void setState(RenderState state);
  void onFrame(const PortraitFrame& frame);
  void onRectangleSelected(const QRectF& rect);
  void updateAxes();
  /// The axis's scale for [lo, hi]: Qwt's ticks for plain labels, core's round ticks (axisTicks) for offset ones.
  void setAxisTicks(int axis, const AxisLabels& labels, double lo, double hi);
  /// As many x ticks as their labels have room for on the canvas, a digit's width apart at least (issue 53, finding
  /// 5: a thin island's view, narrow on screen, ran them together): Qwt's 8 at most, fewer while two come closer.
  void fitXTicks();
  void updateColourBar();
  void layoutPlot();
  void replotSoon();
  [[nodiscard]] QString cursorText(const QPointF& canvasPos) const;
  /// exportPng()'s steps: the plot laid out for an image of `size` (cut to the view's aspect with equal aspect:
  /// `size` is changed) and its canvas; the requests of the export's raster (the indicator's when an indicator map
  /// is shown); the render, waited for (a progress dialog after half a second, its Cancel stops it), null with the
  /// reason in `error`; the plot drawn into an image of `size` with that raster under its axes (the screen's after).
  QRectF layOutExport(QSize& size);
  [[nodiscard]] PortraitRequest exportRequest(const PixelSize& raster) const;
  [[nodiscard]] std::optional<IndicatorRequest> exportIndicatorRequest(const PixelSize& raster) const;
  std::shared_ptr<const PortraitFrame> waitForExportRender(const PortraitRequest& request,
                                                           const std::optional<IndicatorRequest>& indicator,
                                                           const QString& path, QString* error);
  QImage plotImage(const PortraitFrame& frame, const QSize& size);

  MapParameters map_;
  Viewport view_;
  PortraitMode mode_ = PortraitMode::Orbits;
  std::optional<IndicatorKind> indicator_;
  ColourMapName colours_ = ColourMapName::Inferno;
  std::uint64_t points_ = 1'000'000'000;
  bool equalAspect_ = true;
  bool pausedByUser_ = false;
  bool lineTool_ = false;
  QPointF lineStart_;
  bool lineDragging_ = false;

  QwtPlot* plot_ = nullptr;
  PortraitImageItem* image_ = nullptr;
  PrecisionScaleDraw* xScale_ = nullptr;
  PrecisionScaleDraw* yScale_ = nullptr;
  QwtPlotPicker* picker_ = nullptr;
  QwtPanner* panner_ = nullptr;
  QwtPlotTextLabel* legend_ = nullptr;
  QTimer* renderTimer_ = nullptr;
  QTimer* replotTimer_ = nullptr;
  std::map<PortraitLayer, std::vector<QwtPlotItem*>> layers_;
  std::shared_ptr<PauseGate> gate_;
  PortraitWorker* worker_ = nullptr;
  quint64 currentRequest_ = 0;
  RenderState state_ = RenderState::idle;
  bool renderWanted_ = false;   // a render of the current view is due (waits while hidden)
  std::uint64_t pointsSoFar_ = 0;
  QSize renderedSize_;          // raster size of the current request
  QSize lastExportRaster_;
  bool exporting_ = false;      // exportPng() waiting for its render
  std::unique_ptr<PortraitFrame> frame_;
};

}  // namespace archipelago::ui
