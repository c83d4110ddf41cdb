#include "ui/RunWorker.hpp"

#include <QMutexLocker>

#if defined(__linux__)
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include <chrono>
#include <exception>

#include "core/kernels/KernelDispatch.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/theory/TheoryCurves.hpp"

namespace archipelago::ui {

namespace {
// At most this many snapshots travel to the GUI at once; more would only queue up stale copies.
constexpr int kMaxSnapshotsInFlight = 2;
// Nice value of the computing threads (0 = normal, 19 = lowest): low enough that the GUI thread wins.
constexpr int kComputeNice = 10;

TrappingRunOptions coreOptions(const RunSettings& settings) {
  TrappingRunOptions options;
  options.threads = settings.threads;
  options.chunkSeconds = settings.chunkSeconds;
  // The fastest path this CPU supports, or $ARCHIPELAGO_KERNEL; every path gives bit-identical results.
  options.kernel = &selectKernel();
  return options;
}

TrappingProgress progressOf(const TrappingState& state) {
  TrappingProgress p;
  p.blocksDone = state.blocksDone;
  p.blocksTotal = state.params.T;
  p.fraction = state.params.T ? static_cast<double>(state.blocksDone) / static_cast<double>(state.params.T) : 0;
  return p;
}
}  // namespace

RunSnapshotPtr makeSnapshot(std::uint64_t runId, const TrappingState& state, const TrappingProgress& progress) {
  auto snapshot = std::make_shared<RunSnapshot>();
  snapshot->runId = runId;
  snapshot->state = state;
  snapshot->progress = progress;
  snapshot->kernel = state.kernel;
  if (state.blocksDone > 0 && state.total().segments() > 0) {
    snapshot->statistics = statisticsOf(state);
    snapshot->hasStatistics = true;
    snapshot->theory = theoryCurves(state.params, snapshot->statistics);
  }
  return snapshot;
}

void RunWorker::lowerComputePriority() {
#if defined(__linux__)
  // Linux gives every thread its own nice value and a new thread inherits its creator's: niced here, the
  // OpenMP team that runTrapping() starts from this thread is niced too.  The GUI thread then keeps the
  // upper hand over the kernel (and over nothing else), so it stays responsive while every core computes.
  // (QThread::LowPriority has no effect under Linux's default scheduler.)
  const auto tid = static_cast<id_t>(syscall(SYS_gettid));
  setpriority(PRIO_PROCESS, tid, kComputeNice);
#endif
}

QString RunWorker::kernelName() {
  try {
    return QString::fromUtf8(selectKernel().name.data(), static_cast<int>(selectKernel().name.size()));
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
}

QString RunWorker::kernelDescription() {
  try {
    const KernelInfo& k = selectKernel();
    return QString::fromUtf8(k.description.data(), static_cast<int>(k.description.size()));
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
}

RunWorker::RunWorker(QObject* parent) : QThread(parent) {
  qRegisterMetaType<RunSnapshotPtr>("archipelago::ui::RunSnapshotPtr");
  qRegisterMetaType<RunEnd>("archipelago::ui::RunEnd");
}

RunWorker::~RunWorker() {
  {
    QMutexLocker lock(&mutex_);
    abort_ = true;
    pending_.reset();
    session_.request_stop();
    wake_.wakeOne();
  }
  wait();
}

void RunWorker::startRun(std::uint64_t runId, TrappingState state, const RunSettings& settings) {
  QMutexLocker lock(&mutex_);
  session_.request_stop();  // a session still going yields to the new request at its next chunk boundary
  endReason_ = static_cast<int>(RunEnd::stopped);
  pending_ = Request{runId, std::move(state), settings, true};
  if (!isRunning()) start(QThread::LowPriority);  // the GUI thread keeps the upper hand for the CPU
  else wake_.wakeOne();
}

void RunWorker::analyse(std::uint64_t runId, TrappingState state) {
  QMutexLocker lock(&mutex_);
  session_.request_stop();
  endReason_ = static_cast<int>(RunEnd::stopped);
  pending_ = Request{runId, std::move(state), RunSettings{}, false};
  if (!isRunning()) start(QThread::LowPriority);
  else wake_.wakeOne();
}

void RunWorker::requestEnd(std::uint64_t runId, RunEnd how) {
  QMutexLocker lock(&mutex_);
  if (runId != sessionRunId_) return;
  endReason_ = static_cast<int>(how);
  session_.request_stop();
}

void RunWorker::run() {
  lowerComputePriority();
  for (;;) {
    Request request;
    {
      QMutexLocker lock(&mutex_);
      while (!pending_ && !abort_) wake_.wait(&mutex_);
      if (abort_) return;
      request = std::move(*pending_);
      pending_.reset();
      session_ = std::stop_source();
      sessionRunId_ = request.runId;
      endReason_ = static_cast<int>(RunEnd::finished);
      busy_ = request.advance;
    }
    execute(std::move(request));
    busy_ = false;
  }
}

void RunWorker::execute(Request request) {
  std::stop_token stop;
  {
    QMutexLocker lock(&mutex_);
    stop = session_.get_token();
  }
  const std::uint64_t runId = request.runId;
  if (!request.advance) {
    try {
      Q_EMIT runEnded(runId, makeSnapshot(runId, request.state, progressOf(request.state)), RunEnd::finished, QString());
    } catch (const std::exception& e) {
      Q_EMIT runEnded(runId, nullptr, RunEnd::failed, QString::fromStdString(e.what()));
    }
    return;
  }
  TrappingProgress lastProgress = progressOf(request.state);
  const auto observer = [&](const TrappingState& state, const TrappingProgress& progress) {
    lastProgress = progress;
    if (inFlight_.load() >= kMaxSnapshotsInFlight) {
      skipped_.fetch_add(1);
      return;
    }
    inFlight_.fetch_add(1);
    Q_EMIT snapshotReady(makeSnapshot(runId, state, progress));
  };
  try {
    TrappingState state = runTrapping(std::move(request.state), coreOptions(request.settings), observer, stop);
    const auto how = state.finished() ? RunEnd::finished : static_cast<RunEnd>(endReason_.load());
    lastProgress.blocksDone = state.blocksDone;
    lastProgress.fraction = progressOf(state).fraction;
    if (how == RunEnd::finished) lastProgress.etaSeconds = 0;
    Q_EMIT runEnded(runId, makeSnapshot(runId, state, lastProgress), how, QString());
  } catch (const std::exception& e) {
    Q_EMIT runEnded(runId, nullptr, RunEnd::failed, QString::fromStdString(e.what()));
  }
}

}  // namespace archipelago::ui
