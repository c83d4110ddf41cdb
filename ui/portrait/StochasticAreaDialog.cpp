#include "ui/portrait/StochasticAreaDialog.hpp"

#include <QApplication>
#include <QLabel>
#include <QMetaObject>
#include <QPointer>
#include <QVBoxLayout>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_scale_engine.h>
#include <qwt_symbol.h>

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

  QPointer<StochasticAreaDialog> self(this);
  worker_ = std::jthread([self, request](std::stop_token stop) {
    try {
      StochasticAreaRequest withKernel = request;
      withKernel.kernel = &selectKernel();  // the fastest path, or $ARCHIPELAGO_KERNEL (throws on a bad name)
      const StochasticAreaResult result = computeStochasticArea(
          withKernel,
          [&](const StochasticAreaPoint& p) {
            QMetaObject::invokeMethod(qApp, [self, p] {
              if (self) self->addPoint(static_cast<double>(p.iterations), p.b2, false);
            }, Qt::QueuedConnection);
          },
          stop);
      if (!result.cancelled)
        QMetaObject::invokeMethod(qApp, [self, b2 = result.b2()] {
          if (self) self->addPoint(0, b2, true);
        }, Qt::QueuedConnection);
    } catch (const std::exception& e) {
      QMetaObject::invokeMethod(qApp, [self, text = QString::fromStdString(e.what())] {
        if (self) self->summary_->setText(tr("Error: %1").arg(text));
      }, Qt::QueuedConnection);
    }
  });
}

StochasticAreaDialog::~StochasticAreaDialog() {
  worker_.request_stop();
  if (worker_.joinable()) worker_.join();
}

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
