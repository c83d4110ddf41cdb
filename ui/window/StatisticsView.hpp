#pragma once
/// \file StatisticsView.hpp
/// \brief The "Statistics" tab: a live plot of every statistic core's table marks as plotted (Karney 1983,
/// figs. 3, 6 and 7: f_t, P_t, C_τ, the local exponent, S_t, D_t) and a one-line summary.
///
/// showSnapshot() copies a snapshot's series into the plots and replots them; the main window calls it from
/// its refresh timer, never per chunk, so the event loop stays free.

#include <QList>
#include <QWidget>

#include "ui/run/RunSnapshot.hpp"
#include "core/stats/RunSummary.hpp"
#include "core/stats/StatisticsTable.hpp"

class QLabel;

namespace archipelago::ui {

class StatisticsPlot;

class StatisticsView : public QWidget {
  Q_OBJECT
 public:
  explicit StatisticsView(QWidget* parent = nullptr);

  void showSnapshot(const RunSnapshot& snapshot);
  void clear();
  [[nodiscard]] const QList<StatisticsPlot*>& plots() const noexcept { return plots_; }
  /// The plot of a statistic the table marks as plotted; nullptr for any other (p_t).
  [[nodiscard]] StatisticsPlot* plot(Statistic statistic) const;
  /// Number of times the plots were redrawn (the latency script reads it).
  [[nodiscard]] quint64 refreshCount() const noexcept { return refreshes_; }
  /// Wall time spent redrawing, summed over every refresh (the latency script reads it).
  [[nodiscard]] double refreshSeconds() const noexcept { return refreshSeconds_; }
  [[nodiscard]] QString summaryText() const;
  /// The tail's line as plain text: γ_P and the verdict in `stats`'s words (empty until the tail is judged).
  [[nodiscard]] QString tailText() const;
  /// Core's run summary of the snapshot (its statistics and, once judged, the run's tail analysis): what the view
  /// shows and what "Export all" writes in summary.csv.
  [[nodiscard]] static RunSummary summaryOf(const RunSnapshot& snapshot);
  /// Shows `plot` alone, over the room of all six (null: all of them again); a double click on a plot or its menu's
  /// Enlarge toggles it, Esc shows all again (issue 53, missing: P_t with a model and a tail had ~230×180 pixels).
  void enlarge(StatisticsPlot* plot);
  [[nodiscard]] StatisticsPlot* enlargedPlot() const noexcept { return enlarged_; }

 private:
  /// The exact longest segment (the first kept record), in steps.
  [[nodiscard]] static QString longestText(const RunSnapshot& snapshot);
  /// D with the error the data supports (core's tail analysis of a finished or paused run).
  [[nodiscard]] static QString dText(const RunSnapshot& snapshot);
  /// γ_P and the verdict, or empty when the tail is not judged yet.
  [[nodiscard]] static QString tailHtml(const RunSnapshot& snapshot);

  QList<StatisticsPlot*> plots_;
  QLabel* summary_ = nullptr;
  QLabel* tail_ = nullptr;
  StatisticsPlot* enlarged_ = nullptr;
  quint64 refreshes_ = 0;
  double refreshSeconds_ = 0;
};

}  // namespace archipelago::ui
