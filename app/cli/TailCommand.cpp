#include "TailCommand.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stop_token>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/tail/BruteForceSurvival.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailPlan.hpp"

namespace archipelago::cli {

namespace {

// The sampler's own options, as they are named in errors and --help.
const char* const kSamplerOptions[] = {"--population", "--replicas", "--first", "--t-max", "--level-bins", "--epsilon",
                                       "--clones", "--metropolis-steps", "--warmup", "--min-ancestors"};

std::string text(double v) { return io::formatC("%.4g", v); }

void printLevels(const TailState& s, const TailResult& r) {
  std::printf("# tail: K = %s, q = %u, N = %u, R = %u, epsilon = %llu, clones = %s; %s steps%s\n",
              io::shortestText(s.request.run.map.K).c_str(), s.request.run.q, s.request.population,
              s.request.replicas, static_cast<unsigned long long>(s.request.epsilon), cloneRuleName(s.request.clones),
              text(r.steps).c_str(), r.finished ? "" : " (unfinished)");
  if (s.replicas.size() != s.request.replicas)
    std::printf("# the slice of replicas [%u, %zu) of %u: P and its error are those of its replicas alone\n",
                s.firstReplica, s.firstReplica + s.replicas.size(), s.request.replicas);
  std::printf("%12s %12s %10s %10s %10s %8s %9s %12s\n", "t", "P", "P_error", "survivors", "ancestors", "fewest",
              "reliable", "steps");
  for (const TailLevelResult& L : r.levels)
    std::printf("%12.0f %12.5g %10.3g %10llu %10llu %8llu %9s %12.4g\n", L.t, L.P, L.PError,
                static_cast<unsigned long long>(L.survivors), static_cast<unsigned long long>(L.ancestors),
                static_cast<unsigned long long>(L.fewestAncestors), L.reliable ? "yes" : "no", L.steps);
  if (!r.exponents.empty()) {
    std::printf("# running exponent gamma(t) = -dlnP/dlnt over decade windows (as stats: least squares on a log grid)\n");
    std::printf("%12s %12s %12s %8s %8s\n", "t", "t_from", "t_to", "gamma", "error");
    for (const TailExponent& e : r.exponents)
      std::printf("%12.4g %12.0f %12.0f %8.4f %8.3g\n", e.t, e.tFrom, e.tTo, e.gamma, e.gammaError);
  }
}

std::string comparisonCsv(const TailComparison& c) {
  std::string out = "# brute-force steps: " + io::formatC("%.17g", c.bruteSteps) + "\n# alpha: " +
                    io::formatC("%.17g", c.alpha) + "\n";
  out += "t,P,P_error,reliable,brute_P,brute_error,brute_segments,z,tail_steps,brute_steps_same_error,measured\n";
  const auto n = [](double v) { return std::isfinite(v) ? io::formatC("%.17g", v) : std::string(); };
  for (const TailComparisonLevel& l : c.levels)
    out += n(l.t) + "," + n(l.P) + "," + n(l.PError) + "," + (l.reliable ? "1" : "0") + "," + n(l.bruteP) + "," +
           n(l.bruteError) + "," + std::to_string(l.bruteSegments) + "," + n(l.z) + "," + n(l.tailSteps) + "," +
           n(l.bruteStepsSameError) + "," + (l.bruteStepsMeasured ? "1" : "0") + "\n";
  return out;
}

void printComparison(const TailComparison& c) {
  std::printf("# against brute force: %s steps of run, alpha = %.4g steps\n", text(c.bruteSteps).c_str(), c.alpha);
  std::printf("%12s %12s %10s %12s %10s %8s %7s %12s %14s\n", "t", "P", "P_error", "brute_P", "error", "segments", "z",
              "tail_steps", "brute_steps*");
  for (const TailComparisonLevel& l : c.levels)
    std::printf("%12.0f %12.5g %10.3g %12.5g %10.3g %8llu %7.2f %12.4g %13.4g%s\n", l.t, l.P, l.PError, l.bruteP,
                l.bruteError, static_cast<unsigned long long>(l.bruteSegments), l.z, l.tailSteps,
                l.bruteStepsSameError, l.bruteStepsMeasured ? "" : "e");
  std::printf("# brute_steps*: steps a brute-force run needs for the sampler's relative error at t (from the runs' "
              "own error; e: estimated alpha/(P r^2) where they have none)\n");
}

// "I/N" of --slice: slice I of N (0 ≤ I < N ≤ R).
ReplicaRange sliceOption(const std::string& text, std::uint32_t replicas) {
  const std::string rule = "I/N, whole numbers with I < N <= R = " + std::to_string(replicas) + " (slice I of N)";
  const std::vector<std::uint32_t> v = parseNumbers<std::uint32_t>("--slice", text, '/', 2, rule);
  if (!(v[0] < v[1] && v[1] <= replicas)) throw std::invalid_argument("--slice '" + io::shortText(text) + "' must be " + rule);
  return replicaSlice(replicas, v[0], v[1]);
}

int tailCommand(TailOptions& o, const CLI::App& cmd) {
  std::optional<ReplicaRange> slice;
  const CLI::Option* sliceGiven = cmd.get_option_no_throw("--slice");
  if (sliceGiven && sliceGiven->count() > 0) {  // given empty is an error too, not the whole run (issue 36)
    if (!o.resume.empty()) throw std::invalid_argument("--resume takes the slice from the tail file; do not also give --slice");
    slice = sliceOption(o.slice, o.request.replicas);
  }
  TailJob job = prepareTail(o, cmd, slice);
  if (job.printedLevels) return 0;
  const std::string checkpoint = o.checkpoint.empty() ? o.out : o.checkpoint;
  const std::vector<io::FileLock> locks = lockRunFiles(o.out, checkpoint, o.resume);
  std::string lastCheckpoint = o.resume;
  TailState state = runTailSession(std::move(job.state), o, checkpoint, lastCheckpoint);
  if (!state.finished()) {
    saveTailOrSayWhere(checkpoint, state, lastCheckpoint);
    std::fprintf(stderr, "interrupted: checkpoint written to %s (resume with --resume %s)\n", checkpoint.c_str(),
                 checkpoint.c_str());
    return 130;
  }
  io::OutputBatch outputs;  // the tail file and its CSVs: all or nothing (issue 36, class 5)
  saveTailOrSayWhere(o.out, state, lastCheckpoint);
  reportTail(state, o, job.runs);
  outputs.commit();
  if (!o.quiet) {
    const TailResult result = tailResult(state);
    std::fprintf(stderr, "done: %zu levels, the largest reliable t = %.4g; %.3g steps in %.1f s (%s kernel); wrote %s\n",
                 result.levels.size(), largestReliableT(result), result.steps, state.elapsedSeconds,
                 state.kernel.c_str(), o.out.c_str());
    if (state.replicas.size() != state.request.replicas)
      std::fprintf(stderr, "this is replicas [%u, %zu) of %u: merge the slices with archipelago-cli merge\n",
                   state.firstReplica, state.firstReplica + state.replicas.size(), state.request.replicas);
  }
  return 0;
}

}  // namespace


TailJob prepareTail(TailOptions& o, const CLI::App& cmd, std::optional<ReplicaRange> slice, const std::string& resumeFile) {
  TailPlanOptions options;
  options.request = o.request;
  options.clones = o.clones;
  options.spec = [&o, &cmd] {
    RunSpec spec = resolveSpec(o, cmd);
    if (o.warnings) warnIfBoxCutsIsland(spec.parameters);
    return spec;
  };
  options.givenSpec = givenSpecOptions(cmd);
  for (const char* name : kSamplerOptions)
    if (cmd.count(name) > 0) options.givenSampler.emplace_back(name);
  options.threads = o.threads;
  options.checkpointSeconds = o.checkpointSeconds;
  options.printLevels = o.printLevels;
  options.slice = slice;
  options.resume = o.resume;
  options.resumeFile = resumeFile;
  options.out = o.out;
  options.checkpoint = o.checkpoint;
  options.csv = o.csv;
  options.compareCsv = o.compareCsv;
  options.specFile = o.specFile;
  options.compare = o.compare;
  TailPlan plan = planTail(options);
  TailJob job;
  job.state = std::move(plan.state);
  job.runs = std::move(plan.runs);
  if (o.resume.empty()) {  // the new run's settings, for the session that runs it
    o.request = job.state.request;
    o.threads = static_cast<int>(plan.threads);
    o.kernel = plan.kernel;
  }
  if (plan.printLevelsOnly) {
    std::printf("t (steps)\n");
    for (const std::uint64_t L : job.state.levels)
      std::printf("%llu\n", static_cast<unsigned long long>(L * o.request.run.q));
    job.printedLevels = true;
  }
  return job;
}

TailState runTailSession(TailState state, const TailOptions& o, const std::string& checkpoint, std::string& lastCheckpoint) {
  if (state.finished()) return state;
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  installInterruptHandlers();
  const KernelInfo& kernel = selectKernel(o.kernel);
  TailRunOptions options;
  options.threads = o.threads;
  options.kernel = &kernel;
  std::stop_source stopper;
  // A signal's flag stops the sampler within a chunk, even inside a long stage-0 batch or Metropolis step.
  std::jthread watcher([&](std::stop_token done) {
    while (!done.stop_requested()) {
      if (interruptRequested()) {
        stopper.request_stop();
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  });
  auto lastSave = std::chrono::steady_clock::now();
  auto lastLine = std::chrono::steady_clock::now() - std::chrono::hours(1);
  const auto observer = [&](const TailState& s, const TailProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - lastSave).count() >= o.checkpointSeconds && !s.finished()) {
      lastSave = now;
      try {
        saveTailFile(checkpoint, s);
        lastCheckpoint = checkpoint;
      } catch (const std::exception& e) {
        if (tty && !o.quiet) std::fputc('\n', stderr);
        std::fprintf(stderr, "WARNING: checkpoint not written: %s; the sampler goes on and retries in %g s\n", e.what(),
                     o.checkpointSeconds);
      }
    }
    if (!o.quiet && (tty ? std::chrono::duration<double>(now - lastLine).count() >= 0.2
                         : std::chrono::duration<double>(now - lastLine).count() >= 10)) {
      lastLine = now;
      if (p.level == 0 && s.entryOrbits == 0)
        std::fprintf(stderr, "%sstage 0, pilot: %llu of %llu segments reached t = %llu  %.3g steps  %.3g steps/s   %s",
                     tty ? "\r" : "", static_cast<unsigned long long>(s.pilotSuccesses),
                     static_cast<unsigned long long>(s.pilotTrials),
                     static_cast<unsigned long long>(s.levels[0] * s.request.run.q), p.steps, p.stepsPerSecond,
                     tty ? "" : "\n");
      else if (p.level == 0)
        std::fprintf(stderr, "%sstage 0: %llu successes at t = %llu  %.3g steps  %.3g steps/s   %s", tty ? "\r" : "",
                     static_cast<unsigned long long>(p.alive), static_cast<unsigned long long>(s.levels[0] * s.request.run.q),
                     p.steps, p.stepsPerSecond, tty ? "" : "\n");
      else
        std::fprintf(stderr, "%slevel %zu of %zu: t = %.4g, %llu walkers alive  %.3g steps  %.3g steps/s (%s)   %s",
                     tty ? "\r" : "", p.level, p.levels, p.t, static_cast<unsigned long long>(p.alive), p.steps,
                     p.stepsPerSecond, kernel.name.data(), tty ? "" : "\n");
      std::fflush(stderr);
    }
  };
  state = runTail(std::move(state), options, observer, stopper.get_token());
  watcher.request_stop();
  if (!o.quiet && tty) std::fputc('\n', stderr);
  return state;
}

void saveTailOrSayWhere(const std::string& path, const TailState& state, const std::string& lastCheckpoint) {
  try {
    saveTailFile(path, state);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string(e.what()) + (lastCheckpoint.empty()
                                                          ? "; no checkpoint was written"
                                                          : "; the last checkpoint is in " + lastCheckpoint +
                                                                ": resume with --resume " + lastCheckpoint));
  }
}

