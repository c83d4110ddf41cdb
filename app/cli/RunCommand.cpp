#include "RunCommand.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <variant>
#include <stdexcept>
#include <vector>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/runspec/InputRules.hpp"
#include "core/runspec/RunSpec.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago::cli {

namespace {

int runCommand(const RunOptions& o, const std::vector<std::string>& explicitParameters) {
  if (!o.resume.empty() && !o.orbits.empty())
    throw std::invalid_argument("--resume takes the orbit range from the run file; do not also give --orbits");
  if (!o.resume.empty() && !explicitParameters.empty())
    throw std::invalid_argument("--resume takes the parameters from the run file; do not also give " +
                                explicitParameters.front());
  if (auto e = threadsError(o.threads)) throw std::invalid_argument("--" + *e);  // --resume skips the spec's check
  const std::string checkpoint = o.checkpoint.empty() ? o.out : o.checkpoint;
  // Every output path before any work (issue #12, finding 7): a typo fails now, not after the computation.
  io::checkCommandFiles({{"--out", o.out, io::FileUse::SavedState},
                         {"--checkpoint", checkpoint, io::FileUse::SavedState},
                         {"--resume", o.resume, io::FileUse::ResumedState},
                         {"--spec", o.specFile, io::FileUse::Input}});
  // Ctrl-C and SIGTERM are caught before the files are locked: from here on they stop the run at a chunk boundary
  // (or before it starts) and the locks are released, never left behind by the default action.
  installInterruptHandlers();
  const std::vector<io::FileLock> locks = lockRunFiles(o.out, checkpoint, o.resume);

  TrappingState state;
  if (!o.resume.empty()) {
    state = loadRunFile(o.resume);
    if (state.finished()) throw std::invalid_argument(o.resume + " is already finished (" +
                                                      std::to_string(state.blocksDone) + " of T blocks)");
  }
  const TrappingParameters& params = o.resume.empty() ? o.params : state.params;
  if (auto e = memoryError(params, o.threads)) throw std::runtime_error(*e);  // before allocating the orbits
  warnIfBoxCutsIsland(params);
  if (o.resume.empty()) {
    const auto [begin, end] = orbitRange(o.orbits, o.params.M);
    state = startTrapping(o.params, begin, end);
  }
  const bool tty = ::isatty(STDERR_FILENO) != 0;

  const KernelInfo& kernel = selectKernel(o.kernel);
  CheckpointedRunOptions options;
  options.run.kernel = &kernel;
  options.run.threads = o.threads;
  options.run.maxChunkBlocks = o.maxChunkBlocks;
  options.checkpoint = checkpoint;
  options.checkpointSeconds = o.checkpointSeconds;
  options.warning = [&](const std::string& reason, double retrySeconds) {
    if (tty && !o.quiet) std::fputc('\n', stderr);  // off the progress bar's line
    std::fprintf(stderr, "WARNING: checkpoint not written: %s; the run goes on and retries in %g s\n", reason.c_str(),
                 retrySeconds);
  };
  // The spec's q = 1 companion first (issue #26: the short times of the paper's process; a small fraction of the
  // steps), run or resumed in its own file beside --out.
  if (o.companion > 0 && o.resume.empty() && o.orbits.empty()) {
    const std::filesystem::path file = companionRunFile(o.out);
    const TrappingParameters cp = companionParameters(params, o.companion);
    if (!o.quiet)
      std::fprintf(stderr, "companion   q = 1, T = %llu steps (%.3g of the run's steps) -> %s\n",
                   static_cast<unsigned long long>(cp.T), o.companion, file.c_str());
    const RunFileOutcome c = runOrResumeFile(file, cp, options, {}, interruptToken());
    if (!c.state.finished()) {
      std::fprintf(stderr, "interrupted: the companion is saved in %s (the same command resumes it)\n", file.c_str());
      return 130;
    }
  }
  LastCheckpoint last{o.resume, state.blocksDone};
  auto lastLine = std::chrono::steady_clock::now();
  auto progress = [&](const TrappingState&, const TrappingProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    // A progress bar on a terminal; on a pipe or file, a line every 10 s.
    if (!o.quiet && (tty || std::chrono::duration<double>(now - lastLine).count() >= 10)) {
      drawProgress(p, std::string(kernel.name));
      if (!tty) std::fputc('\n', stderr);
      lastLine = now;
    }
  };
  // The final write: when it fails, the ERROR says where the work done so far is kept.
  auto save = [&](const std::string& path) { saveRunFileOrSayWhere(path, state, last); };
  state = runWithCheckpoints(std::move(state), options, last, progress, interruptToken());
  if (!o.quiet && tty) std::fputc('\n', stderr);
  if (!state.finished()) {
    save(checkpoint);
    std::fprintf(stderr, "interrupted: checkpoint written to %s (resume with --resume %s)\n", checkpoint.c_str(),
                 checkpoint.c_str());
    return 130;  // 128 + SIGINT, as a shell reports a process stopped by Ctrl-C
  }
  save(o.out);
  if (!o.quiet) {
    const TrappingHistogram total = state.total();
    const std::uint64_t longest = state.longest.items().empty() ? 0 : state.longest.items().front().length;
    std::fprintf(stderr, "done: %llu segments, longest %llu steps, %.3g steps in %.1f s (%s kernel); wrote %s\n",
                 static_cast<unsigned long long>(total.segments()),
                 static_cast<unsigned long long>(longest * state.params.q), state.stepsDone(),
                 state.elapsedSeconds, state.kernel.c_str(), o.out.c_str());
    if (o.companion > 0 && o.orbits.empty())
      std::fprintf(stderr, "statistics: archipelago-cli stats %s --short %s\n", o.out.c_str(),
                   companionRunFile(o.out).c_str());
  }
  return 0;
}

/// A seed ensemble (`--seeds 1..8`): runCommand() once per seed, each an ordinary run of its own seed written
/// to seededPath(--out, seed) (and its checkpoint to seededPath(--checkpoint, seed) when one is given), so each
/// file equals what `run --seed K --out that-file` writes.  An interrupted seed stops the ensemble (the seeds
/// before it are finished; it is resumed alone with --resume).
int runSeeds(const RunOptions& o, const std::vector<std::string>& given) {
  const std::vector<std::uint64_t> seeds = parseSeedList("--seeds", o.seeds);
  for (const std::uint64_t seed : seeds) {
    RunOptions one = o;
    one.params.seed = seed;
    one.out = seededPath(o.out, seed);
    if (!o.checkpoint.empty()) one.checkpoint = seededPath(o.checkpoint, seed);
    if (!o.quiet) std::fprintf(stderr, "seed %llu -> %s\n", static_cast<unsigned long long>(seed), one.out.c_str());
    const int status = runCommand(one, given);
    if (status != 0) {
      std::fprintf(stderr, "the ensemble stopped at seed %llu (%zu of %zu seeds finished)\n",
                   static_cast<unsigned long long>(seed),
                   static_cast<std::size_t>(&seed - seeds.data()), seeds.size());
      return status;
    }
  }
  return 0;
}

}  // namespace

void addRunCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "trapping statistics: M orbits x T blocks of N^-q (paper section 3)");
  addRunOptions(*cmd, *o);
  cmd->callback([o, cmd, &status] {
    const std::vector<std::string> given = givenSpecOptions(*cmd);
    const bool ensemble = cmd->count("--seeds") > 0;
    if (ensemble) {  // refused before any work: which file would hold what must be clear
      if (!o->resume.empty())
        throw std::invalid_argument("--seeds cannot resume: resume each seed's file with --resume NAME.seed-K.json");
      if (cmd->count("--seed") > 0) throw std::invalid_argument("give --seed or --seeds, not both");
      if (o->printSpec) throw std::invalid_argument("--print-spec prints one run's spec: give --seed, not --seeds");
      (void)parseSeedList("--seeds", o->seeds);
    }
    if (!o->resume.empty()) {
      status = runCommand(*o, given);
      return;
    }
    const RunSpec spec = resolveSpec(*o, *cmd);
    if (o->printSpec) {
      std::fputs(runSpecJson(spec).c_str(), stdout);
      status = 0;
      return;
    }
    o->params = spec.parameters;
    (void)orbitRange(o->orbits, o->params.M);  // a bad range is named before any work
    o->threads = spec.threads;
    o->companion = spec.companion;
    o->kernel = spec.kernel == "auto" ? std::string() : spec.kernel;  // "auto": $ARCHIPELAGO_KERNEL or the fastest
    status = ensemble ? runSeeds(*o, given) : runCommand(*o, given);
  });
}

}  // namespace archipelago::cli
