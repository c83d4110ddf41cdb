#include "ui/portrait/PortraitView.hpp"

#include <QAbstractSpinBox>
#include <QApplication>
#include <QComboBox>
#include <QEventLoop>
#include <QFontMetrics>
#include <QKeyEvent>
#include <QLineEdit>
#include <QLocale>
#include <QPointer>
#include <QProgressDialog>
#include <QResizeEvent>
#include <QShowEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QTimer>
#include <QVBoxLayout>
#include <QWheelEvent>
#include <qwt_color_map.h>
#include <qwt_interval.h>
#include <qwt_picker_machine.h>
#include <qwt_plot.h>
#include <qwt_plot_canvas.h>
#include <qwt_plot_item.h>
#include <qwt_plot_textlabel.h>
#include <qwt_panner.h>
#include <qwt_plot_layout.h>
#include <qwt_plot_picker.h>
#include <qwt_plot_renderer.h>
#include <qwt_scale_div.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_map.h>
#include <qwt_scale_widget.h>
#include <qwt_text.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "core/measures/MeasureExport.hpp"
#include "core/portrait/ExportSizing.hpp"
#include "core/view/AxisLabels.hpp"
#include "core/portrait/PortraitExport.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/portrait/PortraitWorker.hpp"
#include "ui/files/OutputFiles.hpp"

namespace archipelago::ui {

/// Draws the current frame's image over the physical rectangle it was rendered for, so that the old image
/// stays in place (transformed) while the worker renders the new view.
class PortraitImageItem : public QwtPlotItem {
 public:
  PortraitImageItem() { setZ(0); }
  void setImage(const QImage& image, const QRectF& physical) {
    image_ = image;
    rect_ = physical;
  }
  int rtti() const override { return QwtPlotItem::Rtti_PlotUserItem + 1; }
  QRectF boundingRect() const override { return rect_; }
  void draw(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap,
            const QRectF& canvasRect) const override {
    if (image_.isNull() || rect_.isEmpty()) return;
    const QRectF target(QPointF(xMap.transform(rect_.left()), yMap.transform(rect_.bottom())),
                        QPointF(xMap.transform(rect_.right()), yMap.transform(rect_.top())));
    const QRectF visible = target.normalized().intersected(canvasRect);
    if (visible.isEmpty()) return;
    // Only the part of the image inside the canvas: after a deep zoom the full target would be huge.
    const double sx = image_.width() / target.width(), sy = image_.height() / target.height();
    const QRectF source((visible.left() - target.left()) * sx, (visible.top() - target.top()) * sy,
                        visible.width() * sx, visible.height() * sy);
    painter->drawImage(visible, image_, source);
  }

 private:
  QImage image_;
  QRectF rect_;  // physical: x0..x1, y0..y1 (top() = y0)
};

/// Axis labels at any depth: core's AxisLabels (plain with the digits the view needs, or offsets from the view's
/// reference point, which the axis title names).
class PrecisionScaleDraw : public QwtScaleDraw {
 public:
  void setLabels(const AxisLabels& labels) {
    labels_ = labels;
    invalidateCache();
  }
  [[nodiscard]] const AxisLabels& labels() const noexcept { return labels_; }
  QwtText label(double value) const override { return QString::fromStdString(axisTickLabel(labels_, value)); }

 private:
  AxisLabels labels_;
};

/// core's ColourMap for Qwt's colour bar.
class CoreColourMap : public QwtColorMap {
 public:
  explicit CoreColourMap(ColourMapName name) : map_(name) {}
  QRgb rgb(const QwtInterval& interval, double value) const override {
    const double t = interval.width() > 0 ? (value - interval.minValue()) / interval.width() : 1.0;
    const Rgb c = map_.at(kLowest + (1 - kLowest) * t);
    return qRgb(c.r, c.g, c.b);
  }
#if QWT_VERSION < 0x060200
  unsigned char colorIndex(const QwtInterval& interval, double value) const override {
    const double t = interval.width() > 0 ? (value - interval.minValue()) / interval.width() : 1.0;
    return static_cast<unsigned char>(std::clamp(t, 0.0, 1.0) * 255);
  }
#endif

