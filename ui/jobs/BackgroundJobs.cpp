#include "ui/jobs/BackgroundJobs.hpp"

#include <QCoreApplication>
#include <QEvent>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include <algorithm>
#include <cerrno>
#include <new>
#include <stdexcept>

namespace archipelago::ui {

namespace {
// Nice value of the worker threads (0 = normal, 19 = lowest): low enough that the GUI thread wins.  Idle work
// (the portrait's accumulation) at the lowest: against a run's threads (nice 10) it gets a CFS weight of 15
// against 110, so the run keeps ~88 % of a core it shares with it (issue 25, finding 15).
constexpr int kComputeNice = 10;
constexpr int kIdleNice = 19;

void lowerComputePriority(int nice) {
#if defined(__linux__)
  // Linux gives every thread its own nice value and a new thread inherits its creator's: niced here, the
  // OpenMP team that a job starts from this thread is niced too.  The GUI thread then keeps the upper hand
  // over the computation (and over nothing else), so it stays responsive while every core computes.  Relative
  // to the thread's own (at most 19): a GUI started under `nice 10` keeps it too (gui.jobs under nice ctest).
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  errno = 0;
  const int own = getpriority(PRIO_PROCESS, tid);
  setpriority(PRIO_PROCESS, tid, errno == 0 ? std::min(own + nice, 19) : nice);
#else
  (void)nice;
#endif
}
}  // namespace

/// The receiver-thread end of the outbox: a wake-up event makes it run drain().
class BackgroundJobs::Mailbox : public QObject {
 public:
  explicit Mailbox(BackgroundJobs* owner) : owner_(owner) {}
  static QEvent::Type wakeType() {
    static const auto type = static_cast<QEvent::Type>(QEvent::registerEventType());
    return type;
  }

 protected:
  // The wake-up event (the mailbox's only custom event) is allocated by a worker and handed over through Qt's
  // uninstrumented event queue: QObject::event() (Qt's code) reads its type and calls customEvent(), and our
  // code never touches the event itself, only the outbox, under outboxMutex_, which ThreadSanitizer sees.
  void customEvent(QEvent*) override { owner_->drain(); }

