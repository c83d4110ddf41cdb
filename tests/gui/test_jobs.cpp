// The GUI's background-job mechanism (ui/jobs/BackgroundJobs): latest wins, cancel, tagging, throttled
// progress, lifetimes and failures; the ETA text of long tasks (ui/jobs/DurationText).  No timing: a job that must still be running when the test acts waits on
// its stop token (or on a gate the test opens), and "nothing else arrives" is proved by a later job on the same
// channel, whose result is handed over after anything the earlier one could have posted.

#include <QCoreApplication>
#include <QThread>
#include <QtTest>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <stdexcept>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include "GuiTestSupport.hpp"
#include "core/run/TrappingRun.hpp"
#include "ui/run/RunWorker.hpp"
#include "ui/jobs/BackgroundJobs.hpp"
#include "ui/jobs/DurationText.hpp"

using namespace archipelago::ui;
using namespace std::chrono_literals;

namespace {

/// Blocks until the stop token is requested or open() is called; thread-safe.
class Gate {
 public:
  void open() {
    {
      std::lock_guard lock(mutex_);
      open_ = true;
    }
    cv_.notify_all();
  }
  /// True when stopped, false when opened.
  bool wait(const std::stop_token& stop) {
    std::unique_lock lock(mutex_);
    const bool opened = cv_.wait(lock, stop, [&] { return open_; });
    return !opened;
  }

 private:
  std::mutex mutex_;
  std::condition_variable_any cv_;
  bool open_ = false;
};

/// A job returning `value` at once.
Job<int> immediate(int value, int channel = 0, JobOrder order = JobOrder::latest) {
  Job<int> job;
  job.work = [value](JobContext<NoProgress>&) -> std::optional<int> { return value; };
  job.channel = channel;
  job.order = order;
  return job;
}

/// A job that waits for `gate` (or its stop token), records whether it was stopped, and returns `value`.
Job<int> gated(std::shared_ptr<Gate> gate, std::shared_ptr<std::atomic<int>> started,
               std::shared_ptr<std::atomic<bool>> stopped, int value) {
  Job<int> job;
  job.work = [=](JobContext<NoProgress>& context) -> std::optional<int> {
    started->fetch_add(1);
    stopped->store(gate->wait(context.stopToken()));
    return value;
  };
  return job;
}

}  // namespace

class TestJobs : public QObject {
  Q_OBJECT
 private Q_SLOTS:
  void resultIsTaggedAndArrivesOnTheReceiversThread();
  void latestWins();
  void cancelDeliversNothing();
  void requestStopStillDelivers();
  void queuedAndUrgentKeepEveryJob();
  void postedValuesAllArriveInOrder();
  void progressIsThrottled();
  void failuresComeBackAsValues();
  void nullResultDeliversNothing();
  void destroyingTheReceiverMidJob();
  void destroyingTheMechanismMidJob();
  void channelsRunIndependently();
  void backgroundPriorityNicesTheThreads();
  void channelPrioritiesNiceEachChannel();
  void runWorkerLatestRunWinsAndPauseKeepsTheState();
  void durationsAsText();
  void pauseGateHoldsAJobUntilResumedOrStopped();
};

// PauseGate: a job waits at it only while paused; holding() says when it waits (the portrait's pause test waits
// for it instead of a fixed time); a resume or a stop request releases it.
void TestJobs::pauseGateHoldsAJobUntilResumedOrStopped() {
  PauseGate gate;
  std::stop_source never;
  QVERIFY(!gate.paused() && !gate.holding());
  QVERIFY(gate.waitWhilePaused(never.get_token()));  // not paused: passes at once
  QVERIFY(!gate.holding());
  for (const bool byStop : {false, true}) {
    gate.setPaused(true);
    std::stop_source stop;
    std::atomic<int> result{-1};
    std::thread job([&] { result = gate.waitWhilePaused(stop.get_token()) ? 1 : 0; });
    QTRY_VERIFY(gate.holding());
    std::this_thread::sleep_for(50ms);
    QCOMPARE(result.load(), -1);  // still held
    if (byStop) {
      stop.request_stop();
    } else {
      gate.setPaused(false);
    }
    job.join();
    QCOMPARE(result.load(), byStop ? 0 : 1);
    QVERIFY(!gate.holding());
  }
}