 private:
  ColourMap map_;
};

namespace {
QRectF physicalRect(const Viewport& view, const MapParameters& map) {
  const PhysicalRect r = view.physical(map);
  return QRectF(QPointF(static_cast<double>(r.x0), static_cast<double>(r.y0)),
                QPointF(static_cast<double>(r.x1), static_cast<double>(r.y1)));
}

QPointF mousePosition(const QMouseEvent* e) {
#if QT_VERSION >= QT_VERSION_CHECK(6, 0, 0)
  return e->position();
#else
  return e->localPos();
#endif
}
}  // namespace

PortraitView::PortraitView(QWidget* parent) : QWidget(parent) {
  plot_ = new QwtPlot(this);
  plot_->setAutoReplot(false);
  plot_->setCanvasBackground(QColor(16, 16, 24));
  if (auto* canvas = qobject_cast<QwtPlotCanvas*>(plot_->canvas())) canvas->setFrameStyle(QFrame::NoFrame);
  plot_->canvas()->setMouseTracking(true);
  plot_->canvas()->installEventFilter(this);
  // The wheel and a click give the canvas the focus, so that the keys (arrows, +, −, Home) work at once; so
  // does the mouse entering it, unless the user is typing somewhere (issue 25, finding 12).
  plot_->canvas()->setFocusPolicy(Qt::WheelFocus);
  setFocusProxy(plot_->canvas());
  xScale_ = new PrecisionScaleDraw;
  yScale_ = new PrecisionScaleDraw;
  plot_->setAxisScaleDraw(QwtPlot::xBottom, xScale_);
  plot_->setAxisScaleDraw(QwtPlot::yLeft, yScale_);
  plot_->setAxisTitle(QwtPlot::xBottom, QStringLiteral("x"));
  plot_->setAxisTitle(QwtPlot::yLeft, QStringLiteral("y"));
  QwtScaleWidget* bar = plot_->axisWidget(QwtPlot::yRight);
  bar->setColorBarEnabled(true);
  bar->setColorBarWidth(16);
  // The axes' labels get longer digits as the view narrows: they must not grow the window's minimum width.
  plot_->setMinimumSize(200, 160);
  plot_->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Ignored);
  setMinimumSize(200, 160);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);

  image_ = new PortraitImageItem;
  image_->attach(plot_);
  legend_ = new QwtPlotTextLabel;
  legend_->setZ(40);
  legend_->attach(plot_);

  picker_ = new QwtPlotPicker(QwtPlot::xBottom, QwtPlot::yLeft, QwtPicker::RectRubberBand,
                              QwtPicker::AlwaysOff, plot_->canvas());
  picker_->setStateMachine(new QwtPickerDragRectMachine);
  picker_->setRubberBandPen(QPen(Qt::white, 1, Qt::DashLine));
  connect(picker_, qOverload<const QRectF&>(&QwtPlotPicker::selected), this, &PortraitView::onRectangleSelected);

  // A plain QwtPanner: it drags a picture of the canvas and reports the distance; the controller decides the
  // view (clamped to the box) and the axes follow it.  (QwtPlotPanner moved the axes itself, past the box.)
  panner_ = new QwtPanner(plot_->canvas());
  panner_->setMouseButton(Qt::MiddleButton);
  connect(panner_, &QwtPanner::panned, this, [this](int dx, int dy) {
    const QWidget* canvas = plot_->canvas();
    Q_EMIT panRequested(-static_cast<double>(dx) / std::max(1, canvas->width()),
                        static_cast<double>(dy) / std::max(1, canvas->height()));
    plot_->replot();
  });

  renderTimer_ = new QTimer(this);
  renderTimer_->setSingleShot(true);
  renderTimer_->setInterval(60);  // coalesce a burst of wheel steps or resizes into one request
  connect(renderTimer_, &QTimer::timeout, this, &PortraitView::startRender);
  replotTimer_ = new QTimer(this);
  replotTimer_->setSingleShot(true);
  replotTimer_->setInterval(40);  // a burst of layer changes (a session's orbits arriving): one replot
  connect(replotTimer_, &QTimer::timeout, this, [this] { plot_->replot(); });

  gate_ = std::make_shared<PauseGate>();
  worker_ = new PortraitWorker(this);
  // Queued although the worker emits on this thread: a slot of frameShown() or renderFinished() may close the
  // view, which must not happen inside the worker's delivery (BackgroundJobs: a handler must not destroy it).
  connect(worker_, &PortraitWorker::frameReady, this, &PortraitView::onFrame, Qt::QueuedConnection);
  connect(worker_, &PortraitWorker::progress, this, [this](quint64 id, quint64 done, quint64) {
    if (id != currentRequest_ || state_ != RenderState::accumulating) return;
    pointsSoFar_ = std::max<std::uint64_t>(pointsSoFar_, done);
    Q_EMIT renderStateChanged();
  }, Qt::QueuedConnection);
  connect(worker_, &PortraitWorker::failed, this, [this](quint64 id, const QString& message) {
    if (id != currentRequest_) return;
    setState(RenderState::failed);
    Q_EMIT statusMessage(tr("Portrait failed: %1").arg(message));
  }, Qt::QueuedConnection);

  updateAxes();
}

PortraitView::~PortraitView() {
  gate_->setPaused(false);
  delete worker_;  // stops the render in progress and waits for the thread before the plot goes away
  worker_ = nullptr;
  for (auto& [layer, items] : layers_)
    for (QwtPlotItem* item : items) {
      item->detach();
      delete item;
    }
}

void PortraitView::display(const MapParameters& map, const Viewport& view) {
  if (!(map == map_)) frame_.reset();  // an image of another map must not stay under the new axes
  if (!(map == map_)) image_->setImage(QImage(), QRectF());
  map_ = map;
  view_ = view;
  updateAxes();
  layoutPlot();
  scheduleRender();
}

void PortraitView::setMode(PortraitMode mode, std::optional<IndicatorKind> indicator) {
  if (mode == mode_ && indicator == indicator_) return;
  mode_ = mode;
  indicator_ = indicator;
  scheduleRender();
}

void PortraitView::setColourMap(ColourMapName colours) {
  if (colours == colours_) return;
  colours_ = colours;
  scheduleRender();
}

void PortraitView::setPointBudget(std::uint64_t points) {
  points = std::max<std::uint64_t>(points, 1);
  if (points == points_) return;
  points_ = points;
  scheduleRender();
}

void PortraitView::setEqualAspect(bool on) {
  if (on == equalAspect_) return;
  equalAspect_ = on;
  layoutPlot();
  scheduleRender();  // the canvas has another size
}

void PortraitView::setRenderPaused(bool paused) {
  pausedByUser_ = paused;
  gate_->setPaused(pausedByUser_ || !isVisible());
}

bool PortraitView::renderPaused() const noexcept { return gate_->paused(); }

bool PortraitView::renderHeld() const { return gate_->holding(); }

void PortraitView::rerender() { scheduleRender(); }

