#pragma once
/// \file RunSession.hpp
/// \brief What `run` and `scan` share: the options that make a run spec (a preset or spec file, then each
/// parameter of core's table), the locks on a run's files, the interrupt flag, and the loop that advances a run
/// with periodic checkpoints and writes it at the end.  One loop, so that a scan's run file of one K is the file
/// `run` makes with the same spec.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/spec/RunSpec.hpp"

namespace archipelago::cli {

/// The options that make a run spec, as typed.
struct SpecOptions {
  std::map<std::string, double> reals;            // --K, --xmin, --xmax, --Xr as typed
  std::map<std::string, std::uint64_t> integers;  // --q, --T, --M, --seed, --subsets, --longestKept as typed
  std::string preset;                             // --preset ID
  std::string specFile;                           // --spec FILE
  int threads = 0;                                // --threads (added by the command)
  std::string kernel;                             // --kernel (added by the command); empty: auto
};

/// Adds --preset, --spec and one option per parameter of parameterRules() except those in `without`.
void addSpecOptions(CLI::App& cmd, SpecOptions& o, std::initializer_list<std::string_view> without = {});

/// The parameters of `parameterRules()` and --preset/--spec given explicitly on the command line ("--K", …).
[[nodiscard]] std::vector<std::string> givenSpecOptions(const CLI::App& cmd);

/// The run spec of the command line: a preset or a spec file (or the defaults), then every parameter given
/// explicitly on top, --threads and --kernel when given; validated whole (spec/RunSpec.hpp), so a bad value is
/// named before any work starts.  Throws std::invalid_argument.
[[nodiscard]] RunSpec resolveSpec(const SpecOptions& o, const CLI::App& cmd);

/// The run's files, locked for the whole run (issue #12, finding 7): a second process on the same --out,
/// checkpoint or resumed file is refused before it reads or writes anything, and the temporaries a killed
/// writer left beside them are removed once the lock is held.  The resumed file is locked too (resuming the
/// checkpoint of a live run would fork it), unless its folder is read-only.
[[nodiscard]] std::vector<io::FileLock> lockRunFiles(const std::string& out, const std::string& checkpoint,
                                                     const std::string& resume);

/// Installs SIGINT/SIGTERM handlers that set the interrupt flag; the flag stops the run loop at its next chunk.
void installInterruptHandlers();
[[nodiscard]] bool interruptRequested() noexcept;

/// hh:mm:ss, or --:--:-- when unknown.
[[nodiscard]] std::string clockText(double seconds);

/// Where the last good checkpoint of a run is (the resumed file until one is written): what a failing final
/// write reports.
struct LastCheckpoint {
  std::string path;
  std::uint64_t blocks = 0;
};

struct CheckpointedRunOptions {
  TrappingRunOptions run;
  std::string checkpoint;          ///< the checkpoint file
  double checkpointSeconds = 60;   ///< between checkpoints
  bool breakLineBeforeWarning = false;  ///< a progress bar is on the terminal's line
};

/// Advances `state` until finished or interrupted, writing `checkpoint` every checkpointSeconds (a write that
/// fails warns on stderr and is retried at the next interval: it must not cost the run) and calling `progress`
/// at every chunk.  `last` is updated at each checkpoint written.
[[nodiscard]] TrappingState runWithCheckpoints(
    TrappingState state, const CheckpointedRunOptions& options, LastCheckpoint& last,
    const std::function<void(const TrappingState&, const TrappingProgress&)>& progress);

/// Writes the run file; when that fails, throws std::runtime_error whose text says where the work done so far is
/// kept (`last`).
void saveRunFileOrSayWhere(const std::string& path, const TrappingState& state, const LastCheckpoint& last);

}  // namespace archipelago::cli
