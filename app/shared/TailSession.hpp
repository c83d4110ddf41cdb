#pragma once
/// \file TailSession.hpp
/// \brief What `archipelago-cli tail` (app/cli/TailCommand.hpp) and `archipelago-mpi tail` (app/mpi/MpiTail.hpp)
/// share: the options, filled into core's plan (core/tail/TailPlan.hpp), the job run with its progress on stderr
/// (core's runTailJob, core/tail/TailJob.hpp) and the report of a finished run.  Parse, fill, call and format: the
/// plan, the checkpoints, the stop and the rescue of the final write are core's.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "RunSession.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/tail/TailJob.hpp"
#include "core/tail/TailResult.hpp"

namespace archipelago::cli {

struct TailOptions : SpecOptions {
  TailRequest request;
  std::string clones = "perturb";
  std::string out = "tail.json";
  std::string csv;
  std::string checkpoint;  // empty: the --out file
  double checkpointSeconds = 60;
  std::string resume;
  std::vector<std::string> compare;
  std::string compareCsv;
  std::string slice;       // "I/N": this process's slice of the replicas
  bool printLevels = false;
  bool quiet = false;
  bool warnings = true;    // core's warnings about the run (the box and the island) on stderr: archipelago-mpi's rank 0 only
};

/// Every option of `tail` on `cmd` (`withSlice`: --slice too; archipelago-mpi takes the slice from its rank).
void addTailOptions(CLI::App& cmd, TailOptions& o, bool withSlice);

/// The options checked and the sampler run they ask for, read or started, before any work.
struct PreparedTail {
  TailState state;
  std::vector<TrappingState> runs;  // --compare
  bool printedLevels = false;       // --print-levels: printed, nothing to run
};
/// A new run (the spec and the sampler's options; only the replicas `slice` when given) or the one in the tail
/// file `resume` (o.resume when empty): the options filled into core's planTail() (core/tail/TailPlan.hpp), which
/// decides; a new run's request, threads and kernel are written back to `o`; --print-levels prints here.  Throws
/// std::invalid_argument / std::runtime_error for anything wrong.
[[nodiscard]] PreparedTail prepareTail(TailOptions& o, const CLI::App& cmd, std::optional<ReplicaRange> slice,
                                  const std::string& resume = {});

/// Runs core's tail job from `state` with progress on stderr (unless o.quiet), a checkpoint to `checkpoint` every
/// o.checkpointSeconds, stopped by the program's interrupt (interruptToken()); returns the state where it stopped
/// (finished or not).  `last`: where the last checkpoint is (resume's file), updated when one is written.
[[nodiscard]] TailState runTailSession(TailState state, const TailOptions& o, const std::string& checkpoint,
                                       LastCheckpoint& last);

/// core's saveTailOrSayWhere() with the command line's way to resume (howToResume()).
void saveTail(const std::string& path, const TailState& state, const LastCheckpoint& last);

/// The end of a finished run: --csv, the table of levels and the comparison with --compare's runs (unless quiet).
void reportTail(const TailState& state, const TailOptions& o, const std::vector<TrappingState>& runs);

}  // namespace archipelago::cli
