#pragma once
/// \file TailJob.hpp
/// \brief The tail sampler as a job (core/job/Job.hpp; issue 51): its run with a checkpoint into a tail file on a
/// clock, a cooperative stop, and the final write that rescues the work or says where it is; and the whole session
/// of a tail command around it (runTailSession: plan, locks, run, save or rescue, the outputs and the report's text),
/// on one process or sliced over ranks (core/job/Ranks.hpp).  archipelago-cli tail and archipelago-mpi tail (each
/// rank its slice) run the session, Python's tail() and tail_resume() the loop; they only fill the options, show its
/// progress and format its outcome in their own words.

#include <filesystem>
#include <functional>
#include <stop_token>
#include <string>
#include <string_view>

#include <optional>
#include <vector>

#include "core/job/Job.hpp"
#include "core/job/Ranks.hpp"
#include "core/tail/BruteForceSurvival.hpp"
#include "core/tail/TailPlan.hpp"
#include "core/tail/TailResult.hpp"
#include "core/tail/TailSampler.hpp"

namespace archipelago {

struct TailJobOptions {
  TailRunOptions run;
  std::filesystem::path checkpoint;  ///< the tail file checkpointed into; empty: no checkpoints
  double checkpointSeconds = 60;     ///< between checkpoints (checkpointIntervalError()'s rule)
  /// A checkpoint that could not be written: the reason and the seconds until the next attempt.  Empty: silent.
  std::function<void(const std::string& reason, double retrySeconds)> warning;
  /// The front end's name of a setting's role (TailSettingOutOfReach); empty: the role itself.
  std::function<std::string(std::string_view role)> optionName;
};

/// Advances `state` with runTail() until it is finished or `stop` is requested, writing options.checkpoint every
/// checkpointSeconds while unfinished (a failed write goes to `warning` and is retried at the next interval) and
/// calling `progress` at every chunk.  `last` becomes the checkpoint at each one written.  A setting found out of
/// reach while running (TailSettingOutOfReach) is thrown as std::invalid_argument naming it by options.optionName.
[[nodiscard]] TailState runTailJob(TailState state, const TailJobOptions& options, LastCheckpoint& last,
                                   const TailObserver& progress = {}, std::stop_token stop = {});

/// Saves `state` to `path` (saveTailFile); when that fails, saveOrRescue() rescues it to the temporary or home
/// folder, or says where the last checkpoint is, followed by `howToResume` (the front end's words, e.g.
/// ": resume with --resume FILE").
void saveTailOrSayWhere(const std::filesystem::path& path, const TailState& state, const LastCheckpoint& last,
                        const std::string& howToResume = {});

/// The slice file of rank r of R beside NAME: "tail.json" → "tail.slice-1-of-4.json" (the extension kept last),
/// "tail" → "tail.slice-1-of-4".  What each rank of a sliced session checkpoints into and writes when it stops.
[[nodiscard]] std::string tailSliceFileName(const std::string& name, int rank, int size);

/// How a front end shows a tail session (every member may be empty).
struct TailSessionView {
  TailObserver progress;  ///< at every chunk of the sampler (the front end throttles and formats)
  std::function<void()> runEnded;  ///< when the sampler stops, before the final writes (e.g. a progress line ends)
  std::function<void(const std::string& reason, double retrySeconds)> checkpointWarning;  ///< TailJobOptions::warning
};

/// What a front end gives a tail session: its options filled into the plan (its names of the roles too), the kernel
/// it asks for, and its view.  Rank 0 alone gets the plan's warning and the report.
struct TailSessionOptions {
  TailPlanOptions plan;
  std::string kernel;  ///< a resumed run's kernel (a new run's is its spec's); empty: the fastest
  bool quiet = false;  ///< no report's text
  TailSessionView view;
};

/// How a tail session ended.
struct TailSessionOutcome {
  enum class End {
    levelsOnly,   ///< plan.printLevels: `state` holds the new run's levels; nothing was run
    interrupted,  ///< stopped: the state (each rank's slice) is in `checkpoint`
    finished,     ///< the tail file and its CSVs are written
  };
  End end = End::finished;
  TailState state;         ///< the run where it ended (finished and sliced: the merged run on rank 0)
  std::string checkpoint;  ///< interrupted: the file holding the state (sliced: rank 0's slice)
  TailResult result;       ///< finished, on rank 0
  std::string report;      ///< finished, on rank 0, unless quiet: the table of levels and the comparison (stdout's)
};

/// The tail command's session on `ranks` until it finishes or `stop` is requested: the plan (planTail; sliced: rank r
/// runs slice r of R, resumed from NAME.slice-r-of-R.json, tailSliceFileName()), the files locked (lockJobFiles), the
/// job run (runTailJob) with checkpoints into the checkpoint file (sliced: the rank's slice file).  Stopped, the state
/// is saved there (sliced: every rank's slice, finished or not).  Finished, all at once (io::OutputBatch): the tail
/// file (sliced: rank 0 merges the slices, mergeTailSlices, and removes them), its CSV and the comparison's CSV; the
/// outcome holds the result and the report's text (tailLevelsText, tailComparisonText).  An error on any rank is one
/// error on all (Ranks::agree), thrown as std::invalid_argument / std::runtime_error; a final write that fails
/// rescues the work and says how to resume it (plan.nameOf("resume")).
[[nodiscard]] TailSessionOutcome runTailSession(const TailSessionOptions& options, Ranks& ranks,
                                                std::stop_token stop = {});

/// The table of levels of a run and its running exponent, as `tail` prints it: a header line of the settings, the
/// slice when it is one, a row per level (t, P, P_error, survivors, ancestors, fewest, reliable, steps), then the
/// exponents over decade windows.
[[nodiscard]] std::string tailLevelsText(const TailState& state, const TailResult& result);

/// The comparison with runs as `tail --compare` prints it: a row per level with the brute-force P and its error,
/// z, and the steps a brute-force run needs for the sampler's error.
[[nodiscard]] std::string tailComparisonText(const TailComparison& comparison);

/// The comparison with runs as CSV (the CLI's --compare-csv): two comment lines (the runs' steps and α), then
/// t,P,P_error,reliable,brute_P,brute_error,brute_segments,z,tail_steps,brute_steps_same_error,measured; a number
/// with 17 significant digits, empty when not finite.
[[nodiscard]] std::string tailComparisonCsv(const TailComparison& comparison);

}  // namespace archipelago
