#pragma once
/// \file RunGlanceView.hpp
/// \brief The "Run" page beside the phase portrait on the first screen: f_t and C_τ of the run, live, so that
/// the portrait and the statistics it explains are seen together (issue 25, finding 5 and deliverable 3).
///
/// The same StatisticsPlot as the Statistics tab (core's table names, scales and theory), fed by the window's
/// refresh timer with the same snapshot; it replots only while it is shown.

#include <QWidget>

#include "ui/run/RunSnapshot.hpp"

class QLabel;

namespace archipelago::ui {

class StatisticsPlot;

class RunGlanceView : public QWidget {
  Q_OBJECT
 public:
  explicit RunGlanceView(QWidget* parent = nullptr);

  void showSnapshot(const RunSnapshotPtr& snapshot);
  void clear();
  [[nodiscard]] StatisticsPlot* fPlot() const noexcept { return f_; }
  [[nodiscard]] StatisticsPlot* cPlot() const noexcept { return c_; }

 protected:
  void showEvent(QShowEvent* event) override;

 private:
  void draw();

  StatisticsPlot* f_ = nullptr;
  StatisticsPlot* c_ = nullptr;
  QLabel* note_ = nullptr;
  RunSnapshotPtr pending_;  // the newest snapshot, drawn when shown
  RunSnapshotPtr drawn_;
};

}  // namespace archipelago::ui
