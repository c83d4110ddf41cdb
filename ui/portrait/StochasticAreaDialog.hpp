#pragma once
// The stochastic area b₂ (Karney 1983, §5, appendix A: an area, shown with the fraction of the 1024 × 1024 boxes
// of the box visited by the chaotic sea), computed in the background (core/stochasticarea/StochasticArea.hpp) as a job
// of ui/jobs, with its convergence drawn as it grows.  Closing the dialog stops the computation.

#include <QDialog>
#include <QVector>

#include "core/stochasticarea/StochasticArea.hpp"
#include "ui/jobs/BackgroundJobs.hpp"

class QLabel;
class QwtPlot;
class QwtPlotCurve;

namespace archipelago::ui {

class StochasticAreaDialog : public QDialog {
  Q_OBJECT
 public:
  StochasticAreaDialog(const StochasticAreaRequest& request, QWidget* parent = nullptr);
  ~StochasticAreaDialog() override;  // stops the computation and waits for it

 private:
  void addPoint(double iterations, double b2, bool last);

  QwtPlot* plot_ = nullptr;
  QwtPlotCurve* curve_ = nullptr;
  QLabel* summary_ = nullptr;
  QVector<QPointF> points_;
  MapParameters map_;          // the box whose area b₂ is
  BackgroundJobs jobs_{this};  // last: destroyed first, it stops the computation and joins
};

}  // namespace archipelago::ui
