#include "core/scan/ScanRun.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "core/io/AtomicFile.hpp"
#include "core/stochasticarea/StochasticArea.hpp"
#include "core/runfile/CheckpointedRun.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/scan/ScanPoint.hpp"

namespace archipelago {

namespace {

/// The b₂ computation of one K of the scan: the run's map, randomizing zone, q and seed.
StochasticAreaRequest b2Request(const TrappingParameters& p, std::uint64_t iterations, const KernelInfo* kernel) {
  StochasticAreaRequest r;
  r.map = p.map;
  r.Xr = p.Xr;
  r.q = p.q;
  r.seed = p.seed;
  r.iterations = iterations;
  r.firstCheckpoint = std::min<std::uint64_t>(r.firstCheckpoint, iterations);
  r.kernel = kernel;
  return r;
}

double stepsOf(const TrappingParameters& p, std::uint64_t blocks) {
  return static_cast<double>(p.M) * static_cast<double>(blocks) * p.q;
}

/// One K of the scan: its parameters, its file, and what is known of it before this session.
struct ScanItem {
  TrappingParameters params;
  std::filesystem::path file;
  std::uint64_t blocksDone = 0;
  bool finished = false;
};

ScanRunSummary summaryOf(const TrappingState& state, const KScanRequest& r) {
  const TrappingStatistics statistics = statisticsOf(state);
  std::optional<StochasticAreaValue> b2;
  if (r.b2Iterations > 0) {
    const StochasticAreaRequest b = b2Request(state.params, r.b2Iterations, r.kernel);
    b2 = stochasticAreaOf(b.map, computeStochasticArea(b).fraction());
  }
  return {state.params, scanPointOf(state, statistics, b2), statistics};
}

}  // namespace

std::filesystem::path scanRunFile(const std::filesystem::path& dir, double K) {
  return dir / ("K" + scanKText(K) + ".json");
}

TrappingParameters scanParameters(const KScanRequest& r, double K) {
  TrappingParameters p = r.base.parameters;
  p.map = scanBox(K);
  return p;
}

std::optional<std::string> kScanValidationError(const KScanRequest& r) {
  try {
    checkScanValues(r.K);
  } catch (const std::exception& e) {
    return e.what();
  }
  if (!(r.checkpointSeconds >= 0)) return "the checkpoint interval must not be negative";
  if (r.dir.empty()) return "the scan folder is empty: give a folder";
  for (const double K : r.K) {
    RunSpec spec = r.base;
    spec.parameters = scanParameters(r, K);
    if (auto e = validationError(spec)) return "K = " + scanKText(K) + ": " + *e;
    if (auto e = memoryError(spec.parameters, r.base.threads)) return *e;
    if (r.b2Iterations > 0)
      if (auto e = validationError(b2Request(spec.parameters, r.b2Iterations, r.kernel)))
        return "b2 at K = " + scanKText(K) + ": " + *e;
  }
  return std::nullopt;
}

std::optional<std::string> scanFolderError(const std::filesystem::path& dir) {
  if (dir.empty()) return "the scan folder is empty: give a folder";
  std::error_code ec;
  try {
    if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
      return "cannot scan into " + dir.string() + ": it is not a folder";
    if (std::filesystem::exists(dir, ec))
      io::checkWritableTarget(dir / scanSummaryCsvFileName);
    else
      io::checkWritableTarget(dir);  // its parent exists and is writable
  } catch (const std::exception& e) {
    return std::string(e.what());
  }
  return std::nullopt;
}

void writeScanSummaries(const std::filesystem::path& dir, const std::vector<ScanRunSummary>& runs) {
  io::writeFileAtomically(dir / scanFtCsvFileName, scanFtCsv(runs));
  io::writeFileAtomically(dir / scanLocalExponentCsvFileName, scanLocalExponentCsv(runs));
  io::writeFileAtomically(dir / scanSummaryCsvFileName, scanSummaryCsv(runs));
}

KScanOutcome runKScan(const KScanRequest& r, const KScanObserver& observer, std::stop_token stop) {
  if (auto e = kScanValidationError(r)) throw std::invalid_argument(*e);
  const std::filesystem::path& dir = r.dir;
  std::error_code ec;
  if (auto e = scanFolderError(dir)) throw std::runtime_error(*e);
  if (!std::filesystem::exists(dir, ec)) std::filesystem::create_directory(dir);
  io::checkWritableTarget(dir / scanSummaryCsvFileName);
  const io::FileLock scanLock = io::FileLock::acquire(dir / scanSummaryCsvFileName);

  // Every K checked before any work: its parameters and any run file already there.
  std::vector<ScanItem> items;
  for (const double K : r.K) {
    ScanItem item;
    item.params = scanParameters(r, K);
    item.file = scanRunFile(dir, K);
    if (std::filesystem::exists(item.file, ec)) {
      const TrappingState state = loadRunFile(item.file);
      if (!(state.params == item.params))
        throw std::runtime_error(item.file.string() + " holds a run of other parameters than this scan's K = " +
                                 scanKText(K) + " (another folder, or remove the file)");
      item.blocksDone = state.blocksDone;
      item.finished = state.finished();
    }
    items.push_back(item);
  }

  // Progress of the whole scan: steps over every K, the rate of this session, its ETA.
  double totalSteps = 0, stepsBefore = 0;
  for (const ScanItem& item : items) {
    totalSteps += stepsOf(item.params, item.params.T);
    stepsBefore += stepsOf(item.params, item.blocksDone);
  }
  const auto sessionStart = std::chrono::steady_clock::now();
  double stepsFinishedThisSession = 0;  // whole K finished in this session (beyond what they had before)

  KScanOutcome outcome;
  for (std::size_t k = 0; k < items.size(); ++k) {
    ScanItem& item = items[k];
    if (item.finished) {
      outcome.runs.push_back(summaryOf(loadRunFile(item.file), r));
      if (observer.finished) observer.finished(k, outcome.runs.back());
      continue;
    }
    const std::uint64_t blocksAtStart = item.blocksDone;  // read by the check above

    auto report = [&](const TrappingParameters& params, std::uint64_t blocksDone) {
      if (!observer.progress) return;
      KScanProgress p;
      p.index = k;
      p.count = items.size();
      p.K = params.map.K;
      p.blocksDone = blocksDone;
      p.blocksTotal = params.T;
      const double thisSession = stepsFinishedThisSession + stepsOf(params, blocksDone - blocksAtStart);
      p.stepsDone = stepsBefore + thisSession;
      p.stepsTotal = totalSteps;
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sessionStart).count();
      p.stepsPerSecond = seconds > 0 && thisSession > 0 ? thisSession / seconds : 0;
      if (p.stepsPerSecond > 0) {
        p.etaK = stepsOf(params, params.T - blocksDone) / p.stepsPerSecond;
        p.etaScan = (totalSteps - p.stepsDone) / p.stepsPerSecond;
      }
      observer.progress(p);
    };
    report(item.params, blocksAtStart);

    // Run or resume this K's file: core's one step for it (runfile/CheckpointedRun.hpp), as the report's runs.
    CheckpointedRunOptions run;
    run.run.kernel = r.kernel;
    run.run.threads = r.base.threads;
    run.run.maxChunkBlocks = r.maxChunkBlocks;
    run.checkpointSeconds = r.checkpointSeconds;
    if (observer.warning)
      run.warning = [&](const std::string& reason, double) {
        observer.warning("checkpoint not written: " + reason + "; the run goes on and retries");
      };
    const TrappingState state =
        runOrResumeFile(item.file, item.params, run,
                        [&](const TrappingState& s, const TrappingProgress&) { report(s.params, s.blocksDone); }, stop)
            .state;
    if (!state.finished()) {
      outcome.stoppedIndex = k;
      outcome.stoppedFile = item.file;
      outcome.runs.clear();
      return outcome;
    }
    stepsFinishedThisSession += stepsOf(item.params, state.blocksDone - blocksAtStart);
    item.finished = true;
    outcome.runs.push_back(summaryOf(loadRunFile(item.file), r));  // as a later resume reads it
    if (observer.finished) observer.finished(k, outcome.runs.back());
  }
  writeScanSummaries(dir, outcome.runs);
  outcome.finished = true;
  return outcome;
}

}  // namespace archipelago
