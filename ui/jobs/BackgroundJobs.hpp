#pragma once
/// \file BackgroundJobs.hpp
/// \brief The GUI's one background-job mechanism: latest request wins, cancellable, results as values tagged
/// with their request.  Runs (RunWorker), portraits, segment analysis, periodic orbits and b₂ all use it.
///
/// Threads (Qt's threaded-Mandelbrot pattern, STYLE.md).  A BackgroundJobs object serves one receiver, a
/// QObject of the thread that creates it (the GUI thread), and owns one worker thread per *channel*, started
/// at the channel's first job; with JobPriority::background the threads are niced so that the GUI thread keeps
/// the upper hand over long computations (the OpenMP team a job starts inherits the nice value), and with
/// JobPriority::idle niced further, so that a background run keeps most of the cores too (the priority may
/// differ by channel: interactive work and idle work of one panel).  Only the receiver's thread calls
/// submit(), cancel() and requestStop().
///
/// A job is a callable that computes from the values it captured (calling core; it never touches a GUI
/// object) and returns its result as a value.  Every submit() gets a new request id, unique in this object:
/// - JobOrder::latest (the default): the job replaces the channel's queued jobs and stops the running one
///   (std::stop_source; core checks the token at every chunk); whatever an older job of that channel would
///   still deliver is dropped.  Latest wins.
/// - JobOrder::queued / JobOrder::urgent: appended to / put at the front of the channel's queue, the others
///   kept (a channel that works through a list, e.g. the chains of the top segments).
/// cancel() drops the channel's queued jobs, stops the running one, and drops whatever they would still
/// deliver.  requestStop(id) only asks job `id` to end early: its result still arrives (pausing a run).
///
/// Deliveries (the result, a failure, progress values) arrive on the receiver's thread, through its event
/// loop, each tagged with its request id; stale ones (see above) are dropped before any handler runs.  A job
/// that throws, std::bad_alloc included, delivers a failure: JobResult::error holds a one-line message.  A
/// job that returns std::nullopt delivers nothing (it was stopped and has nothing to say).  During the job,
/// JobContext::post() delivers every value (frames of a refinement, run snapshots) and
/// JobContext::progress() at most one value per Job::progressInterval (100 ms by default).
///
/// Hand-off: a worker puts its deliveries in an outbox under a std::mutex and posts one wake-up event; the
/// receiver's thread empties the outbox under the same mutex, so the hand-off is visible to ThreadSanitizer
/// even though Qt is not instrumented.
///
/// Lifetime: nothing is delivered once the receiver is destroyed (QPointer), nor once this object is.  The
/// destructor cancels every job and joins the threads: make this object a member of the receiver declared
/// after everything its jobs use (or destroy it first).  A handler must not destroy this object (deleteLater).

#include <QObject>
#include <QPointer>
#include <QString>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <stop_token>
#include <thread>
#include <utility>
#include <vector>

namespace archipelago::ui {

/// Where a new job goes in its channel's queue.
enum class JobOrder {
  latest,   ///< replaces the queued jobs and stops the running one; older results are dropped
  queued,   ///< after the queued jobs
  urgent,   ///< before the queued jobs (the running one goes on)
};

/// The CPU priority of a BackgroundJobs' threads.
enum class JobPriority {
  normal,       ///< as the GUI thread: short interactive jobs (a replay, an orbit search) finish soonest
  background,   ///< niced (Linux): long computations using every core (a run) leave the GUI thread responsive
  idle,         ///< niced further: work that should yield the cores to a run (the portrait's accumulation)
};

/// A pause switch a long job can wait at between chunks (the portrait's accumulation while its tab is hidden):
/// the receiver's thread sets it, the job calls waitWhilePaused() where stopping would lose work.  A stop
/// request ends the wait at once.
class PauseGate {
 public:
  void setPaused(bool paused);
  [[nodiscard]] bool paused() const;
  /// Blocks while paused, until resumed or `stop` is requested; returns false when stopped.
  bool waitWhilePaused(const std::stop_token& stop);
  /// True while a job is blocked in waitWhilePaused(): everything it sent before has been sent, and it sends
  /// nothing more until resumed (a pause takes effect only at the job's next chunk).
  [[nodiscard]] bool holding() const;

 private:
  mutable std::mutex mutex_;
  std::condition_variable_any wake_;
  bool paused_ = false;  // guarded by mutex_
  int waiting_ = 0;      // jobs blocked in waitWhilePaused(); guarded by mutex_
};

/// The progress type of a job that reports none.
struct NoProgress {};

/// A job's outcome, delivered on the receiver's thread: a value, or the one-line reason it failed.
template <class Result>
struct JobResult {
  quint64 id = 0;               ///< the request this answers (submit()'s return value)
  std::optional<Result> value;  ///< empty when the job failed
  QString error;                ///< why it failed (empty on success)
  [[nodiscard]] bool ok() const noexcept { return value.has_value(); }
};

/// What a running job sees: its id and stop token, and the way to send values back during the job.
template <class Progress>
class JobContext {
 public:
  using Send = std::function<void(Progress&&)>;
  JobContext(quint64 id, std::stop_token stop, Send send, std::chrono::steady_clock::duration interval)
      : id_(id), stop_(std::move(stop)), send_(std::move(send)), interval_(interval) {}

  [[nodiscard]] quint64 id() const noexcept { return id_; }
  [[nodiscard]] const std::stop_token& stopToken() const noexcept { return stop_; }
  [[nodiscard]] bool stopRequested() const noexcept { return stop_.stop_requested(); }

