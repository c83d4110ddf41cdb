#include "ui/portrait/PortraitView.hpp"

#include <QKeyEvent>
#include <QLocale>
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
#include <qwt_plot_panner.h>
#include <qwt_plot_picker.h>
#include <qwt_plot_renderer.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_map.h>
#include <qwt_scale_widget.h>
#include <qwt_text.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/portrait/PortraitExport.hpp"
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

/// Axis labels with as many digits as the view's width needs (the default 6 run out below ~10^-5).
class PrecisionScaleDraw : public QwtScaleDraw {
 public:
  void setDigits(int digits) { digits_ = digits; }
  QwtText label(double value) const override { return QString::number(value, 'g', digits_); }

 private:
  int digits_ = 6;
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

int digitsFor(double a, double b) {
  const double width = std::fabs(b - a), magnitude = std::max(std::fabs(a), std::fabs(b));
  if (!(width > 0)) return 6;
  return std::clamp(static_cast<int>(std::ceil(std::log10(std::max(magnitude, width) / width))) + 3, 3, 19);
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
  plot_->canvas()->setFocusPolicy(Qt::StrongFocus);
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

  panner_ = new QwtPlotPanner(plot_->canvas());
  panner_->setMouseButton(Qt::MiddleButton);
  connect(panner_, &QwtPanner::panned, this, [this](int dx, int dy) {
    const QWidget* canvas = plot_->canvas();
    Q_EMIT panRequested(-static_cast<double>(dx) / std::max(1, canvas->width()),
                        static_cast<double>(dy) / std::max(1, canvas->height()));
  });

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(plot_);

  renderTimer_ = new QTimer(this);
  renderTimer_->setSingleShot(true);
  renderTimer_->setInterval(60);  // coalesce a burst of wheel steps or resizes into one request
  connect(renderTimer_, &QTimer::timeout, this, &PortraitView::startRender);

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
  scheduleRender();
}

void PortraitView::setMode(PortraitMode mode) {
  if (mode == mode_) return;
  mode_ = mode;
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
  plot_->replot();
}

const std::vector<QwtPlotItem*>& PortraitView::layerItems(PortraitLayer layer) const {
  static const std::vector<QwtPlotItem*> none;
  const auto it = layers_.find(layer);
  return it == layers_.end() ? none : it->second;
}

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
  plot_->replot();
}

QWidget* PortraitView::canvas() const { return plot_->canvas(); }

std::pair<double, double> PortraitView::xAxisRange() const {
  const QwtScaleDiv& d = plot_->axisScaleDiv(QwtPlot::xBottom);
  return {d.lowerBound(), d.upperBound()};
}

double PortraitView::canvasAspect() const {
  const QWidget* c = plot_->canvas();
  return c->height() > 0 && c->width() > 0 ? static_cast<double>(c->width()) / c->height() : 1.0;
}

void PortraitView::updateAxes() {
  const QRectF r = physicalRect(view_, map_);
  xScale_->setDigits(digitsFor(r.left(), r.right()));
  yScale_->setDigits(digitsFor(r.top(), r.bottom()));
  plot_->setAxisScale(QwtPlot::xBottom, r.left(), r.right());
  plot_->setAxisScale(QwtPlot::yLeft, r.top(), r.bottom());
  plot_->replot();
}

