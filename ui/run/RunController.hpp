#pragma once
/// \file RunController.hpp
/// \brief The one owner of the run on screen: its state machine, its worker, its files and its checkpoint.
///
/// States (RunStatus) and the events that move between them are one table, runTransition(); the controller
/// applies it and nothing else changes the status.  The table, as a user sees it:
///
///   idle ──start──▶ running ──pause──▶ pausing ──(chunk boundary)──▶ paused ──resume──▶ running
///                    │  ▲                 │                           │
///                    │  └──── resume ─────┼───────────────────────────┘
///                    ├──stop──▶ stopping ◀┘ (stop while pausing)      └──stop──▶ stopped (at once)
///                    ├──(last block)──▶ finished        stopping ──(chunk boundary)──▶ stopped
///                    └──(error)──▶ failed
///
/// A run that ends by itself while a pause or stop is on its way ends as finished.  `stopped` is final: the
/// run keeps its state (it can be saved, and a saved file can be resumed later) but Resume no longer
/// applies — Pause is the way to continue later.  Opening a run file analyses it off the GUI thread and ends
/// in paused (unfinished: Resume continues it) or finished.  Start, open and quit from a run that holds work
/// not written to a file go through ask(): discarding unsaved work always asks (the window answers with a
/// dialog, tests with a script).
///
/// Threads: the RunWorker owns the computation; the controller hands it a TrappingState and receives
/// immutable RunSnapshots through queued signals; snapshots of any other run id are dropped.  latest() is
/// the newest snapshot of the run on screen.

#include <QObject>
#include <QString>

#include <functional>
#include <optional>

#include "ui/run/RunSnapshot.hpp"
#include "ui/run/RunWorker.hpp"

namespace archipelago::ui {

/// Where the run shown in the window stands.
enum class RunStatus { idle, running, pausing, paused, stopping, stopped, finished, failed };

/// What happens to the run: commands of the user, and what the worker reports.
enum class RunEvent {
  start,           ///< a new run (or an opened file being analysed) replaces the current one
  pause,
  resume,
  stop,
  workerPaused,    ///< the session ended at a chunk boundary after a pause request (or an analysed file)
  workerStopped,   ///< the session ended at a chunk boundary after a stop request
  workerFinished,  ///< the last block is done
  workerFailed,
  clear,           ///< nothing on screen any more (a session without a run)
};

/// The state machine: the status after `event` in `from`, or nothing when the event does not apply there.
[[nodiscard]] std::optional<RunStatus> runTransition(RunStatus from, RunEvent event) noexcept;
/// running, pausing or stopping: a worker session computes this run.
[[nodiscard]] bool isLive(RunStatus status) noexcept;
/// A user-facing name ("running", "paused", …).
[[nodiscard]] QString statusName(RunStatus status);

/// A question the controller needs answered before it throws work away.
struct RunQuestion {
  enum class Kind {
    discardUnsaved,  ///< start/open over a run with unsaved work: save, discard or cancel
    quitWhileLive,   ///< quit during a run: stop and keep a checkpoint, or cancel
    quitUnsaved,     ///< quit with a run that has unsaved work: save, discard or cancel
  };
  Kind kind;
  QString title;
  QString text;
};
enum class RunAnswer { save, discard, cancel };

class RunController : public QObject {
  Q_OBJECT
 public:
  explicit RunController(QObject* parent = nullptr);
  ~RunController() override;

  [[nodiscard]] RunStatus status() const noexcept { return status_; }
  /// The newest snapshot of the run on screen (null before any run or file).
  [[nodiscard]] const RunSnapshotPtr& latest() const noexcept { return latest_; }
  /// The run holds blocks that are in no file (a checkpoint on quit counts as a file).
  [[nodiscard]] bool unsaved() const noexcept { return unsaved_; }
  [[nodiscard]] bool canResume() const noexcept;
  /// The file the run was opened from or last saved to (empty when none).
  [[nodiscard]] const QString& currentFile() const noexcept { return currentFile_; }
  [[nodiscard]] const RunWorker& worker() const noexcept { return *worker_; }

