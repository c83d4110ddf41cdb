#include "ui/report/ReportFigures.hpp"

#include <QDir>
#include <QFile>
#include <QBuffer>
#include <QImage>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>
#include <QSvgGenerator>
#include <QTextDocument>
#include <QUrl>
#include <qwt_interval_symbol.h>
#include <qwt_legend.h>
#include <qwt_plot_intervalcurve.h>
#include <qwt_symbol.h>
#include <qwt_text.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_item.h>
#include <qwt_matrix_raster_data.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_scale_map.h>
#include <qwt_plot_renderer.h>
#include <qwt_scale_engine.h>

#include <algorithm>
#include <cmath>

#include "core/export/StatisticsCsv.hpp"
#include "core/theory/SmallKTheory.hpp"
#include "ui/plots/LogScaleDraw.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/scan/KScanPlots.hpp"
#include "ui/files/OutputFiles.hpp"

namespace archipelago::ui::report {

bool writeStatisticFigure(Statistic statistic, const TrappingState& run, const TrappingStatistics& stats,
                          const std::vector<TheoryCurve>& theory, const QString& base, QString* error) {
  return writeStatisticFigure(statistic, run, stats, theory, Series{}, QString(), base, error);
}

bool writeStatisticFigure(Statistic statistic, const TrappingState& run, const TrappingStatistics& stats,
                          const std::vector<TheoryCurve>& theory, const Series& estimate, const QString& estimateTitle,
                          const QString& base, QString* error) {
  StatisticsPlot plot(statistic);
  plot.resize(800, 550);
  plot.setData(seriesOf(stats, statistic), theory);
  plot.setBlockAffectedBelow(stats.blockAffectedBelow);
  plot.setEstimate(estimate, estimateTitle);
  plot.refresh();
  const Provenance provenance = runProvenance(run);  // the GUI's plots' fields and line (ui/window/ExportActions)
  const QString footnote = QString::fromStdString(runParametersLine(run));
  return plot.exportImage(base + QStringLiteral(".png"), error, provenance, footnote) &&
         plot.exportImage(base + QStringLiteral(".svg"), error, provenance, footnote);
}

namespace {

/// The plot as BASE.png (with `provenance` as its text chunks) and BASE.svg, laid out at `widget` pixels and drawn
/// into `rect`.
bool renderPlot(QwtPlot& plot, const QString& base, const Provenance& provenance, QString* error,
                QSize widget = {800, 550}, QRectF rect = {0, 0, 945, 650}) {
  plot.resize(widget);
  plot.replot();
  QwtPlotRenderer renderer;
  renderer.setDiscardFlag(QwtPlotRenderer::DiscardBackground, false);
  QImage image(rect.size().toSize(), QImage::Format_ARGB32);
  image.fill(Qt::white);
  {
    QPainter painter(&image);
    renderer.render(&plot, &painter, rect);
  }
  if (!writePngFile(image, base + QStringLiteral(".png"), error, provenance)) return false;
  QByteArray svg;
  QBuffer buffer(&svg);
  buffer.open(QIODevice::WriteOnly);
  QSvgGenerator generator;
  generator.setOutputDevice(&buffer);
  generator.setSize(rect.size().toSize());
  generator.setViewBox(rect);
  generator.setTitle(plot.title().text());
  QPainter painter(&generator);
  renderer.render(&plot, &painter, rect);
  if (!painter.end() || !isCompleteSvg(svg)) {
    if (error) *error = QStringLiteral("cannot render %1.svg").arg(base);
    return false;
  }
  return publishBytes(svg, base + QStringLiteral(".svg"), error);
}

/// A raster on the canvas, mapped from its physical rectangle by the plot's scales (row 0 at the top, y1).
class RasterItem : public QwtPlotItem {
 public:
  RasterItem(QImage image, QRectF physical) : image_(std::move(image)), physical_(physical) {}
  void draw(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap, const QRectF&) const override {
    const QRectF target(QPointF(xMap.transform(physical_.left()), yMap.transform(physical_.bottom())),
                        QPointF(xMap.transform(physical_.right()), yMap.transform(physical_.top())));
    painter->drawImage(target.normalized(), image_);
  }