  /// Delivers `value` to Job::progress (unless it is stale by then): every value, in order.
  void post(Progress value) {
    if (send_) send_(std::move(value));
  }
  /// Delivers `value` if at least the job's progress interval has passed since the last value delivered
  /// this way (the first always goes); true when delivered.
  bool progress(Progress value) {
    const auto now = std::chrono::steady_clock::now();
    if (last_ && now - *last_ < interval_) return false;
    last_ = now;
    post(std::move(value));
    return true;
  }

 private:
  quint64 id_;
  std::stop_token stop_;
  Send send_;
  std::chrono::steady_clock::duration interval_;
  std::optional<std::chrono::steady_clock::time_point> last_;
};

/// One request: the work (on a worker thread) and its handlers (on the receiver's thread).
template <class Result, class Progress = NoProgress>
struct Job {
  /// Computes the result from captured values; std::nullopt delivers nothing.  May throw.
  std::function<std::optional<Result>(JobContext<Progress>&)> work;
  /// Receives the result or the failure (not called for a stale or cancelled request).
  std::function<void(JobResult<Result>)> done;
  /// Receives the values of JobContext::post() and progress(), tagged with the request id (may be empty).
  std::function<void(quint64 id, Progress)> progress;
  int channel = 0;
  JobOrder order = JobOrder::latest;
  std::chrono::steady_clock::duration progressInterval = std::chrono::milliseconds(100);
};

/// The one-line message of a job's failure: e.what(), "out of memory (std::bad_alloc)", or "unknown error".
[[nodiscard]] QString jobFailureMessage(const std::exception_ptr& failure);

class BackgroundJobs {
 public:
  /// Jobs for `receiver` (which lives on the calling thread), on `channels` worker threads.
  explicit BackgroundJobs(QObject* receiver, int channels = 1, JobPriority priority = JobPriority::normal);
  /// Jobs for `receiver` on one channel per entry of `priorities`, channel c's thread at priorities[c].
  BackgroundJobs(QObject* receiver, std::vector<JobPriority> priorities);
  ~BackgroundJobs();
  BackgroundJobs(const BackgroundJobs&) = delete;
  BackgroundJobs& operator=(const BackgroundJobs&) = delete;

  /// Queues `job` on its channel (see JobOrder); returns its request id.
  template <class Result, class Progress>
  quint64 submit(Job<Result, Progress> job);
  /// Drops the queued jobs of `channel`, stops its running one, and drops everything they would deliver.
  void cancel(int channel = 0);
  /// cancel() on every channel.
  void cancelAll();
  /// Asks job `id` (queued or running) to end early; unlike cancel(), its result is still delivered.
  void requestStop(quint64 id);
  /// Nothing queued and nothing running on `channel` (its deliveries may still be in the event queue).
  [[nodiscard]] bool idle(int channel) const;
  /// idle() on every channel.
  [[nodiscard]] bool idle() const;

 private:
  struct Task {
    quint64 id = 0;
    std::stop_source stop;
    std::function<void(quint64 id, std::stop_token stop)> run;  // catches everything itself
  };
  struct Channel {
    std::deque<std::shared_ptr<Task>> queue;  // guarded by mutex_
    std::shared_ptr<Task> running;            // guarded by mutex_
    std::condition_variable wake;
    std::thread thread;                       // started by the receiver's thread, joined by the destructor
    JobPriority priority = JobPriority::normal;  // of `thread`; set before it starts
    quint64 validFrom = 0;                    // receiver's thread only: older deliveries are stale
  };
  struct Delivery {
    int channel = 0;
    quint64 id = 0;
    std::function<void()> deliver;
  };
  class Mailbox;

  quint64 enqueue(int channel, JobOrder order, std::function<void(quint64, std::stop_token)> run);
  void workerLoop(int channel);
  /// Worker side: hands `deliver` to the receiver's thread (through the outbox).
  void post(int channel, quint64 id, std::function<void()> deliver);
  /// Receiver side: runs the outbox's deliveries that are not stale.
  void drain();
  Channel& channelAt(int channel) const;

  QPointer<QObject> receiver_;
  std::unique_ptr<Mailbox> mailbox_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Channel>> channels_;
  bool quitting_ = false;                   // guarded by mutex_
  quint64 nextId_ = 0;                      // receiver's thread only
  std::mutex outboxMutex_;
  std::vector<Delivery> outbox_;            // guarded by outboxMutex_
  bool wakePosted_ = false;                 // guarded by outboxMutex_
};

template <class Result, class Progress>
quint64 BackgroundJobs::submit(Job<Result, Progress> job) {
  struct Handlers {
    std::function<void(JobResult<Result>)> done;
    std::function<void(quint64, Progress)> progress;
  };
  auto handlers = std::make_shared<const Handlers>(Handlers{std::move(job.done), std::move(job.progress)});
  const int channel = job.channel;
  const auto interval = job.progressInterval;
  auto run = [this, channel, interval, handlers, work = std::move(job.work)](quint64 id, std::stop_token stop) {
    typename JobContext<Progress>::Send send;
    if (handlers->progress)
      send = [this, channel, id, handlers](Progress&& value) {
        post(channel, id, [handlers, id, value = std::move(value)]() mutable {
          handlers->progress(id, std::move(value));
        });
      };
    JobContext<Progress> context(id, std::move(stop), std::move(send), interval);
    JobResult<Result> result;
    result.id = id;
    try {
      std::optional<Result> value = work(context);
      if (!value) return;
      result.value = std::move(value);
    } catch (...) {
      result.error = jobFailureMessage(std::current_exception());
    }
    post(channel, id, [handlers, result = std::move(result)]() mutable {
      if (handlers->done) handlers->done(std::move(result));
    });
  };
  return enqueue(channel, job.order, std::move(run));
}

}  // namespace archipelago::ui
