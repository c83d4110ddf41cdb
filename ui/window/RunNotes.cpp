#include "ui/window/RunNotes.hpp"

#include <QFile>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QMessageBox>
#include <QPushButton>

#include <utility>

namespace archipelago::ui {

CheckpointBanner::CheckpointBanner(RunController* run, std::function<RunSettings()> settings, QWidget* parent)
    : QFrame(parent), run_(run), settings_(std::move(settings)) {
  setObjectName(QStringLiteral("checkpointBanner"));
  setStyleSheet(QStringLiteral("#checkpointBanner { background: #fff6d6; border-bottom: 1px solid #e0c060; }"));
  auto* layout = new QHBoxLayout(this);
  label_ = new QLabel(this);
  label_->setWordWrap(true);
  auto* resume = new QPushButton(tr("Resume"), this);
  auto* discard = new QPushButton(tr("Discard"), this);
  connect(resume, &QPushButton::clicked, this, &CheckpointBanner::resume);
  connect(discard, &QPushButton::clicked, this, &CheckpointBanner::discard);
  layout->addWidget(label_, 1);
  layout->addWidget(resume);
  layout->addWidget(discard);
  hide();
}

bool CheckpointBanner::offerIfKept() {
  const QString path = RunController::checkpointPath();
  if (!QFileInfo::exists(path)) return false;
  label_->setText(tr("An unfinished run was kept when the window closed: %1").arg(path));
  show();
  return true;
}

void CheckpointBanner::resume() {
  const QString path = RunController::checkpointPath();
  if (!QFileInfo::exists(path)) {
    Q_EMIT statusMessage(tr("There is no checkpoint"), 6000);
    return;
  }
  QString error;
  if (!run_->open(path, &error, /*resumeWhenReady=*/true, settings_())) {
    if (error != tr("Cancelled")) QMessageBox::warning(window(), tr("Cannot resume the checkpoint"), error);
    return;
  }
  // Once resumed, the window holds the run; closing again mid-run writes a fresh checkpoint.
  hide();
  QFile::remove(path);
}

void CheckpointBanner::discard() {
  QFile::remove(RunController::checkpointPath());
  hide();
  Q_EMIT statusMessage(tr("Checkpoint discarded"), 6000);
}

StaleRunNote::StaleRunNote(QWidget* parent) : QLabel(parent) {
  setObjectName(QStringLiteral("staleRunNote"));
  setWordWrap(true);
  setContentsMargins(8, 4, 8, 4);
  setStyleSheet(QStringLiteral("#staleRunNote { background: #eef3fb; border-bottom: 1px solid #b8c8e0; }"));
  hide();
}

void StaleRunNote::showFor(const RunController& run, const std::optional<TrappingParameters>& params) {
  const RunSnapshotPtr& latest = run.latest();
  const bool stale = latest && !isLive(run.status()) && run.status() != RunStatus::paused &&
                     (!params || !(*params == latest->state.params));
  if (stale) {
    const TrappingParameters& p = latest->state.params;
    setText(tr("The plots show the %1 run of K = %2 (T = %3, M = %4); the parameters have changed since. "
               "Run (F5) starts a run with the new ones.")
                .arg(statusName(run.status()), QString::number(p.map.K, 'g', 6))
                .arg(p.T)
                .arg(p.M));
  }
  setVisible(stale);
}

RunAnswer askRunQuestion(QWidget* parent, const RunQuestion& q) {
  if (q.kind == RunQuestion::Kind::quitWhileLive) {
    const auto answer = QMessageBox::question(parent, q.title, q.text, QMessageBox::Yes | QMessageBox::Cancel,
                                              QMessageBox::Cancel);
    return answer == QMessageBox::Yes ? RunAnswer::discard : RunAnswer::cancel;
  }
  const auto answer = QMessageBox::warning(parent, q.title, q.text,
                                           QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel,
                                           QMessageBox::Save);
  if (answer == QMessageBox::Save) return RunAnswer::save;
  if (answer == QMessageBox::Discard) return RunAnswer::discard;
  return RunAnswer::cancel;
}

}  // namespace archipelago::ui