 private:
  QImage image_;
  QRectF physical_;
};

QwtPlotCurve* addCurve(QwtPlot& plot, const QVector<QPointF>& points, const QString& title, const QColor& colour) {
  auto* curve = new QwtPlotCurve(title);
  curve->setPen(colour, 2);
  curve->setRenderHint(QwtPlotItem::RenderAntialiased);
  curve->setSamples(points);
  curve->attach(&plot);
  return curve;
}

/// Open circles at `markers`, over everything else.
void addMarkers(QwtPlot& plot, const FigureMarkers& markers) {
  if (markers.points.empty()) return;
  auto* curve = new QwtPlotCurve(markers.name);
  curve->setStyle(QwtPlotCurve::NoCurve);
  curve->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, Qt::NoBrush, QPen(QColor(0, 160, 255), 2), QSize(13, 13)));
  curve->setSamples(QVector<QPointF>(markers.points.begin(), markers.points.end()));
  curve->setZ(100);
  curve->attach(&plot);
  if (!markers.name.isEmpty()) plot.insertLegend(new QwtLegend, QwtPlot::BottomLegend);
}

/// The report's palette for curves without a colour of their own (distinct on white, in print and on screen).
QColor paletteColour(int i) {
  static const QColor colours[] = {QColor(0, 90, 180), QColor(200, 60, 40), QColor(40, 150, 60),
                                   QColor(150, 60, 170), QColor(230, 140, 0), QColor(0, 150, 160),
                                   QColor(120, 90, 40), QColor(90, 90, 90)};
  return colours[i % 8];
}

}  // namespace

bool writeTrappingTimeFigures(const QString& base, const Provenance& provenance, QString* error) {
  const auto& mx = smallk::negativeKMaximum();
  {  // (a) T(X0)
    QwtPlot plot;
    plot.setCanvasBackground(Qt::white);
    plot.setTitle(QStringLiteral("Fig. 5a — T(X₀) for K < 0 (T_max = %1 at X₀ = %2)")
                      .arg(mx.T, 0, 'f', 4).arg(mx.X0, 0, 'f', 4));
    plot.setAxisTitle(QwtPlot::xBottom, QStringLiteral("X₀"));
    plot.setAxisTitle(QwtPlot::yLeft, QStringLiteral("T"));
    QVector<QPointF> pts;
    for (int i = 0; i <= 400; ++i) {
      const double X0 = -4 + 8.0 * i / 400;
      pts.append({X0, smallk::negativeKTrappingTime(X0)});
    }
    addCurve(plot, pts, QStringLiteral("T(X₀)"), QColor(0, 90, 180));
    plot.setAxisScale(QwtPlot::yLeft, 0, 6);
    if (!renderPlot(plot, base + QStringLiteral("a"), provenance, error)) return false;
  }
  {  // (b) F(T) with its two limits
    QwtPlot plot;
    plot.setCanvasBackground(Qt::white);
    plot.setTitle(QStringLiteral("Fig. 5b — F(T) for K < 0, with 6.205·10⁵ T⁻⁷ and 3.024 (T_max − T)^−½"));
    plot.setAxisTitle(QwtPlot::xBottom, QStringLiteral("T"));
    plot.setAxisTitle(QwtPlot::yLeft, QStringLiteral("F(T)"));
    plot.setAxisScaleEngine(QwtPlot::yLeft, new QwtLogScaleEngine);
    plot.insertLegend(new QwtLegend, QwtPlot::BottomLegend);
    const double c0 = smallk::negativeKSmallTCoefficient(), c1 = smallk::negativeKCutoffCoefficient();
    QVector<QPointF> f, small, cut;
    for (int i = 1; i < 500; ++i) {
      const double T = 1.5 + (mx.T - 1.5) * i / 500.0;
      f.append({T, smallk::negativeKSegmentDensity(T)});
      small.append({T, c0 * std::pow(T, -7.0)});
      cut.append({T, c1 / std::sqrt(mx.T - T)});
    }
    addCurve(plot, f, QStringLiteral("F(T)"), QColor(0, 90, 180));
    addCurve(plot, small, QStringLiteral("6.205·10⁵ T⁻⁷"), QColor(200, 60, 40))->setPen(QColor(200, 60, 40), 1, Qt::DashLine);
    addCurve(plot, cut, QStringLiteral("3.024 (T_max − T)^−½"), QColor(40, 150, 60))->setPen(QColor(40, 150, 60), 1, Qt::DashLine);
    plot.setAxisScale(QwtPlot::yLeft, 0.5, 1e4);
    if (!renderPlot(plot, base + QStringLiteral("b"), provenance, error)) return false;
  }
  return true;
}