void PortraitView::stopRender() {
  renderTimer_->stop();
  renderWanted_ = false;
  worker_->cancel();
  if (isRendering()) setState(RenderState::stopped);
}

void PortraitView::setLayer(PortraitLayer layer, std::vector<QwtPlotItem*> items) {
  std::vector<QwtPlotItem*>& slot = layers_[layer];
  for (QwtPlotItem* item : slot) {
    item->detach();
    delete item;
  }
  slot = std::move(items);
  for (QwtPlotItem* item : slot) item->attach(plot_);
  replotSoon();
}

void PortraitView::addLayerItem(PortraitLayer layer, QwtPlotItem* item) {
  layers_[layer].push_back(item);
  item->attach(plot_);
  replotSoon();
}

void PortraitView::removeLayerItem(PortraitLayer layer, QwtPlotItem* item) {
  std::vector<QwtPlotItem*>& slot = layers_[layer];
  const auto it = std::find(slot.begin(), slot.end(), item);
  if (it == slot.end()) return;
  slot.erase(it);
  item->detach();
  delete item;
  replotSoon();
}

void PortraitView::replotSoon() {
  // Adding a thousand orbits from a session is a thousand layer changes: they are drawn once, when the event
  // loop is next free.
  if (!replotTimer_->isActive()) replotTimer_->start();
}

const std::vector<QwtPlotItem*>& PortraitView::layerItems(PortraitLayer layer) const {
  static const std::vector<QwtPlotItem*> none;
  const auto it = layers_.find(layer);
  return it == layers_.end() ? none : it->second;
}

bool PortraitView::layerInView(PortraitLayer layer) const {
  const QRectF view = physicalRect(view_, map_).normalized();
  const auto& items = layerItems(layer);
  return std::any_of(items.begin(), items.end(), [&view](const QwtPlotItem* item) {
    return item->rtti() != PointsItem::kRtti || static_cast<const PointsItem*>(item)->anyPointIn(view);
  });
}

QString PortraitView::legendText() const { return legend_->text().text(); }

void PortraitView::setLegend(const QString& html) {
  if (html.isEmpty()) {
    legend_->setText(QwtText());
  } else {
    QwtText text(html, QwtText::RichText);
    text.setRenderFlags(Qt::AlignTop | Qt::AlignLeft);
    text.setBackgroundBrush(QColor(255, 255, 255, 215));
    text.setBorderRadius(4);
    text.setBorderPen(QPen(QColor(0, 0, 0, 120)));
    QFont font = text.font();
    font.setPointSizeF(font.pointSizeF() * 1.05);
    text.setFont(font);
    legend_->setText(text);
    legend_->setMargin(10);
  }
  replotSoon();
}

QWidget* PortraitView::canvas() const { return plot_->canvas(); }

std::pair<double, double> PortraitView::xAxisRange() const {
  const QwtScaleDiv& d = plot_->axisScaleDiv(QwtPlot::xBottom);
  return {d.lowerBound(), d.upperBound()};
}

std::pair<double, double> PortraitView::yAxisRange() const {
  const QwtScaleDiv& d = plot_->axisScaleDiv(QwtPlot::yLeft);
  return {d.lowerBound(), d.upperBound()};
}

double PortraitView::targetAspect() const {
  // The room the canvas could have: the widget less a fixed allowance for the axes (not their width of the
  // moment, which follows the digits of the labels: a region framed twice gets the same view).
  const int w = width() - 90, h = height() - 50;
  return w > 0 && h > 0 ? static_cast<double>(w) / h : 1.0;
}

void PortraitView::layoutPlot() {
  plot_->setGeometry(rect());
  if (!equalAspect_) return;
  plot_->updateLayout();
  const QWidget* c = plot_->canvas();
  if (c->width() <= 0 || c->height() <= 0) return;
  const int ox = plot_->width() - c->width(), oy = plot_->height() - c->height();
  const long double aspect = view_.widthUnits() / view_.heightUnits();  // the box is square: units are alike
  const int cw = c->width(), ch = c->height();
  QRect r = rect();
  if (cw > ch * aspect) {
    const int w = static_cast<int>(std::lround(static_cast<double>(ch * aspect))) + ox;
    r = QRect((width() - w) / 2, 0, w, height());
  } else {
    const int h = static_cast<int>(std::lround(static_cast<double>(cw / aspect))) + oy;
    r = QRect(0, (height() - h) / 2, width(), h);
  }
  plot_->setGeometry(r);
  plot_->updateLayout();
  fitXTicks();
}

void PortraitView::updateAxes() {
  const QRectF r = physicalRect(view_, map_);
  xScale_->setLabels(axisLabelsFor(r.left(), r.right()));
  yScale_->setLabels(axisLabelsFor(r.top(), r.bottom()));
  plot_->setAxisTitle(QwtPlot::xBottom, QStringLiteral("x") + QString::fromStdString(axisTitleSuffix(xScale_->labels())));
  plot_->setAxisTitle(QwtPlot::yLeft, QStringLiteral("y") + QString::fromStdString(axisTitleSuffix(yScale_->labels())));
  setAxisTicks(QwtPlot::xBottom, xScale_->labels(), r.left(), r.right());
  setAxisTicks(QwtPlot::yLeft, yScale_->labels(), r.top(), r.bottom());
  fitXTicks();
  plot_->replot();
}

