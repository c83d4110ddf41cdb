#include "ui/window/RunProgressLabels.hpp"

#include <QLabel>
#include <QLocale>
#include <QProgressBar>
#include <QStatusBar>

#include "ui/jobs/DurationText.hpp"
#include "ui/run/RunSnapshot.hpp"
#include "ui/run/RunWorker.hpp"

namespace archipelago::ui {

namespace {
QString formatRate(double stepsPerSecond) {
  if (stepsPerSecond >= 1e9) return QObject::tr("%1 G steps/s").arg(stepsPerSecond / 1e9, 0, 'f', 2);
  if (stepsPerSecond >= 1e6) return QObject::tr("%1 M steps/s").arg(stepsPerSecond / 1e6, 0, 'f', 1);
  return QObject::tr("%1 steps/s").arg(stepsPerSecond, 0, 'f', 0);
}
}  // namespace

RunProgressLabels::RunProgressLabels(QStatusBar* bar) : QObject(bar) {
  progress_ = new QProgressBar(bar);
  progress_->setRange(0, 1000);
  progress_->setValue(0);
  progress_->setFormat(QStringLiteral("%p%"));
  progress_->setMinimumWidth(150);
  progress_->setMaximumWidth(320);
  progress_->setToolTip(tr("Blocks done / T"));
  rate_ = new QLabel(bar);
  rate_->setObjectName(QStringLiteral("rateLabel"));
  rate_->setToolTip(tr("Steps of N⁻¹ per second over all orbits (this session)"));
  eta_ = new QLabel(bar);
  eta_->setToolTip(tr("Time left at the current rate"));
  kernel_ = new QLabel(tr("kernel: %1").arg(RunWorker::kernelName()), bar);
  kernel_->setToolTip(tr("The block kernel that computes the run"));
  bar->addPermanentWidget(rate_);
  bar->addPermanentWidget(eta_);
  bar->addPermanentWidget(progress_);
  bar->addPermanentWidget(kernel_);
}

void RunProgressLabels::clearRate() {
  eta_->clear();
  rate_->clear();  // a rate belongs to a computing run
}

void RunProgressLabels::show(const RunSnapshot& s, bool live) {
  if (s.companionRunning && live) {
    showCompanion(s);
    return;
  }
  const QLocale c = QLocale::c();
  progress_->setToolTip(tr("Blocks done / T"));
  progress_->setValue(static_cast<int>(1000 * s.progress.fraction + 0.5));
  progress_->setFormat(tr("%p % · block %1 of %2")
                           .arg(c.toString(static_cast<double>(s.state.blocksDone), 'g', 3),
                                c.toString(static_cast<double>(s.state.params.T), 'g', 3)));
  rate_->setText(live && s.progress.stepsPerSecond > 0 ? formatRate(s.progress.stepsPerSecond) : QString());
  eta_->setText(live && s.progress.stepsPerSecond > 0 ? tr("ETA %1").arg(formatDuration(s.progress.etaSeconds))
                                                      : QString());
  showKernel(s);
}

void RunProgressLabels::showCompanion(const RunSnapshot& s) {
  // The run is done; its q = 1 companion gives the statistics below 10 q steps (issue 37, finding 7).
  progress_->setValue(static_cast<int>(1000 * s.companionFraction + 0.5));
  // A short label: the bar is at most 320 pixels (issue 53, finding 19: the longer one was clipped at 1280×800).
  progress_->setFormat(tr("q = 1 companion: %p %"));
  progress_->setToolTip(tr("The run has finished; its q = 1 companion (a fraction of its steps) now runs, so that "
                           "the statistics below 10 q steps are not those of blocks of q steps: t < %1 steps will "
                           "come from it. When it ends, the plots and α show the spliced statistics.")
                            .arg(10 * s.state.params.q));
  rate_->setText(QString());
  eta_->setText(tr("companion run"));
  showKernel(s);
}

void RunProgressLabels::showKernel(const RunSnapshot& s) {
  if (!s.kernel.empty()) kernel_->setText(tr("kernel: %1").arg(QString::fromStdString(s.kernel)));
}

}  // namespace archipelago::ui
