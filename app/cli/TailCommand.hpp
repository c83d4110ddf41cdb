#pragma once
/// \file TailCommand.hpp
/// \brief `archipelago-cli tail`: P_t beyond brute force by splitting on segment age (core/tail, issue #29), for
/// the process of `run` (the same spec options).  Checkpoints and resumes bit for bit; SIGINT saves and exits 130.
/// With --compare RUN.json…: the brute-force P_t of those runs at the same levels, and the steps each needs.
/// With --slice I/N: replicas [⌊R·I/N⌋, ⌊R·(I+1)/N⌋) only, a tail file that `merge` joins with the other slices.
/// The parts below are shared with `archipelago-mpi tail` (app/mpi/MpiTail.hpp), which runs slice rank/size.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "RunSession.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/run/TrappingRun.hpp"
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
struct TailJob {
  TailState state;
  std::vector<TrappingState> runs;  // --compare
  bool printedLevels = false;       // --print-levels: printed, nothing to run
};
/// A new run (the spec and the sampler's options; only the replicas `slice` when given) or the one in the tail
/// file `resume` (o.resume when empty): the options filled into core's planTail() (core/tail/TailPlan.hpp), which
/// decides; a new run's request, threads and kernel are written back to `o`; --print-levels prints here.  Throws
/// std::invalid_argument / std::runtime_error for anything wrong.
[[nodiscard]] TailJob prepareTail(TailOptions& o, const CLI::App& cmd, std::optional<ReplicaRange> slice,
                                  const std::string& resume = {});

/// Runs the sampler from `state` with progress on stderr (unless o.quiet), a checkpoint to `checkpoint` every
/// o.checkpointSeconds, and SIGINT/SIGTERM; returns the state where it stopped (finished or not).
/// `lastCheckpoint`: where the last checkpoint is (resume's file), updated when one is written.
[[nodiscard]] TailState runTailSession(TailState state, const TailOptions& o, const std::string& checkpoint,
                                       std::string& lastCheckpoint);

/// Saves `state` to `path`; a failure names the last checkpoint to resume from.
void saveTailOrSayWhere(const std::string& path, const TailState& state, const std::string& lastCheckpoint);

/// The end of a finished run: --csv, the table of levels and the comparison with --compare's runs (unless quiet).
void reportTail(const TailState& state, const TailOptions& o, const std::vector<TrappingState>& runs);

void addTailCommand(CLI::App& app, int& status);

}  // namespace archipelago::cli