void PortraitView::setAxisTicks(int axis, const AxisLabels& labels, double lo, double hi) {
  if (!labels.offset) {
    plot_->setAxisScale(axis, lo, hi);  // Qwt's ticks: round while the view is wide against its coordinates
    return;
  }
  // Deep views: core's round ticks from the labels' reference (Qwt's began at the view's edge, issue 53, finding 7).
  const AxisTicks ticks = axisTicks(labels, lo, hi, plot_->axisMaxMajor(axis), plot_->axisMaxMinor(axis));
  QList<double> lists[QwtScaleDiv::NTickTypes];
  lists[QwtScaleDiv::MajorTick] = QList<double>(ticks.major.begin(), ticks.major.end());
  lists[QwtScaleDiv::MinorTick] = QList<double>(ticks.minor.begin(), ticks.minor.end());
  plot_->setAxisScaleDiv(axis, QwtScaleDiv(lo, hi, lists));
}

namespace {
/// True when two neighbouring major ticks' labels of `axis` come closer than `gap` pixels.
bool ticksRunTogether(const QwtPlot& plot, int axis, double gap) {
  const QwtScaleDraw& draw = *plot.axisScaleDraw(axis);
  const QFont font = plot.axisWidget(axis)->font();
  QList<double> ticks = plot.axisScaleDiv(axis).ticks(QwtScaleDiv::MajorTick);
  std::sort(ticks.begin(), ticks.end());
  for (qsizetype i = 1; i < ticks.size(); ++i) {
    const double apart = plot.transform(axis, ticks[i]) - plot.transform(axis, ticks[i - 1]);
    const double room = (draw.labelSize(font, ticks[i]).width() + draw.labelSize(font, ticks[i - 1]).width()) / 2;
    if (apart < room + gap) return true;
  }
  return false;
}
}  // namespace

void PortraitView::fitXTicks() {
  constexpr int kMostTicks = 8;  // Qwt's default
  const double gap = QFontMetrics(plot_->axisWidget(QwtPlot::xBottom)->font()).horizontalAdvance(QLatin1Char('0'));
  const QRectF r = physicalRect(view_, map_);
  for (int most = kMostTicks; most >= 1; --most) {
    plot_->setAxisMaxMajor(QwtPlot::xBottom, most);
    setAxisTicks(QwtPlot::xBottom, xScale_->labels(), r.left(), r.right());  // a deep view's core ticks, `most` at most
    plot_->updateAxes();
    if (!ticksRunTogether(*plot_, QwtPlot::xBottom, gap)) return;
  }
}

void PortraitView::updateColourBar() {
  const bool scale = frame_ && (frame_->indicatorRequest || frame_->request.mode != PortraitMode::Orbits);
  if (!scale) return;
  const QwtInterval interval(frame_->scaleMin, std::max(frame_->scaleMax, frame_->scaleMin + 1e-9));
  plot_->axisWidget(QwtPlot::yRight)->setColorMap(interval, new CoreColourMap(colours_));
  plot_->setAxisScale(QwtPlot::yRight, interval.minValue(), interval.maxValue());
  // An indicator's bar says what it measures, with units (core's quantity names the raw column).
  static const std::map<IndicatorKind, const char*> kTitles = {
      {IndicatorKind::Dig, QT_TRANSLATE_NOOP("PortraitView", "digits of convergence (16: exact)")},
      {IndicatorKind::Rotation, QT_TRANSLATE_NOOP("PortraitView", "rotation number (turns per step)")},
      {IndicatorKind::Fli, QT_TRANSLATE_NOOP("PortraitView", "fast Lyapunov indicator, max ln |v|")},
      {IndicatorKind::Megno, QT_TRANSLATE_NOOP("PortraitView", "MEGNO ⟨Y⟩ (2: regular)")},
      {IndicatorKind::Lyapunov, QT_TRANSLATE_NOOP("PortraitView", "Lyapunov exponent (per step)")}};
  QwtText title(frame_->indicatorRequest ? tr(kTitles.at(frame_->indicatorRequest->measure.kind)) : frame_->quantity);
  QFont font = title.font();
  font.setPointSizeF(font.pointSizeF() * 0.9);
  title.setFont(font);
  plot_->setAxisTitle(QwtPlot::yRight, title);
}

void PortraitView::setState(RenderState state) {
  state_ = state;
  Q_EMIT renderStateChanged();
}

void PortraitView::scheduleRender() {
  renderWanted_ = true;
  worker_->cancel();  // the render in progress is of a view, mode or budget already left: its frames
                      // still queued are dropped (the state is no longer `accumulating`, then a new id)
  pointsSoFar_ = 0;
  setState(RenderState::pending);
  if (isVisible()) renderTimer_->start();  // else showEvent() starts it, at the size the view is shown at
}

void PortraitView::resizeEvent(QResizeEvent* event) {
  QWidget::resizeEvent(event);
  layoutPlot();
  // A new size of the view renders again at the canvas's new size (debounced by the render timer; the old
  // image stays, scaled, meanwhile).  Only the view's own resizes count: the plot's axes changing width
  // (longer labels, the colour bar) must not restart an accumulation.
  QTimer::singleShot(0, this, [this] {
    if (isVisible() && !renderWanted_ && state_ != RenderState::idle && rasterSize() != renderedSize_)
      scheduleRender();
  });
}

void PortraitView::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  gate_->setPaused(pausedByUser_);
  layoutPlot();
  if (renderWanted_) renderTimer_->start();
}

void PortraitView::hideEvent(QHideEvent* event) {
  QWidget::hideEvent(event);
  // Hidden (another tab, a minimised window): the render waits where it is, keeping its orbits, so that the
  // cores go to a run (issue 25, finding 15); it goes on when the view is shown again.
  gate_->setPaused(true);
}

