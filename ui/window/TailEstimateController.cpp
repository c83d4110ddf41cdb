#include "ui/window/TailEstimateController.hpp"

#include <QFileInfo>
#include <QLocale>

#include <string>

#include "core/tail/BruteForceSurvival.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailResult.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/plots/StatisticsPlot.hpp"
#include "ui/run/RunController.hpp"

namespace archipelago::ui {

/// What the job found (on a worker thread, from the file and the run's immutable snapshot).
struct TailEstimateController::Estimate {
  QString refusal;  // why it is not drawn (empty: drawn)
  TailRequest request;
  Series levels;    // the reliable levels, in the run's units
  double factor = 1;
  double largestReliableT = 0;
};

namespace {
QString noRun() { return TailEstimateController::tr("there is no run to compare it with: open or start the run first"); }

QString otherProcess(const std::string& mismatch) {
  return TailEstimateController::tr("it samples another process than the run's: %1").arg(QString::fromStdString(mismatch));
}
}  // namespace

TailEstimateController::TailEstimateController(RunController* run, StatisticsPlot* plot, QObject* parent)
    : QObject(parent), run_(run), plot_(plot), jobs_(std::make_unique<BackgroundJobs>(this)) {
  connect(run_, &RunController::runReplaced, this, [this] { file_.clear(); });
}

TailEstimateController::~TailEstimateController() = default;

bool TailEstimateController::open(const QString& path, QString* error) {
  const RunSnapshotPtr shown = run_->latest();
  if (!shown || !shown->hasStatistics) {
    if (error) *error = noRun();
    Q_EMIT refused(tr("Cannot draw the tail estimate"), path, noRun());
    return false;
  }
  Job<std::shared_ptr<const Estimate>> job;  // latest wins: a second file replaces the first
  job.work = [file = path.toStdString(), shown](JobContext<NoProgress>&) -> std::optional<std::shared_ptr<const Estimate>> {
    auto e = std::make_shared<Estimate>();
    const TailState tail = loadTailFile(file);  // throws: the failure's message is core's
    e->request = tail.request;
    if (const auto mismatch = tailRunMismatch(tail.request, shown->state)) {
      e->refusal = otherProcess(*mismatch);
      return e;
    }
    const TailResult result = tailResult(tail);
    e->levels = reliableSurvivalIn(result, shown->state, shown->statistics, &e->factor);
    e->largestReliableT = largestReliableT(result);
    if (e->levels.x.empty()) e->refusal = tr("it has no reliable level yet");
    return e;
  };
  job.done = [this, path](JobResult<std::shared_ptr<const Estimate>> r) {
    request_ = 0;
    Q_EMIT pendingChanged(false);
    finish(path, r.ok() ? *r.value : nullptr, r.error);
  };
  request_ = jobs_->submit(std::move(job));
  Q_EMIT pendingChanged(true);
  Q_EMIT statusMessage(tr("Reading the tail estimate %1…").arg(QFileInfo(path).fileName()), 0);
  return true;
}

QString TailEstimateController::refusalNow(const Estimate& e) const {
  if (!e.refusal.isEmpty()) return e.refusal;
  const RunSnapshotPtr now = run_->latest();
  if (!now || !now->hasStatistics) return noRun();  // the run was closed while the file was read
  if (const auto mismatch = tailRunMismatch(e.request, now->state)) return otherProcess(*mismatch);  // or another opened
  return {};
}

void TailEstimateController::finish(const QString& path, const std::shared_ptr<const Estimate>& estimate,
                                    const QString& error) {
  const QString why = estimate ? refusalNow(*estimate) : error;
  if (why.isEmpty()) {
    show(path, *estimate);
    return;
  }
  Q_EMIT refused(tr("Cannot draw the tail estimate"), path, why);
  Q_EMIT finished(path, why);
}

void TailEstimateController::show(const QString& path, const Estimate& e) {
  // A short legend entry (issue 37, finding 5: the whole description was cut off at the canvas' edge); the details
  // go to the status bar.
  QString details = tr("tail %1 × %2, %3 reliable levels").arg(e.request.population).arg(e.request.replicas).arg(e.levels.x.size());
  if (e.factor != 1)  // spliced statistics count the q = 1 process's segments
    details += tr(", × %1 (α₁/α_q)").arg(QLocale::c().toString(e.factor, 'g', 3));
  plot_->setEstimate(e.levels, tr("P_t by splitting (tail)"));
  file_ = QFileInfo(path).absoluteFilePath();
  Q_EMIT shown(file_);
  plot_->refresh();
  Q_EMIT statusMessage(tr("Drew %1 levels of %2 to t = %3 steps on P_t (%4)")
                           .arg(e.levels.x.size())
                           .arg(QFileInfo(path).fileName())
                           .arg(QLocale::c().toString(e.largestReliableT, 'g', 3))
                           .arg(details),
                       6000);
  Q_EMIT finished(path, QString());
}

}  // namespace archipelago::ui
