#pragma once
/// \file TailPlan.hpp
/// \brief The plan of a tail command (`archipelago-cli tail`, `archipelago-mpi tail`): the options a front end
/// filled, checked in one call that returns the sampler run to do (started, or read from the tail file to resume)
/// with the runs to compare it with, or throws one error (docs/design.md, "Front ends fill, call and format").
/// The front end then locks its files, runs the sampler and writes its outputs.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/run/TrappingRun.hpp"
#include "core/runspec/RunSpec.hpp"
#include "core/tail/TailSampler.hpp"

namespace archipelago {

/// The inverse of cloneRuleName(); throws std::invalid_argument "<option> '<text>' must be perturb or metropolis"
/// (`option`: the front end's name of the setting).
[[nodiscard]] CloneRule parseCloneRule(const std::string& text, const std::string& option = "clones");

/// Slice I of N of the replicas from the text "I/N" (the CLI's --slice): whole numbers with I < N ≤ R = `replicas`.
/// Throws std::invalid_argument "<option> '<text>' must be I/N, whole numbers with I < N <= R = <R> (slice I of N)".
[[nodiscard]] ReplicaRange parseReplicaSlice(const std::string& option, const std::string& text, std::uint32_t replicas);

/// What a front end filled: its options as given, and how it names them.  Core's messages name each setting and
/// file by its role ("resume", "checkpoint-interval", "compare-csv", "out", "checkpoint", "csv", "spec", "compare",
/// "print-levels", "clones", "slice"); `optionName` maps a role to the front end's own name (archipelago-cli: "--resume";
/// Python: "resume"), so that nobody is told of an option their front end does not have.
struct TailPlanOptions {
  std::function<std::string(std::string_view role)> optionName;  ///< empty: the role itself
  /// The front end's name of a role (optionName, or the role).
  [[nodiscard]] std::string nameOf(std::string_view role) const;

  /// The sampler's settings of a new run (request.run is filled from `spec`, request.clones from `clones`).
  TailRequest request;
  std::string clones = "perturb";
  /// The spec of a new run (a preset, a spec file, the options given), resolved when the plan needs it, after the
  /// checks of the options that precede it; it may throw.  Not called when resuming.
  std::function<RunSpec()> spec;
  /// The names of the spec options and of the sampler's options given (a resumed run takes both from its file).
  std::vector<std::string> givenSpec;
  std::vector<std::string> givenSampler;
  std::int64_t threads = 0;         ///< as given (--threads): checked by threadsError()
  double checkpointSeconds = 60;    ///< checkpointIntervalError()'s rule
  bool printLevels = false;         ///< a new run's levels only: nothing read, nothing run
  std::optional<ReplicaRange> slice;  ///< a new run's replicas; none: all
  std::optional<std::string> sliceText;  ///< the slice as given, "I/N" (parseReplicaSlice(), role "slice"); replaces slice
  /// Core's warning about a new run (checkBoxAgainstIsland(): the box or its zone cuts the central island), given
  /// when the spec is resolved; empty: none is looked for.
  std::function<void(const std::string& warning)> warning;
  std::string resume;               ///< --resume as given: the tail file of the run to continue; empty: a new run
  std::string resumeFile;           ///< the file actually read (archipelago-mpi: this rank's slice); empty: resume
  std::string out = "tail.json";    ///< --out
  std::string checkpoint;           ///< --checkpoint; empty: out
  std::string csv;                  ///< --csv
  std::string compareCsv;           ///< --compare-csv
  std::string specFile;             ///< --spec (an input no output may overwrite)
  std::vector<std::string> compare; ///< --compare: run files of the same process
};

/// A ready sampler run.
struct TailPlan {
  TailState state;                  ///< started (or a slice of one), or read from the resumed file
  std::vector<TrappingState> runs;  ///< --compare's, checked to pool at the state's levels
  bool printLevelsOnly = false;     ///< printLevels: state holds the new run's levels; nothing else was read
  std::int64_t threads = 0;         ///< a new run's: the spec's; resumed: as given
  std::string kernel;               ///< a new run's: the spec's ("" for auto); resumed: empty (the front end's)
};

/// Checks the options and starts or reads the run, in this order: the slice as given (not with a resumed run); the
/// options a resumed run must not repeat;
/// the threads and the checkpoint interval; a new run's spec, clone rule and request (and, for printLevels, its
/// levels: then it returns); the files (no output over another or over an input, a run compared once); the
/// resumed file (not already finished, unless resumeFile is given: a rank's finished slice); each compared run,
/// read and matched to the sampler's process, and their pooling.  Throws std::invalid_argument (or the file
/// readers' errors) with the one wording of each rule.
[[nodiscard]] TailPlan planTail(const TailPlanOptions& options);

}  // namespace archipelago