void TestJobs::resultIsTaggedAndArrivesOnTheReceiversThread() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  std::vector<JobResult<int>> got;
  QThread* deliveredOn = nullptr;
  Job<int> job = immediate(42);
  job.done = [&](JobResult<int> r) {
    deliveredOn = QThread::currentThread();
    got.push_back(std::move(r));
  };
  const quint64 id = jobs.submit(std::move(job));
  QVERIFY(id != 0);
  QTRY_COMPARE(got.size(), std::size_t{1});
  QCOMPARE(got[0].id, id);
  QVERIFY(got[0].ok());
  QCOMPARE(*got[0].value, 42);
  QVERIFY(got[0].error.isEmpty());
  QCOMPARE(deliveredOn, QThread::currentThread());
  Job<int> second = immediate(7);
  second.done = [&](JobResult<int> r) { got.push_back(std::move(r)); };
  const quint64 id2 = jobs.submit(std::move(second));
  QVERIFY(id2 != id);
  QTRY_COMPARE(got.size(), std::size_t{2});
  QCOMPARE(got[1].id, id2);
  QCOMPARE(*got[1].value, 7);
}

void TestJobs::latestWins() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  auto gate = std::make_shared<Gate>();
  auto started = std::make_shared<std::atomic<int>>(0);
  auto stopped = std::make_shared<std::atomic<bool>>(false);
  std::vector<quint64> ids;
  Job<int> first = gated(gate, started, stopped, 1);
  first.done = [&](const JobResult<int>& r) { ids.push_back(r.id); };
  jobs.submit(std::move(first));
  QTRY_COMPARE(started->load(), 1);  // running, waiting on its gate
  // Queued behind it, then replaced before it ever runs.
  Job<int> replaced = immediate(2);
  bool replacedRan = false;
  replaced.work = [&replacedRan](JobContext<NoProgress>&) -> std::optional<int> {
    replacedRan = true;
    return 2;
  };
  replaced.done = [&](const JobResult<int>& r) { ids.push_back(r.id); };
  jobs.submit(std::move(replaced));
  Job<int> last = immediate(3);
  last.done = [&](const JobResult<int>& r) { ids.push_back(r.id); };
  const quint64 lastId = jobs.submit(std::move(last));
  QTRY_VERIFY(!ids.empty());
  QTRY_VERIFY(jobs.idle());
  QCoreApplication::sendPostedEvents();
  QCOMPARE(ids, std::vector<quint64>{lastId});  // only the latest request's result
  QVERIFY(stopped->load());                     // the running job was stopped, not waited for
  QVERIFY(!replacedRan);                        // the queued one was dropped
}

void TestJobs::cancelDeliversNothing() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  auto gate = std::make_shared<Gate>();
  auto started = std::make_shared<std::atomic<int>>(0);
  auto stopped = std::make_shared<std::atomic<bool>>(false);
  int delivered = 0;
  Job<int> job = gated(gate, started, stopped, 1);
  job.done = [&](const JobResult<int>&) { ++delivered; };
  jobs.submit(std::move(job));
  QTRY_COMPARE(started->load(), 1);
  jobs.cancel();
  // A fence: queued after the cancelled job on the same channel, it is handed over after anything that one posted.
  bool fence = false;
  Job<int> after = immediate(0, 0, JobOrder::queued);
  after.done = [&](const JobResult<int>&) { fence = true; };
  jobs.submit(std::move(after));
  QTRY_VERIFY(fence);
  QCOMPARE(delivered, 0);
  QVERIFY(stopped->load());
}

void TestJobs::requestStopStillDelivers() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  auto gate = std::make_shared<Gate>();
  auto started = std::make_shared<std::atomic<int>>(0);
  auto stopped = std::make_shared<std::atomic<bool>>(false);
  std::vector<int> values;
  Job<int> job = gated(gate, started, stopped, 5);
  job.done = [&](const JobResult<int>& r) { values.push_back(*r.value); };
  const quint64 id = jobs.submit(std::move(job));
  QTRY_COMPARE(started->load(), 1);
  jobs.requestStop(id + 1000);  // another id: nothing happens
  jobs.requestStop(id);
  QTRY_COMPARE(values, std::vector<int>{5});
  QVERIFY(stopped->load());
}

