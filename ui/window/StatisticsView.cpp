#include "ui/window/StatisticsView.hpp"

#include <QElapsedTimer>
#include <QGridLayout>
#include <QLabel>
#include <QLocale>
#include <QShortcut>
#include <QTextDocument>
#include <QVBoxLayout>

#include <cmath>

#include "core/stats/RunSummary.hpp"
#include "ui/plots/StatisticsPlot.hpp"

namespace archipelago::ui {

namespace {
QString withError(double v, double e) {
  if (e > 0) return QStringLiteral("%1 ± %2").arg(v, 0, 'g', 4).arg(e, 0, 'g', 2);
  return QString::number(v, 'g', 4);
}
}  // namespace

StatisticsView::StatisticsView(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  summary_ = new QLabel(this);
  summary_->setObjectName(QStringLiteral("statisticsSummary"));
  summary_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  summary_->setWordWrap(true);  // a long summary wraps instead of widening the window
  summary_->setText(tr("No statistics yet: choose a preset and press Run (F5)."));
  layout->addWidget(summary_);
  // The tail's γ_P and verdict (issue 37, finding 19): core's run summary, in `stats`'s words.
  tail_ = new QLabel(this);
  tail_->setObjectName(QStringLiteral("statisticsTail"));
  tail_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  tail_->setWordWrap(true);
  tail_->setVisible(false);
  layout->addWidget(tail_);
  auto* grid = new QGridLayout;
  grid->setSpacing(6);
  // The table's order is the paper's reading order: fig. 6 (f, P, C, exponent), then fig. 7 (S, D_t).
  int i = 0;
  for (const StatisticInfo& info : statisticsTable()) {
    if (!info.plotted) continue;
    auto* plot = new StatisticsPlot(info.statistic, this);
    connect(plot, &StatisticsPlot::enlargeToggled, this, [this, plot] { enlarge(enlarged_ == plot ? nullptr : plot); });
    plots_.append(plot);
    grid->addWidget(plot, i / 3, i % 3);
    ++i;
  }
  layout->addLayout(grid, 1);
  auto* back = new QShortcut(QKeySequence(Qt::Key_Escape), this, [this] { enlarge(nullptr); });
  back->setContext(Qt::WidgetWithChildrenShortcut);
}

void StatisticsView::enlarge(StatisticsPlot* plot) {
  enlarged_ = plot;
  for (StatisticsPlot* p : std::as_const(plots_)) {
    p->setVisible(!plot || p == plot);
    p->setEnlarged(p == plot);
  }
}

StatisticsPlot* StatisticsView::plot(Statistic statistic) const {
  for (StatisticsPlot* p : plots_)
    if (p->statistic() == statistic) return p;
  return nullptr;
}

void StatisticsView::showSnapshot(const RunSnapshot& snapshot) {
  if (!snapshot.hasStatistics) {
    clear();
    return;
  }
  QElapsedTimer clock;
  clock.start();
  const TrappingStatistics& s = snapshot.statistics;
  for (StatisticsPlot* plot : std::as_const(plots_)) {
    plot->setData(seriesOf(s, plot->statistic()), snapshot.theory);
    plot->setBlockAffectedBelow(s.blockAffectedBelow);
    plot->refresh();
  }
  ++refreshes_;
  refreshSeconds_ += static_cast<double>(clock.nsecsElapsed()) * 1e-9;
  const QLocale c = QLocale::c();
  // Spliced statistics (the q = 1 companion below 10 q) say so: α changes when they replace the run's own (issue 37,
  // finding 7: it fell from 18.9 to 2.72 with no word why).
  const QString spliced = snapshot.companion
                              ? tr(" <i>(spliced: t &lt; %1 steps from the q = 1 companion run)</i>")
                                    .arg(10 * snapshot.state.params.q)
                              : QString();
  summary_->setText(tr("<b>α</b> (mean segment) = %1 steps%6 &nbsp;&nbsp; <b>D</b> = %2 &nbsp;&nbsp; "
                       "Σ t f<sub>t</sub> = %3 &nbsp;&nbsp; segments: %4 &nbsp;&nbsp; longest: %5 steps")
                        .arg(withError(s.alpha, s.alphaError), dText(snapshot),
                             QString::number(s.sumTf, 'f', 4), c.toString(static_cast<qulonglong>(s.segments)),
                             longestText(snapshot))
                        .arg(spliced));
  const QString tail = tailHtml(snapshot);
  tail_->setText(tail);
  tail_->setVisible(!tail.isEmpty());
}

QString StatisticsView::longestText(const RunSnapshot& snapshot) {
  // The exact longest segment is the first of the kept records (the Long segments table's first row); without
  // records (longestKept = 0) only its histogram bin is known, an upper bound.
  const QLocale c = QLocale::c();
  const auto& items = snapshot.state.longest.items();
  if (!items.empty())
    return c.toString(static_cast<qulonglong>(items.front().length * snapshot.state.params.q));
  return tr("≤ %1").arg(c.toString(static_cast<double>(snapshot.statistics.longestBlocks) * snapshot.state.params.q, 'g', 4));
}

RunSummary StatisticsView::summaryOf(const RunSnapshot& snapshot) {
  return summarizeRun(snapshot.statistics, snapshot.tail.get(), "its error is judged when the run pauses or ends");
}

QString StatisticsView::dText(const RunSnapshot& snapshot) {
  // D, its error and the error's words from core's one run summary (issue 35; issue 37, finding 10: the GUI once
  // wrote its own label, "bootstrap over segments" beside the spliced D, where `stats` names the subsets' error).
  const RunSummary summary = summaryOf(snapshot);
  QString text = QString::number(summary.D, 'g', 4);
  if (std::isfinite(summary.DError)) text += QStringLiteral(" ± ") + QString::number(summary.DError, 'g', 2);
  return text + QStringLiteral(" <i>(%1)</i>").arg(QString::fromStdString(summary.DErrorNote).toHtmlEscaped());
}

QString StatisticsView::tailHtml(const RunSnapshot& snapshot) {
  const RunSummary summary = summaryOf(snapshot);
  if (!summary.judged) return {};
  return tr("<b>γ<sub>P</sub></b> (tail, P<sub>t</sub> ~ t<sup>−γ</sup>) = %1 &nbsp;&nbsp; <b>verdict</b>: %2")
      .arg(QString::fromStdString(summary.gammaPText).toHtmlEscaped(),
           QString::fromStdString(summary.tailVerdict).toHtmlEscaped());
}

void StatisticsView::clear() {
  for (StatisticsPlot* plot : std::as_const(plots_)) {
    plot->clearData();
    plot->resetZoom();
  }
  summary_->setText(tr("No trapped segment has ended yet."));
  tail_->clear();
  tail_->setVisible(false);
}

QString StatisticsView::summaryText() const { return summary_->text(); }

QString StatisticsView::tailText() const {
  QTextDocument document;
  document.setHtml(tail_->text());
  return document.toPlainText();
}

}  // namespace archipelago::ui
