#include "ui/plots/StatisticsPlot.hpp"

#include <QBrush>
#include <QBuffer>
#include <QContextMenuEvent>
#include <QFile>
#include <QFileInfo>
#include <QMenu>
#include <QImage>
#include <QPainter>
#include <QPdfWriter>
#include <QPen>
#include <QSvgGenerator>
#include <QTextDocument>
#include <qwt_interval_symbol.h>
#include <QLayout>
#include <qwt_legend.h>
#include <qwt_legend_label.h>
#include <qwt_plot_canvas.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_intervalcurve.h>
#include <qwt_plot_legenditem.h>
#include <qwt_plot_magnifier.h>
#include <qwt_plot_marker.h>
#include <qwt_plot_panner.h>
#include <qwt_plot_renderer.h>
#include <qwt_plot_textlabel.h>
#include <qwt_plot_zoneitem.h>
#include <qwt_plot_zoomer.h>
#include <qwt_scale_engine.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <algorithm>
#include <cmath>
#include <string_view>

#include "core/stats/ReferenceSlopes.hpp"
#include "core/stats/TailAnalysis.hpp"
#include "ui/plots/CrosshairPicker.hpp"
#include "ui/plots/LogScaleDraw.hpp"
#include "ui/plots/QwtCompat.hpp"
#include "ui/files/OutputFiles.hpp"

