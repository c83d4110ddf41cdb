#include "ui/portrait/PortraitView.hpp"

#include <QKeyEvent>
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
#include <qwt_plot_marker.h>
#include <qwt_plot_panner.h>
#include <qwt_plot_picker.h>
#include <qwt_plot_renderer.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_map.h>
#include <qwt_scale_widget.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "core/portrait/MapOverlays.hpp"
#include "core/portrait/PortraitExport.hpp"
#include "ui/portrait/PortraitWorker.hpp"

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

/// One orbit launched by a click, drawn as dots in its own colour.  (A plain QwtPlotItem: Qwt 6.1's
/// QwtPlotCurve headers do not compile as C++20, and only the points inside the canvas need drawing.)
class OrbitItem : public QwtPlotItem {
 public:
  OrbitItem(std::vector<QPointF> points, QColor colour) : points_(std::move(points)), colour_(colour) { setZ(20); }
  int rtti() const override { return QwtPlotItem::Rtti_PlotUserItem + 2; }
  void draw(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap,
            const QRectF& canvasRect) const override {
    painter->setPen(QPen(colour_, 2));
    QVector<QPointF> visible;
    for (const QPointF& p : points_) {
      const QPointF q(xMap.transform(p.x()), yMap.transform(p.y()));
      if (canvasRect.contains(q)) visible.append(q);
    }
    painter->drawPoints(visible.constData(), static_cast<int>(visible.size()));
  }
  [[nodiscard]] std::size_t size() const noexcept { return points_.size(); }

 private:
  std::vector<QPointF> points_;
  QColor colour_;
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

  image_ = new PortraitImageItem;
  image_->attach(plot_);

  picker_ = new QwtPlotPicker(QwtPlot::xBottom, QwtPlot::yLeft, QwtPicker::RectRubberBand,
                              QwtPicker::AlwaysOff, plot_->canvas());
  picker_->setStateMachine(new QwtPickerDragRectMachine);
  picker_->setRubberBandPen(QPen(Qt::white, 1, Qt::DashLine));
  connect(picker_, qOverload<const QRectF&>(&QwtPlotPicker::selected), this, &PortraitView::onRectangleSelected);

  panner_ = new QwtPlotPanner(plot_->canvas());
  panner_->setMouseButton(Qt::MiddleButton);
  connect(panner_, &QwtPanner::panned, this, [this](int dx, int dy) {
    const QWidget* canvas = plot_->canvas();
    panBy(-static_cast<double>(dx) / std::max(1, canvas->width()), static_cast<double>(dy) / std::max(1, canvas->height()));
  });

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(plot_);

  renderTimer_ = new QTimer(this);
  renderTimer_->setSingleShot(true);
  renderTimer_->setInterval(40);  // coalesce a burst of wheel steps or resizes into one request
  connect(renderTimer_, &QTimer::timeout, this, &PortraitView::startRender);

  worker_ = new PortraitWorker(this);
  connect(worker_, &PortraitWorker::frameReady, this, &PortraitView::onFrame, Qt::QueuedConnection);
  connect(worker_, &PortraitWorker::progress, this, [this](quint64 id, quint64 done, quint64 total) {
    if (id == currentRequest_ && total > 0)
      Q_EMIT statusMessage(tr("Rendering %1: %2%").arg(QString::fromLatin1(toString(mode_).data())).arg(100.0 * static_cast<double>(done) / static_cast<double>(total), 0, 'f', 0));
  }, Qt::QueuedConnection);
  connect(worker_, &PortraitWorker::failed, this, [this](quint64 id, const QString& message) {
    if (id != currentRequest_) return;
    rendering_ = false;
    Q_EMIT statusMessage(tr("Portrait failed: %1").arg(message));
  }, Qt::QueuedConnection);

  updateFixedPoints();
  updateAxes();
  scheduleRender();
}

PortraitView::~PortraitView() {
  delete worker_;  // stops the render in progress and waits for the thread before the plot goes away
  worker_ = nullptr;
}

bool PortraitView::setParameters(const MapParameters& parameters) {
  if (auto e = mapError(parameters)) {
    Q_EMIT statusMessage(tr("Invalid parameters: %1").arg(QString::fromStdString(*e)));
    return false;
  }
  parameters_ = parameters;
  history_.assign(1, Viewport());
  historyIndex_ = 0;
  clearOrbits();
  updateFixedPoints();
  updateAxes();
  Q_EMIT viewportChanged();
  scheduleRender();
  return true;
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
  points_ = std::max<std::uint64_t>(points, 1);
  scheduleRender();
}

void PortraitView::setViewport(const Viewport& view) { showViewport(true, view); }

void PortraitView::zoomAt(double fx, double fy, double factor) {
  showViewport(true, viewport().zoomedAboutFraction(fx, fy, factor));
}