QSize PortraitView::rasterSize() const {
  const QWidget* canvas = plot_->canvas();
  const qreal ratio = canvas->devicePixelRatioF();
  return {std::clamp(static_cast<int>(canvas->width() * ratio), 16, 4096),
          std::clamp(static_cast<int>(canvas->height() * ratio), 16, 4096)};
}

void PortraitView::startRender() {
  if (!isVisible()) return;  // showEvent() comes back here
  renderWanted_ = false;
  // The colour bar takes its room before the raster size is chosen (Orbits mode has none).
  const bool bar = indicator_ || mode_ != PortraitMode::Orbits;
  if (plot_->axisEnabled(QwtPlot::yRight) != bar) {
    plot_->enableAxis(QwtPlot::yRight, bar);
    layoutPlot();
  }
  renderedSize_ = rasterSize();
  if (indicator_) {
    IndicatorRequest request;
    request.measure.map = map_;
    request.measure.kind = *indicator_;
    request.view = view_;
    // At most 512 × 512 orbits of 2·10⁴ steps: the finest pass stays a few seconds on two cores; the first
    // (1/256 of the pixels) arrives within a fraction of a second (issue #27).
    const double scale = std::min(1.0, 512.0 / std::max(renderedSize_.width(), renderedSize_.height()));
    request.width = std::max(1, static_cast<int>(renderedSize_.width() * scale));
    request.height = std::max(1, static_cast<int>(renderedSize_.height() * scale));
    request.passes = 5;
    if (auto e = validationError(request)) {
      setState(RenderState::failed);
      Q_EMIT statusMessage(tr("Indicator map: %1").arg(QString::fromStdString(*e)));
      return;
    }
    pointsSoFar_ = 0;
    gate_->setPaused(pausedByUser_);
    currentRequest_ = worker_->renderIndicator(request, colours_, gate_);
    setState(RenderState::accumulating);
    return;
  }
  PortraitRequest request;
  request.map = map_;
  request.view = view_;
  request.mode = mode_;
  request.width = renderedSize_.width();
  request.height = renderedSize_.height();
  request.points = points_;
  // A first snapshot after ~2^20 points (2^18 in the slower scalar modes), then one at least every 2^28
  // (Density, ~0.3 s with the vector kernels) or 2^22 points, until the budget is reached.
  const bool density = mode_ == PortraitMode::Density;
  setProgressiveSchedule(request, density ? std::uint64_t{1} << 20 : std::uint64_t{1} << 18,
                         density ? std::uint64_t{1} << 28 : std::uint64_t{1} << 22);
  if (auto e = validationError(request)) {
    setState(RenderState::failed);
    Q_EMIT statusMessage(tr("Portrait: %1").arg(QString::fromStdString(*e)));
    return;
  }
  pointsSoFar_ = 0;
  gate_->setPaused(pausedByUser_);
  currentRequest_ = worker_->render(request, colours_, gate_);
  setState(RenderState::accumulating);
}

void PortraitView::onFrame(const PortraitFrame& frame) {
  if (frame.requestId != currentRequest_ || state_ != RenderState::accumulating) return;  // stale or stopped
  frame_ = std::make_unique<PortraitFrame>(frame);
  image_->setImage(frame.image, physicalRect(frame.request.view, frame.request.map));
  updateColourBar();
  plot_->replot();
  pointsSoFar_ = frame.pointsDone;
  Q_EMIT frameShown();
  if (frame.noSea) {
    setState(RenderState::noSea);
    Q_EMIT renderFinished();
  } else if (frame.final) {
    setState(RenderState::done);
    Q_EMIT renderFinished();
  } else {
    Q_EMIT renderStateChanged();
  }
}

bool PortraitView::sparse() const {
  return state_ == RenderState::done && frame_ && frame_->raster && frame_->pixelCount() > 0 &&
         static_cast<double>(frame_->nonEmptyPixels()) < kSparseFraction * static_cast<double>(frame_->pixelCount());
}

double PortraitView::visitedPercent() const {
  return 100.0 * static_cast<double>(frame_->nonEmptyPixels()) / static_cast<double>(frame_->pixelCount());
}

QString PortraitView::readout() const {
  const QLocale locale;
  if (indicator_) {
    const QString done = frame_ ? locale.toString(static_cast<qulonglong>(frame_->pointsDone)) : QStringLiteral("0");
    const QString total = frame_ ? locale.toString(static_cast<qulonglong>(frame_->pointsTotal)) : QStringLiteral("?");
    switch (state_) {
      case RenderState::idle: return tr("No map yet");
      case RenderState::pending: return tr("Waiting to compute…");
      case RenderState::accumulating: return tr("%1 of %2 orbits measured — refining…").arg(done, total);
      case RenderState::done: return tr("%1 orbits measured — done").arg(done);
      case RenderState::stopped: return tr("%1 of %2 orbits measured — stopped").arg(done, total);
      case RenderState::noSea:
      case RenderState::failed: return tr("The map could not be computed");
    }
    return {};
  }
  const QString points = locale.toString(static_cast<double>(pointsSoFar_), 'g', 3);
  const QString pixels = frame_ ? locale.toString(static_cast<qulonglong>(frame_->nonEmptyPixels())) : QStringLiteral("0");
  // Orbits mode with no island orbit: say so, rather than leave a plain sea unexplained.
  const auto allSea = [this] {
    return frame_ && frame_->raster && frame_->request.mode == PortraitMode::Orbits && frame_->raster->allOrbitsWrapped()
               ? tr(" · every seed here is in the chaotic sea (no island orbit; shaded by visits)")
               : QString();
  };
  switch (state_) {
    case RenderState::idle: return tr("No portrait yet");
    case RenderState::pending: return tr("Waiting to render…");
    case RenderState::accumulating:
      return tr("%1 points, %2 pixels — accumulating…").arg(points, pixels) + allSea();
    case RenderState::done:
      if (sparse() && frame_->raster->orbitsLeaveView())  // core's rule: the budget would add little here
        return tr("%1 points, %2 pixels (%3 %) — done; sparse: the seeds' orbits leave this deep view, a larger "
                  "budget (Ctrl+B) adds little: choose an indicator map (Fast Lyapunov indicator) to see it")
            .arg(points, pixels)
            .arg(visitedPercent(), 0, 'f', 0);
      if (sparse())
        return tr("%1 points, %2 pixels (%3 %) — done; sparse: raise the budget (Ctrl+B)")
                   .arg(points, pixels)
                   .arg(visitedPercent(), 0, 'f', 0);
      return tr("%1 points, %2 pixels — done (budget reached)").arg(points, pixels) + allSea();
    case RenderState::stopped: return tr("%1 points, %2 pixels — stopped").arg(points, pixels) + allSea();
    case RenderState::noSea:
      return tr("No chaotic points in this view after %1 points (an all-sea view would have had %2): it lies "
                "inside an island — try Island orbits")
          .arg(points)
          .arg(kNoSeaExpectedPoints, 0, 'f', 0);
    case RenderState::failed: return tr("The portrait could not be rendered");
  }
  return {};
}