namespace {

/// An image on the physical rectangle [x0, x1] × [y0, y1] with x, y axes and `markers`, as `base`.png/.svg: the
/// portraits and the replayed segments.
bool writeRasterFigure(const QImage& raster, double x0, double x1, double y0, double y1, const QString& title,
                       const QString& base, const Provenance& provenance, QString* error,
                       const FigureMarkers& markers) {
  QwtPlot plot;
  plot.setTitle(title);
  plot.setCanvasBackground(Qt::white);
  (new RasterItem(raster, QRectF(QPointF(x0, y0), QPointF(x1, y1))))->attach(&plot);
  plot.setAxisTitle(QwtPlot::xBottom, QStringLiteral("x"));
  plot.setAxisTitle(QwtPlot::yLeft, QStringLiteral("y"));
  plot.setAxisScale(QwtPlot::xBottom, x0, x1);
  plot.setAxisScale(QwtPlot::yLeft, y0, y1);
  addMarkers(plot, markers);
  return renderPlot(plot, base, provenance, error, {800, 800}, QRectF(0, 0, 800, 800));
}

}  // namespace

bool writePortraitFigure(const RasterImage& image, double x0, double x1, double y0, double y1, const QString& title,
                         const QString& base, const Provenance& provenance, QString* error,
                         const FigureMarkers& markers) {
  // A deep copy: QImage must not borrow the vector past this scope's end.
  const QImage raster = QImage(image.rgb.data(), image.width, image.height, 3 * image.width, QImage::Format_RGB888).copy();
  return writeRasterFigure(raster, x0, x1, y0, y1, title, base, provenance, error, markers);
}

bool writePointsFigure(const std::vector<QPointF>& points, double x0, double x1, double y0, double y1,
                       const QString& title, const QString& base, const Provenance& provenance, QString* error,
                       const FigureMarkers& markers) {
  if (!(x1 > x0) || !(y1 > y0)) {
    if (error) *error = QStringLiteral("%1: an empty view").arg(base);
    return false;
  }
  constexpr int n = 900;  // pixels each way: finer than the canvas, so that no two dots merge on screen
  QImage raster(n, n, QImage::Format_RGB888);
  raster.fill(Qt::white);
  for (const QPointF& p : points) {
    const double fx = (p.x() - x0) / (x1 - x0), fy = (y1 - p.y()) / (y1 - y0);  // row 0 at the top
    if (!(fx >= 0 && fx < 1 && fy >= 0 && fy < 1)) continue;
    raster.setPixelColor(static_cast<int>(fx * n), static_cast<int>(fy * n), Qt::black);
  }
  return writeRasterFigure(raster, x0, x1, y0, y1, title, base, provenance, error, markers);
}

bool writeScanFigures(const std::vector<ScanRunSummary>& runs, const QString& base, const Provenance& provenance,
                      QString* error) {
  KScanPlots plots;
  plots.showRuns(runs);
  for (const char* name : {"ft", "heatMap", "D", "long"}) {
    QwtPlot* plot = plots.plot(QString::fromLatin1(name));
    if (plot == nullptr) {
      if (error) *error = QStringLiteral("the K-scan plots have no plot %1").arg(QLatin1String(name));
      return false;
    }
    if (!renderPlot(*plot, base + QLatin1Char('-') + QString::fromLatin1(name).toLower(), provenance, error)) return false;
  }
  return true;
}

bool writeCurvesFigure(const std::vector<FigureCurve>& curves, const FigureAxes& axes, const QString& base,
                       const Provenance& provenance, QString* error) {
  QwtPlot plot;
  plot.setCanvasBackground(Qt::white);
  plot.setTitle(axes.title);
  plot.setAxisTitle(QwtPlot::xBottom, axes.xLabel);
  plot.setAxisTitle(QwtPlot::yLeft, axes.yLabel);
  if (axes.logX) {
    plot.setAxisScaleEngine(QwtPlot::xBottom, new QwtLogScaleEngine);
    plot.setAxisScaleDraw(QwtPlot::xBottom, new LogScaleDraw);
  }
  if (axes.logY) {
    plot.setAxisScaleEngine(QwtPlot::yLeft, new QwtLogScaleEngine);
    plot.setAxisScaleDraw(QwtPlot::yLeft, new LogScaleDraw);
  }
  int named = 0, next = 0;
  for (const FigureCurve& c : curves) {
    const QColor colour = c.colour.isValid() ? c.colour : paletteColour(next++);
    QVector<QPointF> pts;
    QVector<QwtIntervalSample> bars;
    for (std::size_t i = 0; i < c.x.size() && i < c.y.size(); ++i) {
      const double x = c.x[i], y = c.y[i];
      if (!std::isfinite(x) || !std::isfinite(y) || (axes.logX && x <= 0) || (axes.logY && y <= 0)) continue;
      pts.append({x, y});
      if (i < c.error.size() && std::isfinite(c.error[i]) && c.error[i] > 0) {
        const double lo = axes.logY ? std::max(y - c.error[i], y * 1e-3) : y - c.error[i];
        bars.append(QwtIntervalSample(x, lo, y + c.error[i]));
      }
    }
    QwtPlotCurve* curve = addCurve(plot, pts, c.name, colour);
    if (c.dashed) curve->setPen(colour, 1, Qt::DashLine);
    if (c.symbols) {
      curve->setStyle(QwtPlotCurve::NoCurve);
      curve->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(colour), QPen(colour), QSize(7, 7)));
    }
    if (c.name.isEmpty()) curve->setItemAttribute(QwtPlotItem::Legend, false);
    else ++named;
    if (!bars.isEmpty()) {
      auto* band = new QwtPlotIntervalCurve;
      band->setStyle(QwtPlotIntervalCurve::NoCurve);
      auto* bar = new QwtIntervalSymbol(QwtIntervalSymbol::Bar);
      bar->setWidth(7);
      bar->setPen(QPen(colour, 1));
      band->setSymbol(bar);
      band->setSamples(bars);
      band->setItemAttribute(QwtPlotItem::Legend, false);
      band->attach(&plot);
    }
  }
  if (named > 1) plot.insertLegend(new QwtLegend, QwtPlot::RightLegend);
  return renderPlot(plot, base, provenance, error);
}