void PortraitView::panBy(double fx, double fy) { showViewport(true, viewport().panned(fx, fy)); }

void PortraitView::back() {
  if (!canGoBack()) return;
  --historyIndex_;
  showViewport(false, viewport());
}

void PortraitView::forward() {
  if (!canGoForward()) return;
  ++historyIndex_;
  showViewport(false, viewport());
}

void PortraitView::resetView() { showViewport(true, Viewport()); }

void PortraitView::showViewport(bool record, const Viewport& view) {
  if (record) {
    if (view == viewport()) return;
    history_.resize(historyIndex_ + 1);  // a new view drops the forward history, as in a browser
    history_.push_back(view);
    historyIndex_ = history_.size() - 1;
  }
  updateAxes();
  Q_EMIT viewportChanged();
  scheduleRender();
}

void PortraitView::updateAxes() {
  const QRectF r = physicalRect(viewport(), parameters_);
  xScale_->setDigits(digitsFor(r.left(), r.right()));
  yScale_->setDigits(digitsFor(r.top(), r.bottom()));
  plot_->setAxisScale(QwtPlot::xBottom, r.left(), r.right());
  plot_->setAxisScale(QwtPlot::yLeft, r.top(), r.bottom());
  plot_->replot();
}

void PortraitView::updateColourBar() {
  const bool scale = frame_ && frame_->request.mode != PortraitMode::Orbits;
  plot_->enableAxis(QwtPlot::yRight, scale);
  if (!scale) return;
  const QwtInterval interval(frame_->scaleMin, std::max(frame_->scaleMax, frame_->scaleMin + 1e-9));
  plot_->axisWidget(QwtPlot::yRight)->setColorMap(interval, new CoreColourMap(colours_));
  plot_->setAxisScale(QwtPlot::yRight, interval.minValue(), interval.maxValue());
  plot_->setAxisTitle(QwtPlot::yRight, frame_->quantity);
}

void PortraitView::updateFixedPoints() {
  for (QwtPlotMarker* m : fixedPointMarkers_) {
    m->detach();
    delete m;
  }
  fixedPointMarkers_.clear();
  for (const FixedPoint& p : fixedPoints(parameters_)) {
    auto* marker = new QwtPlotMarker;
    marker->setValue(static_cast<double>(p.position.x), static_cast<double>(p.position.y));
    marker->setSymbol(new QwtSymbol(p.elliptic ? QwtSymbol::Ellipse : QwtSymbol::XCross, QBrush(Qt::NoBrush),
                                    QPen(Qt::white, 1.5), QSize(9, 9)));
    marker->setZ(30);
    marker->setTitle(p.elliptic ? tr("elliptic fixed point") : tr("hyperbolic fixed point"));
    marker->attach(plot_);
    fixedPointMarkers_.push_back(marker);
  }
}

void PortraitView::scheduleRender() { renderTimer_->start(); }

void PortraitView::startRender() {
  const QWidget* canvas = plot_->canvas();
  const qreal ratio = canvas->devicePixelRatioF();
  PortraitRequest request;
  request.map = parameters_;
  request.view = viewport();
  request.mode = mode_;
  request.width = std::clamp(static_cast<int>(canvas->width() * ratio), 16, 4096);
  request.height = std::clamp(static_cast<int>(canvas->height() * ratio), 16, 4096);
  request.points = points_;
  if (auto e = validationError(request)) {
    Q_EMIT statusMessage(tr("Portrait: %1").arg(QString::fromStdString(*e)));
    return;
  }
  rendering_ = true;
  currentRequest_ = worker_->render(request, colours_);
}

void PortraitView::onFrame(const PortraitFrame& frame) {
  if (frame.requestId != currentRequest_) return;  // a view already left
  frame_ = std::make_unique<PortraitFrame>(frame);
  image_->setImage(frame.image, physicalRect(frame.request.view, frame.request.map));
  updateColourBar();
  plot_->replot();
  const double rate = frame.seconds > 0 ? static_cast<double>(frame.pointsDone) / frame.seconds : 0;
  const PhysicalRect r = frame.request.view.physical(frame.request.map);
  Q_EMIT statusMessage(tr("%1: %2 of %3 points in %4 s (%5 points/s), %6 pixels visited, view width %7")
                           .arg(QString::fromLatin1(toString(frame.request.mode).data()))
                           .arg(static_cast<double>(frame.pointsDone), 0, 'g', 3)
                           .arg(static_cast<double>(frame.pointsTotal), 0, 'g', 3)
                           .arg(frame.seconds, 0, 'f', 2)
                           .arg(rate, 0, 'g', 3)
                           .arg(static_cast<qulonglong>(frame.raster->nonEmptyPixels()))
                           .arg(static_cast<double>(r.x1 - r.x0), 0, 'g', 3));
  if (frame.final) {
    rendering_ = false;
    Q_EMIT renderFinished();
  }
}

