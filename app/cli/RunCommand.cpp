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
#include "core/io/AtomicFile.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/spec/RunSpec.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago::cli {

namespace {

volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) { gInterrupted = 1; }

struct RunOptions {
  TrappingParameters params;      // the run's parameters once resolved (resolveSpec)
  std::map<std::string, double> reals;            // --K, --xmin, --xmax, --Xr as typed
  std::map<std::string, std::uint64_t> integers;  // --q, --T, --M, --seed, --subsets, --longestKept as typed
  std::string preset;             // --preset ID
  std::string specFile;           // --spec FILE
  bool printSpec = false;
  std::string out = "run.json";
  std::string checkpoint;  // empty: the output file
  double checkpointSeconds = 60;
  std::string resume;
  int threads = 0;
  std::uint64_t maxChunkBlocks = 0;
  std::string kernel;  // empty: $ARCHIPELAGO_KERNEL, else the fastest the CPU supports
  bool quiet = false;
  std::string seeds;   // --seeds LIST: a seed ensemble, one run file per seed (issue #14, item 2)
};

std::string clock(double seconds) {
  if (!(seconds >= 0) || seconds > 1e8) return "--:--:--";
  const auto s = static_cast<long long>(seconds + 0.5);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%02lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60);
  return buf;
}

void drawProgress(const TrappingProgress& p, const std::string& kernel) {
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(p.fraction * kWidth);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r[%s] %5.1f%%  %.3g steps/s  ETA %s  (%s)   ", bar.c_str(), 100 * p.fraction,
               p.stepsPerSecond, clock(p.etaSeconds).c_str(), kernel.c_str());
  std::fflush(stderr);
}

/// The run's files, locked for the whole run (issue #12, finding 7): a second process on the same --out,
/// checkpoint or resumed file is refused before it reads or writes anything, and the temporaries a killed
/// writer left beside them are removed once the lock is held.
/// The resumed file is locked too (resuming the checkpoint of a live run would fork it), unless its folder
/// is read-only: nobody can be writing it then, and a run may start from a file it cannot lock.
std::vector<io::FileLock> lockRunFiles(const std::string& out, const std::string& checkpoint, const std::string& resume) {
  std::vector<io::FileLock> locks;
  std::vector<std::filesystem::path> held;
  const std::filesystem::path resumeFolder = std::filesystem::path(resume).parent_path();
  const bool lockResume = !resume.empty() && ::access(resumeFolder.empty() ? "." : resumeFolder.c_str(), W_OK) == 0;
  for (const std::string& path : {out, checkpoint, lockResume ? resume : std::string()}) {
    if (path.empty()) continue;
    const std::filesystem::path same = std::filesystem::weakly_canonical(path);  // one lock per file, however named
    if (std::find(held.begin(), held.end(), same) != held.end()) continue;
    locks.push_back(io::FileLock::acquire(path));
    held.push_back(same);
    io::removeStaleTemporaries(path);
  }
  return locks;
}

