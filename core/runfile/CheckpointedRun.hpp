#pragma once
/// \file CheckpointedRun.hpp
/// \brief The trapping run as a job (core/job/Job.hpp): the one loop that advances a run with periodic checkpoints
/// into a run file, and the final write that rescues the work or says where it is when it fails.
/// `archipelago-cli run` and archipelago-mpi, the K scan (core/scan/ScanRun: the CLI's `scan` and the GUI's dialog)
/// and the reproduction report all call it, so a checkpoint is written, retried and reported the same way everywhere.
///
/// A checkpoint that cannot be written (a full disk, a vanished folder) must not cost the run: the warning is
/// reported and the write retried at the next interval (not at every chunk).  No checkpoint is written once the
/// run is finished: the caller's final write follows.

#include <string_view>
#include <optional>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <stop_token>
#include <string>

#include "core/job/Job.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago {

struct CheckpointedRunOptions {
  TrappingRunOptions run;
  std::filesystem::path checkpoint;  ///< the checkpoint file
  double checkpointSeconds = 60;     ///< between checkpoints, ≥ 0
  /// Polled at every chunk; true stops the run at that chunk (e.g. a signal's flag).  Empty: never.
  std::function<bool()> stopRequested;
  /// A checkpoint that could not be written: the reason, and the seconds until the next attempt.  Empty: silent.
  std::function<void(const std::string& reason, double retrySeconds)> warning;
};

/// Advances `state` until it is finished, `stop` is requested or options.stopRequested() says so, writing
/// options.checkpoint every checkpointSeconds and calling `progress` at every chunk.  `last` is updated at each
/// checkpoint written.  Throws what runTrapping() throws.
[[nodiscard]] TrappingState runWithCheckpoints(TrappingState state, const CheckpointedRunOptions& options,
                                               LastCheckpoint& last, const TrappingObserver& progress = {},
                                               std::stop_token stop = {});

/// Writes the run file.  When that fails (a full disk, a vanished folder), the run is written instead to
/// "<temporary folder>/NAME.rescued-PID.json" or, failing that, to the same name in $HOME, and a
/// std::runtime_error says where it went; when that fails too, the error says where the work done so far is
/// (`last`, followed by `howToResume` when it holds a checkpoint, e.g. ": resume with --resume FILE").
void saveRunFileOrSayWhere(const std::filesystem::path& path, const TrappingState& state, const LastCheckpoint& last,
                           const std::string& howToResume = {});

/// What to do with a run file that should hold a run of some parameters (runOrResumeFile()'s plan; the report's
/// "reusing …" and "resumed …").
enum class RunFileAction {
  start,   ///< no file: a fresh run
  resume,  ///< an unfinished run of these parameters: continued
  reuse,   ///< the finished run of these parameters: nothing to compute
};

/// The plan for `file` given what it holds (`held`: nullptr when it does not exist) and the parameters wanted.
/// Pure.  Throws std::runtime_error "FILE holds a run of other parameters" when `held` is a run of others.
[[nodiscard]] RunFileAction runFileAction(const std::filesystem::path& file, const TrappingState* held,
                                          const TrappingParameters& wanted);

/// What runOrResumeFile() found and did.
struct RunFileOutcome {
  TrappingState state;      ///< the run as it is now (finished, or stopped and saved)
  bool reused = false;      ///< the file held the finished run: nothing was computed
  bool resumed = false;     ///< the file held an unfinished run of these parameters: it was continued
};

/// The one "run or resume this file" step of the K scan (one file per K), the report (one file per run) and
/// `archipelago-cli run` when its output is its own checkpoint: `file` is locked for the whole call (one writer at
/// a time; io::FileLock) and its stale temporaries removed; when it exists it must hold a run of `params` (else
/// std::runtime_error: "… holds a run of other parameters") and is reused when finished or resumed; when it does
/// not, a fresh run of `params` over [orbitBegin, orbitEnd) starts.  The run goes on with runWithCheckpoints()
/// into `file` (options.checkpoint is set to it) and is saved there at the end (saveRunFileOrSayWhere(), so a
/// failing final write says where the work is).  A stopped run is saved and returned unfinished.
[[nodiscard]] RunFileOutcome runOrResumeFile(const std::filesystem::path& file, const TrappingParameters& params,
                                             CheckpointedRunOptions options, const TrappingObserver& progress = {},
                                             std::stop_token stop = {}, std::uint64_t orbitBegin = 0,
                                             std::uint64_t orbitEnd = UINT64_MAX);

}  // namespace archipelago