void reportTail(const TailState& state, const TailOptions& o, const std::vector<TrappingState>& runs) {
  const TailResult result = tailResult(state);
  if (!o.csv.empty()) io::writeFileAtomically(o.csv, tailCsvText(state, result));
  if (!o.quiet) printLevels(state, result);
  if (!runs.empty()) {
    const TailComparison c = compareWithRuns(state, result, runs);
    if (!o.compareCsv.empty()) io::writeFileAtomically(o.compareCsv, comparisonCsv(c));
    if (!o.quiet) printComparison(c);
  }
}

void addTailOptions(CLI::App& cmd_, TailOptions& o_, bool withSlice) {
  CLI::App* cmd = &cmd_;
  TailOptions* o = &o_;
  addSpecOptions(*cmd, *o, {"T", "M", "subsets", "longestKept"});
  TailRequest& r = o->request;
  addNumberOption(*cmd, "--population", r.population, "N: walkers per replica (2 to " + std::to_string(kMaxTailPopulation) + ")");
  addNumberOption(*cmd, "--replicas", r.replicas, "R: independent replicas; the error of P is their spread (1 to " +
                                                       std::to_string(kMaxTailReplicas) + ")");
  addNumberOption(*cmd, "--first", r.firstSteps, "the first level is the lowest at or above this t (steps): entries are sampled by brute force up to it");
  addNumberOption(*cmd, "--t-max", r.maxSteps, "the last level is the lowest at or above this t (steps)");
  addNumberOption(*cmd, "--level-bins", r.binsPerLevel, "levels every this many histogram bins (30 a decade; 10: x2.15)");
  addNumberOption(*cmd, "--epsilon", r.epsilon, "clones move by up to this many lattice units (2^-52 of the box) in X and Y");
  cmd->add_option("--clones", o->clones, "perturb (a move) or metropolis (a move kept only when the exact inverse map "
                                         "shows the state has the survivor's age)")->capture_default_str();
  addNumberOption(*cmd, "--metropolis-steps", r.metropolisSteps, "Metropolis moves per clone (--clones metropolis)");
  addNumberOption(*cmd, "--warmup", r.warmupBlocks, "blocks an entry orbit runs before its window of trials (stage 0)");
  addNumberOption(*cmd, "--min-ancestors", r.minAncestors,
                  "a level is reliable when its survivors descend from at least this many entries (all replicas)");
  addNumberOption(*cmd, "--threads", o->threads, "OpenMP threads (0: all cores; at most " + std::to_string(kMaxThreads) + ")");
  addKernelOption(*cmd, o->kernel);
  cmd->add_option("--out", o->out, "tail file written at the end (JSON: levels, exponents, the resumable state)")
      ->capture_default_str();
  cmd->add_option("--csv", o->csv, "the levels and the running exponent as CSV");
  cmd->add_option("--checkpoint", o->checkpoint, "checkpoint file (default: the --out file)");
  addNumberOption(*cmd, "--checkpoint-interval", o->checkpointSeconds, "seconds between checkpoints");
  cmd->add_option("--resume", o->resume, "continue the sampler run in this tail file");
  cmd->add_option("--compare", o->compare, "run files of the same process (one, or a seed ensemble): their brute-force P_t at the same levels");
  cmd->add_option("--compare-csv", o->compareCsv, "the comparison as CSV");
  cmd->add_flag("--print-levels", o->printLevels, "print the levels (t in steps) of these settings and run nothing");
  cmd->add_flag("--quiet", o->quiet, "no progress, table or summary");
  if (withSlice)
    cmd->add_option("--slice", o->slice, "I/N: run only slice I of N of the replicas, [R*I/N, R*(I+1)/N) "
                                         "(archipelago-cli merge joins the slices' tail files)");
}

void addTailCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<TailOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tail", "P_t beyond brute force: splitting on the age of trapped segments, for the process of run (issue 29)");
  addTailOptions(*cmd, *o, /*withSlice=*/true);
  cmd->callback([o, cmd, &status] { status = tailCommand(*o, *cmd); });
}

}  // namespace archipelago::cli