void PortraitView::onRectangleSelected(const QRectF& rect) {
  const QRectF r = physicalRect(view_, map_);
  const QWidget* canvas = plot_->canvas();
  const double fx0 = (rect.left() - r.left()) / r.width(), fx1 = (rect.right() - r.left()) / r.width();
  const double fy0 = (rect.top() - r.top()) / r.height(), fy1 = (rect.bottom() - r.top()) / r.height();
  const bool click = std::fabs(fx1 - fx0) * canvas->width() < 4 && std::fabs(fy1 - fy0) * canvas->height() < 4;
  if (click) {
    // Launch from the exact position: the view's centre plus the click's offset, in long double.
    const PhysicalRect b = view_.physical(map_);
    const long double fx = (fx0 + fx1) / 2, fy = (fy0 + fy1) / 2;
    Q_EMIT clicked(b.x0 + fx * (b.x1 - b.x0), b.y0 + fy * (b.y1 - b.y0));
    return;
  }
  Q_EMIT cropRequested(std::min(fx0, fx1), std::max(fx0, fx1), std::min(fy0, fy1), std::max(fy0, fy1));
}

void PortraitView::setLineTool(bool on) {
  lineTool_ = on;
  lineDragging_ = false;
  picker_->setEnabled(!on);
  plot_->canvas()->setCursor(on ? Qt::CrossCursor : Qt::ArrowCursor);
}

bool PortraitView::exportPng(const QString& path, const QSize& requested) {
  // One export at a time: the wait below runs the event loop, where a second request could otherwise replace
  // the first one's render (latest wins) and leave it waiting.
  if (exporting_) {
    Q_EMIT statusMessage(tr("An export of the portrait is in progress"));
    return false;
  }
  exporting_ = true;
  const struct Done {
    bool& flag;
    ~Done() { flag = false; }
  } done{exporting_};
  QSize size = requested;
  const QRectF canvas = layOutExport(size);
  const PixelSize raster = exportRasterSize(canvas.width(), canvas.height());
  const int w = raster.width;
  const int h = raster.height;

  const PortraitRequest request = exportRequest(raster);
  const std::optional<IndicatorRequest> indicator = exportIndicatorRequest(raster);
  if (auto e = indicator ? validationError(*indicator) : validationError(request)) {
    Q_EMIT statusMessage(tr("Export failed: %1").arg(QString::fromStdString(*e)));
    return false;
  }

  QString error;
  const std::shared_ptr<const PortraitFrame> frame = waitForExportRender(request, indicator, path, &error);
  if (!frame) {
    Q_EMIT statusMessage(tr("Export failed: %1").arg(error.isEmpty() ? tr("no raster") : error));
    return false;
  }

  lastExportRaster_ = QSize(frame->image.width(), frame->image.height());
  const QImage image = plotImage(*frame, size);
  QString writeError;
  const bool ok = writePngFile(image, path, &writeError,
                               indicator ? indicatorProvenance(*indicator) : portraitProvenance(request));
  Q_EMIT statusMessage(ok ? tr("Exported %1 (%2 × %3, its raster %4 × %5)").arg(path).arg(size.width()).arg(size.height()).arg(w).arg(h)
                          : writeError);
  return ok;
}

QRectF PortraitView::layOutExport(QSize& size) {
  // The export's own layout: the canvas it gets in an image of that size (with equal aspect, the image is cut
  // to the view's aspect: core's exportImageSize), then a raster rendered at exactly that canvas size.
  QwtPlotLayout* layout = plot_->plotLayout();
  const auto canvasIn = [&](const QSize& s) {
    layout->activate(plot_, QRectF(QPointF(0, 0), QSizeF(s)), QwtPlotLayout::IgnoreScrollbars);
    return layout->canvasRect();
  };
  QRectF canvas = canvasIn(size);
  if (equalAspect_ && canvas.width() > 0 && canvas.height() > 0) {
    const PixelSize cut = exportImageSize({size.width(), size.height()}, canvas.width(), canvas.height(),
                                          static_cast<double>(view_.widthUnits() / view_.heightUnits()));
    size = QSize(cut.width, cut.height);
    canvas = canvasIn(size);
  }
  layout->invalidate();
  plot_->updateLayout();
  return canvas;
}

