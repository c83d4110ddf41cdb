#include "ui/plots/StatisticsPlot.hpp"

#include <QBrush>
#include <QContextMenuEvent>
#include <QFile>
#include <QFileInfo>
#include <QMenu>
#include <QPen>
#include <qwt_interval_symbol.h>
#include <qwt_plot_canvas.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_intervalcurve.h>
#include <qwt_plot_legenditem.h>
#include <qwt_plot_magnifier.h>
#include <qwt_plot_marker.h>
#include <qwt_plot_panner.h>
#include <qwt_plot_renderer.h>
#include <qwt_plot_zoomer.h>
#include <qwt_scale_engine.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <cmath>
#include <string_view>

#include "core/stats/TailAnalysis.hpp"
#include "ui/plots/CrosshairPicker.hpp"
#include "ui/plots/LogScaleDraw.hpp"
#include "ui/plots/QwtCompat.hpp"

namespace archipelago::ui {

namespace {
const QColor kDataColor(31, 78, 154);
const QColor kBandColor(31, 78, 154, 55);
const QColor kTheoryColors[] = {QColor(214, 96, 18), QColor(160, 30, 60), QColor(40, 130, 60)};

QString fromTable(std::string_view text) {
  return QString::fromUtf8(text.data(), static_cast<int>(text.size()));
}

bool usable(double x, double y, bool logY) {
  return std::isfinite(x) && std::isfinite(y) && x > 0 && (!logY || y > 0);
}

class Zoomer : public QwtPlotZoomer {
 public:
  explicit Zoomer(QWidget* canvas) : QwtPlotZoomer(canvas) {
    setTrackerMode(QwtPicker::AlwaysOff);  // the crosshair shows the coordinates
    setRubberBandPen(QPen(QColor(31, 78, 154), 1, Qt::DashLine));
    // Right click: one zoom level back; Ctrl + right click: the whole data.
    setMousePattern(QwtEventPattern::MouseSelect2, Qt::RightButton, Qt::ControlModifier);
    setMousePattern(QwtEventPattern::MouseSelect3, Qt::RightButton);
  }
};
// The literature's tail slopes t^−γ on the P_t plot (issue #14, item 7): the lines, their anchor and labels
// are core's (stats/TailAnalysis.hpp, referenceSlopes()); this draws them, thin and grey, into `items`.
void addReferenceSlopes(QwtPlot& plot, const Series& P, bool logY, std::vector<QwtPlotCurve*>& items) {
  static const Qt::PenStyle kStyles[] = {Qt::DotLine, Qt::DashDotLine, Qt::DashDotDotLine, Qt::DashLine};
  int index = 0;
  for (const ReferenceSlope& r : referenceSlopes(P)) {
    QVector<QPointF> points;
    for (std::size_t i = 0; i < r.line.x.size(); ++i)
      if (usable(r.line.x[i], r.line.value[i], logY)) points.append(QPointF(r.line.x[i], r.line.value[i]));
    auto* c = new QwtPlotCurve(QwtText(QString::fromStdString(r.labelRich), QwtText::RichText));
    c->setPen(QPen(QColor(110, 110, 110), 1.2, kStyles[index++ % 4]));
    c->setRenderHint(QwtPlotItem::RenderAntialiased);
    c->setItemAttribute(QwtPlotItem::AutoScale, false);  // references never move the ranges of the data
    c->setSamples(points);
    c->attach(&plot);
    items.push_back(c);
  }
}
}  // namespace

StatisticsPlot::StatisticsPlot(Statistic statistic, QWidget* parent) : QwtPlot(parent), statistic_(statistic) {
  const StatisticInfo& info = statisticInfo(statistic);
  setObjectName(QStringLiteral("plot_") + fromTable(info.fileStem));
  setAutoReplot(false);
  QwtText title(fromTable(info.symbolRich), QwtText::RichText);
  QFont titleFont = font();
  titleFont.setPointSizeF(titleFont.pointSizeF() * 1.1);
  titleFont.setBold(true);
  title.setFont(titleFont);
  setTitle(title);
  setCanvasBackground(Qt::white);
  if (auto* c = qobject_cast<QwtPlotCanvas*>(canvas())) c->setFrameStyle(static_cast<int>(QFrame::Box) | static_cast<int>(QFrame::Plain));

  QFont axisFont = font();
  axisFont.setPointSizeF(axisFont.pointSizeF() * 0.9);
  QwtText xTitle(fromTable(info.abscissaLabelRich), QwtText::RichText);
  xTitle.setFont(axisFont);
  QwtText yTitle(fromTable(info.valueLabelRich), QwtText::RichText);
  yTitle.setFont(axisFont);
  setAxisTitle(kAxisX, xTitle);
  setAxisTitle(kAxisY, yTitle);
  setAxisFont(kAxisX, axisFont);
  setAxisFont(kAxisY, axisFont);
  if (info.abscissaScale == AxisScale::logarithmic) {
    setAxisScaleEngine(kAxisX, new QwtLogScaleEngine);
    setAxisScaleDraw(kAxisX, new LogScaleDraw);
  }
  if (logY()) {
    setAxisScaleEngine(kAxisY, new QwtLogScaleEngine);
    setAxisScaleDraw(kAxisY, new LogScaleDraw);
  }

  auto* grid = new QwtPlotGrid;
  grid->enableXMin(true);
  grid->setMajorPen(QPen(QColor(200, 200, 200), 0, Qt::SolidLine));
  grid->setMinorPen(QPen(QColor(235, 235, 235), 0, Qt::DotLine));
  grid->attach(this);

  band_ = new QwtPlotIntervalCurve(tr("±1σ over subsets"));
  band_->setStyle(QwtPlotIntervalCurve::Tube);
  band_->setPen(QPen(Qt::NoPen));
  band_->setBrush(QBrush(kBandColor));
  band_->setRenderHint(QwtPlotItem::RenderAntialiased);
  band_->setItemAttribute(QwtPlotItem::AutoScale, false);  // ranges follow the data, not its error
  band_->attach(this);

  curve_ = new QwtPlotCurve(tr("data"));
  curve_->setPen(QPen(kDataColor, 1.6));
  curve_->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(kDataColor), QPen(kDataColor), QSize(3, 3)));
  curve_->setRenderHint(QwtPlotItem::RenderAntialiased);
  curve_->setItemAttribute(QwtPlotItem::AutoScale, true);
  curve_->attach(this);

  auto* legend = new QwtPlotLegendItem;
  // Where the curve leaves room: f, P, C fall (top right is empty), S and D_t rise (bottom right is).
  const Qt::Alignment corner = statistic == Statistic::S || statistic == Statistic::Dt ? Qt::AlignBottom | Qt::AlignRight
                               : statistic == Statistic::localExponent ? Qt::AlignTop | Qt::AlignLeft
                                                                       : Qt::AlignTop | Qt::AlignRight;