int runCommand(const RunOptions& o, const std::vector<std::string>& explicitParameters) {
  if (!o.resume.empty() && !explicitParameters.empty())
    throw std::invalid_argument("--resume takes the parameters from the run file; do not also give " +
                                explicitParameters.front());
  if (o.threads < 0 || o.threads > kMaxThreads)  // --resume skips the spec's validation
    throw std::invalid_argument("--threads = " + std::to_string(o.threads) + " must lie in [0, " +
                                std::to_string(kMaxThreads) + "] (0: one per core)");
  const std::string checkpoint = o.checkpoint.empty() ? o.out : o.checkpoint;
  // Every output path before any work (issue #12, finding 7): a typo fails now, not after the computation.
  io::checkWritableTarget(o.out);
  io::checkWritableTarget(checkpoint);
  const std::vector<io::FileLock> locks = lockRunFiles(o.out, checkpoint, o.resume);

  TrappingState state;
  if (!o.resume.empty()) {
    state = loadRunFile(o.resume);
    if (state.finished()) throw std::invalid_argument(o.resume + " is already finished (" +
                                                      std::to_string(state.blocksDone) + " of T blocks)");
  }
  const TrappingParameters& params = o.resume.empty() ? o.params : state.params;
  if (auto e = memoryError(params, o.threads)) throw std::runtime_error(*e);  // before allocating the orbits
  if (o.resume.empty()) state = startTrapping(o.params);
  const bool tty = ::isatty(STDERR_FILENO) != 0;

  std::stop_source stopper;
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  const KernelInfo& kernel = selectKernel(o.kernel);
  TrappingRunOptions options;
  options.kernel = &kernel;
  options.threads = o.threads;
  options.maxChunkBlocks = o.maxChunkBlocks;
  // Where the last good checkpoint is (the resumed file until one is written): what a failing write reports.
  std::string lastCheckpoint = o.resume;
  std::uint64_t lastCheckpointBlocks = state.blocksDone;
  auto lastCheckpointTime = std::chrono::steady_clock::now();
  auto lastLine = lastCheckpointTime;
  auto observer = [&](const TrappingState& s, const TrappingProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (gInterrupted) stopper.request_stop();
    if (std::chrono::duration<double>(now - lastCheckpointTime).count() >= o.checkpointSeconds && !s.finished()) {
      lastCheckpointTime = now;  // a failed write is retried at the next interval, not at every chunk
      // A checkpoint that cannot be written (full disk, vanished folder) must not cost the run: warn, go on.
      try {
        saveRunFile(checkpoint, s);
        lastCheckpoint = checkpoint;
        lastCheckpointBlocks = s.blocksDone;
      } catch (const std::exception& e) {
        if (tty && !o.quiet) std::fputc('\n', stderr);
        std::fprintf(stderr, "WARNING: checkpoint not written: %s; the run goes on and retries in %g s\n", e.what(),
                     o.checkpointSeconds);
      }
    }
    // A progress bar on a terminal; on a pipe or file, a line every 10 s.
    if (!o.quiet && (tty || std::chrono::duration<double>(now - lastLine).count() >= 10)) {
      drawProgress(p, std::string(kernel.name));
      if (!tty) std::fputc('\n', stderr);
      lastLine = now;
    }
  };
  // The final write: when it fails, the ERROR says where the work done so far is kept.
  auto save = [&](const std::string& path) {
    try {
      saveRunFile(path, state);
    } catch (const std::exception& e) {
      const std::string kept = lastCheckpoint.empty()
          ? std::string("no checkpoint was written")
          : "the last checkpoint (" + std::to_string(lastCheckpointBlocks) + " of " + std::to_string(state.params.T) +
                " blocks) is in " + lastCheckpoint + ": resume with --resume " + lastCheckpoint;
      throw std::runtime_error(std::string(e.what()) + "; " + kept);
    }
  };
  state = runTrapping(std::move(state), options, observer, stopper.get_token());
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
  }
  return 0;
}

