#pragma once
/// \file TailSession.hpp
/// \brief What `archipelago-cli tail` (app/cli/TailCommand.hpp) and `archipelago-mpi tail` (app/mpi/MpiTail.hpp)
/// share: the options, filled into core's tail session (core/tail/TailJob.hpp: runTailSession), its progress on
/// stderr, and the outcome's text.  Parse, fill, call and format: the plan, the locks, the checkpoints, the stop, the
/// rescue of the final write, the merge of the ranks' slices and the report's text are core's.

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "RunSession.hpp"
#include "core/tail/TailJob.hpp"

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

/// The sampler's own options (--population, --replicas, --first, --t-max, --level-bins, --epsilon, --clones,
/// --metropolis-steps, --warmup, --min-ancestors): `tail`'s and `tail-scan`'s.
void addSamplerOptions(CLI::App& cmd, TailRequest& r, std::string& clones);

/// Every option of `tail` on `cmd` (`withSlice`: --slice too; archipelago-mpi takes the slice from its rank).
void addTailOptions(CLI::App& cmd, TailOptions& o, bool withSlice);

/// The options filled into core's tail session (core/tail/TailJob.hpp: runTailSession), named as the command line
/// names them (flagOf): the plan's options (the spec resolved from the command line when the plan needs it; --slice
/// as given), the kernel, and the view — progress on stderr unless o.quiet (a line every 10 s, or a line redrawn on a
/// terminal), checkpoint warnings, core's warning about the box when o.warnings.
[[nodiscard]] TailSessionOptions tailSession(const TailOptions& o, const CLI::App& cmd);

/// The session's text for stdout: the levels of --print-levels, or the report of a finished run (its table of
/// levels and comparison).
void printTailOutcome(const TailSessionOutcome& outcome);

}  // namespace archipelago::cli
