#pragma once
/// \file TailScanPlots.hpp
/// \brief What a tail scan (core/tail/TailScan.hpp, `archipelago-cli tail-scan`) looks like: the figure γ(t, K) of
/// issue 55.  Above, γ = −d ln P/d ln t as a heat map over (K, log t) (core's tailGammaHeatMap: the numbers of
/// PREFIX_gamma.csv and the colours of PREFIX_gamma.png, with KScanPlots' heat-map code, ScanPlotParts.hpp); below, γ
/// per window against t, one point per K (coloured blue to red as KScanPlots' curves), the K-average with its spread
/// over K as bars, and the literature's exponents as labelled horizontal lines (core's tailScanReferenceExponents:
/// 1.57 and 1.44).  The K-scan dialog shows it for a folder that tail-scan wrote.  No maths here: every number comes
/// from core's summary.

#include <QString>
#include <QWidget>

#include "core/tail/TailScan.hpp"

class QwtPlot;
class QwtPlotSpectrogram;

namespace archipelago::ui {

class TailScanPlots : public QWidget {
  Q_OBJECT
 public:
  explicit TailScanPlots(QWidget* parent = nullptr);

  /// Shows a tail scan's summary (replacing whatever was shown).
  void showSummary(const TailScanSummary& summary);
  /// Shows nothing (fixed typical ranges).
  void clear();

  /// The plots by object name: "tailGammaMap" (the heat map), "tailGammaWindows" (γ per window); nullptr for another.
  [[nodiscard]] QwtPlot* plot(const QString& name) const;
  /// The heat map's cell drawn at (K, t): γ of the K nearest to K over the window whose centre is nearest to t in
  /// log t; NaN where that K does not reach the window (drawn grey) or nothing is shown.
  [[nodiscard]] double heatMapValue(double K, double t) const;

 private:
  void removeCurves();
  void addKPoints(const TailScanSummary& s);
  void addAverage(const TailScanSummary& s);
  void addReferences(const TailScanSummary& s);

  QwtPlot* mapPlot_ = nullptr;
  QwtPlotSpectrogram* map_ = nullptr;
  QwtPlot* windowsPlot_ = nullptr;
};

}  // namespace archipelago::ui