#if QWT_VERSION >= 0x060200
  legend->setAlignmentInCanvas(corner);
#else
  legend->setAlignment(corner);
#endif
  legend->setMaxColumns(1);
  legend->setBackgroundMode(QwtPlotLegendItem::LegendBackground);
  legend->setBackgroundBrush(QColor(255, 255, 255, 220));
  legend->setBorderPen(QPen(QColor(180, 180, 180)));
  legend->setBorderRadius(3);
  legend->setMargin(2);
  legend->setSpacing(2);
  legend->setItemMargin(1);
  QFont legendFont = font();
  legendFont.setPointSizeF(legendFont.pointSizeF() * 0.85);
  legend->setFont(legendFont);
  legend->attach(this);

  zoomer_ = new Zoomer(canvas());
  auto* panner = new QwtPlotPanner(canvas());
  panner->setMouseButton(Qt::MiddleButton);
  auto* magnifier = new QwtPlotMagnifier(canvas());
  magnifier->setMouseButton(Qt::NoButton);  // the wheel only; the right button belongs to the zoomer
  new CrosshairPicker(canvas());

  setMinimumSize(260, 200);
}

StatisticsPlot::~StatisticsPlot() = default;

QString StatisticsPlot::fileName() const { return fromTable(statisticInfo(statistic_).fileStem); }
QString StatisticsPlot::displayName() const {
  const StatisticInfo& info = statisticInfo(statistic_);
  return fromTable(info.symbol) + QStringLiteral(": ") + fromTable(info.description);
}

bool StatisticsPlot::logY() const noexcept {
  return statisticInfo(statistic_).valueScale == AxisScale::logarithmic;
}

void StatisticsPlot::setData(const Series& data, const std::vector<TheoryCurve>& theory) {
  data_ = data;
  theory_.clear();
  for (const TheoryCurve& t : theory)
    if (t.statistic == statistic_) theory_.push_back(t);

  const bool ly = logY();
  QVector<QPointF> points;
  QVector<QwtIntervalSample> band;
  points.reserve(static_cast<int>(data.x.size()));
  for (std::size_t i = 0; i < data.x.size() && i < data.value.size(); ++i) {
    const double x = data.x[i], y = data.value[i];
    if (!usable(x, y, ly)) continue;
    points.append(QPointF(x, y));
    const double e = i < data.error.size() && std::isfinite(data.error[i]) ? std::abs(data.error[i]) : 0;
    double lo = y - e;
    // A band that reaches zero cannot be drawn on a log axis: clip it a decade below the point.
    if (ly && lo <= 0) lo = y / 10;
    band.append(QwtIntervalSample(x, lo, y + e));
  }
  curve_->setSamples(points);
  band_->setSamples(band);

  // Theory items are few and change rarely in count: rebuild them.
  for (QwtPlotCurve* c : theoryCurves_) { c->detach(); delete c; }
  for (QwtPlotMarker* m : theoryMarkers_) { m->detach(); delete m; }
  theoryCurves_.clear();
  theoryMarkers_.clear();
  int colorIndex = 0;
  for (const TheoryCurve& t : theory_) {
    const QColor color = kTheoryColors[colorIndex++ % 3];
    const QwtText legend(QString::fromStdString(t.labelRich.empty() ? t.label : t.labelRich), QwtText::RichText);
    if (t.kind == TheoryCurve::Kind::verticalLine) {
      auto* marker = new QwtPlotMarker(legend);
      marker->setLineStyle(QwtPlotMarker::VLine);
      marker->setLinePen(QPen(color, 1.4, Qt::DashDotLine));
      marker->setXValue(t.at);
      QwtText label(legend);
      label.setColor(color);
      marker->setLabel(label);
      marker->setLabelAlignment(Qt::AlignLeft | Qt::AlignBottom);
      marker->setItemAttribute(QwtPlotItem::Legend, true);
      marker->setItemAttribute(QwtPlotItem::AutoScale, false);
      marker->attach(this);
      theoryMarkers_.push_back(marker);
      continue;
    }
    QVector<QPointF> tp;
    for (std::size_t i = 0; i < t.curve.x.size() && i < t.curve.value.size(); ++i)
      if (usable(t.curve.x[i], t.curve.value[i], ly)) tp.append(QPointF(t.curve.x[i], t.curve.value[i]));
    auto* c = new QwtPlotCurve(legend);
    c->setPen(QPen(color, 1.8, Qt::DashLine));
    c->setRenderHint(QwtPlotItem::RenderAntialiased);
    c->setItemAttribute(QwtPlotItem::AutoScale, false);  // theory never moves the ranges of the data
    c->setSamples(tp);
    c->attach(this);
    theoryCurves_.push_back(c);
  }
  if (statistic_ == Statistic::P) addReferenceSlopes(*this, data, ly, theoryCurves_);  // rebuilt with the theory
}