void TestJobs::queuedAndUrgentKeepEveryJob() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  auto gate = std::make_shared<Gate>();
  auto started = std::make_shared<std::atomic<int>>(0);
  auto stopped = std::make_shared<std::atomic<bool>>(false);
  std::vector<int> order;
  Job<int> blocker = gated(gate, started, stopped, 0);
  blocker.done = [&](const JobResult<int>& r) { order.push_back(*r.value); };
  jobs.submit(std::move(blocker));
  QTRY_COMPARE(started->load(), 1);
  for (int v : {1, 2, 3}) {
    Job<int> job = immediate(v, 0, JobOrder::queued);
    job.done = [&](const JobResult<int>& r) { order.push_back(*r.value); };
    jobs.submit(std::move(job));
  }
  Job<int> urgent = immediate(4, 0, JobOrder::urgent);
  urgent.done = [&](const JobResult<int>& r) { order.push_back(*r.value); };
  jobs.submit(std::move(urgent));
  gate->open();
  QTRY_COMPARE(order.size(), std::size_t{5});
  QCOMPARE(order, (std::vector<int>{0, 4, 1, 2, 3}));
  QVERIFY(!stopped->load());
}

void TestJobs::postedValuesAllArriveInOrder() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  static constexpr int kValues = 1000;
  std::vector<int> progress;
  std::vector<quint64> progressIds;
  int result = -1;
  Job<int, int> job;
  job.work = [](JobContext<int>& context) -> std::optional<int> {
    for (int i = 0; i < kValues; ++i) context.post(i);
    return kValues;
  };
  job.progress = [&](quint64 id, int value) {
    progressIds.push_back(id);
    progress.push_back(value);
  };
  job.done = [&](const JobResult<int>& r) {
    QCOMPARE(progress.size(), std::size_t{kValues});  // every posted value came before the result
    result = *r.value;
  };
  const quint64 id = jobs.submit(std::move(job));
  QTRY_COMPARE(result, kValues);
  std::vector<int> expected(kValues);
  for (int i = 0; i < kValues; ++i) expected[static_cast<std::size_t>(i)] = i;
  QCOMPARE(progress, expected);
  QCOMPARE(progressIds, std::vector<quint64>(kValues, id));
}

void TestJobs::progressIsThrottled() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  // An interval far longer than the job: of 1000 progress() calls only the first goes.
  std::vector<int> progress;
  int accepted = -1;
  Job<int, int> job;
  job.progressInterval = std::chrono::hours(1);
  job.work = [](JobContext<int>& context) -> std::optional<int> {
    int n = 0;
    for (int i = 0; i < 1000; ++i) n += context.progress(i) ? 1 : 0;
    return n;
  };
  job.progress = [&](quint64, int value) { progress.push_back(value); };
  job.done = [&](const JobResult<int>& r) { accepted = *r.value; };
  jobs.submit(std::move(job));
  QTRY_COMPARE(accepted, 1);
  QCOMPARE(progress, std::vector<int>{0});
  // No interval: every one goes.
  Job<int, int> unthrottled;
  unthrottled.progressInterval = std::chrono::steady_clock::duration::zero();
  unthrottled.work = [](JobContext<int>& context) -> std::optional<int> {
    int n = 0;
    for (int i = 0; i < 100; ++i) n += context.progress(i) ? 1 : 0;
    return n;
  };
  progress.clear();
  accepted = -1;
  unthrottled.progress = [&](quint64, int value) { progress.push_back(value); };
  unthrottled.done = [&](const JobResult<int>& r) { accepted = *r.value; };
  jobs.submit(std::move(unthrottled));
  QTRY_COMPARE(accepted, 100);
  QCOMPARE(progress.size(), std::size_t{100});
  // The default is the GUI's refresh period.
  QVERIFY(Job<int>{}.progressInterval == std::chrono::steady_clock::duration(100ms));
}

