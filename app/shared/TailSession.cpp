#include "TailSession.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago::cli {

namespace {

// The sampler's own options, as they are named in errors and --help.
const char* const kSamplerOptions[] = {"--population", "--replicas", "--first", "--t-max", "--level-bins", "--epsilon",
                                       "--clones", "--metropolis-steps", "--warmup", "--min-ancestors"};

/// One line of the sampler's progress: the pilot, stage 0 or the level under way.
void printProgress(const TailState& s, const TailProgress& p, bool tty) {
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
                 p.stepsPerSecond, s.kernel.c_str(), tty ? "" : "\n");
  std::fflush(stderr);
}

/// The session on stderr: the progress (unless quiet: a line every 10 s, redrawn every 0.2 s on a terminal, ended
/// when the run stops) and the checkpoints that could not be written.
TailSessionView stderrView(bool quiet) {
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  TailSessionView view;
  view.checkpointWarning = [tty, quiet](const std::string& reason, double retrySeconds) {
    if (tty && !quiet) std::fputc('\n', stderr);
    std::fprintf(stderr, "WARNING: checkpoint not written: %s; the sampler goes on and retries in %g s\n",
                 reason.c_str(), retrySeconds);
  };
  if (quiet) return view;
  view.progress = [tty, lastLine = std::chrono::steady_clock::now() - std::chrono::hours(1)](
                      const TailState& s, const TailProgress& p) mutable {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - lastLine).count() < (tty ? 0.2 : 10)) return;
    lastLine = now;
    printProgress(s, p, tty);
  };
  view.runEnded = [tty] {
    if (tty) std::fputc('\n', stderr);
  };
  return view;
}

}  // namespace

TailSessionOptions tailSession(const TailOptions& o, const CLI::App& cmd) {
  TailSessionOptions session;
  session.view = stderrView(o.quiet);
  session.quiet = o.quiet;
  session.kernel = o.kernel;
  TailPlanOptions& plan = session.plan;
  plan.optionName = flagOf;
  if (o.warnings)
    plan.warning = [](const std::string& warning) { std::fprintf(stderr, "WARNING: %s\n", warning.c_str()); };
  plan.request = o.request;
  plan.clones = o.clones;
  plan.givenSpec = givenSpecOptions(cmd);
  for (const char* name : kSamplerOptions)
    if (cmd.count(name) > 0) plan.givenSampler.emplace_back(name);
  const CLI::Option* slice = cmd.get_option_no_throw("--slice");
  if (slice != nullptr && slice->count() > 0) plan.sliceText = o.slice;  // given empty is an error too (issue 36)
  plan.threads = o.threads;
  plan.checkpointSeconds = o.checkpointSeconds;
  plan.printLevels = o.printLevels;
  plan.resume = o.resume;
  plan.out = o.out;
  plan.checkpoint = o.checkpoint;
  plan.csv = o.csv;
  plan.compareCsv = o.compareCsv;
  plan.specFile = o.specFile;
  plan.compare = o.compare;
  plan.spec = [&o, &cmd] { return resolveSpec(o, cmd); };  // when the plan needs it, after the checks before it
  return session;
}

void printTailOutcome(const TailSessionOutcome& r) {
  if (r.end == TailSessionOutcome::End::levelsOnly) {
    std::printf("t (steps)\n");
    for (const std::uint64_t L : r.state.levels)
      std::printf("%llu\n", static_cast<unsigned long long>(L * r.state.request.run.q));
  }
  std::fputs(r.report.c_str(), stdout);
}

void addSamplerOptions(CLI::App& cmd, TailRequest& r, std::string& clones) {
  addNumberOption(cmd, "--population", r.population, "N: walkers per replica (2 to " + std::to_string(kMaxTailPopulation) + ")");
  addNumberOption(cmd, "--replicas", r.replicas, "R: independent replicas; the error of P is their spread (1 to " +
                                                      std::to_string(kMaxTailReplicas) + ")");
  addNumberOption(cmd, "--first", r.firstSteps, "the first level is the lowest at or above this t (steps): entries are sampled by brute force up to it");
  addNumberOption(cmd, "--t-max", r.maxSteps, "the last level is the lowest at or above this t (steps)");
  addNumberOption(cmd, "--level-bins", r.binsPerLevel, "levels every this many histogram bins (30 a decade; 10: x2.15)");
  addNumberOption(cmd, "--epsilon", r.epsilon, "clones move by up to this many lattice units (2^-52 of the box) in X and Y");
  cmd.add_option("--clones", clones, "perturb (a move) or metropolis (a move kept only when the exact inverse map "
                                     "shows the state has the survivor's age)")->capture_default_str();
  addNumberOption(cmd, "--metropolis-steps", r.metropolisSteps, "Metropolis moves per clone (--clones metropolis)");
  addNumberOption(cmd, "--warmup", r.warmupBlocks, "blocks an entry orbit runs before its window of trials (stage 0)");
  addNumberOption(cmd, "--min-ancestors", r.minAncestors,
                  "a level is reliable when its survivors descend from at least this many entries (all replicas)");
}

void addTailOptions(CLI::App& cmd_, TailOptions& o_, bool withSlice) {
  CLI::App* cmd = &cmd_;
  TailOptions* o = &o_;
  addSpecOptions(*cmd, *o, {"T", "M", "subsets", "longestKept"});
  addSamplerOptions(*cmd, o->request, o->clones);
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