void PortraitView::onRectangleSelected(const QRectF& rect) {
  const QRectF r = physicalRect(viewport(), parameters_);
  const QWidget* canvas = plot_->canvas();
  const double fx0 = (rect.left() - r.left()) / r.width(), fx1 = (rect.right() - r.left()) / r.width();
  const double fy0 = (rect.top() - r.top()) / r.height(), fy1 = (rect.bottom() - r.top()) / r.height();
  const bool click = std::fabs(fx1 - fx0) * canvas->width() < 4 && std::fabs(fy1 - fy0) * canvas->height() < 4;
  if (click) {
    // Launch from the exact position: the view's centre plus the click's offset, in long double.
    const Viewport& v = viewport();
    const PhysicalRect b = v.physical(parameters_);
    const long double fx = (fx0 + fx1) / 2, fy = (fy0 + fy1) / 2;
    const long double x = b.x0 + fx * (b.x1 - b.x0), y = b.y0 + fy * (b.y1 - b.y0);
    launchOrbit(static_cast<double>(x), static_cast<double>(y));
    return;
  }
  showViewport(true, viewport().cropped(std::min(fx0, fx1), std::max(fx0, fx1), std::min(fy0, fy1), std::max(fy0, fy1)));
}

void PortraitView::launchOrbit(double x, double y, int steps) {
  std::vector<PhysicalPoint> points;
  try {
    points = traceOrbit(parameters_, x, y, static_cast<std::uint64_t>(std::max(steps, 0)));
  } catch (const std::exception& e) {
    Q_EMIT statusMessage(tr("Orbit: %1").arg(QString::fromUtf8(e.what())));
    return;
  }
  std::vector<QPointF> samples;
  samples.reserve(points.size());
  for (const PhysicalPoint& p : points) samples.emplace_back(static_cast<double>(p.x), static_cast<double>(p.y));
  const Rgb c = orbitColour(static_cast<std::uint32_t>(orbits_.size() + 1));
  auto* curve = new OrbitItem(std::move(samples), QColor(c.r, c.g, c.b));
  curve->setTitle(tr("orbit %1").arg(orbits_.size() + 1));
  curve->attach(plot_);
  orbits_.push_back(curve);
  plot_->replot();
  Q_EMIT statusMessage(tr("Orbit %1 from (%2, %3): %4 steps").arg(orbits_.size()).arg(x, 0, 'g', 17).arg(y, 0, 'g', 17).arg(steps));
}

void PortraitView::clearOrbits() {
  for (OrbitItem* c : orbits_) {
    c->detach();
    delete c;
  }
  orbits_.clear();
  plot_->replot();
}

bool PortraitView::exportPng(const QString& path, const QSize& size) {
  QImage image(size, QImage::Format_ARGB32);
  image.fill(Qt::white);
  {
    QPainter painter(&image);
    QwtPlotRenderer renderer;
    renderer.render(plot_, &painter, QRectF(QPointF(0, 0), QSizeF(size)));
  }
  const bool ok = image.save(path, "PNG");
  Q_EMIT statusMessage(ok ? tr("Exported %1").arg(path) : tr("Could not write %1").arg(path));
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
  const Viewport& v = viewport();
  const PhysicalRect b = v.physical(parameters_);
  const long double x = b.x0 + fx * (b.x1 - b.x0), y = b.y0 + fy * (b.y1 - b.y0);
  const long double X = static_cast<long double>(v.centre().X) + (fx - 0.5) * v.widthUnits();
  const long double Y = static_cast<long double>(v.centre().Y) + (fy - 0.5) * v.heightUnits();
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
        zoomAt(fx, fy, std::pow(1.25, steps));
      }
      return true;
    }
    if (event->type() == QEvent::MouseMove) Q_EMIT cursorMoved(cursorText(mousePosition(static_cast<QMouseEvent*>(event))));
  }
  return QWidget::eventFilter(watched, event);
}

void PortraitView::keyPressEvent(QKeyEvent* event) {
  switch (event->key()) {
    case Qt::Key_Left: panBy(-0.1, 0); break;
    case Qt::Key_Right: panBy(0.1, 0); break;
    case Qt::Key_Up: panBy(0, 0.1); break;
    case Qt::Key_Down: panBy(0, -0.1); break;
    case Qt::Key_Plus: zoomIn(); break;
    case Qt::Key_Minus: zoomOut(); break;
    case Qt::Key_Home: resetView(); break;
    case Qt::Key_Backspace: back(); break;
    default: QWidget::keyPressEvent(event); return;
  }
}

}  // namespace archipelago::ui
