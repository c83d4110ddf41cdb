#pragma once
/// \file KScanPlots.hpp
/// \brief What a K scan (§5) looks like: its plots and its table, fed the scan's summaries.  The K-scan dialog
/// shows it beside its settings as each K finishes; the reproduction report (ui/report) builds one offscreen and
/// renders its plots, so both draw the same figures from the same code.
///
/// Over τ (the upper tab widget): f_t, one curve per K (log-log); the local exponent −d log C_τ / d log τ as a
/// heat map over (K, log τ) with a titled colour bar (core's localExponentHeatMap: the numbers of
/// scan_local_exponent.csv) and as curves.  Against K (the lower one): D ± its supported error (no bar where the
/// longest segments dominate D), the longest segment and the fraction of the steps in segments ≥ 10⁴, b₂ (area
/// and fraction, when computed) — the ScanPoint columns of scan_summary.csv — and a table of them.  The curves of
/// K number i of n are coloured from blue (first) to red (last).  No maths here: every number comes from core.
///
/// The heat map's colour scale is one function, heatMapColour(); everything that colours the map (cells, colour
/// bar, the no-data grey) calls it.

#include <QColor>
#include <QString>
#include <QWidget>

#include <optional>
#include <vector>

#include "core/scan/ScanHeatMap.hpp"
#include "core/scan/ScanSummary.hpp"

class QTableWidget;
class QwtPlot;
class QwtPlotSpectrogram;

namespace archipelago::ui {

class KScanPlots : public QWidget {
  Q_OBJECT
 public:
  explicit KScanPlots(QWidget* parent = nullptr);

  /// Shows a scan's K as they finish: `runs[i]` is K number i of the scan's list, empty until it has finished.
  /// Replaces whatever was shown.  Before any K has finished, the plots keep fixed typical ranges.
  void showRuns(const std::vector<std::optional<ScanRunSummary>>& runs);
  /// Shows a finished scan (every K).
  void showRuns(const std::vector<ScanRunSummary>& runs);
  /// Shows nothing.
  void clear();

  /// The plots by object name: "ft", "heatMap", "exponent", "D", "long", "b2"; nullptr for another name.
  [[nodiscard]] QwtPlot* plot(const QString& name) const;
  /// The names plot() knows, in the order of the tabs (upper, then lower).
  [[nodiscard]] static QStringList plotNames();
  [[nodiscard]] QTableWidget* table() const noexcept { return table_; }
  /// The heat map's cell drawn at (K, τ): the local exponent of the finished K nearest to K at the grid τ nearest
  /// in log τ; NaN where there is no data (drawn grey) or no K has finished.
  [[nodiscard]] double heatMapValue(double K, double tau) const;

  /// The colours stop at 0 and at this local exponent (values beyond take the end colours): core's.
  static constexpr double kHeatMapTop = archipelago::kHeatMapTop;
  /// The heat map's colour of a local exponent; NaN (no data) gives the no-data grey: core's one scale
  /// (core/scan/ScanHeatMap.hpp), the colours of the CLI's PNG and the report.
  [[nodiscard]] static QColor heatMapColour(double exponent);

 private:
  /// showRuns()'s steps: the curves and rows of the runs shown before removed; a K's curve over τ (f_t, local
  /// exponent), its point against K and its table row; the plots against K drawn with their footers; the heat map
  /// of the K finished; the ranges (fixed before any K has finished, then autoscaled).
  struct AgainstK;
  void removeCurves();
  void addCurve(QwtPlot* plot, const ScanRunSummary& run, const Series& s, const QColor& colour);
  void addTableRow(const ScanPoint& p);
  void drawAgainstK(const AgainstK& k, const std::vector<ScanRunSummary>& done);
  void showHeatMap(const std::vector<ScanRunSummary>& done);
  void rescale(bool empty);

  QwtPlot* ftPlot_ = nullptr;
  QwtPlot* dPlot_ = nullptr;
  QwtPlot* exponentPlot_ = nullptr;
  QwtPlot* heatMapPlot_ = nullptr;
  QwtPlotSpectrogram* heatMap_ = nullptr;
  QwtPlot* longPlot_ = nullptr;
  QwtPlot* b2Plot_ = nullptr;
  QTableWidget* table_ = nullptr;
};

}  // namespace archipelago::ui
