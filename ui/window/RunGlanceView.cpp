#include "ui/window/RunGlanceView.hpp"

#include <QLabel>
#include <QVBoxLayout>

#include "ui/plots/StatisticsPlot.hpp"

namespace archipelago::ui {

RunGlanceView::RunGlanceView(QWidget* parent) : QWidget(parent) {
  note_ = new QLabel(tr("Run (F5) to watch the distribution of trapping times f<sub>t</sub> and the correlation "
                        "C<sub>τ</sub> grow here; the Statistics tab has all six plots."),
                     this);
  note_->setWordWrap(true);
  f_ = new StatisticsPlot(Statistic::f, this);
  c_ = new StatisticsPlot(Statistic::C, this);
  for (StatisticsPlot* p : {f_, c_}) p->setMinimumSize(160, 150);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 4, 2, 2);
  layout->addWidget(note_);
  layout->addWidget(f_, 1);
  layout->addWidget(c_, 1);
}

void RunGlanceView::showSnapshot(const RunSnapshotPtr& snapshot) {
  pending_ = snapshot;
  if (isVisible()) draw();
}

void RunGlanceView::clear() {
  note_->show();
  pending_.reset();
  drawn_.reset();
  f_->clearData();
  c_->clearData();
  f_->refresh();
  c_->refresh();
}

void RunGlanceView::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  draw();
}

void RunGlanceView::draw() {
  if (!pending_ || pending_ == drawn_) return;
  drawn_ = pending_;
  if (!drawn_->hasStatistics) {
    clear();
    return;
  }
  note_->hide();  // the plots speak for themselves once there is data
  for (StatisticsPlot* p : {f_, c_}) {
    p->setData(seriesOf(drawn_->statistics, p->statistic()), drawn_->theory);
    p->setBlockAffectedBelow(drawn_->statistics.blockAffectedBelow);
    p->refresh();
  }
}

}  // namespace archipelago::ui