void PortraitView::updateColourBar() {
  const bool scale = frame_ && frame_->request.mode != PortraitMode::Orbits;
  if (!scale) return;
  const QwtInterval interval(frame_->scaleMin, std::max(frame_->scaleMax, frame_->scaleMin + 1e-9));
  plot_->axisWidget(QwtPlot::yRight)->setColorMap(interval, new CoreColourMap(colours_));
  plot_->setAxisScale(QwtPlot::yRight, interval.minValue(), interval.maxValue());
  plot_->setAxisTitle(QwtPlot::yRight, frame_->quantity);
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
  if (renderWanted_) renderTimer_->start();
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
  const bool bar = mode_ != PortraitMode::Orbits;
  if (plot_->axisEnabled(QwtPlot::yRight) != bar) {
    plot_->enableAxis(QwtPlot::yRight, bar);
    plot_->updateLayout();
  }
  PortraitRequest request;
  request.map = map_;
  request.view = view_;
  request.mode = mode_;
  renderedSize_ = rasterSize();
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
  currentRequest_ = worker_->render(request, colours_);
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

QString PortraitView::readout() const {
  const QLocale locale;
  const QString points = locale.toString(static_cast<double>(pointsSoFar_), 'g', 3);
  const QString pixels =
      frame_ ? locale.toString(static_cast<qulonglong>(frame_->raster->nonEmptyPixels())) : QStringLiteral("0");
  // Orbits mode with no island orbit: say so, rather than leave a plain sea unexplained.
  const auto allSea = [this] {
    return frame_ && frame_->request.mode == PortraitMode::Orbits && frame_->raster->allOrbitsWrapped()
               ? tr(" · every seed here is in the chaotic sea (no island orbit; shaded by visits)")
               : QString();
  };
  switch (state_) {
    case RenderState::idle: return tr("No portrait yet");
    case RenderState::pending: return tr("Waiting to render…");
    case RenderState::accumulating:
      return tr("%1 points so far, %2 pixels visited — accumulating…").arg(points, pixels) + allSea();
    case RenderState::done:
      return tr("%1 points, %2 pixels visited — done (budget reached)").arg(points, pixels) + allSea();
    case RenderState::stopped: return tr("%1 points, %2 pixels visited — stopped").arg(points, pixels) + allSea();
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
    const long double x = b.x0 + fx * (b.x1 - b.x0), y = b.y0 + fy * (b.y1 - b.y0);
    Q_EMIT clicked(static_cast<double>(x), static_cast<double>(y));
    return;
  }
  Q_EMIT cropRequested(std::min(fx0, fx1), std::max(fx0, fx1), std::min(fy0, fy1), std::max(fy0, fy1));
}

bool PortraitView::exportPng(const QString& path, const QSize& size) {
  QImage image(size, QImage::Format_ARGB32);
  image.fill(Qt::white);
  {
    QPainter painter(&image);
    QwtPlotRenderer renderer;
    renderer.render(plot_, &painter, QRectF(QPointF(0, 0), QSizeF(size)));
  }
  QString error;
  const bool ok = writePngFile(image, path, &error);
  Q_EMIT statusMessage(ok ? tr("Exported %1").arg(path) : error);
  return ok;
}

bool PortraitView::exportNpy(const QString& path) {
  if (!frame_) {
    Q_EMIT statusMessage(tr("Nothing to export yet"));
    return false;
  }
  try {
    exportPortraitNpy(path.toStdString(), frame_->request, *frame_->raster);
  } catch (const std::exception& e) {
    Q_EMIT statusMessage(tr("Export failed: %1").arg(QString::fromUtf8(e.what())));
    return false;
  }
  Q_EMIT statusMessage(tr("Exported %1 and %2").arg(path, QString::fromStdString(sidecarPath(path.toStdString()))));
  return true;
}

QString PortraitView::cursorText(const QPointF& pos) const {
  const QwtScaleMap xMap = plot_->canvasMap(QwtPlot::xBottom), yMap = plot_->canvasMap(QwtPlot::yLeft);
  const double fx = (pos.x() - xMap.p1()) / (xMap.p2() - xMap.p1());
  const double fy = (pos.y() - yMap.p1()) / (yMap.p2() - yMap.p1());  // p1 is y0 (bottom)
  const PhysicalRect b = view_.physical(map_);
  const long double x = b.x0 + fx * (b.x1 - b.x0), y = b.y0 + fy * (b.y1 - b.y0);
  const long double X = static_cast<long double>(view_.centre().X) + (fx - 0.5) * view_.widthUnits();
  const long double Y = static_cast<long double>(view_.centre().Y) + (fy - 0.5) * view_.heightUnits();
  const int digits = digitsFor(static_cast<double>(b.x0), static_cast<double>(b.x1)) + 2;
  return tr("x = %1, y = %2   X = %3, Y = %4 (unit)")
      .arg(static_cast<double>(x), 0, 'g', digits)
      .arg(static_cast<double>(y), 0, 'g', digits)
      .arg(static_cast<double>(std::ldexp(X, -52)), 0, 'g', digits)
      .arg(static_cast<double>(std::ldexp(Y, -52)), 0, 'g', digits);
}

bool PortraitView::eventFilter(QObject* watched, QEvent* event) {
  if (watched == plot_->canvas()) {
    if (event->type() == QEvent::Wheel) {
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
    if (event->type() == QEvent::MouseMove) Q_EMIT cursorMoved(cursorText(mousePosition(static_cast<QMouseEvent*>(event))));
  }
  return QWidget::eventFilter(watched, event);
}

void PortraitView::keyPressEvent(QKeyEvent* event) {
  // Alt+Left / Alt+Right (and the Back/Forward mouse and keyboard keys) go through the history, as in a browser;
  // plain arrows pan.
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
    case Qt::Key_Plus: Q_EMIT zoomRequested(0.5, 0.5, 2.0); break;
    case Qt::Key_Minus: Q_EMIT zoomRequested(0.5, 0.5, 0.5); break;
    case Qt::Key_Home: Q_EMIT resetRequested(); break;
    case Qt::Key_Backspace: Q_EMIT backRequested(); break;
    default: QWidget::keyPressEvent(event); return;
  }
}

}  // namespace archipelago::ui
