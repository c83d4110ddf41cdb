#include "ui/scan/KScanPlots.hpp"

#include <QHeaderView>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <qwt_interval_symbol.h>
#include <qwt_legend.h>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_intervalcurve.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_symbol.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <utility>

#include "core/scan/ScanBox.hpp"
#include "core/scan/ScanHeatMap.hpp"
#include "ui/plots/QwtCompat.hpp"
#include "ui/scan/ScanPlotParts.hpp"

namespace archipelago::ui {

QColor KScanPlots::heatMapColour(double exponent) { return heatMapQColour(exponent, kHeatMapTop); }

KScanPlots::KScanPlots(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("kScanPlots"));
  ftPlot_ = makePlot(this, tr("t (steps)"), tr("f_t"), true, true);
  ftPlot_->setTitle(tr("f_t, one curve per K"));
  ftPlot_->insertLegend(new QwtLegend, QwtPlot::RightLegend);
  dPlot_ = makePlot(this, tr("K"), tr("D ± 1σ (bootstrap)"), false, true);
  dPlot_->setTitle(tr("D against K (error: bootstrap over segments)"));
  exponentPlot_ = makePlot(this, tr("τ (steps)"), tr("−d log C_τ / d log τ"), true, false);
  exponentPlot_->setTitle(tr("local exponent of C_τ, one curve per K"));

  // The heat map: K across, log τ upwards (as the CLI's scan_local_exponent.png), the colour bar on the right.
  heatMapPlot_ = makePlot(this, tr("K"), tr("τ (steps)"), false, true);
  heatMapPlot_->setTitle(tr("local exponent −d log C_τ / d log τ over K and τ"));
  heatMapPlot_->setFooter(tr("grey: no data (C_τ = 0, or τ beyond that K's run); colours stop at 0 and %1")
                              .arg(kHeatMapTop));
  heatMap_ = addHeatMap(heatMapPlot_, tr("local exponent"), tr("−d log C_τ / d log τ"), QStringLiteral("τ"),
                        kHeatMapTop);

  // The long segments: the longest (log, left) and the fraction of the steps in segments ≥ 10⁴ (right).
  longPlot_ = makePlot(this, tr("K"), tr("longest segment (steps)"), false, true);
  longPlot_->setTitle(tr("the longest segment and the steps in segments ≥ 10⁴ against K"));
  longPlot_->enableAxis(kAxisYRight);
  longPlot_->setAxisTitle(kAxisYRight, tr("steps in segments ≥ 10⁴ (fraction)"));
  longPlot_->insertLegend(new QwtLegend, QwtPlot::BottomLegend);

  // b₂ against K: the area (left) and the fraction of the box (right).
  b2Plot_ = makePlot(this, tr("K"), tr("b₂ (area)"), false, false);
  b2Plot_->setTitle(tr("b₂, the area of the sea (appendix A), against K"));
  b2Plot_->enableAxis(kAxisYRight);
  b2Plot_->setAxisTitle(kAxisYRight, tr("b₂ / L²"));
  b2Plot_->insertLegend(new QwtLegend, QwtPlot::BottomLegend);

  ftPlot_->setObjectName(QStringLiteral("ft"));
  dPlot_->setObjectName(QStringLiteral("D"));
  exponentPlot_->setObjectName(QStringLiteral("exponent"));
  heatMapPlot_->setObjectName(QStringLiteral("heatMap"));
  longPlot_->setObjectName(QStringLiteral("long"));
  b2Plot_->setObjectName(QStringLiteral("b2"));

  table_ = new QTableWidget(0, 9, this);
  table_->setHorizontalHeaderLabels({tr("K"), tr("xmin"), tr("xmax"), tr("blocks"), tr("segments"), tr("D ± error"),
                                     tr("longest (steps)"), tr("steps in ≥10⁴"), tr("b₂ area (fraction)")});
  // Each column as wide as its contents (a horizontal scroll bar rather than cut cells); the last fills the rest.
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setStretchLastSection(true);
  table_->setWordWrap(false);
  table_->verticalHeader()->setVisible(false);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  // Small minimum sizes: the dialog fits a 1280 × 800 screen whatever the plots' size hints.
  for (QWidget* w : std::initializer_list<QWidget*>{ftPlot_, exponentPlot_, heatMapPlot_, dPlot_, longPlot_,
                                                    b2Plot_, table_})
    w->setMinimumSize(320, 180);