 private:
  BackgroundJobs* owner_;
};

void PauseGate::setPaused(bool paused) {
  {
    std::lock_guard lock(mutex_);
    paused_ = paused;
  }
  wake_.notify_all();
}

bool PauseGate::paused() const {
  std::lock_guard lock(mutex_);
  return paused_;
}

bool PauseGate::waitWhilePaused(const std::stop_token& stop) {
  std::unique_lock lock(mutex_);
  ++waiting_;
  const bool resumed = wake_.wait(lock, stop, [this] { return !paused_; });
  --waiting_;
  return resumed;
}

bool PauseGate::holding() const {
  std::lock_guard lock(mutex_);
  return waiting_ > 0;
}

QString jobFailureMessage(const std::exception_ptr& failure) {
  try {
    std::rethrow_exception(failure);
  } catch (const std::bad_alloc&) {
    return QStringLiteral("out of memory (std::bad_alloc)");
  } catch (const std::exception& e) {
    const QString what = QString::fromUtf8(e.what());
    return what.isEmpty() ? QStringLiteral("unknown error") : what;
  } catch (...) {
    return QStringLiteral("unknown error");
  }
}

BackgroundJobs::BackgroundJobs(QObject* receiver, int channels, JobPriority priority)
    : BackgroundJobs(receiver, std::vector<JobPriority>(static_cast<std::size_t>(std::max(channels, 0)), priority)) {}

BackgroundJobs::BackgroundJobs(QObject* receiver, std::vector<JobPriority> priorities) : receiver_(receiver) {
  if (priorities.empty()) throw std::invalid_argument("BackgroundJobs: at least one channel");
  (void)Mailbox::wakeType();  // registered once, on the receiver's thread
  mailbox_ = std::make_unique<Mailbox>(this);
  for (const JobPriority priority : priorities) {
    channels_.push_back(std::make_unique<Channel>());
    channels_.back()->priority = priority;
  }
}

BackgroundJobs::~BackgroundJobs() {
  std::vector<std::shared_ptr<Task>> dropped;  // destroyed outside the lock
  {
    std::lock_guard lock(mutex_);
    quitting_ = true;
    for (auto& ch : channels_) {
      dropped.insert(dropped.end(), ch->queue.begin(), ch->queue.end());
      ch->queue.clear();
      if (ch->running) ch->running->stop.request_stop();
    }
  }
  for (auto& ch : channels_) {
    ch->wake.notify_all();
    if (ch->thread.joinable()) ch->thread.join();
  }
  // No worker is left to post; the wake-up events still queued die with the mailbox.
  mailbox_.reset();
  std::lock_guard lock(outboxMutex_);
  outbox_.clear();
}

BackgroundJobs::Channel& BackgroundJobs::channelAt(int channel) const {
  if (channel < 0 || channel >= static_cast<int>(channels_.size()))
    throw std::out_of_range("BackgroundJobs: no channel " + std::to_string(channel));
  return *channels_[static_cast<std::size_t>(channel)];
}

quint64 BackgroundJobs::enqueue(int channel, JobOrder order, std::function<void(quint64, std::stop_token)> run) {
  Channel& ch = channelAt(channel);
  auto task = std::make_shared<Task>();
  task->id = ++nextId_;
  task->run = std::move(run);
  std::deque<std::shared_ptr<Task>> dropped;  // destroyed outside the lock
  {
    std::lock_guard lock(mutex_);
    switch (order) {
      case JobOrder::latest:
        dropped.swap(ch.queue);
        if (ch.running) ch.running->stop.request_stop();
        ch.queue.push_back(task);
        break;
      case JobOrder::queued:
        ch.queue.push_back(task);
        break;
      case JobOrder::urgent:
        ch.queue.push_front(task);
        break;
    }
    if (!ch.thread.joinable()) ch.thread = std::thread([this, channel] { workerLoop(channel); });
  }
  ch.wake.notify_one();
  if (order == JobOrder::latest) ch.validFrom = task->id;
  return task->id;
}

void BackgroundJobs::cancel(int channel) {
  Channel& ch = channelAt(channel);
  std::deque<std::shared_ptr<Task>> dropped;
  {
    std::lock_guard lock(mutex_);
    dropped.swap(ch.queue);
    if (ch.running) ch.running->stop.request_stop();
  }
  ch.validFrom = nextId_ + 1;
}

void BackgroundJobs::cancelAll() {
  for (int c = 0; c < static_cast<int>(channels_.size()); ++c) cancel(c);
}

void BackgroundJobs::requestStop(quint64 id) {
  std::lock_guard lock(mutex_);
  for (auto& ch : channels_) {
    if (ch->running && ch->running->id == id) ch->running->stop.request_stop();
    for (auto& task : ch->queue)
      if (task->id == id) task->stop.request_stop();
  }
}

bool BackgroundJobs::idle(int channel) const {
  const Channel& ch = channelAt(channel);
  std::lock_guard lock(mutex_);
  return ch.queue.empty() && !ch.running;
}

bool BackgroundJobs::idle() const {
  for (int c = 0; c < static_cast<int>(channels_.size()); ++c)
    if (!idle(c)) return false;
  return true;
}

void BackgroundJobs::workerLoop(int channel) {
  Channel& ch = channelAt(channel);
  if (ch.priority == JobPriority::background) lowerComputePriority(kComputeNice);
  if (ch.priority == JobPriority::idle) lowerComputePriority(kIdleNice);
  for (;;) {
    std::shared_ptr<Task> task;
    {
      std::unique_lock lock(mutex_);
      ch.wake.wait(lock, [&] { return quitting_ || !ch.queue.empty(); });
      if (quitting_) return;
      task = std::move(ch.queue.front());
      ch.queue.pop_front();
      ch.running = task;
    }
    try {
      task->run(task->id, task->stop.get_token());
    } catch (...) {
      // Only posting the outcome can throw here (out of memory): nothing is left to tell the receiver.
    }
    std::lock_guard lock(mutex_);
    ch.running.reset();
    task.reset();  // the job's captures die on this thread, before the channel reports idle
  }
}

void BackgroundJobs::post(int channel, quint64 id, std::function<void()> deliver) {
  std::lock_guard lock(outboxMutex_);
  outbox_.push_back(Delivery{channel, id, std::move(deliver)});
  if (wakePosted_) return;
  wakePosted_ = true;
  QCoreApplication::postEvent(mailbox_.get(), new QEvent(Mailbox::wakeType()));
}

void BackgroundJobs::drain() {
  std::vector<Delivery> ready;
  {
    std::lock_guard lock(outboxMutex_);
    ready.swap(outbox_);
    wakePosted_ = false;
  }
  for (Delivery& d : ready) {
    if (receiver_.isNull()) return;
    // Checked one by one: a handler may submit or cancel, which makes the deliveries after it stale.
    if (d.id < channelAt(d.channel).validFrom) continue;
    d.deliver();
  }
}

}  // namespace archipelago::ui
