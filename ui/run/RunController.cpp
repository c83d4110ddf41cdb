#include "ui/run/RunController.hpp"

#include <filesystem>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStandardPaths>

#include <exception>

#include "core/atlas/BoxIslandCheck.hpp"
#include "core/runfile/RunFile.hpp"
#include "ui/jobs/DurationText.hpp"

namespace archipelago::ui {

std::optional<RunStatus> runTransition(RunStatus from, RunEvent event) noexcept {
  using S = RunStatus;
  using E = RunEvent;
  switch (event) {
    case E::start:  // a new run replaces a run that is not computing
      if (isLive(from)) return std::nullopt;
      return S::running;
    case E::pause:
      if (from == S::running) return S::pausing;
      return std::nullopt;
    case E::resume:
      if (from == S::paused) return S::running;
      return std::nullopt;
    case E::stop:
      if (from == S::running || from == S::pausing) return S::stopping;
      if (from == S::paused) return S::stopped;
      return std::nullopt;
    case E::workerPaused:
      if (from == S::pausing || from == S::running) return S::paused;  // running: an analysed file
      return std::nullopt;
    case E::workerStopped:
      if (from == S::stopping) return S::stopped;
      return std::nullopt;
    case E::workerFinished:
      if (isLive(from)) return S::finished;
      return std::nullopt;
    case E::workerFailed:
      if (isLive(from)) return S::failed;
      return std::nullopt;
    case E::clear:
      if (isLive(from)) return std::nullopt;
      return S::idle;
  }
  return std::nullopt;
}

bool isLive(RunStatus s) noexcept {
  return s == RunStatus::running || s == RunStatus::pausing || s == RunStatus::stopping;
}

QString statusName(RunStatus s) {
  switch (s) {
    case RunStatus::idle: return QObject::tr("idle");
    case RunStatus::running: return QObject::tr("running");
    case RunStatus::pausing: return QObject::tr("pausing");
    case RunStatus::paused: return QObject::tr("paused");
    case RunStatus::stopping: return QObject::tr("stopping");
    case RunStatus::stopped: return QObject::tr("stopped");
    case RunStatus::finished: return QObject::tr("finished");
    case RunStatus::failed: return QObject::tr("failed");
  }
  return {};
}

RunController::RunController(QObject* parent) : QObject(parent) {
  qRegisterMetaType<RunStatus>("archipelago::ui::RunStatus");
  worker_ = new RunWorker(this);
  connect(worker_, &RunWorker::snapshotReady, this, &RunController::onSnapshot, Qt::QueuedConnection);
  connect(worker_, &RunWorker::runEnded, this, &RunController::onRunEnded, Qt::QueuedConnection);
}

RunController::~RunController() {
  delete worker_;  // aborts the session and waits for its thread before anything it reports to goes away
}

bool RunController::canResume() const noexcept {
  return status_ == RunStatus::paused && latest_ && !latest_->state.finished();
}

bool RunController::apply(RunEvent event) {
  const auto next = runTransition(status_, event);
  if (!next) return false;
  status_ = *next;
  Q_EMIT statusChanged(status_);
  return true;
}

RunAnswer RunController::ask(RunQuestion::Kind kind) {
  RunQuestion q{kind, {}, {}};
  const QString where = currentFile_.isEmpty() ? QString() : tr(" (last saved to %1)").arg(currentFile_);
  switch (kind) {
    case RunQuestion::Kind::discardUnsaved:
      q.title = tr("Unsaved run");
      q.text = tr("The %1 run has blocks that are in no file%2. Save it before it is replaced?")
                   .arg(statusName(status_), where);
      break;
    case RunQuestion::Kind::quitWhileLive:
      q.title = tr("A run is in progress");
      q.text = tr("Stop the run and quit? Its state is kept as a checkpoint that the next start offers to resume.");
      break;
    case RunQuestion::Kind::quitUnsaved:
      q.title = tr("Unsaved run");
      q.text = tr("The %1 run has blocks that are in no file%2. Save it before quitting?").arg(statusName(status_), where);
      break;
  }
  return ask_ ? ask_(q) : RunAnswer::discard;
}

bool RunController::confirmDiscard() {
  if (isLive(status_)) return false;
  if (!unsaved_ || !latest_) return true;
  switch (ask(RunQuestion::Kind::discardUnsaved)) {
    case RunAnswer::cancel: return false;
    case RunAnswer::discard: return !isLive(status_);
    case RunAnswer::save:
      if (!(save_ ? save_() : (!currentFile_.isEmpty() && save(currentFile_)))) return false;
      return !isLive(status_);
  }
  return false;
}

void RunController::launch(TrappingState state, const RunSettings& settings) {
  runId_ += 1;
  latest_.reset();
  unsaved_ = true;
  worker_->startRun(runId_, std::move(state), settings);
}

bool RunController::start(const TrappingParameters& parameters, const RunSettings& settings, QString* error) {
  if (isLive(status_)) {
    if (error) *error = tr("A run is computing: pause or stop it first");
    return false;
  }
  if (!confirmDiscard()) return false;
  TrappingState state;
  try {
    state = startTrapping(parameters);
  } catch (const std::exception& e) {
    const QString text = tr("Cannot start: %1").arg(QString::fromStdString(e.what()));
    if (error) *error = text;
    Q_EMIT message(text, true);
    return false;
  }
  resumeWhenReady_.reset();
  currentFile_.clear();
  Q_EMIT currentFileChanged(currentFile_);
  Q_EMIT runReplaced();
  launch(std::move(state), settings);
  apply(RunEvent::start);
  // Core's one message when the box or its randomizing zone cuts the central island (issue 39): the run goes on,
  // the warning stays in the status bar until the next message.
  if (const BoxIslandCheck check = checkBoxAgainstIsland(parameters.map, parameters.Xr); check.cuts())
    Q_EMIT message(tr("Running. Warning: %1").arg(QString::fromStdString(check.warning)), true);
  else
    Q_EMIT message(tr("Running…"), false);
  return true;
}

bool RunController::pause() {
  if (!apply(RunEvent::pause)) return false;
  worker_->requestEnd(runId_, RunEnd::paused);
  Q_EMIT message(tr("Pausing at the next chunk boundary…"), false);
  return true;
}

bool RunController::stop() {
  const RunStatus before = status_;
  if (!apply(RunEvent::stop)) return false;
  if (before == RunStatus::paused) {
    const TrappingState& s = latest_->state;
    Q_EMIT message(tr("Stopped at block %1 of %2; the run can be saved").arg(s.blocksDone).arg(s.params.T), true);
    return true;
  }
  worker_->requestEnd(runId_, RunEnd::stopped);
  Q_EMIT message(tr("Stopping at the next chunk boundary…"), false);
  return true;
}

bool RunController::resume(const RunSettings& settings) {
  if (!canResume()) return false;
  const std::uint64_t at = latest_->state.blocksDone, total = latest_->state.params.T;
  launch(latest_->state, settings);
  apply(RunEvent::resume);
  Q_EMIT message(tr("Resumed at block %1 of %2").arg(at).arg(total), false);
  return true;
}

bool RunController::open(const QString& path, QString* error, bool resumeWhenReady, const RunSettings& settings) {
  if (isLive(status_)) {
    const QString e = tr("Stop or pause the run before opening another");
    if (error) *error = e;
    Q_EMIT message(e, false);
    return false;
  }
  TrappingState state;
  std::shared_ptr<const TrappingState> companion;
  try {
    state = loadRunFile(path.toStdString());
    // Its q = 1 companion beside it (issue #26: `run` writes k01.short.json next to k01.json): the spliced
    // statistics.  A companion that does not load is named, and the run is shown without it.
    const std::filesystem::path shortFile = companionRunFile(path.toStdString());
    if (state.params.q > 1 && std::filesystem::exists(shortFile)) {
      try {
        companion = std::make_shared<const TrappingState>(loadRunFile(shortFile));
      } catch (const std::exception& e) {
        Q_EMIT message(tr("The companion %1 is not used: %2")
                           .arg(QString::fromStdString(shortFile.string()), QString::fromStdString(e.what())),
                       true);
      }
    }
  } catch (const std::exception& e) {
    const QString text = QString::fromStdString(e.what());
    if (error) *error = text;
    Q_EMIT message(tr("Cannot open %1: %2").arg(path, text), true);
    return false;
  }
  if (!confirmDiscard()) {
    if (error) *error = tr("Cancelled");
    return false;
  }
  resumeWhenReady_.reset();
  if (resumeWhenReady) resumeWhenReady_ = settings;
  analyse(std::move(state), path, std::move(companion));
  Q_EMIT message(tr("Opened %1").arg(path), false);
  return true;
}

bool RunController::adopt(TrappingState state, QString* error) {
  if (isLive(status_)) {
    if (error) *error = tr("Stop or pause the run first");
    return false;
  }
  if (!confirmDiscard()) {
    if (error) *error = tr("Cancelled");
    return false;
  }
  resumeWhenReady_.reset();
  analyse(std::move(state), QString());
  return true;
}

bool RunController::clear() {
  if (isLive(status_) || !confirmDiscard()) return false;
  Q_EMIT runReplaced();
  runId_ += 1;
  latest_.reset();
  unsaved_ = false;
  resumeWhenReady_.reset();
  currentFile_.clear();
  Q_EMIT currentFileChanged(currentFile_);
  apply(RunEvent::clear);
  return true;
}

void RunController::analyse(TrappingState state, const QString& path, std::shared_ptr<const TrappingState> companion) {
  Q_EMIT runReplaced();
  Q_EMIT runOpened(state.params);
  runId_ += 1;
  latest_.reset();
  unsaved_ = false;
  currentFile_ = path;
  Q_EMIT currentFileChanged(currentFile_);
  // The analysis is a short worker session: the run is live (nothing else may start) until it answers.
  apply(RunEvent::start);
  worker_->analyse(runId_, std::move(state), std::move(companion));
}

bool RunController::save(const QString& path, QString* error) {
  if (!latest_) {
    if (error) *error = tr("There is no run to save");
    return false;
  }
  try {
    saveRunFile(path.toStdString(), latest_->state);
    if (latest_->companion) saveRunFile(companionRunFile(path.toStdString()), *latest_->companion);
  } catch (const std::exception& e) {
    const QString text = QString::fromStdString(e.what());
    if (error) *error = text;
    Q_EMIT message(tr("Cannot save: %1").arg(text), true);
    return false;
  }
  currentFile_ = path;
  // A live run goes on computing blocks that are not in the file.
  unsaved_ = isLive(status_);
  Q_EMIT currentFileChanged(currentFile_);
  Q_EMIT message(tr("Saved %1 (block %2 of %3)").arg(path).arg(latest_->state.blocksDone).arg(latest_->state.params.T),
                 false);
  return true;
}

void RunController::onSnapshot(const RunSnapshotPtr& snapshot) {
  worker_->snapshotConsumed();
  if (!snapshot || snapshot->runId != runId_) return;  // a stale run: drop it
  latest_ = snapshot;
}

void RunController::onRunEnded(quint64 runId, const RunSnapshotPtr& last, RunEnd how, const QString& text) {
  if (runId != runId_) return;
  if (how == RunEnd::failed || !last) {
    apply(RunEvent::workerFailed);
    resumeWhenReady_.reset();
    Q_EMIT message(tr("The run failed: %1").arg(text), true);
    if (closeAfterStop_) finishClose();
    return;
  }
  latest_ = last;
  const TrappingState& s = last->state;
  if (s.finished()) {
    apply(RunEvent::workerFinished);
    resumeWhenReady_.reset();
    Q_EMIT message(tr("Finished: %1 blocks × %2 orbits in %3").arg(s.params.T).arg(s.params.M)
                       .arg(formatDuration(s.elapsedSeconds)), true);
  } else if (how == RunEnd::stopped || status_ == RunStatus::stopping) {
    // Stopped — also an opened file whose analysis (which cannot be cut short) ends after Stop was pressed.
    apply(RunEvent::workerStopped);
    resumeWhenReady_.reset();
    Q_EMIT message(tr("Stopped at block %1 of %2; the run can be saved").arg(s.blocksDone).arg(s.params.T), true);
  } else {
    apply(RunEvent::workerPaused);  // paused, or an analysed run file that is not finished
    if (resumeWhenReady_ && !closeAfterStop_) {
      const RunSettings settings = *resumeWhenReady_;
      resumeWhenReady_.reset();
      resume(settings);
    } else {
      Q_EMIT message(tr("Paused at block %1 of %2 (%3 %)").arg(s.blocksDone).arg(s.params.T)
                         .arg(100.0 * last->progress.fraction, 0, 'f', 1), true);
    }
  }
  if (closeAfterStop_ && !isLive(status_)) finishClose();
}

bool RunController::requestClose() {
  if (closeAfterStop_) return false;  // already stopping to close: closeReady() follows
  if (isLive(status_)) {
    if (ask(RunQuestion::Kind::quitWhileLive) == RunAnswer::cancel) return false;
    // The dialog ran an event loop: the run may have ended meanwhile (finished, failed).
    if (!isLive(status_)) {
      QString error;
      if (!unsaved_ || !latest_ || writeCheckpoint(&error)) return true;
      Q_EMIT message(tr("%1. The window stays open: save the run before quitting.").arg(error), true);
      return false;
    }
    closeAfterStop_ = true;
    resumeWhenReady_.reset();
    if (status_ != RunStatus::stopping) {
      apply(RunEvent::stop);
      worker_->requestEnd(runId_, RunEnd::stopped);
    }
    Q_EMIT message(tr("Stopping the run to keep a checkpoint…"), true);
    return false;
  }
  if (unsaved_ && latest_) {
    switch (ask(RunQuestion::Kind::quitUnsaved)) {
      case RunAnswer::cancel: return false;
      case RunAnswer::discard: return !isLive(status_);
      case RunAnswer::save: return (save_ ? save_() : (!currentFile_.isEmpty() && save(currentFile_))) && !isLive(status_);
    }
  }
  return true;
}

void RunController::finishClose() {
  closeAfterStop_ = false;
  QString error;
  if (latest_ && unsaved_ && !writeCheckpoint(&error)) {
    // Never lose the run: the window stays open with the stopped run, which can still be saved elsewhere.
    Q_EMIT message(tr("%1. The window stays open: save the run (Ctrl+Shift+S) before quitting.").arg(error), true);
    return;
  }
  Q_EMIT closeReady();
}

QString RunController::checkpointPath() {
  return QDir(QStandardPaths::writableLocation(QStandardPaths::AppDataLocation))
      .filePath(QStringLiteral("checkpoint.json"));
}

bool RunController::writeCheckpoint(QString* error) {
  if (!latest_) return false;
  try {
    QDir().mkpath(QFileInfo(checkpointPath()).absolutePath());
    saveRunFile(checkpointPath().toStdString(), latest_->state);
  } catch (const std::exception& e) {
    if (error) *error = tr("Could not keep a checkpoint: %1").arg(QString::fromStdString(e.what()));
    return false;
  }
  unsaved_ = false;
  Q_EMIT message(tr("Checkpoint kept in %1").arg(checkpointPath()), true);
  return true;
}

}  // namespace archipelago::ui
