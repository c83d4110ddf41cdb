#include "ui/scan/TailScanPlots.hpp"

#include <QBrush>
#include <QPen>
#include <QSplitter>
#include <QVBoxLayout>
#include <qwt_interval_symbol.h>
#include <qwt_legend.h>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_intervalcurve.h>
#include <qwt_plot_marker.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_symbol.h>
#include <qwt_text.h>

#include <cmath>
#include <initializer_list>

#include "ui/plots/QwtCompat.hpp"
#include "ui/scan/ScanPlotParts.hpp"

namespace archipelago::ui {

namespace {

/// Before anything is shown: 10 to 10⁸ steps, K over the 0.05 … 0.25, γ over the colour scale.
constexpr std::array<double, 4> kEmptyMap = {0.05, 0.25, 10, 1e8};

/// The reference lines' colours, in the order of tailScanReferenceExponents().
const QColor kReferenceColours[] = {QColor(0, 120, 60), QColor(120, 40, 160)};

QwtPlotCurve* addCurve(QwtPlot* plot, const QString& title, const QVector<QPointF>& points) {
  auto* curve = new QwtPlotCurve(title);
  curve->setSamples(points);
  curve->attach(plot);
  return curve;
}

}  // namespace

TailScanPlots::TailScanPlots(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("tailScanPlots"));
  // γ(t, K): K across, log t upwards (as tail-scan's PREFIX_gamma.png), the colour bar on the right.
  mapPlot_ = makePlot(this, tr("K"), tr("t (steps)"), false, true);
  mapPlot_->setObjectName(QStringLiteral("tailGammaMap"));
  mapPlot_->setTitle(tr("tail scan: γ = −d ln P_t / d ln t over K and t"));
  mapPlot_->setFooter(tr("each row a window [t/√10, t·√10] about its centre t; grey: the K does not reach it (no "
                         "reliable level at or below its start and one at or above its end); colours stop at 0 and %1")
                          .arg(kTailGammaTop));
  map_ = addHeatMap(mapPlot_, tr("γ"), tr("γ"), QStringLiteral("t"), kTailGammaTop);

  windowsPlot_ = makePlot(this, tr("t (steps): the window's centre"), tr("γ = −d ln P_t / d ln t"), true, false);
  windowsPlot_->setObjectName(QStringLiteral("tailGammaWindows"));
  windowsPlot_->setTitle(tr("γ per window, one point per K, against the literature's exponents"));
  windowsPlot_->insertLegend(new QwtLegend, QwtPlot::BottomLegend);
  for (QWidget* w : std::initializer_list<QWidget*>{mapPlot_, windowsPlot_}) w->setMinimumSize(320, 180);

  auto* splitter = new QSplitter(Qt::Vertical, this);
  splitter->addWidget(mapPlot_);
  splitter->addWidget(windowsPlot_);
  splitter->setSizes({900, 1100});  // whatever the plots' size hints (the legend, the footers)
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(splitter);
}

QwtPlot* TailScanPlots::plot(const QString& name) const {
  for (QwtPlot* plot : {mapPlot_, windowsPlot_})
    if (plot->objectName() == name) return plot;
  return nullptr;
}

double TailScanPlots::heatMapValue(double K, double t) const { return map_->data()->value(K, t); }

void TailScanPlots::clear() {
  removeCurves();
  showHeatMap(mapPlot_, map_, ScanHeatMap{}, kEmptyMap);
  windowsPlot_->setFooter(QString());
  windowsPlot_->setAxisScale(kAxisX, kEmptyMap[2], kEmptyMap[3]);
  windowsPlot_->setAxisScale(kAxisY, 0, kTailGammaTop);
  windowsPlot_->replot();
}