void TestJobs::failuresComeBackAsValues() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  std::vector<JobResult<int>> got;
  const auto submitThrowing = [&](auto thrower) {
    Job<int> job;
    job.work = [thrower](JobContext<NoProgress>&) -> std::optional<int> {
      thrower();
      return 1;
    };
    job.done = [&](JobResult<int> r) { got.push_back(std::move(r)); };
    job.order = JobOrder::queued;
    return jobs.submit(std::move(job));
  };
  const quint64 a = submitThrowing([] { throw std::runtime_error("K must be positive"); });
  const quint64 b = submitThrowing([] { throw std::bad_alloc(); });
  const quint64 c = submitThrowing([] { throw 17; });
  QTRY_COMPARE(got.size(), std::size_t{3});
  QCOMPARE(got[0].id, a);
  QCOMPARE(got[1].id, b);
  QCOMPARE(got[2].id, c);
  for (const auto& r : got) QVERIFY(!r.ok());
  QCOMPARE(got[0].error, QStringLiteral("K must be positive"));
  QCOMPARE(got[1].error, QStringLiteral("out of memory (std::bad_alloc)"));
  QCOMPARE(got[2].error, QStringLiteral("unknown error"));
  // The channel's thread survived: the next job runs.
  bool ran = false;
  Job<int> next = immediate(1);
  next.done = [&](const JobResult<int>& r) { ran = r.ok(); };
  jobs.submit(std::move(next));
  QTRY_VERIFY(ran);
}

void TestJobs::nullResultDeliversNothing() {
  QObject receiver;
  BackgroundJobs jobs(&receiver);
  int delivered = 0;
  Job<int> job;
  job.work = [](JobContext<NoProgress>&) -> std::optional<int> { return std::nullopt; };
  job.done = [&](const JobResult<int>&) { ++delivered; };
  job.order = JobOrder::queued;
  jobs.submit(std::move(job));
  bool fence = false;
  Job<int> after = immediate(0, 0, JobOrder::queued);
  after.done = [&](const JobResult<int>&) { fence = true; };
  jobs.submit(std::move(after));
  QTRY_VERIFY(fence);
  QCOMPARE(delivered, 0);
}

void TestJobs::destroyingTheReceiverMidJob() {
  auto* receiver = new QObject;
  BackgroundJobs jobs(receiver);
  auto gate = std::make_shared<Gate>();
  auto started = std::make_shared<std::atomic<int>>(0);
  auto stopped = std::make_shared<std::atomic<bool>>(false);
  auto delivered = std::make_shared<int>(0);
  Job<int, int> job;
  job.work = [=](JobContext<int>& context) -> std::optional<int> {
    context.post(1);
    started->fetch_add(1);
    stopped->store(gate->wait(context.stopToken()));
    context.post(2);
    return 3;
  };
  job.progress = [delivered](quint64, int) { ++*delivered; };
  job.done = [delivered](const JobResult<int>&) { ++*delivered; };
  jobs.submit(std::move(job));
  // Wait without running the event loop, so that the value posted first is still undelivered.
  while (started->load() == 0) std::this_thread::sleep_for(1ms);
  delete receiver;
  gate->open();  // the job ends normally and posts its result
  while (!jobs.idle()) std::this_thread::sleep_for(1ms);
  QCoreApplication::sendPostedEvents();
  QCOMPARE(*delivered, 0);
  QVERIFY(!stopped->load());
}

void TestJobs::destroyingTheMechanismMidJob() {
  QObject receiver;
  auto jobs = std::make_unique<BackgroundJobs>(&receiver, 2);
  auto gate = std::make_shared<Gate>();
  auto started = std::make_shared<std::atomic<int>>(0);
  auto stopped = std::make_shared<std::atomic<bool>>(false);
  auto delivered = std::make_shared<int>(0);
  for (int channel : {0, 1}) {
    Job<int, int> job;
    job.channel = channel;
    job.work = [=](JobContext<int>& context) -> std::optional<int> {
      context.post(1);
      started->fetch_add(1);
      stopped->store(gate->wait(context.stopToken()));
      return 2;
    };
    job.progress = [delivered](quint64, int) { ++*delivered; };
    job.done = [delivered](const JobResult<int>&) { ++*delivered; };
    jobs->submit(std::move(job));
  }
  Job<int> queued = immediate(9, 0, JobOrder::queued);
  queued.done = [delivered](const JobResult<int>&) { ++*delivered; };
  jobs->submit(std::move(queued));
  // Wait without running the event loop, so that the values posted first are still undelivered.
  while (started->load() < 2) std::this_thread::sleep_for(1ms);
  jobs.reset();  // stops both running jobs, drops the queued one, joins
  QVERIFY(stopped->load());
  QCoreApplication::sendPostedEvents();
  QCoreApplication::processEvents();
  QCOMPARE(*delivered, 0);
}

