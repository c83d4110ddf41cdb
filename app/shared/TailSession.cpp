#include "TailSession.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "core/io/NumberText.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/limits/Limits.hpp"
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

/// One line of the sampler's progress: the pilot, stage 0 or the level under way.
void printProgress(const TailState& s, const TailProgress& p, const KernelInfo& kernel, bool tty) {
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

}  // namespace

PreparedTail prepareTail(TailOptions& o, const CLI::App& cmd, std::optional<ReplicaRange> slice, const std::string& resumeFile) {
  TailPlanOptions options;
  options.optionName = flagOf;
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
  PreparedTail job;
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

TailState runTailSession(TailState state, const TailOptions& o, const std::string& checkpoint, LastCheckpoint& last) {
  if (state.finished()) return state;
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  const KernelInfo& kernel = selectKernel(o.kernel);
  TailJobOptions options;
  options.run.threads = o.threads;
  options.run.kernel = &kernel;
  options.checkpoint = checkpoint;
  options.checkpointSeconds = o.checkpointSeconds;
  options.warning = [&](const std::string& reason, double retrySeconds) {
    if (tty && !o.quiet) std::fputc('\n', stderr);
    std::fprintf(stderr, "WARNING: checkpoint not written: %s; the sampler goes on and retries in %g s\n",
                 reason.c_str(), retrySeconds);
  };
  auto lastLine = std::chrono::steady_clock::now() - std::chrono::hours(1);
  const auto progress = [&](const TailState& s, const TailProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (o.quiet || std::chrono::duration<double>(now - lastLine).count() < (tty ? 0.2 : 10)) return;
    lastLine = now;
    printProgress(s, p, kernel, tty);
  };
  state = runTailJob(std::move(state), options, last, progress, interruptToken());
  if (!o.quiet && tty) std::fputc('\n', stderr);
  return state;
}

void saveTail(const std::string& path, const TailState& state, const LastCheckpoint& last) {
  saveTailOrSayWhere(path, state, last, howToResume(last));
}

void reportTail(const TailState& state, const TailOptions& o, const std::vector<TrappingState>& runs) {
  const TailResult result = tailResult(state);
  if (!o.csv.empty()) io::writeFileAtomically(o.csv, tailCsvText(state, result));
  if (!o.quiet) printLevels(state, result);
  if (!runs.empty()) {
    const TailComparison c = compareWithRuns(state, result, runs);
    if (!o.compareCsv.empty()) io::writeFileAtomically(o.compareCsv, tailComparisonCsv(c));
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

}  // namespace archipelago::cli