bool writeLevelCurveFigure(const std::function<double(double, double)>& z, double x0, double x1, double y0, double y1,
                           const std::vector<double>& levels, const QString& title, const QString& base,
                           const Provenance& provenance, QString* error) {
  constexpr int n = 300;
  QVector<double> values;
  values.reserve(n * n);
  double lo = 1e300, hi = -1e300;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double v = z(x0 + (x1 - x0) * (i + 0.5) / n, y0 + (y1 - y0) * (j + 0.5) / n);
      values.append(v);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  auto* data = new QwtMatrixRasterData;
  data->setInterval(Qt::XAxis, QwtInterval(x0, x1));
  data->setInterval(Qt::YAxis, QwtInterval(y0, y1));
  data->setInterval(Qt::ZAxis, QwtInterval(lo, hi));
  data->setValueMatrix(values, n);
  data->setResampleMode(QwtMatrixRasterData::BilinearInterpolation);
  QwtPlot plot;
  plot.setCanvasBackground(Qt::white);
  plot.setTitle(title);
  plot.setAxisTitle(QwtPlot::xBottom, QStringLiteral("X"));
  plot.setAxisTitle(QwtPlot::yLeft, QStringLiteral("Y"));
  plot.setAxisScale(QwtPlot::xBottom, x0, x1);
  plot.setAxisScale(QwtPlot::yLeft, y0, y1);
  auto* spectrogram = new QwtPlotSpectrogram;
  spectrogram->setData(data);
  spectrogram->setDisplayMode(QwtPlotSpectrogram::ImageMode, false);
  spectrogram->setDisplayMode(QwtPlotSpectrogram::ContourMode, true);
  spectrogram->setDefaultContourPen(QPen(QColor(0, 90, 180), 1.2));
  spectrogram->setContourLevels(QList<double>(levels.begin(), levels.end()));
  spectrogram->attach(&plot);
  return renderPlot(plot, base, provenance, error);
}

bool writePdf(const QString& html, const QString& dir, const QStringList& images, const QString& pdfPath,
              QString* error) {
  QTextDocument doc;
  for (const QString& name : images) {
    QImage image(QDir(dir).filePath(name));
    if (image.isNull()) {
      if (error) *error = QStringLiteral("cannot read %1").arg(name);
      return false;
    }
    doc.addResource(QTextDocument::ImageResource, QUrl(name), image);
  }
  doc.setHtml(html);
  // Rendered in memory and checked whole before it is published atomically: a full disk once left a PDF cut
  // at 3.0 of its 3.8 MB while the report exited 0 (issue #23).
  QByteArray pdf;
  QBuffer buffer(&pdf);
  buffer.open(QIODevice::WriteOnly);
  {
    QPdfWriter writer(&buffer);
    writer.setPageSize(QPageSize(QPageSize::A4));
    writer.setResolution(96);  // the offscreen screen's logical dpi: fonts and the 600-pixel figures keep their size
    writer.setTitle(QStringLiteral("Karney (1983) reproduced by Archipelago"));
    doc.setPageSize(QSizeF(writer.width(), writer.height()));
    doc.print(&writer);
  }
  if (!isCompletePdf(pdf)) {
    if (error) *error = QStringLiteral("cannot render %1: the PDF is incomplete").arg(pdfPath);
    return false;
  }
  return publishBytes(pdf, pdfPath, error);
}

}  // namespace archipelago::ui::report