  // Over τ (above) and against K (below), each a tab widget: any curve of one beside any of the other.
  auto* upper = new QTabWidget(this);
  upper->setObjectName(QStringLiteral("upperTabs"));
  upper->addTab(ftPlot_, tr("f_t"));
  upper->addTab(heatMapPlot_, tr("Local exponent map"));
  upper->addTab(exponentPlot_, tr("Local exponent curves"));
  auto* lower = new QTabWidget(this);
  lower->setObjectName(QStringLiteral("lowerTabs"));
  lower->addTab(dPlot_, tr("D(K)"));
  lower->addTab(longPlot_, tr("Long segments(K)"));
  lower->addTab(b2Plot_, tr("b₂(K)"));
  lower->addTab(table_, tr("Table"));
  auto* splitter = new QSplitter(Qt::Vertical, this);
  splitter->addWidget(upper);
  splitter->addWidget(lower);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(splitter);
  // Not replotted here: the first showRuns() or clear() does it, as the dialog always did.  (A first replot with
  // the empty ranges would leave Qwt's layout of the heat map a pixel off in the report's figure.)
}

QwtPlot* KScanPlots::plot(const QString& name) const {
  for (QwtPlot* plot : {ftPlot_, heatMapPlot_, exponentPlot_, dPlot_, longPlot_, b2Plot_})
    if (plot->objectName() == name) return plot;
  return nullptr;
}

QStringList KScanPlots::plotNames() {
  return {QStringLiteral("ft"), QStringLiteral("heatMap"), QStringLiteral("exponent"),
          QStringLiteral("D"),  QStringLiteral("long"),    QStringLiteral("b2")};
}

double KScanPlots::heatMapValue(double K, double tau) const { return heatMap_->data()->value(K, tau); }

void KScanPlots::clear() { showRuns(std::vector<std::optional<ScanRunSummary>>{}); }

void KScanPlots::showRuns(const std::vector<ScanRunSummary>& runs) {
  showRuns(std::vector<std::optional<ScanRunSummary>>(runs.begin(), runs.end()));
}

/// The points against K of the K finished (the ScanPoint columns of scan_summary.csv): D and its bars, the longest
/// segment, the steps in segments ≥ 10⁴, b₂.
struct KScanPlots::AgainstK {
  QVector<QPointF> dPoints, longest, longFraction, b2Area, b2Fraction;
  QVector<QwtIntervalSample> dErrors;

  void add(const ScanPoint& p) {
    if (p.D > 0) {
      dPoints.append(QPointF(p.K, p.D));
      // No bar where the longest segments dominate D (DError NaN): the data support no error there.
      if (std::isfinite(p.DError))
        dErrors.append(QwtIntervalSample(p.K, std::max(p.D - p.DError, p.D * 1e-3), p.D + p.DError));
    }
    if (p.longestSteps > 0) longest.append(QPointF(p.K, static_cast<double>(p.longestSteps)));  // 0: unknown
    longFraction.append(QPointF(p.K, p.longFraction));
    if (p.boxInvariant) {
      b2Area.append(QPointF(p.K, p.boxInvariant->b2.area));
      b2Fraction.append(QPointF(p.K, p.boxInvariant->b2.fraction));
    }
  }
};

namespace {
/// Points against K, with a symbol, on `yAxis`.
QwtPlotCurve* addPoints(QwtPlot* plot, const QString& title, const QVector<QPointF>& points, const QColor& colour,
                        QwtSymbol::Style style, int yAxis) {
  auto* curve = new QwtPlotCurve(title);
  curve->setPen(colour, 1.5);
  curve->setSymbol(new QwtSymbol(style, colour, colour, QSize(7, 7)));
  curve->setSamples(points);
  curve->setYAxis(yAxis);
  curve->attach(plot);
  return curve;
}
}  // namespace

void KScanPlots::showRuns(const std::vector<std::optional<ScanRunSummary>>& runs) {
  removeCurves();
  AgainstK againstK;
  std::vector<ScanRunSummary> done;  // the K finished so far, in the scan's order: the heat map's columns
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!runs[i]) continue;
    const ScanRunSummary& run = *runs[i];
    done.push_back(run);
    const QColor colour = colourOf(i, runs.size());
    addCurve(ftPlot_, run, run.statistics.f, colour);
    addCurve(exponentPlot_, run, run.statistics.localExponent, colour);
    againstK.add(run.point);
    addTableRow(run.point);
  }
  drawAgainstK(againstK, done);
  showHeatMap(done);
  rescale(done.empty());
}

void KScanPlots::removeCurves() {
  for (QwtPlot* plot : {ftPlot_, dPlot_, exponentPlot_, longPlot_, b2Plot_})
    plot->detachItems(QwtPlotItem::Rtti_PlotCurve, true);
  dPlot_->detachItems(QwtPlotItem::Rtti_PlotIntervalCurve, true);
  table_->setRowCount(0);
}

void KScanPlots::addCurve(QwtPlot* plot, const ScanRunSummary& run, const Series& s, const QColor& colour) {
  QVector<QPointF> points;
  for (std::size_t j = 0; j < s.x.size(); ++j)
    if (s.x[j] > 0 && std::isfinite(s.value[j]) && (plot != ftPlot_ || s.value[j] > 0))
      points.append(QPointF(s.x[j], s.value[j]));
  auto* curve = new QwtPlotCurve(QStringLiteral("K = %1").arg(kText(run.point.K)));
  curve->setPen(colour, 1.5);
  curve->setSamples(points);
  curve->attach(plot);
}

