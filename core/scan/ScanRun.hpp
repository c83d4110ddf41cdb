#pragma once
/// \file ScanRun.hpp
/// \brief The K scan of §5 as a resumable computation: the one loop that `archipelago-cli scan` and the GUI's
/// K-scan dialog both call, so that a scan folder made by one is resumed, and summarised, identically by the other.
///
/// A scan folder holds one run file per K (K0.05.json: the shortest text that reads back as K), each the
/// run of the scan's parameters in the box of scanBox(K), and, once every K is finished, the summaries of
/// scan/ScanSummary.hpp.  A K whose run file is finished is not run again; an unfinished one is resumed from its
/// file.  The folder's summary file is locked for the whole scan (one scan per folder at a time), each K's
/// run file while it runs.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "core/scan/ScanBox.hpp"
#include "core/scan/ScanSummary.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/runspec/RunSpec.hpp"

namespace archipelago {

/// The run file of K in the scan folder `dir`: dir/K<scanKText(K)>.json.
[[nodiscard]] std::filesystem::path scanRunFile(const std::filesystem::path& dir, double K);

/// A scan to run.
struct KScanRequest {
  RunSpec base;                    ///< the parameters but the map (K and the box are the scan's), threads, kernel name
  std::vector<double> K;           ///< the K values, in the order of the summaries
  std::filesystem::path dir;       ///< the scan folder (created when missing; its parent must exist)
  const KernelInfo* kernel = nullptr;  ///< chosen at the edge (selectKernel); nullptr: the fastest
  double checkpointSeconds = 60;   ///< between checkpoints of the K running
  std::uint64_t maxChunkBlocks = 0;
  std::uint64_t b2Iterations = 0;  ///< > 0: b₂ of every box with this many steps (recomputed on every invocation)
};

/// The parameters of K in the scan `r` (r.base's parameters in the box of scanBox(K)).
[[nodiscard]] TrappingParameters scanParameters(const KScanRequest& r, double K);

/// Every check of the scan before any work, without touching the disk: the K list, the parameters of every K
/// (runspec/RunSpec.hpp rules), their memory, the b₂ request, the checkpoint interval.  The first problem as one
/// line, or nothing.
[[nodiscard]] std::optional<std::string> kScanValidationError(const KScanRequest& r);

/// Whether `dir` can hold a scan, without changing anything: an existing writable folder, or a missing one whose
/// parent is a writable folder.  The reason as one line naming the path, or nothing.
[[nodiscard]] std::optional<std::string> scanFolderError(const std::filesystem::path& dir);

/// Where a scan is, at every chunk of the K running (and once for each K at its start).
struct KScanProgress {
  std::size_t index = 0;            ///< the K running (0-based)
  std::size_t count = 0;            ///< the number of K
  double K = 0;
  std::uint64_t blocksDone = 0;     ///< of this K
  std::uint64_t blocksTotal = 0;    ///< T
  double stepsDone = 0;             ///< of the whole scan (orbits × blocks × q, over every K)
  double stepsTotal = 0;
  double stepsPerSecond = 0;        ///< of this session; 0 until known
  double etaK = -1;                 ///< seconds left for this K at that rate; < 0 when unknown
  double etaScan = -1;              ///< seconds left for the whole scan; < 0 when unknown
  [[nodiscard]] double fractionK() const {
    return blocksTotal > 0 ? static_cast<double>(blocksDone) / static_cast<double>(blocksTotal) : 0;
  }
  [[nodiscard]] double fractionScan() const { return stepsTotal > 0 ? stepsDone / stepsTotal : 0; }
};

/// What a scan reports while it runs.  Each callback may be empty; all are called on the scan's thread.
struct KScanObserver {
  std::function<void(const KScanProgress&)> progress;
  /// A K is finished (already at the start, or just now): its summary, with b₂ when asked.
  std::function<void(std::size_t index, const ScanRunSummary&)> finished;
  /// A checkpoint could not be written (the run goes on and retries at the next interval).
  std::function<void(const std::string&)> warning;
};

/// The end of a scan.
struct KScanOutcome {
  bool finished = false;               ///< every K finished and the summaries written
  std::vector<ScanRunSummary> runs;    ///< every K, in the request's order (when finished)
  std::size_t stoppedIndex = 0;        ///< when stopped: the K whose run file holds the checkpoint
  std::filesystem::path stoppedFile;
};

/// Runs (or resumes) the scan until every K is finished, then writes scan_f_t.csv, scan_local_exponent.csv and
/// scan_summary.csv into r.dir; or until `stop` is requested (checked at chunk ends), when the K running is
/// saved in its run file and the outcome says so.  Throws std::invalid_argument for a bad request
/// (kScanValidationError), std::runtime_error for a folder that cannot be used, a run file of other parameters,
/// a lock held by another process, or a final write that fails (saying where the last checkpoint is).
[[nodiscard]] KScanOutcome runKScan(const KScanRequest& r, const KScanObserver& observer = {},
                                    std::stop_token stop = {});

/// The scan summaries of `runs` in `dir` (scan_f_t.csv, scan_local_exponent.csv, scan_summary.csv), each
/// written atomically.
void writeScanSummaries(const std::filesystem::path& dir, const std::vector<ScanRunSummary>& runs);

}  // namespace archipelago
