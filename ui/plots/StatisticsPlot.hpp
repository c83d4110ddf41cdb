#pragma once
/// \file StatisticsPlot.hpp
/// \brief One live statistics plot (f_t, P_t, C_τ, S_t, D_t: log-log; local exponent: log-linear).
///
/// Titles, axis labels, axis scales and file names come from core's statistics table
/// (stats/StatisticsTable.hpp); this class only adds presentation: colours, legend placement, zoom.
///
/// Follows Qwt's realtime examples: autoReplot is off and the owner decides when to replot (a GUI timer);
/// setData() only copies the snapshot's series into the curves.  The plot draws the data, an error band
/// (one sigma over the subsets of orbits, QwtPlotIntervalCurve) and the theory curves; on a log axis points
/// ≤ 0 are left out and a band reaching ≤ 0 is clipped.  Ranges follow the data until the user zooms, pans
/// or turns the wheel; "Reset zoom" (or a right click at the base of the zoom stack) follows the data again.
/// A crosshair shows the coordinates under the mouse.  Before any data arrives the plot shows a placeholder
/// ("No run yet — press Run (F5)") over fixed typical axes, without legend or crosshair.  The local exponent's
/// y range follows its well-measured points (error ≤ 0.5), so K = 0's exponent 5 is on scale; vertical
/// theory lines (t_max) widen the x range so that they and their labels stay on the canvas.

#include <QString>
#include <QVector>
#include <qwt_interval.h>
#include <qwt_plot.h>

#include <optional>
#include <vector>

#include "core/provenance/Provenance.hpp"
#include "core/stats/StatisticsTable.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/theory/TheoryCurves.hpp"

class QFont;
class QMenu;
class QwtPlotCurve;
class QwtPlotIntervalCurve;
class QwtPlotMarker;
class QwtPlotLegendItem;
class QwtPlotTextLabel;
class QwtPlotZoneItem;
class QwtPlotZoomer;
class QwtPlotPicker;

namespace archipelago::ui {

class StatisticsPlot : public QwtPlot {
  Q_OBJECT
 public:
  explicit StatisticsPlot(Statistic statistic, QWidget* parent = nullptr);
  ~StatisticsPlot() override;

  [[nodiscard]] Statistic statistic() const noexcept { return statistic_; }
  /// The table's file stem: "f_t", "P_t", "C_tau", "local_exponent", "S_t", "D_t".
  [[nodiscard]] QString fileName() const;
  /// The symbol and the table's words, for menus ("f_t: distribution of trapping times").
  [[nodiscard]] QString displayName() const;

  /// Copies the data and the theory curves that belong to this statistic; call refresh() to show them.
  void setData(const Series& data, const std::vector<TheoryCurve>& theory);
  /// Shades the times below `steps` (TrappingStatistics::blockAffectedBelow: 10 q for a run of q > 1 without its
  /// q = 1 companion) as affected by the q-block artefact (docs/design.md, "Blocks of q steps"); 0 removes the shade.
  void setBlockAffectedBelow(double steps);
  [[nodiscard]] double blockAffectedBelow() const noexcept { return blockAffectedBelow_; }
  /// Draws an estimate of the same statistic made another way — P_t beyond the run's data by the tail sampler
  /// (core/tail, issue #29) — as points with ±1σ bars in a colour of its own, titled `title` in the legend; an
  /// empty series removes it.  It takes part in the autoscale (the estimate reaches beyond the run's data).
  void setEstimate(const Series& estimate, const QString& title);
  [[nodiscard]] QVector<QPointF> estimatePoints() const;
  /// Draws a model of the same statistic — P_t of the Markov tree of an atlas (core/markovtree, issue 40) — as a
  /// line in a colour of its own, titled `title` in the legend; an empty series removes it.  It does not move the
  /// ranges (the model's exponential tail reaches far below any measured P_t): it is drawn where the run's data,
  /// a tail estimate or the user's zoom show.
  void setModel(const Series& model, const QString& title);
  [[nodiscard]] QVector<QPointF> modelPoints() const;
  [[nodiscard]] QString modelTitle() const;
  void clearData();
  /// Replots, rescaling to the data unless the user has zoomed or panned.
  void refresh();
  /// Follows the data again.
  void resetZoom();
  /// The range the user chose (zoom, pan, wheel) as (x, y, width, height) in plot units, or nothing while the
  /// plot follows its data.  setUserView() shows such a range (a session being restored).
  [[nodiscard]] std::optional<QRectF> userView() const;
  void setUserView(const QRectF& view);

