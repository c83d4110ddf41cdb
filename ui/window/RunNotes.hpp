#pragma once
/// \file RunNotes.hpp
/// \brief What the window tells and asks about the run: the banner of a checkpoint kept when the window closed during
/// a run (Resume, Discard), the note that the plots show a run whose parameters differ from the panel's, and the
/// RunController's questions as message boxes.

#include <QFrame>
#include <QLabel>

#include <functional>
#include <optional>

#include "ui/run/RunController.hpp"

namespace archipelago::ui {

/// "An unfinished run was kept when the window closed: <path>", with Resume and Discard (RunController's
/// checkpointPath()).
class CheckpointBanner : public QFrame {
  Q_OBJECT
 public:
  /// The checkpoint of `run`, resumed with `settings` (the threads and companion of the parameter panel).
  CheckpointBanner(RunController* run, std::function<RunSettings()> settings, QWidget* parent);
  /// Shows the banner when a checkpoint is kept; true then.
  bool offerIfKept();
  /// Run ▸ Resume Checkpoint and the banner's Resume: the run opened from the checkpoint, resumed once ready, and
  /// the checkpoint removed (closing again mid-run writes a fresh one).
  void resume();
  void discard();

 Q_SIGNALS:
  void statusMessage(const QString& text, int timeoutMs);

 private:
  RunController* run_;
  std::function<RunSettings()> settings_;
  QLabel* label_ = nullptr;
};

/// The note over the plots when they show a finished, stopped or opened run whose parameters are not the panel's.
class StaleRunNote : public QLabel {
  Q_OBJECT
 public:
  explicit StaleRunNote(QWidget* parent);
  /// Shown or hidden for `run` against the panel's `parameters` (none: invalid).
  void showFor(const RunController& run, const std::optional<TrappingParameters>& parameters);
  /// The note as shown (empty when hidden).
  [[nodiscard]] QString note() const { return isHidden() ? QString() : text(); }
};

/// The RunController's question `q` in a message box of `parent`: Yes or Cancel before quitting during a run, else
/// Save, Discard or Cancel.
[[nodiscard]] RunAnswer askRunQuestion(QWidget* parent, const RunQuestion& q);

}  // namespace archipelago::ui
