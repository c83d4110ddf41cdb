#include "ui/run/RunWorker.hpp"

#include "core/stats/RunEnsemble.hpp"

#include <exception>
#include <utility>

#include "core/kernels/KernelDispatch.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/theory/TheoryCurves.hpp"

namespace archipelago::ui {

namespace {
// At most this many snapshots travel to the GUI at once; more would only queue up stale copies.
constexpr int kMaxSnapshotsInFlight = 2;

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

RunSnapshotPtr makeSnapshot(std::uint64_t runId, const TrappingState& state, const TrappingProgress& progress,
                            bool judgeTail, std::shared_ptr<const TrappingState> companion) {
  auto snapshot = std::make_shared<RunSnapshot>();
  snapshot->runId = runId;
  snapshot->state = state;
  snapshot->progress = progress;
  snapshot->kernel = state.kernel;
  if (state.blocksDone > 0 && state.total().segments() > 0) {
    snapshot->statistics = statisticsOf(state);
    if (companion && companion->finished() && state.finished()) {
      try {
        snapshot->statistics = splicedStatisticsOf(state, *companion);
        snapshot->companion = std::move(companion);
      } catch (const std::exception&) {
        // Not this run's companion, or the two never agree above 10 q: the run's own statistics, whose block-
        // affected times the plots shade (blockAffectedBelow).
      }
    }
    snapshot->hasStatistics = true;
    snapshot->theory = theoryCurves(state.params, snapshot->statistics);
    if (judgeTail) {
      try {
        // `stats`'s own options (the default seed and replicates): the Statistics page's D error, γ_P and
        // verdict are the CLI's for the same run file (issue 37, finding 19).
        snapshot->tail = std::make_shared<const TailAnalysis>(analyseTail(ensembleOf({state})));
      } catch (const std::exception&) {
        // Too few segments to judge: the view says the error is not known.
      }
    }
  }
  return snapshot;
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

RunWorker::RunWorker(QObject* parent) : QObject(parent) {
  qRegisterMetaType<RunSnapshotPtr>("archipelago::ui::RunSnapshotPtr");
  qRegisterMetaType<RunEnd>("archipelago::ui::RunEnd");
}

RunWorker::~RunWorker() = default;  // jobs_ goes first: it stops the session and waits for its thread

void RunWorker::startRun(std::uint64_t runId, TrappingState state, const RunSettings& settings) {
  submit(runId, std::move(state), settings, true);
}

void RunWorker::analyse(std::uint64_t runId, TrappingState state, std::shared_ptr<const TrappingState> companion) {
  submit(runId, std::move(state), RunSettings{}, false, std::move(companion));
}

void RunWorker::requestEnd(std::uint64_t runId, RunEnd how) {
  if (runId != sessionRunId_ || !endReason_) return;
  endReason_->store(static_cast<int>(how));
  jobs_.requestStop(sessionJob_);  // its result still comes back, with `how`
}

void RunWorker::snapshotConsumed() noexcept {
  // Never below zero: a session's start forgets the snapshots of the one it replaced (dropped, never consumed).
  int n = inFlight_.load();
  while (n > 0 && !inFlight_.compare_exchange_weak(n, n - 1)) {
  }
}

void RunWorker::submit(std::uint64_t runId, TrappingState state, const RunSettings& settings, bool advance,
                       std::shared_ptr<const TrappingState> companion) {
  auto endReason = std::make_shared<std::atomic<int>>(static_cast<int>(RunEnd::finished));
  struct Ended {
    RunSnapshotPtr last;
    RunEnd how = RunEnd::finished;
  };
  Job<Ended, RunSnapshotPtr> job;
  job.work = [this, runId, state = std::move(state), settings, advance, endReason,
              companion = std::move(companion)](JobContext<RunSnapshotPtr>& context) mutable -> std::optional<Ended> {
    if (!advance) return Ended{makeSnapshot(runId, state, progressOf(state), true, companion), RunEnd::finished};
    busy_ = true;
    inFlight_ = 0;  // the snapshots of a replaced session were dropped
    struct NotBusy {
      std::atomic<bool>& busy;
      ~NotBusy() { busy = false; }
    } notBusy{busy_};
    TrappingProgress lastProgress = progressOf(state);
    const auto observer = [&](const TrappingState& now, const TrappingProgress& progress) {
      lastProgress = progress;
      if (inFlight_.load() >= kMaxSnapshotsInFlight) {
        skipped_.fetch_add(1);
        return;
      }
      inFlight_.fetch_add(1);
      context.post(makeSnapshot(runId, now, progress));
    };
    TrappingState ended = runTrapping(std::move(state), coreOptions(settings), observer, context.stopToken());
    const auto how = ended.finished() ? RunEnd::finished : static_cast<RunEnd>(endReason->load());
    lastProgress.blocksDone = ended.blocksDone;
    lastProgress.fraction = progressOf(ended).fraction;
    if (how == RunEnd::finished) lastProgress.etaSeconds = 0;
    // The q = 1 companion (issue #26), a small fraction of the run's steps, once the run is finished.
    if (how == RunEnd::finished && settings.companion > 0 && ended.params.q > 1) {
      // The window says that the companion runs, and how far it is (the run itself is at 100 %).
      auto base = std::make_shared<RunSnapshot>(*makeSnapshot(runId, ended, lastProgress));
      base->companionRunning = true;
      inFlight_.fetch_add(1);
      context.post(base);
      const auto companionObserver = [&](const TrappingState&, const TrappingProgress& progress) {
        if (inFlight_.load() >= kMaxSnapshotsInFlight) {
          skipped_.fetch_add(1);
          return;
        }
        auto now = std::make_shared<RunSnapshot>(*base);
        now->companionFraction = progress.fraction;
        inFlight_.fetch_add(1);
        context.post(std::move(now));
      };
      TrappingState short1 = runTrapping(startTrapping(companionParameters(ended.params, settings.companion)),
                                         coreOptions(settings), companionObserver, context.stopToken());
      if (short1.finished()) companion = std::make_shared<const TrappingState>(std::move(short1));
    }
    return Ended{makeSnapshot(runId, ended, lastProgress, true, companion), how};
  };
  job.progress = [this](quint64, RunSnapshotPtr snapshot) { Q_EMIT snapshotReady(std::move(snapshot)); };
  job.done = [this, runId](JobResult<Ended> result) {
    if (result.ok())
      Q_EMIT runEnded(runId, std::move(result.value->last), result.value->how, QString());
    else
      Q_EMIT runEnded(runId, nullptr, RunEnd::failed, result.error);
  };
  // A replaced session stops at its next chunk boundary (RunEnd::stopped), its reports dropped: latest wins.
  if (endReason_) endReason_->store(static_cast<int>(RunEnd::stopped));
  sessionRunId_ = runId;
  endReason_ = std::move(endReason);
  sessionJob_ = jobs_.submit(std::move(job));
}

}  // namespace archipelago::ui