void KScanPlots::addTableRow(const ScanPoint& p) {
  const int row = table_->rowCount();
  table_->insertRow(row);
  const QStringList cells = {kText(p.K), QString::number(p.box.xmin, 'g', 4), QString::number(p.box.xmax, 'g', 4),
                             QStringLiteral("%1 / %2").arg(p.blocksDone).arg(p.blocksTotal),
                             QString::number(p.segments),
                             std::isfinite(p.DError)
                                 ? QStringLiteral("%1 ± %2").arg(p.D, 0, 'g', 4).arg(p.DError, 0, 'g', 2)
                                 : tr("%1 (tail dominates: no error)").arg(p.D, 0, 'g', 4),
                             p.longestSteps > 0 ? QString::number(p.longestSteps) : QStringLiteral("—"),
                             QString::number(p.longFraction, 'f', 3),
                             p.boxInvariant ? QStringLiteral("%1 (%2)")
                                                  .arg(p.boxInvariant->b2.area, 0, 'g', 5)
                                                  .arg(p.boxInvariant->b2.fraction, 0, 'f', 4)
                                            : tr("not computed")};
  for (int c = 0; c < cells.size(); ++c) table_->setItem(row, c, new QTableWidgetItem(cells[c]));
  if (!std::isfinite(p.DError))
    table_->item(row, 5)->setToolTip(tr("D is dominated by its longest segments: the run supports no error of D "
                                        "(archipelago-cli stats says why)"));
}

void KScanPlots::drawAgainstK(const AgainstK& k, const std::vector<ScanRunSummary>& done) {
  auto* bars = new QwtPlotIntervalCurve(tr("one sigma"));
  bars->setStyle(QwtPlotIntervalCurve::NoCurve);
  bars->setSymbol(new QwtIntervalSymbol(QwtIntervalSymbol::Bar));
  bars->setSamples(k.dErrors);
  bars->attach(dPlot_);
  const QColor blue(31, 119, 180), orange(230, 120, 20);
  addPoints(dPlot_, tr("D"), k.dPoints, blue, QwtSymbol::Ellipse, kAxisY);
  addPoints(longPlot_, tr("longest segment (left)"), k.longest, blue, QwtSymbol::Ellipse, kAxisY);
  addPoints(longPlot_, tr("steps in segments ≥ 10⁴, fraction (right)"), k.longFraction, orange, QwtSymbol::Rect,
            kAxisYRight);
  addPoints(b2Plot_, tr("b₂, area (left)"), k.b2Area, blue, QwtSymbol::Ellipse, kAxisY);
  addPoints(b2Plot_, tr("b₂ / L², fraction of the box (right)"), k.b2Fraction, orange, QwtSymbol::Rect, kAxisYRight);
  b2Plot_->setFooter(k.b2Area.isEmpty() && !done.empty() ? tr("b₂ not computed: set b₂ steps > 0 and start again")
                                                         : QString());
  const auto noError = std::count_if(done.begin(), done.end(), [](const ScanRunSummary& r) {
    return r.point.D > 0 && !std::isfinite(r.point.DError);
  });
  dPlot_->setFooter(noError > 0 ? tr("no error bar at %1 of %2 K: their longest segments dominate D, the run supports "
                                     "no error there (see the table)")
                                      .arg(noError)
                                      .arg(done.size())
                                : QString());
}

void KScanPlots::showHeatMap(const std::vector<ScanRunSummary>& done) {
  // The heat map: core's localExponentHeatMap of the K finished (the numbers of scan_local_exponent.csv).
  archipelago::ui::showHeatMap(heatMapPlot_, heatMap_, localExponentHeatMap(done), {0, 1.3, 1, 1e6});
}

void KScanPlots::rescale(bool empty) {
  // Before any result, fixed ranges (an empty log axis would span hundreds of decades); then autoscale.
  const std::pair<QwtPlot*, std::array<double, 4>> ranges[] = {
      {ftPlot_, {1, 1e6, 1e-8, 1}},   {dPlot_, {0, 1.3, 1, 1e4}},  {exponentPlot_, {1, 1e6, 0, 3}},
      {longPlot_, {0, 1.3, 1, 1e6}}, {b2Plot_, {0, 1.3, 0, 4}}};
  for (const auto& [plot, r] : ranges) {
    if (empty) {
      plot->setAxisScale(kAxisX, r[0], r[1]);
      plot->setAxisScale(kAxisY, r[2], r[3]);
      if (plot == longPlot_ || plot == b2Plot_) plot->setAxisScale(kAxisYRight, 0, 1);
    } else {
      plot->setAxisAutoScale(kAxisX, true);
      plot->setAxisAutoScale(kAxisY, true);
      if (plot == longPlot_ || plot == b2Plot_) plot->setAxisAutoScale(kAxisYRight, true);
    }
    plot->replot();
  }
}

}  // namespace archipelago::ui