/// The run spec of the command line: a preset or a spec file (or the defaults), then every parameter given
/// explicitly on top; validated whole (spec/RunSpec.hpp), so a bad value is named before any work starts.
RunSpec resolveSpec(const RunOptions& o, const CLI::App& cmd) {
  if (!o.preset.empty() && !o.specFile.empty()) throw std::invalid_argument("give --preset or --spec, not both");
  // An empty --preset= or --spec= is a mistake, never a silent fall back to the defaults.
  if (cmd.count("--preset") > 0 && o.preset.empty())
    throw std::invalid_argument("--preset is empty (archipelago-cli presets lists the presets)");
  if (cmd.count("--spec") > 0 && o.specFile.empty()) throw std::invalid_argument("--spec is empty: give a spec file");
  RunSpec spec;
  if (!o.preset.empty()) {
    const Preset* preset = findPreset(o.preset);
    if (!preset) {
      std::string ids;
      for (const Preset& p : presets()) ids += (ids.empty() ? "" : ", ") + p.id;
      throw std::invalid_argument("--preset " + o.preset + " is not a preset (presets: " + ids + ")");
    }
    spec = preset->spec;
  } else if (!o.specFile.empty()) {
    spec = loadRunSpec(o.specFile);
  }
  for (const ParameterRule& rule : parameterRules()) {
    const std::string key(rule.key);
    if (cmd.count("--" + key) == 0) continue;
    if (rule.integer) setParameterValue(spec.parameters, key, o.integers.at(key));
    else setParameterValue(spec.parameters, key, o.reals.at(key));
  }
  if (cmd.count("--threads") > 0) spec.threads = o.threads;
  if (cmd.count("--kernel") > 0) spec.kernel = o.kernel.empty() ? "auto" : o.kernel;
  if (auto e = validationError(spec)) throw std::invalid_argument(*e);
  return spec;
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
  cmd->add_option("--preset", o->preset, "start from a preset of the paper (archipelago-cli presets lists them)");
  cmd->add_option("--spec", o->specFile, "start from a run spec file (JSON; --print-spec writes one)");
  // One option per parameter of the run, from core's table (TrappingParameters.hpp): name, meaning, range.
  // Given explicitly, a parameter overrides the preset's or the spec file's.
  const RunSpec defaults;
  for (const ParameterRule& rule : parameterRules()) {
    const std::string key(rule.key);
    const std::string help = std::string(rule.meaning) + "; " + std::string(rule.range);
    const ParameterValue value = parameterValue(defaults.parameters, key);
    const std::string names = "--" + key + (key == "longestKept" ? ",--longest" : "");  // --longest: the old name
    if (rule.integer) addNumberOption(*cmd, names, o->integers[key] = std::get<std::uint64_t>(value), help);
    else addNumberOption(*cmd, names, o->reals[key] = std::get<double>(value), help);
  }
  addNumberOption(*cmd, "--threads", o->threads, "OpenMP threads (0: all cores; at most " + std::to_string(kMaxThreads) + ")");
  cmd->add_option("--out", o->out, "run file written at the end")->capture_default_str();
  cmd->add_option("--checkpoint", o->checkpoint, "checkpoint file (default: the --out file)");
  addNumberOption(*cmd, "--checkpoint-interval", o->checkpointSeconds, "seconds between checkpoints");
  cmd->add_option("--resume", o->resume, "continue the run in this checkpoint or run file");
  addNumberOption(*cmd, "--max-chunk", o->maxChunkBlocks, "at most this many blocks between progress reports (0: adaptive)");
  addKernelOption(*cmd, o->kernel);
  cmd->add_flag("--print-spec", o->printSpec, "print the run spec (JSON) these options make, and run nothing");
  cmd->add_flag("--quiet", o->quiet, "no progress bar or summary");
  cmd->add_option("--seeds", o->seeds,
                  "a seed ensemble: one independent run per seed (e.g. 1..8 or 1,2,5..7, at most " +
                      std::to_string(kMaxSeeds) + "), written to NAME.seed-K.json for --out NAME.json; "
                      "`stats` combines the files");
  cmd->callback([o, cmd, &status] {
    std::vector<std::string> given;
    for (const ParameterRule& rule : parameterRules())
      if (cmd->count("--" + std::string(rule.key)) > 0) given.push_back("--" + std::string(rule.key));
    for (const char* name : {"--preset", "--spec"})
      if (cmd->count(name) > 0) given.emplace_back(name);
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
    o->threads = spec.threads;
    o->kernel = spec.kernel == "auto" ? std::string() : spec.kernel;  // "auto": $ARCHIPELAGO_KERNEL or the fastest
    status = ensemble ? runSeeds(*o, given) : runCommand(*o, given);
  });
}

}  // namespace archipelago::cli