PortraitRequest PortraitView::exportRequest(const PixelSize& raster) const {
  PortraitRequest request;
  request.map = map_;
  request.view = view_;
  request.mode = mode_;
  request.width = raster.width;
  request.height = raster.height;
  request.points = exportPoints(pointsSoFar_, frame_ ? frame_->pixelCount() : 0, raster);
  request.passes = 1;
  return request;
}

std::optional<IndicatorRequest> PortraitView::exportIndicatorRequest(const PixelSize& raster) const {
  if (!indicator_) return std::nullopt;
  IndicatorRequest r;
  r.measure.map = map_;
  r.measure.kind = *indicator_;
  r.view = view_;
  r.width = raster.width;
  r.height = raster.height;
  r.passes = 1;
  return r;
}

std::shared_ptr<const PortraitFrame> PortraitView::waitForExportRender(const PortraitRequest& request,
                                                                       const std::optional<IndicatorRequest>& indicator,
                                                                       const QString& path, QString* error) {
  const int w = request.width;
  const int h = request.height;
  const quint64 id = worker_->renderForExport(request, indicator, colours_);
  std::shared_ptr<const PortraitFrame> frame;
  bool finished = false;
  QEventLoop loop;
  QProgressDialog progress(tr("Rendering the portrait at %1 × %2 pixels for %3…").arg(w).arg(h).arg(path), tr("Cancel"),
                           0, 1000, this);
  progress.setWindowModality(Qt::ApplicationModal);
  progress.setMinimumDuration(std::numeric_limits<int>::max());  // shown below, at half a second, not by setValue
  progress.setAutoClose(false);
  progress.setAutoReset(false);
  progress.hide();
  const auto ready = connect(worker_, &PortraitWorker::exportReady, &loop,
                             [&](quint64 answered, std::shared_ptr<const PortraitFrame> f, const QString& e) {
                               if (answered != id) return;
                               frame = std::move(f);
                               *error = e;
                               finished = true;
                               loop.quit();
                             });
  const auto moved = connect(worker_, &PortraitWorker::exportProgress, &progress, [&](quint64 answered, double f) {
    if (answered == id) progress.setValue(static_cast<int>(1000 * f));
  });
  connect(&progress, &QProgressDialog::canceled, &loop, [&] {
    worker_->cancelExport();
    *error = tr("cancelled");
    loop.quit();
  });
  // The first half second without user input (nothing can close the window under this wait); a longer render
  // shows the (modal) progress dialog, whose Cancel stops it.
  QTimer::singleShot(500, &loop, [&] {
    if (!finished) loop.exit(1);
  });
  if (!finished && loop.exec(QEventLoop::ExcludeUserInputEvents) == 1 && !finished) {
    progress.show();
    loop.exec();
  }
  disconnect(ready);
  disconnect(moved);
  progress.close();
  return frame;
}

QImage PortraitView::plotImage(const PortraitFrame& frame, const QSize& size) {
  // The plot as on screen, with the export's raster under its axes.
  const QImage screenImage = frame_ ? frame_->image : QImage();
  const bool hadBar = plot_->axisEnabled(QwtPlot::yRight);
  image_->setImage(frame.image, physicalRect(view_, map_));
  QImage image(size, QImage::Format_ARGB32);
  image.fill(Qt::white);
  {
    QPainter painter(&image);
    QwtPlotRenderer renderer;
    renderer.render(plot_, &painter, QRectF(QPointF(0, 0), QSizeF(size)));
  }
  if (frame_) image_->setImage(screenImage, physicalRect(frame_->request.view, frame_->request.map));
  else image_->setImage(QImage(), QRectF());
  plot_->enableAxis(QwtPlot::yRight, hadBar);
  plot_->replot();
  return image;
}

bool PortraitView::exportNpy(const QString& path) {
  if (!frame_) {
    Q_EMIT statusMessage(tr("Nothing to export yet"));
    return false;
  }
  try {
    if (frame_->indicator) {
      IndicatorResult result;
      result.raster = *frame_->indicator;
      result.cancelled = !frame_->final;
      exportIndicatorNpy(path.toStdString(), *frame_->indicatorRequest, result, {});
    } else {
      exportPortraitNpy(path.toStdString(), frame_->request, *frame_->raster);
    }
  } catch (const std::exception& e) {
    Q_EMIT statusMessage(tr("Export failed: %1").arg(QString::fromUtf8(e.what())));
    return false;
  }
  Q_EMIT statusMessage(tr("Exported %1 and %2").arg(path, QString::fromStdString(sidecarPath(path.toStdString()))));
  return true;
}

PhysicalPoint PortraitView::physicalAt(const QPointF& pos) const {
  const QwtScaleMap xMap = plot_->canvasMap(QwtPlot::xBottom), yMap = plot_->canvasMap(QwtPlot::yLeft);
  const double fx = (pos.x() - xMap.p1()) / (xMap.p2() - xMap.p1());
  const double fy = (pos.y() - yMap.p1()) / (yMap.p2() - yMap.p1());  // p1 is y0 (bottom)
  const PhysicalRect b = view_.physical(map_);
  return {b.x0 + fx * (b.x1 - b.x0), b.y0 + fy * (b.y1 - b.y0)};
}