namespace archipelago::ui {

namespace {
const QColor kDataColor(31, 78, 154);
const QColor kBandColor(31, 78, 154, 55);
const QColor kEstimateColor(200, 70, 20);  // another method's estimate of the same statistic (setEstimate)
const QColor kModelColor(20, 140, 120);    // a model of the same statistic (setModel): the Markov tree's P_t
const QColor kTheoryColors[] = {QColor(214, 96, 18), QColor(160, 30, 60), QColor(40, 130, 60)};

QString fromTable(std::string_view text) {
  return QString::fromUtf8(text.data(), static_cast<int>(text.size()));
}

/// Rich text as plain Unicode text: <sub>t</sub> → ₜ where Unicode has the subscript (else "_τ"), <sup>−1</sup>
/// → ⁻¹, then the tags dropped (QTextDocument).  For file metadata (SVG and PDF titles), which hold no markup.
QString plainText(const QString& rich) {
  static const QString normal = QStringLiteral("0123456789+−-=()aehijklmnoprstuvx");
  static const QString sub = QStringLiteral("₀₁₂₃₄₅₆₇₈₉₊₋₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ");
  static const QString sup = QStringLiteral("⁰¹²³⁴⁵⁶⁷⁸⁹⁺⁻⁻⁼⁽⁾ᵃᵉʰⁱʲᵏˡᵐⁿᵒᵖʳˢᵗᵘᵛˣ");
  QString text = rich;
  for (const auto& [tag, table] : {std::pair{QStringLiteral("sub"), &sub}, std::pair{QStringLiteral("sup"), &sup}}) {
    const QString open = QLatin1Char('<') + tag + QLatin1Char('>'), close = QStringLiteral("</") + tag + QLatin1Char('>');
    for (qsizetype at = text.indexOf(open); at >= 0; at = text.indexOf(open, at)) {
      const qsizetype end = text.indexOf(close, at);
      if (end < 0) break;
      const QString inner = text.mid(at + open.size(), end - at - open.size());
      QString converted;
      bool all = true;
      for (const QChar c : inner) {
        const qsizetype i = normal.indexOf(c);
        if (i < 0) { all = false; break; }
        converted += table->at(i);
      }
      if (!all) converted = (tag == QLatin1String("sub") ? QStringLiteral("_") : QStringLiteral("^")) + inner;
      text.replace(at, end + close.size() - at, converted);
    }
  }
  QTextDocument document;
  document.setHtml(text);
  return document.toPlainText();
}

/// `base` with its point size times `factor`.
QFont scaledFont(const QFont& base, double factor) {
  QFont scaled = base;
  scaled.setPointSizeF(base.pointSizeF() * factor);
  return scaled;
}

bool usable(double x, double y, bool logY) {
  return std::isfinite(x) && std::isfinite(y) && x > 0 && (!logY || y > 0);
}

void setLegendCorner(QwtPlotLegendItem* legend, Qt::Alignment corner) {
#if QWT_VERSION >= 0x060200
  legend->setAlignmentInCanvas(corner);
#else
  legend->setAlignment(corner);
#endif
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
// The literature's tail slopes t^−γ on the P_t plot (issue #14, item 7): the lines, their anchor and exponents
// are core's (stats/ReferenceSlopes.hpp, referenceSlopes()); this draws them thin, each in its own colour and
// dash so that the legend tells them apart, and labels them as what they are: asymptotic values from the
// literature (issue 25, finding 6; the sources are in core's table and the CSV).
void addReferenceSlopes(QwtPlot& plot, const Series& P, bool logY, std::vector<QwtPlotCurve*>& items) {
  static const Qt::PenStyle kStyles[] = {Qt::DashLine, Qt::DashDotLine, Qt::DotLine, Qt::DashDotDotLine};
  static const QColor kColours[] = {QColor(140, 86, 75), QColor(148, 103, 189), QColor(23, 150, 170), QColor(110, 110, 110)};
  int index = 0;
  for (const ReferenceSlope& r : referenceSlopes(P)) {
    QVector<QPointF> points;
    for (std::size_t i = 0; i < r.line.x.size(); ++i)
      if (usable(r.line.x[i], r.line.value[i], logY)) points.append(QPointF(r.line.x[i], r.line.value[i]));
    auto* c = new QwtPlotCurve(QwtText(QObject::tr("t<sup>−%1</sup> asymptotic (literature)").arg(r.gamma), QwtText::RichText));
    c->setPen(QPen(kColours[index % 4], 1.4, kStyles[index % 4]));
    ++index;
    c->setRenderHint(QwtPlotItem::RenderAntialiased);
    c->setItemAttribute(QwtPlotItem::AutoScale, false);  // references never move the ranges of the data
    c->setLegendIconSize(QSize(22, 8));
    c->setSamples(points);
    c->attach(&plot);
    items.push_back(c);
  }
}

/// P_t's legend below the plot, its entries with room to spare: an entry measured to the pixel at the screen's
/// resolution needs a few pixels more when an export draws it at 150 dpi, and "t⁻¹·⁵ asymptotic (literature)" wrapped
/// onto two lines there, cut to its item's height, its exponent lost (issue 53, finding 4).
class RoomyLegend : public QwtLegend {
  class Label : public QwtLegendLabel {
   public:
    QSize sizeHint() const override {
      const QSize s = QwtLegendLabel::sizeHint();
      return {s.width() + s.width() / 16 + fontMetrics().averageCharWidth(), s.height()};
    }
  };

 protected:
  QWidget* createWidget(const QwtLegendData&) const override {
    auto* label = new Label;
    label->setItemMode(defaultItemMode());  // read-only (the default): no clicks to connect
    return label;
  }
};
}  // namespace

StatisticsPlot::StatisticsPlot(Statistic statistic, QWidget* parent) : QwtPlot(parent), statistic_(statistic) {
  const StatisticInfo& info = statisticInfo(statistic);
  setObjectName(QStringLiteral("plot_") + fromTable(info.fileStem));
  setAutoReplot(false);
  setUpTitleAndAxes(info);
  attachGridAndCurves();
  createLegend();
  createMouseTools();
  createPlaceholder();
  canvas()->installEventFilter(this);  // a double click enlarges
  setMinimumSize(200, 160);  // three columns and the parameter dock fit a 1024-pixel-wide window
}

void StatisticsPlot::setUpTitleAndAxes(const StatisticInfo& info) {
  QwtText title(fromTable(info.symbolRich), QwtText::RichText);
  QFont titleFont = scaledFont(font(), 1.1);
  titleFont.setBold(true);
  title.setFont(titleFont);
  setTitle(title);
  setCanvasBackground(Qt::white);
  if (auto* c = qobject_cast<QwtPlotCanvas*>(canvas())) c->setFrameStyle(static_cast<int>(QFrame::Box) | static_cast<int>(QFrame::Plain));

  const QFont axisFont = scaledFont(font(), 0.9);
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
}

void StatisticsPlot::attachGridAndCurves() {
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
}

void StatisticsPlot::createLegend() {
  legend_ = new QwtPlotLegendItem;
  auto* legend = legend_;
  // Where the curve leaves room: f, P, C fall from the top left (the bottom left is empty; the top right
  // holds the t_max label of K < 0), S and D_t rise (bottom right is empty).
  const Qt::Alignment corner = statistic_ == Statistic::S || statistic_ == Statistic::Dt ? Qt::AlignBottom | Qt::AlignRight
                               : statistic_ == Statistic::localExponent ? Qt::AlignTop | Qt::AlignLeft
                                                                        : Qt::AlignBottom | Qt::AlignLeft;
  setLegendCorner(legend, corner);
  legend->setMaxColumns(1);
  legend->setBackgroundMode(QwtPlotLegendItem::LegendBackground);
  legend->setBackgroundBrush(QColor(255, 255, 255, 220));
  legend->setBorderPen(QPen(QColor(180, 180, 180)));
  legend->setBorderRadius(3);
  legend->setMargin(2);
  legend->setSpacing(2);
  legend->setItemMargin(1);
  const QFont legendFont = scaledFont(font(), 0.8);
  legendPointSize_ = legendFont.pointSizeF();
  legend->setFont(legendFont);
  if (statistic_ == Statistic::P) {
    // P_t's legend is below the plot, in two columns (issue 37, finding 5): its seven entries (the data, four
    // reference slopes, theory, a tail estimate) covered the 10⁴–10⁷ tail, the slopes and the estimate's levels
    // in any corner of a plot a few hundred pixels wide, and the estimate's entry was cut off.
    insertLegendBelow(legendFont);
  } else {
    legend->attach(this);
  }
}

void StatisticsPlot::insertLegendBelow(const QFont& legendFont) {
  auto* below = new RoomyLegend;
  below->setMaxColumns(2);
  below->setFont(scaledFont(legendFont, 0.88));  // two columns in a plot 330 pixels wide
  if (QLayout* rows = below->contentsWidget()->layout()) rows->setSpacing(0);
  // Up to 0.7 of the plot's height (Qwt's default is a third), taken only when needed: at Qt 5's 12-point font
  // the seven entries of a plot 260 pixels high took more rows than a third or a half of it holds, and the last
  // were clipped (gui.issue37 under Qt 5).
  insertLegend(below, QwtPlot::BottomLegend, 0.7);
  // After insertLegend(), which makes a legend below the plot as many columns as fit (Qwt sets maxColumns 0):
  // the export's 945 pixels then took three, too narrow for "t⁻¹·³⁷ asymptotic (literature)", which wrapped and lost
  // its exponent (issue 53, finding 4).
  below->setMaxColumns(2);
  below->setVisible(false);  // until there is data (showPlaceholder)
}

void StatisticsPlot::createMouseTools() {
  zoomer_ = new Zoomer(canvas());
  auto* panner = new QwtPlotPanner(canvas());
  panner->setMouseButton(Qt::MiddleButton);
  auto* magnifier = new QwtPlotMagnifier(canvas());
  magnifier->setMouseButton(Qt::NoButton);  // the wheel only; the right button belongs to the zoomer
  crosshair_ = new CrosshairPicker(canvas());
}

void StatisticsPlot::createPlaceholder() {
  // Before a run: a placeholder in the canvas, fixed sensible axes, no legend and no crosshair (an empty plot
  // with a legend and a readout looked like a broken one).
  QwtText hint(tr("No run yet — press Run (F5)"));
  hint.setFont(scaledFont(font(), 1.05));
  hint.setColor(QColor(110, 110, 110));
  hint.setRenderFlags(Qt::AlignCenter);
  placeholder_ = new QwtPlotTextLabel;
  placeholder_->setText(hint);
  placeholder_->attach(this);
  showPlaceholder(true);
}

StatisticsPlot::~StatisticsPlot() {
  if (!legend_->plot()) delete legend_;  // P_t's, never attached (its legend is below the plot)
  if (model_ && !model_->plot()) delete model_;  // removed (an attached one is the plot's)
}

QString StatisticsPlot::fileName() const { return fromTable(statisticInfo(statistic_).fileStem); }
QString StatisticsPlot::displayName() const {
  const StatisticInfo& info = statisticInfo(statistic_);
  return fromTable(info.symbol) + QStringLiteral(": ") + fromTable(info.description);
}

bool StatisticsPlot::logY() const noexcept {
  return statisticInfo(statistic_).valueScale == AxisScale::logarithmic;
}

void StatisticsPlot::setBlockAffectedBelow(double steps) {
  blockAffectedBelow_ = std::isfinite(steps) && steps > 0 ? steps : 0;
  if (blockAffectedBelow_ == 0) {
    if (blockZone_) blockZone_->detach();
    return;
  }
  if (!blockZone_) {
    blockZone_ = new QwtPlotZoneItem();
    blockZone_->setOrientation(Qt::Vertical);  // between two values of t
    blockZone_->setBrush(QColor(120, 120, 120, 40));
    blockZone_->setPen(QPen(QColor(120, 120, 120, 140), 1, Qt::DotLine));
    blockZone_->setTitle(tr("t < 10 q: blocks of q steps (no q = 1 companion)"));
    blockZone_->setItemAttribute(QwtPlotItem::Legend, true);
    blockZone_->setItemAttribute(QwtPlotItem::AutoScale, false);
    blockZone_->setZ(curve_->z() - 2);
  }
  // From far left of any axis (log axes start at t ≥ 1) to the bound.
  blockZone_->setInterval(1e-6, blockAffectedBelow_);
  if (!blockZone_->plot()) blockZone_->attach(this);
}

void StatisticsPlot::setEstimate(const Series& estimate, const QString& title) {
  const bool ly = logY();
  QVector<QPointF> points;
  QVector<QwtIntervalSample> bars;
  for (std::size_t i = 0; i < estimate.x.size() && i < estimate.value.size(); ++i) {
    const double x = estimate.x[i], y = estimate.value[i];
    if (!usable(x, y, ly)) continue;
    points.append(QPointF(x, y));
    const double e = i < estimate.error.size() && std::isfinite(estimate.error[i]) ? std::abs(estimate.error[i]) : 0;
    bars.append(QwtIntervalSample(x, ly && y - e <= 0 ? y / 10 : y - e, y + e));
  }
  if (points.isEmpty()) {
    if (estimate_) estimate_->detach();
    if (estimateBars_) estimateBars_->detach();
    return;
  }
  if (!estimate_) {
    estimateBars_ = new QwtPlotIntervalCurve();
    estimateBars_->setStyle(QwtPlotIntervalCurve::NoCurve);
    auto* bar = new QwtIntervalSymbol(QwtIntervalSymbol::Bar);
    bar->setWidth(5);
    bar->setPen(QPen(kEstimateColor, 1.2));
    estimateBars_->setSymbol(bar);
    estimateBars_->setItemAttribute(QwtPlotItem::Legend, false);
    estimateBars_->setItemAttribute(QwtPlotItem::AutoScale, false);
    estimate_ = new QwtPlotCurve();
    estimate_->setPen(QPen(kEstimateColor, 1.2, Qt::DashLine));
    estimate_->setSymbol(new QwtSymbol(QwtSymbol::Diamond, QBrush(Qt::white), QPen(kEstimateColor, 1.4), QSize(7, 7)));
    estimate_->setRenderHint(QwtPlotItem::RenderAntialiased);
    estimate_->setItemAttribute(QwtPlotItem::AutoScale, true);  // beyond the run's data: the ranges follow it
    estimate_->setLegendAttribute(QwtPlotCurve::LegendShowSymbol, true);
  }
  estimate_->setTitle(title);
  estimate_->setSamples(points);
  estimateBars_->setSamples(bars);
  if (!estimate_->plot()) {
    estimateBars_->attach(this);
    estimate_->attach(this);
  }
}

QVector<QPointF> StatisticsPlot::estimatePoints() const {
  QVector<QPointF> points;
  if (estimate_ && estimate_->plot())
    for (size_t i = 0; i < estimate_->dataSize(); ++i) points.append(estimate_->sample(static_cast<int>(i)));
  return points;
}

void StatisticsPlot::setModel(const Series& model, const QString& title) {
  const bool ly = logY();
  QVector<QPointF> points;
  for (std::size_t i = 0; i < model.x.size() && i < model.value.size(); ++i)
    if (usable(model.x[i], model.value[i], ly)) points.append(QPointF(model.x[i], model.value[i]));
  if (points.isEmpty()) {
    if (model_) model_->detach();
    return;
  }
  if (!model_) {
    model_ = new QwtPlotCurve();
    model_->setPen(QPen(kModelColor, 2.0, Qt::SolidLine));
    model_->setRenderHint(QwtPlotItem::RenderAntialiased);
    model_->setItemAttribute(QwtPlotItem::AutoScale, false);
    model_->setZ(curve_->z() + 1);
  }
  model_->setTitle(title);
  model_->setSamples(points);
  if (!model_->plot()) model_->attach(this);
}

QVector<QPointF> StatisticsPlot::modelPoints() const {
  QVector<QPointF> points;
  if (model_ && model_->plot())
    for (size_t i = 0; i < model_->dataSize(); ++i) points.append(model_->sample(static_cast<int>(i)));
  return points;
}

QString StatisticsPlot::modelTitle() const { return model_ && model_->plot() ? model_->title().text() : QString(); }

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
      // The label stands left of its line, at the top where the falling curves leave room, on a white
      // ground so that neither the line nor the grid cuts through it.
      QwtText label(legend);
      label.setColor(color);
      label.setBackgroundBrush(QColor(255, 255, 255, 225));
      label.setBorderRadius(2);
      marker->setLabel(label);
      marker->setLabelAlignment(Qt::AlignLeft | Qt::AlignTop);
      marker->setSpacing(6);
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

void StatisticsPlot::clearData() {
  // Another run's data follows: the user's zoom of this one does not apply to it, and the placeholder's fixed
  // axes (showPlaceholder) must not pass for a zoom (issue 37, finding 1: the Run page's f_t and C_τ kept
  // t 1…10⁴ after File ▸ Open or F5).
  forceFollow_ = true;
  setData(Series{}, {});
  setBlockAffectedBelow(0);
  setEstimate(Series{}, QString());
  setModel(Series{}, QString());
}

bool StatisticsPlot::isEmpty() const { return curve_->dataSize() == 0; }

bool StatisticsPlot::placeholderShown() const { return placeholder_->isVisible(); }

bool StatisticsPlot::legendShown() const { return legend() ? legend()->isVisibleTo(this) : legend_->isVisible(); }

bool StatisticsPlot::crosshairEnabled() const { return crosshair_->isEnabled(); }

void StatisticsPlot::showPlaceholder(bool empty) {
  placeholder_->setVisible(empty);
  legend_->setVisible(!empty);
  if (legend()) {
    legend()->setVisible(!empty);
    updateLayout();
  }
  crosshair_->setEnabled(!empty);
  if (!empty) return;
  // Axes of a typical run: t from 1 to 10⁴ steps; falling statistics from 10⁻⁶ to 1, rising ones (S_t, D_t)
  // from 1 to 10⁶; the local exponent from 0 to 3.
  setAxisScale(kAxisX, statisticInfo(statistic_).abscissaScale == AxisScale::logarithmic ? 1.0 : 0.0, 1e4);
  if (statistic_ == Statistic::localExponent) setAxisScale(kAxisY, 0.0, 3.0);
  else if (statistic_ == Statistic::S || statistic_ == Statistic::Dt) setAxisScale(kAxisY, 1.0, 1e6);
  else if (logY()) setAxisScale(kAxisY, 1e-6, 1.0);
  else setAxisScale(kAxisY, 0.0, 1.0);
}

QwtInterval StatisticsPlot::exponentRange() const {
  // The range of interest is the paper's 0 … 2 (fig. 5d: the exponent of C_τ's slow decay, ¼ … 3/2), whatever
  // the few noisy points at the end of the tail reach (they once set 0 … 16, issue 25, finding 7).  Only when
  // most of the well-measured points (error ≤ 0.5) lie above 2 — K = 0's τ⁻⁵ regime — does the range follow
  // them, to their 90th percentile.  Reset Zoom (Ctrl+0) comes back here after a zoom.
  std::vector<double> measured;
  double lo = 0;
  for (std::size_t i = 0; i < data_.x.size() && i < data_.value.size(); ++i) {
    const double v = data_.value[i];
    const double e = i < data_.error.size() ? std::abs(data_.error[i]) : 0;
    if (!std::isfinite(v) || !(data_.x[i] > 0) || !(e <= 0.5)) continue;
    measured.push_back(v);
    lo = std::min(lo, v);
  }
  if (measured.empty()) return QwtInterval(0, 2);
  std::sort(measured.begin(), measured.end());
  const double median = measured[measured.size() / 2];
  double hi = 2;
  if (median > 2) hi = 1.15 * measured[std::min(measured.size() - 1, measured.size() * 9 / 10)];
  return QwtInterval(lo < 0 ? std::max(lo, -1.0) - 0.1 : 0, hi);
}

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

std::vector<const QwtPlotCurve*> StatisticsPlot::referenceCurves() const {
  std::vector<const QwtPlotCurve*> curves;
  for (const QwtPlotCurve* c : theoryCurves_)
    if (c->title().text().contains(QStringLiteral("asymptotic (literature)"))) curves.push_back(c);
  return curves;
}

QRectF StatisticsPlot::legendRect() const {
  return legend_->isVisible() && legend_->plot() ? legend_->geometry(canvas()->contentsRect()) : QRectF();
}

void StatisticsPlot::fitLegend() {
  // The legend stays inside the frame (issue 25, finding 6): a smaller font while it does not fit, down to 6 pt.
  QFont f = legend_->font();
  f.setPointSizeF(legendPointSize_);
  legend_->setFont(f);
  const QRectF frame = canvas()->contentsRect();
  while (legend_->font().pointSizeF() > 6.0) {
    const QRectF r = legend_->geometry(frame);
    if (frame.contains(r)) break;
    QFont smaller = legend_->font();
    smaller.setPointSizeF(smaller.pointSizeF() - 0.5);
    legend_->setFont(smaller);
  }
}

void StatisticsPlot::resizeEvent(QResizeEvent* event) {
  QwtPlot::resizeEvent(event);
  fitLegend();
}

void StatisticsPlot::refresh() {
  const bool empty = isEmpty();
  if (empty != placeholderShown()) showPlaceholder(empty);
  const bool follow = followingData();
  if (follow && !empty) {
    // x: the data and every vertical theory line (t_max may lie beyond the last data point: its line and
    // label stay on the canvas).
    const QRectF box = curve_->boundingRect();
    double xHigh = box.right();
    for (const QwtPlotMarker* m : theoryMarkers_) xHigh = std::max(xHigh, m->xValue() * 1.25);
    if (xHigh > box.right()) setAxisScale(kAxisX, box.left(), xHigh);
    else setAxisAutoScale(kAxisX, true);
    if (statistic_ == Statistic::localExponent) {
      const QwtInterval y = exponentRange();
      setAxisScale(kAxisY, y.minValue(), y.maxValue());
    } else {
      setAxisAutoScale(kAxisY, true);
    }
  }
  fitLegend();
  replot();
  if (follow && !empty) {
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

QString StatisticsPlot::plainTitle() const {
  const StatisticInfo& info = statisticInfo(statistic_);
  return plainText(fromTable(info.symbolRich)) + QStringLiteral(" — ") + fromTable(info.description);
}

bool StatisticsPlot::exportImage(const QString& path, QString* error, const Provenance& provenance,
                                 const QString& footnote) {
  const QString format = QFileInfo(path).suffix().toLower();
  if (format != QLatin1String("png") && format != QLatin1String("svg") && format != QLatin1String("pdf")) {
    if (error) *error = tr("unknown image format \"%1\" (use .png, .svg or .pdf)").arg(format);
    return false;
  }
  QwtPlotRenderer renderer;
  renderer.setDiscardFlag(QwtPlotRenderer::DiscardBackground, false);
  renderer.setDiscardFlag(QwtPlotRenderer::DiscardCanvasFrame, false);
  // 160 × 110 mm at 150 dpi: a journal column, and about 950 × 650 pixels for PNG.  QwtPlotRenderer's
  // renderDocument() would put the title's markup ("f<sub>t</sub>") into the SVG and PDF metadata, so the
  // documents are set up here with a plain Unicode title and the plot is rendered into them.  Each is rendered
  // in memory, checked and published atomically (ui/files/OutputFiles.hpp): never a truncated file.
  const QSizeF sizeMm(160, 110);
  constexpr int dpi = 150;
  const double mmToInch = 1.0 / 25.4;
  const QRectF rect(0, 0, sizeMm.width() * mmToInch * dpi, sizeMm.height() * mmToInch * dpi);
  const QString title = plainTitle();
  // The plot above a strip holding the footnote (the run's parameters), when there is one.
  const auto render = [&](QPainter& painter) {
    if (footnote.isEmpty()) {
      renderer.render(this, &painter, rect);
      return;
    }
    QFont font = painter.font();
    font.setPixelSize(qRound(rect.height() / 45));
    const qreal strip = 1.8 * font.pixelSize();
    renderer.render(this, &painter, rect.adjusted(0, 0, 0, -strip));
    painter.setFont(font);
    painter.setPen(Qt::black);
    painter.drawText(QRectF(rect.left(), rect.bottom() - strip, rect.width(), strip),
                     Qt::AlignHCenter | Qt::AlignVCenter | Qt::TextSingleLine, footnote);
  };
  if (format == QLatin1String("png")) {
    QImage image(rect.size().toSize(), QImage::Format_ARGB32);
    image.setDotsPerMeterX(qRound(dpi / 0.0254));
    image.setDotsPerMeterY(qRound(dpi / 0.0254));
    image.fill(Qt::white);
    image.setText(QStringLiteral("Title"), title);
    image.setText(QStringLiteral("Software"), QStringLiteral("Archipelago"));
    for (const auto& [key, value] : provenance.fields) image.setText(QString::fromStdString(key), QString::fromStdString(value));
    {
      QPainter painter(&image);
      render(painter);
    }
    return writePngFile(image, path, error);
  }
  QByteArray bytes;
  QBuffer buffer(&bytes);
  buffer.open(QIODevice::WriteOnly);
  bool ok = true;
  if (format == QLatin1String("svg")) {
    QSvgGenerator generator;
    generator.setTitle(title);
    generator.setDescription(tr("Archipelago: %1").arg(title));
    generator.setOutputDevice(&buffer);
    generator.setResolution(dpi);
    generator.setSize(rect.size().toSize());
    generator.setViewBox(rect);
    QPainter painter(&generator);
    render(painter);
    ok = painter.end() && isCompleteSvg(bytes);
  } else {
    {
      QPdfWriter writer(&buffer);
      writer.setTitle(title);
      writer.setCreator(QStringLiteral("Archipelago"));
      writer.setPageSize(QPageSize(sizeMm, QPageSize::Millimeter));
      writer.setPageMargins(QMarginsF(0, 0, 0, 0));
      writer.setResolution(dpi);
      QPainter painter(&writer);
      render(painter);
      ok = painter.end();
    }  // the writer finishes the document when it is destroyed
    ok = ok && isCompletePdf(bytes);
  }
  if (!ok) {
    if (error) *error = tr("could not render %1").arg(path);
    return false;
  }
  return publishBytes(bytes, path, error);
}

QMenu* StatisticsPlot::createContextMenu(QWidget* parent) {
  auto* menu = new QMenu(parent);
  menu->addAction(tr("Reset zoom"), this, &StatisticsPlot::resetZoom);
  menu->addAction(enlarged_ ? tr("Show All Plots (Esc)") : tr("Enlarge (double-click)"), this,
                  &StatisticsPlot::enlargeToggled);
  menu->addAction(tr("Export…"), this, &StatisticsPlot::exportRequested);
  return menu;
}

void StatisticsPlot::contextMenuEvent(QContextMenuEvent* event) {
  // The canvas uses the right button for the zoomer; the menu opens over the axes and title.
  QMenu* menu = createContextMenu(this);
  menu->exec(event->globalPos());
  delete menu;
}

bool StatisticsPlot::eventFilter(QObject* watched, QEvent* event) {
  if (watched == canvas() && event->type() == QEvent::MouseButtonDblClick) {
    Q_EMIT enlargeToggled();
    return true;
  }
  return QwtPlot::eventFilter(watched, event);
}

}  // namespace archipelago::ui
