#pragma once
/// \file RunWorker.hpp
/// \brief The trapping run of the GUI: one session at a time, computed on a background job (ui/jobs).
///
/// Threads: the window hands the worker a request (a state to advance, or one to analyse only); it becomes a
/// job on the worker's BackgroundJobs channel, where the latest request wins: a session still going is
/// stopped at its next chunk boundary and whatever it would still report is dropped.  The job calls core's
/// runTrapping() and, at every chunk boundary, turns the state into a RunSnapshot (statistics and theory
/// computed there, off the GUI thread) and posts it; it never waits for the GUI.  When the GUI is slower than
/// the run, snapshots that would pile up are skipped (the next one supersedes them), so memory stays bounded.
/// Pause and stop are requestEnd(), which stops the session through its std::stop_source at the next chunk
/// boundary without dropping its result: the state at that boundary comes back with runEnded(), so pause =
/// keep it, resume = run it again.  Both signals are emitted on the GUI thread.  The destructor stops any
/// session and waits for its thread.

#include <QObject>

#include <atomic>
#include <memory>

#include "ui/run/RunSnapshot.hpp"
#include "ui/jobs/BackgroundJobs.hpp"

namespace archipelago::ui {

/// How the worker runs core: threads and chunk length (the snapshot period).
struct RunSettings {
  int threads = 0;             ///< 0: every core (OpenMP's default)
  double chunkSeconds = 0.1;   ///< chunk wall time, hence the snapshot period (≥ 5 Hz refresh)
  /// A run of q > 1 finished runs its q = 1 companion of this fraction of its steps (RunSpec::companion; 0: none),
  /// and its last snapshot carries the spliced statistics (issue #26).
  double companion = 0;
};

class RunWorker : public QObject {
  Q_OBJECT
 public:
  explicit RunWorker(QObject* parent = nullptr);
  ~RunWorker() override;

  /// Advances `state` (fresh from startTrapping, a paused state or a loaded checkpoint) until it is finished,
  /// paused or stopped.  A session of another run still going is stopped first.
  void startRun(std::uint64_t runId, TrappingState state, const RunSettings& settings);
  /// Computes the snapshot of `state` without advancing it (an opened run file); answers with runEnded().
  void analyse(std::uint64_t runId, TrappingState state, std::shared_ptr<const TrappingState> companion = {});
  /// Ends the session of `runId` at the next chunk boundary; runEnded() reports `how` (paused or stopped).
  void requestEnd(std::uint64_t runId, RunEnd how);
  /// True while a session is computing.
  [[nodiscard]] bool busy() const noexcept { return busy_.load(); }
  /// The GUI calls this when it has taken a snapshot, so the worker may emit the next one.
  void snapshotConsumed() noexcept;
  /// Snapshots the worker skipped because the GUI had not taken the previous ones (diagnostics).
  [[nodiscard]] std::uint64_t skippedSnapshots() const noexcept { return skipped_.load(); }

  /// The kernel path the worker uses (core's selectKernel(): the fastest the CPU supports, or
  /// $ARCHIPELAGO_KERNEL), as core names it in TrappingState::kernel; and its one-line description.
  [[nodiscard]] static QString kernelName();
  [[nodiscard]] static QString kernelDescription();

 Q_SIGNALS:
  /// A chunk boundary of a running session (emitted on the GUI thread).
  void snapshotReady(archipelago::ui::RunSnapshotPtr snapshot);
  /// The session ended; `last` is the state where it ended (finished, paused, stopped) or the analysed state
  /// (null when it failed, with the reason in `message`).
  void runEnded(quint64 runId, archipelago::ui::RunSnapshotPtr last, archipelago::ui::RunEnd how, QString message);

 private:
  void submit(std::uint64_t runId, TrappingState state, const RunSettings& settings, bool advance,
              std::shared_ptr<const TrappingState> companion = {});

  std::uint64_t sessionRunId_ = 0;             // GUI thread: the run of the latest request
  quint64 sessionJob_ = 0;                     // GUI thread: its job
  std::shared_ptr<std::atomic<int>> endReason_; // GUI thread: the RunEnd requested for that session
  std::atomic<bool> busy_{false};
  std::atomic<int> inFlight_{0};
  std::atomic<std::uint64_t> skipped_{0};
  // Last: destroyed first, it stops the session and joins before the rest goes.  Niced: a run uses every core.
  BackgroundJobs jobs_{this, 1, JobPriority::background};
};

/// The snapshot of `state` (statistics and theory from core); used by the worker, and by tests to compare.
/// With `judgeTail`, also D's honest error and the tail's verdict (the end of a session).  With a finished
/// `companion` of a finished run, the statistics are the spliced ones (issue #26) and the snapshot keeps it.
[[nodiscard]] RunSnapshotPtr makeSnapshot(std::uint64_t runId, const TrappingState& state,
                                          const TrappingProgress& progress, bool judgeTail = false,
                                          std::shared_ptr<const TrappingState> companion = {});

}  // namespace archipelago::ui