void TailScanPlots::showSummary(const TailScanSummary& s) {
  removeCurves();
  showHeatMap(mapPlot_, map_, tailGammaHeatMap(s), kEmptyMap);
  addKPoints(s);
  addAverage(s);
  addReferences(s);
  windowsPlot_->setFooter(
      s.windows.empty()
          ? tr("no window: the levels span less than a decade from max(the first level, 10, 2q)")
          : tr("one point per K and window, coloured from blue (K = %1) to red (K = %2); black: the K-average, its "
               "bars the spread over K")
                .arg(kText(s.K.front()), kText(s.K.back())));
  windowsPlot_->setAxisAutoScale(kAxisX, true);
  windowsPlot_->setAxisAutoScale(kAxisY, true);
  windowsPlot_->replot();
}

void TailScanPlots::removeCurves() {
  windowsPlot_->detachItems(QwtPlotItem::Rtti_PlotCurve, true);
  windowsPlot_->detachItems(QwtPlotItem::Rtti_PlotIntervalCurve, true);
  windowsPlot_->detachItems(QwtPlotItem::Rtti_PlotMarker, true);
}

void TailScanPlots::addKPoints(const TailScanSummary& s) {
  for (std::size_t k = 0; k < s.K.size(); ++k) {
    QVector<QPointF> points;
    for (const TailExponent& e : s.gamma[k])
      if (std::isfinite(e.gamma)) points.append(QPointF(e.t, e.gamma));
    const QColor colour = colourOf(k, s.K.size());
    QwtPlotCurve* curve = addCurve(windowsPlot_, QStringLiteral("K = %1").arg(kText(s.K[k])), points);
    curve->setStyle(QwtPlotCurve::NoCurve);
    curve->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, colour, colour, QSize(6, 6)));
    curve->setItemAttribute(QwtPlotItem::Legend, false);  // the footer says how K is coloured
  }
}

void TailScanPlots::addAverage(const TailScanSummary& s) {
  QVector<QPointF> mean;
  QVector<QwtIntervalSample> spread;
  for (const TailScanWindow& a : s.average) {
    if (!std::isfinite(a.mean)) continue;
    mean.append(QPointF(a.t, a.mean));
    if (std::isfinite(a.spread)) spread.append(QwtIntervalSample(a.t, a.mean - a.spread, a.mean + a.spread));
  }
  auto* bars = new QwtPlotIntervalCurve(tr("spread over K"));
  bars->setStyle(QwtPlotIntervalCurve::NoCurve);
  bars->setItemAttribute(QwtPlotItem::Legend, false);  // the footer says what the bars are
  bars->setSymbol(new QwtIntervalSymbol(QwtIntervalSymbol::Bar));
  bars->setSamples(spread);
  bars->attach(windowsPlot_);
  QwtPlotCurve* curve = addCurve(windowsPlot_, tr("K-average"), mean);
  curve->setPen(Qt::black, 1.5);
  curve->setSymbol(new QwtSymbol(QwtSymbol::Rect, QBrush(Qt::black), QPen(Qt::black), QSize(7, 7)));
}

void TailScanPlots::addReferences(const TailScanSummary& s) {
  if (s.windows.empty()) return;
  const double from = s.windows.front().from, to = s.windows.back().to;
  const std::vector<ReferenceExponent>& references = tailScanReferenceExponents();
  for (std::size_t i = 0; i < references.size(); ++i) {
    const ReferenceExponent& r = references[i];
    const QString gamma = QString::number(r.gamma, 'g', 3);
    QwtPlotCurve* line = addCurve(windowsPlot_, tr("%1: %2").arg(gamma, QString::fromUtf8(r.source)),
                                  {QPointF(from, r.gamma), QPointF(to, r.gamma)});
    line->setPen(kReferenceColours[i % 2], 1.5, Qt::DashLine);
    auto* label = new QwtPlotMarker;  // the line's value at its right end: the first (1.57) above, the next below
    label->setValue(to, r.gamma);
    QwtText text(gamma);
    text.setColor(kReferenceColours[i % 2]);
    label->setLabel(text);
    label->setLabelAlignment(Qt::AlignLeft | (i == 0 ? Qt::AlignTop : Qt::AlignBottom));
    label->attach(windowsPlot_);
  }
}

}  // namespace archipelago::ui
