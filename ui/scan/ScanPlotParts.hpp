#pragma once
/// \file ScanPlotParts.hpp
/// \brief What the plots of the K scan (KScanPlots) and of the tail scan (TailScanPlots) share: a plot with its axes
/// and grid, the colour of K number i of n, and the heat map over (K, log y) of a ScanHeatMap
/// (core/scan/ScanHeatMap.hpp): its cells, coloured by core's one scale up to the map's top (heatMapColour, the
/// colours of the CLI's PNGs), a titled colour bar, the no-data grey, the value under the mouse.  No maths here: the
/// cells are core's numbers.

#include <QColor>
#include <QString>
#include <qwt_global.h>
#include <qwt_interval.h>
#include <qwt_plot.h>
#include <qwt_raster_data.h>

#include <array>
#include <cstddef>
#include <vector>

#include "core/scan/ScanHeatMap.hpp"

class QWidget;
class QwtPlotSpectrogram;

namespace archipelago::ui {

#if QWT_VERSION >= 0x060200
inline constexpr int kAxisYRight = QwtAxis::YRight;
#else
inline constexpr int kAxisYRight = QwtPlot::yRight;
#endif

/// A plot on a white canvas with a dotted grid, its axes titled, each logarithmic or not.
[[nodiscard]] QwtPlot* makePlot(QWidget* parent, const QString& x, const QString& y, bool logX, bool logY);
/// The colour of K number `i` of `n`: blue (small K) through red (large K).
[[nodiscard]] QColor colourOf(std::size_t i, std::size_t n);
/// K as its file names and messages write it (core's scanKText).
[[nodiscard]] QString kText(double K);
/// core's heatMapColour(value, top) (NaN: the no-data grey).
[[nodiscard]] QColor heatMapQColour(double value, double top);

/// The cells of a ScanHeatMap over x = K, y = τ (or t): each K a column reaching half way to its neighbours, each
/// row's τ a row reaching to the τ nearest in log τ (the lookup of the CLI's PNG), nothing below the first τ or above
/// the last.  No values of its own: value() returns the map's number of the cell, or NaN.  Its z interval is
/// [0, the map's top].
class HeatMapData : public QwtRasterData {
 public:
  explicit HeatMapData(ScanHeatMap map);
#if QWT_VERSION >= 0x060200
  QwtInterval interval(Qt::Axis axis) const override;
#endif
  [[nodiscard]] bool empty() const { return map_.K.empty() || map_.tau.empty(); }
  double value(double K, double tau) const override;
  /// The cells' extent along x (Qt::XAxis) or y (Qt::YAxis).
  [[nodiscard]] QwtInterval cells(Qt::Axis axis) const { return axis == Qt::XAxis ? x_ : y_; }

 private:
  ScanHeatMap map_;
  std::vector<std::size_t> order_;  // the columns by increasing K
  std::vector<double> edges_;
  QwtInterval x_, y_, z_;
};

/// A heat map in `plot` (K across, log y up, as the CLI's PNGs): a spectrogram titled `title` of HeatMapData cells
/// (none yet) coloured by core's one scale up to `top`, on a canvas of the no-data grey without grid; the colour bar
/// on the right titled `barTitle`; the value under the mouse ("K 0.100, <yName> 1e+03: 1.52").  Returns the
/// spectrogram.
QwtPlotSpectrogram* addHeatMap(QwtPlot* plot, const QString& title, const QString& barTitle, const QString& yName,
                               double top);
/// Shows `map` in `heatMap` (addHeatMap's) and replots: the axes span its cells exactly (autoscale would pad them with
/// no-data grey); a map without cells shows the range `empty` = {x from, x to, y from, y to}.
void showHeatMap(QwtPlot* plot, QwtPlotSpectrogram* heatMap, ScanHeatMap map, const std::array<double, 4>& empty);

}  // namespace archipelago::ui