void TestJobs::channelsRunIndependently() {
  QObject receiver;
  BackgroundJobs jobs(&receiver, 2);
  auto gate = std::make_shared<Gate>();
  auto started = std::make_shared<std::atomic<int>>(0);
  auto stopped = std::make_shared<std::atomic<bool>>(false);
  int blocked = 0;
  Job<int> job = gated(gate, started, stopped, 1);
  job.done = [&](const JobResult<int>&) { ++blocked; };
  jobs.submit(std::move(job));  // channel 0, waiting on its gate
  QTRY_COMPARE(started->load(), 1);
  // A latest-wins job on channel 1 neither waits for nor replaces the one on channel 0.
  int other = 0;
  Job<int> second = immediate(2, 1);
  second.done = [&](const JobResult<int>& r) { other = *r.value; };
  jobs.submit(std::move(second));
  QTRY_COMPARE(other, 2);
  QVERIFY(!jobs.idle(0));
  QVERIFY(jobs.idle(1));
  gate->open();
  QTRY_COMPARE(blocked, 1);
  QVERIFY(!stopped->load());
  bool threw = false;
  try {
    jobs.cancel(2);  // no such channel: a clear error, not undefined behaviour
  } catch (const std::out_of_range&) {
    threw = true;
  }
  QVERIFY(threw);
}

void TestJobs::backgroundPriorityNicesTheThreads() {
#if defined(__linux__)
  const auto niceOfThisThread = []() -> std::optional<int> {
    errno = 0;
    const int nice = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
    if (errno != 0) return std::nullopt;
    return nice;
  };
  const int ours = *niceOfThisThread();
  QObject receiver;
  for (JobPriority priority : {JobPriority::normal, JobPriority::background}) {
    BackgroundJobs jobs(&receiver, 1, priority);
    std::optional<int> seen;
    Job<int> job;
    job.work = [niceOfThisThread](JobContext<NoProgress>&) { return niceOfThisThread(); };
    job.done = [&](const JobResult<int>& r) { seen = r.value; };
    jobs.submit(std::move(job));
    QTRY_VERIFY(seen.has_value());
    if (priority == JobPriority::normal)
      QCOMPARE(*seen, ours);
    else
      QCOMPARE(*seen, std::min(ours + 10, 19));  // RunWorker's runs, which use every core
  }
#else
  QSKIP("thread nice values are Linux's");
#endif
}

void TestJobs::channelPrioritiesNiceEachChannel() {
  // Issue 41: the segment panel's chain identifications (channel 1) yield to a run at the portrait's idle
  // priority, while its replays (channel 0), which the user waits for, keep the GUI's.
#if defined(__linux__)
  const auto niceOfThisThread = []() -> std::optional<int> {
    errno = 0;
    const int nice = getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
    if (errno != 0) return std::nullopt;
    return nice;
  };
  const int ours = *niceOfThisThread();
  QObject receiver;
  BackgroundJobs jobs(&receiver, std::vector<JobPriority>{JobPriority::normal, JobPriority::idle});
  std::optional<int> seen[2];
  for (int channel : {0, 1}) {
    Job<int> job;
    job.channel = channel;
    job.work = [niceOfThisThread](JobContext<NoProgress>&) { return niceOfThisThread(); };
    job.done = [&seen, channel](const JobResult<int>& r) { seen[channel] = r.value; };
    jobs.submit(std::move(job));
  }
  QTRY_VERIFY(seen[0].has_value() && seen[1].has_value());
  QCOMPARE(*seen[0], ours);
  QCOMPARE(*seen[1], 19);  // the lowest: what the portrait's accumulation gets
#else
  QSKIP("thread nice values are Linux's");
#endif
}

