#include "ui/scan/ScanPlotParts.hpp"

#include <QPen>
#include <qwt_color_map.h>
#include <qwt_picker_machine.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_picker.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_scale_engine.h>
#include <qwt_scale_widget.h>
#include <qwt_text.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

#include "core/scan/ScanBox.hpp"
#include "ui/plots/LogScaleDraw.hpp"
#include "ui/plots/QwtCompat.hpp"

namespace archipelago::ui {

QwtPlot* makePlot(QWidget* parent, const QString& x, const QString& y, bool logX, bool logY) {
  auto* plot = new QwtPlot(parent);
  plot->setCanvasBackground(Qt::white);
  plot->setAxisTitle(kAxisX, x);
  plot->setAxisTitle(kAxisY, y);
  if (logX) {
    plot->setAxisScaleEngine(kAxisX, new QwtLogScaleEngine);
    plot->setAxisScaleDraw(kAxisX, new LogScaleDraw);
  }
  if (logY) {
    plot->setAxisScaleEngine(kAxisY, new QwtLogScaleEngine);
    plot->setAxisScaleDraw(kAxisY, new LogScaleDraw);
  }
  auto* grid = new QwtPlotGrid;
  grid->setMajorPen(QColor(0, 0, 0, 40), 0, Qt::DotLine);
  grid->attach(plot);
  return plot;
}

QColor colourOf(std::size_t i, std::size_t n) {
  const float s = n > 1 ? static_cast<float>(i) / static_cast<float>(n - 1) : 0.0f;
  return QColor::fromHsvF(0.66f * (1 - s), 0.85f, 0.8f);
}

QString kText(double K) { return QString::fromStdString(scanKText(K)); }

QColor heatMapQColour(double value, double top) {
  const Rgb c = heatMapColour(value, top);  // core's one scale (core/scan/ScanHeatMap.hpp)
  return {c.r, c.g, c.b};
}

HeatMapData::HeatMapData(ScanHeatMap map) : map_(std::move(map)) {
  order_.resize(map_.K.size());
  std::iota(order_.begin(), order_.end(), std::size_t{0});
  std::sort(order_.begin(), order_.end(), [&](std::size_t a, std::size_t b) { return map_.K[a] < map_.K[b]; });
  // Column edges: half way between neighbouring K; the outer ones as far out as the nearest inner one
  // (±0.025 for a single K, the paper's half step).
  const std::size_t n = order_.size();
  edges_.resize(n + 1);
  for (std::size_t i = 1; i < n; ++i) edges_[i] = (map_.K[order_[i - 1]] + map_.K[order_[i]]) / 2;
  if (n == 1) {
    edges_[0] = map_.K[order_[0]] - 0.025;
    edges_[1] = map_.K[order_[0]] + 0.025;
  } else if (n > 1) {
    edges_[0] = 2 * map_.K[order_[0]] - edges_[1];
    edges_[n] = 2 * map_.K[order_[n - 1]] - edges_[n - 1];
  }
  x_ = n > 0 ? QwtInterval(edges_.front(), edges_.back()) : QwtInterval();
  y_ = map_.tau.empty() ? QwtInterval() : QwtInterval(map_.tau.front(), map_.tau.back());
  z_ = QwtInterval(0, map_.top);
#if QWT_VERSION < 0x060200
  setInterval(Qt::XAxis, x_);
  setInterval(Qt::YAxis, y_);
  setInterval(Qt::ZAxis, z_);
#endif
}

#if QWT_VERSION >= 0x060200
QwtInterval HeatMapData::interval(Qt::Axis axis) const { return axis == Qt::XAxis ? x_ : axis == Qt::YAxis ? y_ : z_; }
#endif

double HeatMapData::value(double K, double tau) const {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (empty() || !x_.contains(K) || !y_.contains(tau)) return nan;  // outside every cell
  const auto column = static_cast<std::size_t>(
      std::min<std::ptrdiff_t>(std::upper_bound(edges_.begin() + 1, edges_.end() - 1, K) - (edges_.begin() + 1),
                               static_cast<std::ptrdiff_t>(order_.size()) - 1));
  const std::vector<double>& t = map_.tau;
  auto it = std::lower_bound(t.begin(), t.end(), tau);
  if (it != t.begin() && tau * tau < *it * *(it - 1)) {
    --it;  // nearer in log τ to the grid τ below
  }
  const auto row = static_cast<std::size_t>(it - t.begin());
  return map_.value[row * map_.K.size() + order_[column]];
}

namespace {

/// The heat map's colours (heatMapQColour up to the plot's top, whatever interval Qwt passes: the scale is
/// absolute); a cell without data (NaN) transparent, so that the canvas, painted in the no-data colour, shows
/// through.  (A QwtLinearColorMap only for the rest of QwtColorMap's interface, which differs between Qwt 6.1 and
/// 6.2; its own stops are never used: the map is drawn in RGB format, through rgb().)
class HeatColours : public QwtLinearColorMap {
 public:
  explicit HeatColours(double top) : top_(top) {}
  QRgb rgb(const QwtInterval&, double value) const override {
    return std::isnan(value) ? qRgba(0, 0, 0, 0) : heatMapQColour(value, top_).rgb();
  }

