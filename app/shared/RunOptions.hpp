#pragma once
/// \file RunOptions.hpp
/// \brief The options of a trapping run, as archipelago-cli run and archipelago-mpi take them (one definition,
/// issue #15), and the progress bar both draw.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

#include "RunSession.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago::cli {

/// Every option of `run`: the spec options (RunSession.hpp), --threads, --kernel, the files, checkpoints,
/// --orbits, --seeds.  archipelago-mpi (app/mpi) takes the same set.
struct RunOptions : SpecOptions {
  TrappingParameters params;      // the run's parameters once resolved (resolveSpec)
  bool printSpec = false;
  std::string out = "run.json";
  std::string checkpoint;  // empty: the output file
  double checkpointSeconds = 60;
  std::string resume;
  std::uint64_t maxChunkBlocks = 0;
  bool quiet = false;
  std::string orbits;  // --orbits BEGIN:END: only these orbits (a part for `merge`, issue #15)
  std::string seeds;   // --seeds LIST: a seed ensemble, one run file per seed (issue #14, item 2)
  double companion = 0;  // the spec's q = 1 companion (fraction of the steps; 0: none), written beside --out
};

/// Registers the options of `run` on `cmd`.
void addRunOptions(CLI::App& cmd, RunOptions& o);

/// The progress bar of a run on stderr (carriage return, no newline).
void drawProgress(const TrappingProgress& p, const std::string& kernel);

}  // namespace archipelago::cli
