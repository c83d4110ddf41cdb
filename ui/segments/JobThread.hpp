#pragma once
/// \file JobThread.hpp
/// \brief One background thread that runs queued jobs, each with a stop token (Qt's threaded-Mandelbrot pattern).
///
/// The GUI thread submits jobs (plain callables taking a std::stop_token) under a mutex and wakes the thread;
/// the thread takes one job, releases the lock and runs it.  A job hands its result back as a value through a
/// queued call to a GUI-thread object, tagged with the request it answers, so the receiver can drop stale
/// results (postTo()).  cancelAll() drops the queued jobs and requests the running one to stop; core's
/// replays check the token every few thousand blocks.  The destructor cancels everything and waits.

#include <QMutex>
#include <QPointer>
#include <QThread>
#include <QWaitCondition>

#include <atomic>
#include <deque>
#include <functional>
#include <stop_token>
#include <utility>

namespace archipelago::ui {

class JobThread : public QThread {
  Q_OBJECT
 public:
  using Job = std::function<void(std::stop_token)>;

  explicit JobThread(QObject* parent = nullptr);
  ~JobThread() override;

  /// Queues `job` (at the front when urgent) and starts the thread if needed.
  void submit(Job job, bool urgent = false);
  /// Drops every queued job and asks the running one to stop.
  void cancelAll();
  /// Nothing queued and nothing running.
  [[nodiscard]] bool idle() const noexcept { return !running_.load() && queued_.load() == 0; }

  /// Calls `deliver` on `receiver`'s thread (the GUI thread) unless the receiver has been destroyed.
  template <class Deliver>
  static void postTo(QObject* receiver, Deliver&& deliver) {
    QMetaObject::invokeMethod(receiver, std::forward<Deliver>(deliver), Qt::QueuedConnection);
  }

 protected:
  void run() override;

 private:
  QMutex mutex_;
  QWaitCondition wake_;
  std::deque<Job> queue_;            // guarded by mutex_
  std::stop_source current_;         // guarded by mutex_: stops the running job
  std::atomic<bool> abort_{false};
  std::atomic<bool> running_{false};
  std::atomic<int> queued_{0};
};

}  // namespace archipelago::ui
