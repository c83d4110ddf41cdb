#pragma once
/// \file TailJob.hpp
/// \brief The tail sampler as a job (core/job/Job.hpp; issue 51): its run with a checkpoint into a tail file on a
/// clock, a cooperative stop, and the final write that rescues the work or says where it is.  archipelago-cli tail,
/// archipelago-mpi tail (each rank its slice) and Python's tail() and tail_resume() run this one loop; they only
/// show its progress and say how to resume in their own words.

#include <filesystem>
#include <functional>
#include <stop_token>
#include <string>

#include "core/job/Job.hpp"
#include "core/tail/BruteForceSurvival.hpp"
#include "core/tail/TailSampler.hpp"

namespace archipelago {

struct TailJobOptions {
  TailRunOptions run;
  std::filesystem::path checkpoint;  ///< the tail file checkpointed into; empty: no checkpoints
  double checkpointSeconds = 60;     ///< between checkpoints (checkpointIntervalError()'s rule)
  /// A checkpoint that could not be written: the reason and the seconds until the next attempt.  Empty: silent.
  std::function<void(const std::string& reason, double retrySeconds)> warning;
};

/// Advances `state` with runTail() until it is finished or `stop` is requested, writing options.checkpoint every
/// checkpointSeconds while unfinished (a failed write goes to `warning` and is retried at the next interval) and
/// calling `progress` at every chunk.  `last` becomes the checkpoint at each one written.
[[nodiscard]] TailState runTailJob(TailState state, const TailJobOptions& options, LastCheckpoint& last,
                                   const TailObserver& progress = {}, std::stop_token stop = {});

/// Saves `state` to `path` (saveTailFile); when that fails, saveOrRescue() rescues it to the temporary or home
/// folder, or says where the last checkpoint is, followed by `howToResume` (the front end's words, e.g.
/// ": resume with --resume FILE").
void saveTailOrSayWhere(const std::filesystem::path& path, const TailState& state, const LastCheckpoint& last,
                        const std::string& howToResume = {});

/// The comparison with runs as CSV (the CLI's --compare-csv): two comment lines (the runs' steps and α), then
/// t,P,P_error,reliable,brute_P,brute_error,brute_segments,z,tail_steps,brute_steps_same_error,measured; a number
/// with 17 significant digits, empty when not finite.
[[nodiscard]] std::string tailComparisonCsv(const TailComparison& comparison);

}  // namespace archipelago