 private:
  double top_;
};

/// The heat map's value under the mouse: the pointer's K and y and the cell's number (the colours stop at 0 and
/// the top; this says what lies beyond), or "no data".
class HeatMapPicker : public QwtPlotPicker {
 public:
  HeatMapPicker(QwtPlot* plot, const QwtPlotSpectrogram* map, QString yName)
      : QwtPlotPicker(kAxisX, kAxisY, QwtPicker::NoRubberBand, QwtPicker::AlwaysOn, plot->canvas()), map_(map),
        yName_(std::move(yName)) {
    setStateMachine(new QwtPickerTrackerMachine);
    setTrackerPen(QPen(Qt::black));
  }

 protected:
  QwtText trackerTextF(const QPointF& pos) const override {
    const double v = map_->data()->value(pos.x(), pos.y());
    QwtText text(QStringLiteral("K %1, %2 %3: %4")
                     .arg(pos.x(), 0, 'f', 3)
                     .arg(yName_)
                     .arg(pos.y(), 0, 'g', 3)
                     .arg(std::isnan(v) ? QObject::tr("no data") : QString::number(v, 'g', 4)));
    text.setBackgroundBrush(QColor(255, 255, 255, 220));
    return text;
  }

 private:
  const QwtPlotSpectrogram* map_;
  QString yName_;
};

}  // namespace

QwtPlotSpectrogram* addHeatMap(QwtPlot* plot, const QString& title, const QString& barTitle, const QString& yName,
                               double top) {
  plot->setCanvasBackground(heatMapQColour(std::numeric_limits<double>::quiet_NaN(), top));
  plot->detachItems(QwtPlotItem::Rtti_PlotGrid, true);
  auto* heatMap = new QwtPlotSpectrogram(title);
  heatMap->setRenderThreadCount(1);
  heatMap->setColorMap(new HeatColours(top));
  heatMap->setData(new HeatMapData(ScanHeatMap{}));
  heatMap->attach(plot);
  new HeatMapPicker(plot, heatMap, yName);  // owned by the canvas
  plot->enableAxis(kAxisYRight);
  QwtScaleWidget* colourBar = plot->axisWidget(kAxisYRight);
  colourBar->setColorBarEnabled(true);
  colourBar->setColorBarWidth(14);
  colourBar->setColorMap(QwtInterval(0, top), new HeatColours(top));
  plot->setAxisScale(kAxisYRight, 0, top);
  plot->setAxisTitle(kAxisYRight, barTitle);
  return heatMap;
}

void showHeatMap(QwtPlot* plot, QwtPlotSpectrogram* heatMap, ScanHeatMap map, const std::array<double, 4>& empty) {
  auto* cells = new HeatMapData(std::move(map));
  const bool mapEmpty = cells->empty();
  heatMap->setData(cells);
  if (mapEmpty) {
    plot->setAxisScale(kAxisX, empty[0], empty[1]);
    plot->setAxisScale(kAxisY, empty[2], empty[3]);
  } else {
    const QwtInterval x = cells->cells(Qt::XAxis), y = cells->cells(Qt::YAxis);
    plot->setAxisScale(kAxisX, x.minValue(), x.maxValue());
    plot->setAxisScale(kAxisY, y.minValue(), y.maxValue());
  }
  plot->replot();
}

}  // namespace archipelago::ui
