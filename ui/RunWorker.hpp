#pragma once
/// \file RunWorker.hpp
/// \brief The thread that owns a trapping run (Qt's threaded-Mandelbrot pattern, STYLE.md).
///
/// The GUI hands the worker a request (a state to advance, or one to analyse only) under a mutex and wakes
/// it; the worker copies the request and computes without the lock, calling core's runTrapping().  At every
/// chunk boundary it turns the state into a RunSnapshot (statistics and theory computed here, off the GUI
/// thread) and emits it through a queued signal; it never waits for the GUI.  When the GUI is slower than
/// the run, snapshots that would pile up are skipped (the next one supersedes them), so memory stays
/// bounded.  Pause and stop are requests through a std::stop_source, honoured at the next chunk boundary;
/// the state at that boundary comes back with runEnded(), so pause = keep it, resume = run it again.
/// The destructor aborts any session and waits for the thread.

#include <QMutex>
#include <QThread>
#include <QWaitCondition>

#include <atomic>
#include <optional>
#include <stop_token>

#include "ui/RunSnapshot.hpp"

namespace archipelago::ui {

/// How the worker runs core: threads and chunk length (the snapshot period).
struct RunSettings {
  int threads = 0;             ///< 0: every core (OpenMP's default)
  double chunkSeconds = 0.1;   ///< chunk wall time, hence the snapshot period (≥ 5 Hz refresh)
};

class RunWorker : public QThread {
  Q_OBJECT
 public:
  explicit RunWorker(QObject* parent = nullptr);
  ~RunWorker() override;

  /// Advances `state` (fresh from startTrapping, a paused state or a loaded checkpoint) until it is finished,
  /// paused or stopped.  A session of another run still going is stopped first.
  void startRun(std::uint64_t runId, TrappingState state, const RunSettings& settings);
  /// Computes the snapshot of `state` without advancing it (an opened run file); answers with runEnded().
  void analyse(std::uint64_t runId, TrappingState state);
  /// Ends the session of `runId` at the next chunk boundary; runEnded() reports `how` (paused or stopped).
  void requestEnd(std::uint64_t runId, RunEnd how);
  /// True while a session is computing.
  [[nodiscard]] bool busy() const noexcept { return busy_.load(); }
  /// The GUI calls this when it has taken a snapshot, so the worker may emit the next one.
  void snapshotConsumed() noexcept { inFlight_.fetch_sub(1); }
  /// Snapshots the worker skipped because the GUI had not taken the previous ones (diagnostics).
  [[nodiscard]] std::uint64_t skippedSnapshots() const noexcept { return skipped_.load(); }

  /// The kernel path the worker uses (core's selectKernel(): the fastest the CPU supports, or
  /// $ARCHIPELAGO_KERNEL), as core names it in TrappingState::kernel; and its one-line description.
  [[nodiscard]] static QString kernelName();
  [[nodiscard]] static QString kernelDescription();

 Q_SIGNALS:
  /// A chunk boundary of a running session (queued to the GUI thread).
  void snapshotReady(archipelago::ui::RunSnapshotPtr snapshot);
  /// The session ended; `last` is the state where it ended (finished, paused, stopped) or the analysed state
  /// (null when it failed, with the reason in `message`).
  void runEnded(quint64 runId, archipelago::ui::RunSnapshotPtr last, archipelago::ui::RunEnd how, QString message);

 protected:
  void run() override;

 private:
  struct Request {
    std::uint64_t runId = 0;
    TrappingState state;
    RunSettings settings;
    bool advance = true;
  };

  void execute(Request request);
  static void lowerComputePriority();

  QMutex mutex_;
  QWaitCondition wake_;
  std::optional<Request> pending_;      // guarded by mutex_
  std::stop_source session_;            // guarded by mutex_: stops the running session
  std::uint64_t sessionRunId_ = 0;      // guarded by mutex_
  std::atomic<int> endReason_{0};       // RunEnd requested for the running session
  std::atomic<bool> abort_{false};
  std::atomic<bool> busy_{false};
  std::atomic<int> inFlight_{0};
  std::atomic<std::uint64_t> skipped_{0};
};

/// The snapshot of `state` (statistics and theory from core); used by the worker, and by tests to compare.
[[nodiscard]] RunSnapshotPtr makeSnapshot(std::uint64_t runId, const TrappingState& state,
                                          const TrappingProgress& progress);

}  // namespace archipelago::ui
