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
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/runfile/CheckpointedRun.hpp"
#include "core/runspec/RunSpec.hpp"

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
/// explicitly on top, --threads and --kernel when given; validated whole (runspec/RunSpec.hpp), so a bad value is
/// named before any work starts.  Throws std::invalid_argument.
[[nodiscard]] RunSpec resolveSpec(const SpecOptions& o, const CLI::App& cmd);

/// Prints core's warning (checkBoxAgainstIsland, core/atlas/BoxIslandCheck.hpp) on stderr when the box or its
/// randomizing zone cuts the central island: the run goes on, but it is not the paper's process (issue 39).
void warnIfBoxCutsIsland(const TrappingParameters& p);

/// The run's files (--out, the checkpoint, --resume), locked for the whole run: core's lockJobFiles()
/// (core/job/Job.hpp), which every job's files go through.
[[nodiscard]] std::vector<io::FileLock> lockRunFiles(const std::string& out, const std::string& checkpoint,
                                                     const std::string& resume);

/// The program's one stop (issue 51): SIGINT/SIGTERM set the interrupt flag and request the stop of
/// interruptToken(), which every job of core is given.  installInterruptHandlers() installs the handlers once (a
/// second call does nothing); interruptToken() installs them too.
void installInterruptHandlers();
[[nodiscard]] std::stop_token interruptToken();
[[nodiscard]] bool interruptRequested() noexcept;

/// hh:mm:ss, or --:--:-- when unknown.
[[nodiscard]] std::string clockText(double seconds);

/// The final write of `run` (core's saveRunFileOrSayWhere, runfile/CheckpointedRun.hpp, whose loop
/// runWithCheckpoints the commands call): when it fails, the error says where the last checkpoint is and how to
/// resume it (--resume).
using archipelago::LastCheckpoint;
/// ": resume with --resume FILE" for the last checkpoint, or "" when there is none: how the command line resumes.
[[nodiscard]] std::string howToResume(const LastCheckpoint& last);
void saveRunFileOrSayWhere(const std::string& path, const TrappingState& state, const LastCheckpoint& last);

}  // namespace archipelago::cli
