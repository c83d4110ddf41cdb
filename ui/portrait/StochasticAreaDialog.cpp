#include "ui/portrait/StochasticAreaDialog.hpp"

#include <QLabel>
#include <QVBoxLayout>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_scale_engine.h>
#include <qwt_symbol.h>

#include "core/kernels/KernelDispatch.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "ui/plots/QwtCompat.hpp"

namespace archipelago::ui {

StochasticAreaDialog::StochasticAreaDialog(const StochasticAreaRequest& request, QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Stochastic area b₂"));
  map_ = request.map;
  setAttribute(Qt::WA_DeleteOnClose);
  auto* layout = new QVBoxLayout(this);
  summary_ = new QLabel(tr("Iterating the sea of Q* and counting the visited boxes of a %1 × %1 grid…")
                            .arg(1 << request.gridBits),
                        this);
  summary_->setWordWrap(true);
  layout->addWidget(summary_);
  plot_ = new QwtPlot(this);
  plot_->setAxisTitle(kAxisX, tr("iterations of N⁻¹"));
  plot_->setAxisTitle(kAxisY, tr("b₂ / L² (fraction of the box visited)"));
  plot_->setAxisScaleEngine(kAxisX, new QwtLogScaleEngine);
  plot_->setCanvasBackground(Qt::white);
  auto* grid = new QwtPlotGrid;
  grid->setMajorPen(QColor(0, 0, 0, 40), 0, Qt::DotLine);
  grid->attach(plot_);
  curve_ = new QwtPlotCurve(tr("b₂"));
  curve_->setPen(QColor(31, 119, 180), 2);
  curve_->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QColor(31, 119, 180), QColor(31, 119, 180), QSize(6, 6)));
  curve_->attach(plot_);
  layout->addWidget(plot_, 1);
  resize(640, 440);

  Job<double, StochasticAreaPoint> job;
  job.work = [request](JobContext<StochasticAreaPoint>& context) -> std::optional<double> {
    StochasticAreaRequest withKernel = request;
    withKernel.kernel = &selectKernel();  // the fastest path, or $ARCHIPELAGO_KERNEL (throws on a bad name)
    const StochasticAreaResult result = computeStochasticArea(
        withKernel, [&](const StochasticAreaPoint& p) { context.post(p); }, context.stopToken());
    if (result.cancelled) return std::nullopt;
    return result.fraction();
  };
  job.progress = [this](quint64, const StochasticAreaPoint& p) {
    addPoint(static_cast<double>(p.iterations), p.b2, false);
  };
  job.done = [this](const JobResult<double>& result) {
    if (result.ok())
      addPoint(0, *result.value, true);
    else
      summary_->setText(tr("Error: %1").arg(result.error));
  };
  jobs_.submit(std::move(job));
}

StochasticAreaDialog::~StochasticAreaDialog() = default;  // jobs_ stops the computation and waits for it

void StochasticAreaDialog::addPoint(double iterations, double b2, bool last) {
  if (last) {
    // b₂ is an area (appendix A); the paper's value is compared only at its K = 0.1 (core says which box).
    const StochasticAreaValue value = stochasticAreaOf(map_, b2);
    QString text = tr("%1, after %2 iterations.")
                       .arg(QString::fromStdString(stochasticAreaText(map_, value)))
                       .arg(points_.isEmpty() ? 0.0 : points_.back().x(), 0, 'g', 3);
    if (const auto paper = paperStochasticAreaComparison(map_, value)) text += u' ' + QString::fromStdString(*paper);
    summary_->setText(text);
    return;
  }
  points_.append(QPointF(iterations, b2));
  curve_->setSamples(points_);
  summary_->setText(tr("b₂ = %1 (area; fraction %2 of the box) after %3 iterations…")
                        .arg(stochasticAreaOf(map_, b2).area, 0, 'f', 4)
                        .arg(b2, 0, 'f', 4)
                        .arg(iterations, 0, 'g', 3));
  plot_->replot();
}

}  // namespace archipelago::ui
