#include "TailScanSession.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "CliCommon.hpp"
#include "TailSession.hpp"
#include "core/limits/Limits.hpp"
#include "core/scan/ScanBox.hpp"

namespace archipelago::cli {

void addTailScanOptions(CLI::App& cmd, TailScanOptions& o) {
  cmd.add_option("--K", o.K, "the K values: FROM:TO:STEP (e.g. 0.05:0.3:0.05) or K1,K2,...; each in [0, 4]")
      ->required();
  cmd.add_option("--dir", o.dir, "folder of the scan: a tail file per K (tail-K0.1.json, ...)")->capture_default_str();
  // tail's spec options but the map's K and box (the scan's: core/scan/ScanBox.hpp) and a run's length.
  addSpecOptions(cmd, o, {"K", "xmin", "xmax", "T", "M", "subsets", "longestKept"});
  addSamplerOptions(cmd, o.request, o.clones);
  addNumberOption(cmd, "--threads", o.threads, "OpenMP threads (0: all cores; at most " + std::to_string(kMaxThreads) + ")");
  addKernelOption(cmd, o.kernel);
  addNumberOption(cmd, "--checkpoint-interval", o.checkpointSeconds, "seconds between checkpoints of the K running");
  cmd.add_option("--task", o.task, "I/N: only the K of task I of N (K number i when i mod N = I; a Slurm array: "
                                   "$SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT)");
  cmd.add_option("--csv", o.csv, "the summary as PREFIX_P.csv, PREFIX_gamma.csv and PREFIX_average.csv, and the figure "
                                 "gamma(t, K) as PREFIX_gamma.png (K across, log t up; written once every K is "
                                 "finished)");
  cmd.add_flag("--quiet", o.quiet, "no progress or summary");
}

TailScanRequest tailScanRequest(const TailScanOptions& o, const CLI::App& cmd) {
  TailScanRequest r;
  r.optionName = flagOf;
  r.K = o.K;
  r.base = resolveSpec(o, cmd);
  r.request = o.request;
  r.clones = o.clones;
  r.dir = o.dir;
  r.checkpointSeconds = o.checkpointSeconds;
  if (cmd.count("--task") > 0) r.task = o.task;  // given empty is an error too
  r.csv = o.csv;
  if (o.warnings) r.warning = [](const std::string& warning) { std::fprintf(stderr, "WARNING: %s\n", warning.c_str()); };
  return r;
}

TailScanView tailScanView(bool quiet) {
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  TailScanView view;
  view.checkpointWarning = [tty, quiet](const std::string& reason, double retrySeconds) {
    if (tty && !quiet) std::fputc('\n', stderr);
    std::fprintf(stderr, "WARNING: checkpoint not written: %s; the sampler goes on and retries in %g s\n",
                 reason.c_str(), retrySeconds);
  };
  if (quiet) return view;
  view.begins = [](std::size_t index, std::size_t count, double K, const std::string& how) {
    std::fprintf(stderr, "K = %s (%zu of %zu): %s\n", scanKText(K).c_str(), index + 1, count, how.c_str());
  };
  view.progress = [tty, lastLine = std::chrono::steady_clock::now()](std::size_t, double K, const TailState& s,
                                                                      const TailProgress& p) mutable {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - lastLine).count() < (tty ? 0.2 : 10)) return;
    lastLine = now;
    std::fprintf(stderr, "%sK = %s: level %zu of %zu, t = %.4g  %.3g steps  %.3g steps/s (%s)   %s", tty ? "\r" : "",
                 scanKText(K).c_str(), p.level, p.levels, p.t, p.steps, p.stepsPerSecond, s.kernel.c_str(),
                 tty ? "" : "\n");
    std::fflush(stderr);
  };
  view.finished = [tty](std::size_t, double K, const TailState& s) {
    std::fprintf(stderr, "%sK = %s: finished, the largest reliable t = %.4g; %.3g steps in %.1f s\n", tty ? "\r" : "",
                 scanKText(K).c_str(), largestReliableT(tailResult(s)), static_cast<double>(s.steps),
                 s.elapsedSeconds);
  };
  view.outOfReach = [tty](std::size_t, double K, const std::string& reason) {
    std::fprintf(stderr, "%sK = %s: out of reach, %s; the scan goes on without it\n", tty ? "\r" : "",
                 scanKText(K).c_str(), reason.c_str());
  };
  return view;
}

int tailScanEnd(const TailScanOutcome& r, const TailScanOptions& o, const std::string& resume) {
  if (r.end == TailScanOutcome::End::interrupted) {
    std::fprintf(stderr, "interrupted: %s holds the checkpoint; run the same %s command again to resume\n",
                 r.checkpoint.empty() ? "each K's file" : r.checkpoint.c_str(), resume.c_str());
    return 130;
  }
  if (r.end == TailScanOutcome::End::waiting) {
    std::string waiting;
    for (const double K : r.waitingFor) waiting += (waiting.empty() ? "" : ", ") + scanKText(K);
    std::fprintf(stderr, "this task's K are finished; the summary waits for K = %s (other tasks, or run the scan "
                         "without --task)\n", waiting.c_str());
    return 0;
  }
  if (!o.quiet) std::fputs(tailScanText(r.summary).c_str(), stdout);
  if (!o.quiet)
    std::fprintf(stderr, "done: %zu K in %s%s%s\n", r.K.size(), o.dir.c_str(), o.csv.empty() ? "" : "; wrote ",
                 o.csv.empty() ? "" : (o.csv + "_{P,gamma,average}.csv and " + o.csv + "_gamma.png").c_str());
  return 0;
}

}  // namespace archipelago::cli