void TestJobs::runWorkerLatestRunWinsAndPauseKeepsTheState() {
  // The run's worker on the mechanism, without a window: a replaced run reports nothing, a paused one comes
  // back with the state where it stopped, which then continues exactly as an uninterrupted run (core's rule).
  RunWorker worker;
  struct Ended {
    quint64 runId;
    RunSnapshotPtr last;
    RunEnd how;
  };
  std::vector<Ended> ended;
  std::vector<quint64> snapshotRuns;
  QObject::connect(&worker, &RunWorker::runEnded, [&](quint64 id, RunSnapshotPtr last, RunEnd how, const QString&) {
    ended.push_back({id, std::move(last), how});
  });
  QObject::connect(&worker, &RunWorker::snapshotReady, [&](const RunSnapshotPtr& s) {
    snapshotRuns.push_back(s->runId);
    worker.snapshotConsumed();
  });
  RunSettings settings;
  settings.threads = 2;
  settings.chunkSeconds = 0.02;
  const archipelago::TrappingParameters endless = archipelago::test::endlessRun();
  worker.startRun(1, archipelago::startTrapping(endless), settings);
  worker.startRun(2, archipelago::startTrapping(endless), settings);  // replaces run 1 before or while it runs
  QTRY_VERIFY_WITH_TIMEOUT(!snapshotRuns.empty(), 900000);
  QVERIFY(worker.busy());
  worker.requestEnd(1, RunEnd::paused);  // not the session's run: ignored
  worker.requestEnd(2, RunEnd::paused);
  QTRY_VERIFY_WITH_TIMEOUT(!ended.empty(), 900000);
  QTRY_VERIFY(!worker.busy());
  QCOMPARE(ended.size(), std::size_t{1});
  QCOMPARE(ended[0].runId, quint64{2});
  QCOMPARE(ended[0].how, RunEnd::paused);
  QVERIFY(ended[0].last);
  for (quint64 id : snapshotRuns) QCOMPARE(id, quint64{2});
  const archipelago::TrappingState paused = ended[0].last->state;
  QVERIFY(paused.blocksDone > 0);
  // A short run resumed from a pause ends as the same run never paused.
  archipelago::TrappingParameters shortParams = archipelago::test::shortRun();
  archipelago::TrappingRunOptions one;
  one.threads = 1;
  const archipelago::TrappingState reference = archipelago::runTrapping(archipelago::startTrapping(shortParams), one);
  ended.clear();
  worker.startRun(3, archipelago::startTrapping(shortParams), settings);
  worker.requestEnd(3, RunEnd::paused);  // before or during its first chunk
  QTRY_VERIFY_WITH_TIMEOUT(!ended.empty(), 900000);
  QCOMPARE(ended[0].runId, quint64{3});
  QVERIFY(ended[0].how == RunEnd::paused || ended[0].how == RunEnd::finished);
  const archipelago::TrappingState midway = ended[0].last->state;
  ended.clear();
  worker.startRun(4, midway, settings);
  QTRY_VERIFY_WITH_TIMEOUT(!ended.empty(), 900000);
  QCOMPARE(ended[0].runId, quint64{4});
  QCOMPARE(ended[0].how, RunEnd::finished);
  const archipelago::TrappingState& resumed = ended[0].last->state;
  QVERIFY(resumed.finished());
  QVERIFY(resumed.subsets == reference.subsets);
  QVERIFY(resumed.longest == reference.longest);
  // Analysing a state answers with its snapshot and does not advance it.
  ended.clear();
  worker.analyse(5, paused);
  QTRY_VERIFY_WITH_TIMEOUT(!ended.empty(), 900000);
  QCOMPARE(ended[0].runId, quint64{5});
  QCOMPARE(ended[0].how, RunEnd::finished);
  QCOMPARE(ended[0].last->state.blocksDone, paused.blocksDone);
}

// formatDuration: rounded to the second; m:ss below an hour, h:mm:ss from it; "—" for what is no duration.
void TestJobs::durationsAsText() {
  QCOMPARE(formatDuration(0), QStringLiteral("0:00"));
  QCOMPARE(formatDuration(0.49), QStringLiteral("0:00"));
  QCOMPARE(formatDuration(59.5), QStringLiteral("1:00"));
  QCOMPARE(formatDuration(61), QStringLiteral("1:01"));
  QCOMPARE(formatDuration(3599.4), QStringLiteral("59:59"));
  QCOMPARE(formatDuration(3600), QStringLiteral("1:00:00"));
  QCOMPARE(formatDuration(36000 + 9 * 60 + 5), QStringLiteral("10:09:05"));
  QCOMPARE(formatDuration(1e9), QStringLiteral("277777:46:40"));
  QCOMPARE(formatDuration(1.5e9), QStringLiteral("—"));
  QCOMPARE(formatDuration(-1), QStringLiteral("—"));
  QCOMPARE(formatDuration(std::nan("")), QStringLiteral("—"));
  QCOMPARE(formatDuration(std::numeric_limits<double>::infinity()), QStringLiteral("—"));
}

QTEST_GUILESS_MAIN(TestJobs)
#include "test_jobs.moc"