QString PortraitView::cursorText(const QPointF& pos) const {
  const QwtScaleMap xMap = plot_->canvasMap(QwtPlot::xBottom), yMap = plot_->canvasMap(QwtPlot::yLeft);
  const double fx = (pos.x() - xMap.p1()) / (xMap.p2() - xMap.p1());
  const double fy = (pos.y() - yMap.p1()) / (yMap.p2() - yMap.p1());  // p1 is y0 (bottom)
  const PhysicalRect b = view_.physical(map_);
  const long double x = b.x0 + fx * (b.x1 - b.x0), y = b.y0 + fy * (b.y1 - b.y0);
  const long double X = static_cast<long double>(view_.centre().X) + (fx - 0.5) * view_.widthUnits();
  const long double Y = static_cast<long double>(view_.centre().Y) + (fy - 0.5) * view_.heightUnits();
  const int digits = axisDigits(static_cast<double>(b.x0), static_cast<double>(b.x1)) + 2;
  return tr("x = %1, y = %2   X = %3, Y = %4 (unit)")
      .arg(static_cast<double>(x), 0, 'g', digits)
      .arg(static_cast<double>(y), 0, 'g', digits)
      .arg(static_cast<double>(std::ldexp(X, -52)), 0, 'g', digits)
      .arg(static_cast<double>(std::ldexp(Y, -52)), 0, 'g', digits);
}

namespace {
/// True when the focus is in a field the user types into: the mouse passing over the portrait leaves it there.
bool typing() {
  QWidget* w = QApplication::focusWidget();
  if (!w) return false;
  if (qobject_cast<QLineEdit*>(w) || qobject_cast<QAbstractSpinBox*>(w)) return true;
  if (auto* box = qobject_cast<QComboBox*>(w)) return box->isEditable();
  return false;
}
}  // namespace

bool PortraitView::eventFilter(QObject* watched, QEvent* event) {
  if (watched == plot_->canvas()) {
    switch (event->type()) {
      case QEvent::Enter:
        if (!typing() && window()->isActiveWindow()) plot_->canvas()->setFocus(Qt::MouseFocusReason);
        break;
      case QEvent::Wheel: {
        auto* wheel = static_cast<QWheelEvent*>(event);
        const double steps = wheel->angleDelta().y() / 120.0;
        if (steps != 0) {
          const QPointF pos = wheel->position();
          const QwtScaleMap xMap = plot_->canvasMap(QwtPlot::xBottom), yMap = plot_->canvasMap(QwtPlot::yLeft);
          const double fx = (pos.x() - xMap.p1()) / (xMap.p2() - xMap.p1());
          const double fy = (pos.y() - yMap.p1()) / (yMap.p2() - yMap.p1());
          Q_EMIT zoomRequested(fx, fy, std::pow(1.25, steps));
        }
        return true;
      }
      case QEvent::MouseButtonPress:
        // Shift+click: the periodic orbit there (issue 37, finding 16); the picker takes unmodified drags only.
        if (!lineTool_ && static_cast<QMouseEvent*>(event)->button() == Qt::LeftButton &&
            (static_cast<QMouseEvent*>(event)->modifiers() & Qt::ShiftModifier)) {
          const PhysicalPoint p = physicalAt(mousePosition(static_cast<QMouseEvent*>(event)));
          Q_EMIT periodicOrbitRequested(p.x, p.y);
          return true;
        }
        if (lineTool_ && static_cast<QMouseEvent*>(event)->button() == Qt::LeftButton) {
          lineStart_ = mousePosition(static_cast<QMouseEvent*>(event));
          lineDragging_ = true;
          return true;
        }
        break;
      case QEvent::MouseMove: {
        const QPointF pos = mousePosition(static_cast<QMouseEvent*>(event));
        Q_EMIT cursorMoved(cursorText(pos));
        break;
      }
      case QEvent::MouseButtonRelease:
        if (lineTool_ && lineDragging_ && static_cast<QMouseEvent*>(event)->button() == Qt::LeftButton) {
          lineDragging_ = false;
          const QPointF end = mousePosition(static_cast<QMouseEvent*>(event));
          if ((end - lineStart_).manhattanLength() >= 4) Q_EMIT lineSelected(physicalAt(lineStart_), physicalAt(end));
          return true;
        }
        break;
      default: break;
    }
  }
  return QWidget::eventFilter(watched, event);
}

void PortraitView::keyPressEvent(QKeyEvent* event) {
  // The keys of a view without its panel (the panel's Portrait actions take them first when it is there):
  // Alt+Left / Alt+Right (and the Back/Forward keys) go through the history, as in a browser; arrows pan.
  if (event->matches(QKeySequence::Back) || event->key() == Qt::Key_Back) {
    Q_EMIT backRequested();
    return;
  }
  if (event->matches(QKeySequence::Forward) || event->key() == Qt::Key_Forward) {
    Q_EMIT forwardRequested();
    return;
  }
  switch (event->key()) {
    case Qt::Key_Left: Q_EMIT panRequested(-0.1, 0); break;
    case Qt::Key_Right: Q_EMIT panRequested(0.1, 0); break;
    case Qt::Key_Up: Q_EMIT panRequested(0, 0.1); break;
    case Qt::Key_Down: Q_EMIT panRequested(0, -0.1); break;
    case Qt::Key_Plus:
    case Qt::Key_Equal: Q_EMIT zoomRequested(0.5, 0.5, 2.0); break;
    case Qt::Key_Minus: Q_EMIT zoomRequested(0.5, 0.5, 0.5); break;
    case Qt::Key_Home: Q_EMIT resetRequested(); break;
    case Qt::Key_Backspace: Q_EMIT backRequested(); break;
    default: QWidget::keyPressEvent(event); return;
  }
}

}  // namespace archipelago::ui