void StatisticsPlot::clearData() { setData(Series{}, {}); }

QVector<QPointF> StatisticsPlot::plottedPoints() const {
  QVector<QPointF> points;
  const QwtSeriesData<QPointF>* d = curve_->data();
  for (size_t i = 0; i < d->size(); ++i) points.append(d->sample(i));
  return points;
}

bool StatisticsPlot::followingData() const {
  if (forceFollow_) return true;
  if (zoomer_->zoomRectIndex() != 0) return false;
  // Panning and the wheel change the scales without the zoom stack: any range other than the last
  // automatic one is the user's.
  return axisInterval(kAxisX) == autoX_ && axisInterval(kAxisY) == autoY_;
}

void StatisticsPlot::refresh() {
  const bool follow = followingData();
  if (follow && curve_->dataSize() > 0) {
    setAxisAutoScale(kAxisX, true);
    // The local exponent is noisy where C_τ has few segments left (its last points reach 10 or more); the
    // paper's fig. 5d shows 0 … 2, so the default range is 0 … 3 (zoom out to see the tail).
    if (statistic_ == Statistic::localExponent) setAxisScale(kAxisY, 0.0, 3.0);
    else setAxisAutoScale(kAxisY, true);
  }
  replot();
  if (follow && curve_->dataSize() > 0) {
    zoomer_->setZoomBase(false);
    autoX_ = axisInterval(kAxisX);
    autoY_ = axisInterval(kAxisY);
    forceFollow_ = false;
  }
}

void StatisticsPlot::resetZoom() {
  forceFollow_ = true;
  refresh();
}

std::optional<QRectF> StatisticsPlot::userView() const {
  if (followingData()) return std::nullopt;
  const QwtInterval x = axisInterval(kAxisX), y = axisInterval(kAxisY);
  return QRectF(x.minValue(), y.minValue(), x.width(), y.width());
}

void StatisticsPlot::setUserView(const QRectF& view) {
  forceFollow_ = false;
  setAxisAutoScale(kAxisX, false);
  setAxisAutoScale(kAxisY, false);
  setAxisScale(kAxisX, view.left(), view.right());
  setAxisScale(kAxisY, view.top(), view.bottom());
  replot();
  zoomer_->setZoomBase(false);
}

bool StatisticsPlot::exportImage(const QString& path, QString* error) {
  const QString format = QFileInfo(path).suffix().toLower();
  if (format != QLatin1String("png") && format != QLatin1String("svg") && format != QLatin1String("pdf")) {
    if (error) *error = tr("unknown image format \"%1\" (use .png, .svg or .pdf)").arg(format);
    return false;
  }
  QFile::remove(path);
  QwtPlotRenderer renderer;
  renderer.setDiscardFlag(QwtPlotRenderer::DiscardBackground, false);
  renderer.setDiscardFlag(QwtPlotRenderer::DiscardCanvasFrame, false);
  // 160 × 110 mm at 150 dpi: a journal column, and about 950 × 650 pixels for PNG.
  renderer.renderDocument(this, path, format, QSizeF(160, 110), 150);
  if (!QFileInfo(path).exists() || QFileInfo(path).size() == 0) {
    if (error) *error = tr("could not write %1").arg(path);
    return false;
  }
  return true;
}

void StatisticsPlot::contextMenuEvent(QContextMenuEvent* event) {
  // The canvas uses the right button for the zoomer; the menu opens over the axes and title.
  QMenu menu(this);
  menu.addAction(tr("Reset zoom"), this, &StatisticsPlot::resetZoom);
  menu.exec(event->globalPos());
}

}  // namespace archipelago::ui