  /// The points drawn for the data curve (x, value), after dropping points a log axis cannot show.
  [[nodiscard]] QVector<QPointF> plottedPoints() const;
  [[nodiscard]] const Series& data() const noexcept { return data_; }
  [[nodiscard]] int theoryCurveCount() const noexcept { return static_cast<int>(theory_.size()); }

  /// True before any data point: the placeholder shows, the legend and the crosshair are off.
  [[nodiscard]] bool isEmpty() const;
  [[nodiscard]] bool placeholderShown() const;
  [[nodiscard]] bool legendShown() const;
  [[nodiscard]] bool crosshairEnabled() const;
  /// Where the legend is drawn, in canvas coordinates (empty when hidden, or outside the canvas: P_t's is below the
  /// plot, issue 37, finding 5): always inside the canvas.
  [[nodiscard]] QRectF legendRect() const;
  /// The reference slopes drawn (P_t only): one curve each, with its own pen (tests).
  [[nodiscard]] std::vector<const QwtPlotCurve*> referenceCurves() const;
  /// The title as plain Unicode text for file metadata: "fₜ — distribution of trapping times".
  [[nodiscard]] QString plainTitle() const;

  /// Writes the plot as PNG, SVG or PDF (chosen by the suffix) with QwtPlotRenderer; the document's title
  /// (SVG <title>, PDF and PNG metadata) is plainTitle().  `provenance` (core's runProvenance() of the run shown)
  /// goes into the PNG's text chunks, and `footnote` (its parameters in one line, runParametersLine()) is drawn
  /// under the plot in every format (issue 54, item 6: the plots' PNGs carried no K, q, Xr, T or M).  (Its numbers
  /// are written by core's CSV writer: see ExportActions.hpp.)
  bool exportImage(const QString& path, QString* error = nullptr, const Provenance& provenance = {},
                   const QString& footnote = {});

  /// Shown alone, enlarged over the other plots (the view says so: the menu then offers the way back).
  void setEnlarged(bool enlarged) noexcept { enlarged_ = enlarged; }
  [[nodiscard]] bool enlarged() const noexcept { return enlarged_; }
  /// The menu a right click over the axes or the title opens (issue 53, finding 19: it offered only Reset zoom):
  /// Reset zoom, Enlarge / Show All Plots, Export….
  [[nodiscard]] QMenu* createContextMenu(QWidget* parent);

 Q_SIGNALS:
  /// A double click on the canvas, or the menu's Enlarge / Show All Plots: the view shows it alone, or all again.
  void enlargeToggled();
  /// The menu's Export…: the window asks where.
  void exportRequested();

 protected:
  void contextMenuEvent(QContextMenuEvent* event) override;
  bool eventFilter(QObject* watched, QEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;

 private:
  /// The constructor's steps: the title and the axes (log where the statistic's table says); the grid, the ±1σ band
  /// and the data curve; the legend (in a corner, or below the plot for P_t: insertLegendBelow); the zoomer, panner,
  /// wheel and crosshair; the placeholder shown before a run.
  void setUpTitleAndAxes(const StatisticInfo& info);
  void attachGridAndCurves();
  void createLegend();
  void insertLegendBelow(const QFont& legendFont);
  void createMouseTools();
  void createPlaceholder();
  [[nodiscard]] bool logY() const noexcept;
  [[nodiscard]] bool followingData() const;
  void showPlaceholder(bool empty);
  [[nodiscard]] QwtInterval exponentRange() const;
  void fitLegend();

  Statistic statistic_;
  Series data_;
  std::vector<TheoryCurve> theory_;
  QwtPlotCurve* curve_ = nullptr;
  QwtPlotIntervalCurve* band_ = nullptr;
  QwtPlotZoneItem* blockZone_ = nullptr;  ///< t < blockAffectedBelow_, shaded
  QwtPlotCurve* estimate_ = nullptr;                ///< setEstimate(): the points
  QwtPlotIntervalCurve* estimateBars_ = nullptr;    ///< … and their ±1σ bars
  QwtPlotCurve* model_ = nullptr;                   ///< setModel(): the line
  double blockAffectedBelow_ = 0;
  std::vector<QwtPlotCurve*> theoryCurves_;
  std::vector<QwtPlotMarker*> theoryMarkers_;
  QwtPlotZoomer* zoomer_ = nullptr;
  QwtPlotLegendItem* legend_ = nullptr;
  QwtPlotTextLabel* placeholder_ = nullptr;
  QwtPlotPicker* crosshair_ = nullptr;
  QwtInterval autoX_, autoY_;  // the ranges last chosen by autoscaling; anything else is the user's view
  bool forceFollow_ = true;
  bool enlarged_ = false;
  double legendPointSize_ = 8;
};

}  // namespace archipelago::ui