  /// How unsaved work is handled: the answer to a question.  Without one, the answer is `discard`
  /// (scripts).  The function may run a nested event loop (a modal dialog): the controller re-reads its
  /// state after it returns.
  void setAsk(std::function<RunAnswer(const RunQuestion&)> ask) { ask_ = std::move(ask); }
  /// How `save` answers are carried out (the window shows a save dialog when there is no current file);
  /// returns false when nothing was saved.  Without one, save = the current file, else nothing.
  void setSaveHandler(std::function<bool()> save) { save_ = std::move(save); }

  // Commands.  Each returns false when it does not apply now (or the user cancelled); `error` says why.
  bool start(const TrappingParameters& parameters, const RunSettings& settings, QString* error = nullptr);
  bool pause();
  bool resume(const RunSettings& settings);
  bool stop();
  /// Opens a run file: loads it (core validates it), asks when unsaved work would be lost, analyses it off the
  /// GUI thread; ends in paused or finished.  With `resumeWhenReady`, it continues as soon as it is analysed.
  bool open(const QString& path, QString* error = nullptr, bool resumeWhenReady = false,
            const RunSettings& settings = {});
  /// Shows a run that is already in memory (a session's embedded run): analysed like an opened file; no current
  /// file, nothing unsaved (it is in the session).  Asks before unsaved work is lost.
  bool adopt(TrappingState state, QString* error = nullptr);
  /// Nothing on screen any more (idle).  Asks before unsaved work is lost; false when it is live or cancelled.
  bool clear();
  /// Writes the newest state (atomically, through core) and makes it the current file.
  bool save(const QString& path, QString* error = nullptr);
  /// The run as it is now was written into a session file (embedded): quitting or replacing it loses nothing,
  /// so nothing asks (issue 25, finding 13).  A live run goes on computing blocks that are in no file.
  void markSavedInSession() noexcept { unsaved_ = isLive(status_); }
  /// Called when the window is asked to close.  True: close now.  False: not yet — either the user cancelled,
  /// or the run is stopping and closeReady() follows once its checkpoint is written.
  bool requestClose();
  /// True while a close waits for the run to stop.
  [[nodiscard]] bool closing() const noexcept { return closeAfterStop_; }
  /// Asks before unsaved work is discarded (start, open, session).  True: go on.
  bool confirmDiscard();

  /// Where a run interrupted by closing the window is kept.
  [[nodiscard]] static QString checkpointPath();
  bool writeCheckpoint(QString* error = nullptr);

 Q_SIGNALS:
  void statusChanged(archipelago::ui::RunStatus status);
  /// A one-line account of what happened, for the status bar (`sticky`: keep it until the next one).
  void message(const QString& text, bool sticky);
  /// A new run or file replaces the one on screen: views clear what they show of the old one.
  void runReplaced();
  /// The current file changed (opened or saved), or was cleared by a new run.
  void currentFileChanged(const QString& path);
  /// A run from a file or a session is about to be shown: the window shows its parameters.
  void runOpened(const archipelago::TrappingParameters& parameters);
  /// A close requested while the run was live can now go ahead (the checkpoint is written or failed).
  void closeReady();

 private:
  bool apply(RunEvent event);
  void launch(TrappingState state, const RunSettings& settings);
  void onSnapshot(const RunSnapshotPtr& snapshot);
  void onRunEnded(quint64 runId, const RunSnapshotPtr& last, RunEnd how, const QString& text);
  RunAnswer ask(RunQuestion::Kind kind);
  void finishClose();
  void analyse(TrappingState state, const QString& path, std::shared_ptr<const TrappingState> companion = {});

  RunWorker* worker_ = nullptr;
  RunStatus status_ = RunStatus::idle;
  quint64 runId_ = 0;
  RunSnapshotPtr latest_;
  QString currentFile_;
  bool unsaved_ = false;
  bool closeAfterStop_ = false;
  std::optional<RunSettings> resumeWhenReady_;
  std::function<RunAnswer(const RunQuestion&)> ask_;
  std::function<bool()> save_;
};

}  // namespace archipelago::ui

Q_DECLARE_METATYPE(archipelago::ui::RunStatus)
