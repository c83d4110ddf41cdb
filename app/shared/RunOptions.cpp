#include "RunOptions.hpp"

#include <cstdio>
#include <string>

#include "CliCommon.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago::cli {

void drawProgress(const TrappingProgress& p, const std::string& kernel) {
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(p.fraction * kWidth);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r[%s] %5.1f%%  %.3g steps/s  ETA %s  (%s)   ", bar.c_str(), 100 * p.fraction,
               p.stepsPerSecond, clockText(p.etaSeconds).c_str(), kernel.c_str());
  std::fflush(stderr);
}

void addRunOptions(CLI::App& cmd, RunOptions& o) {
  addSpecOptions(cmd, o);
  addNumberOption(cmd, "--threads", o.threads, "OpenMP threads (0: all cores; at most " + std::to_string(kMaxThreads) + ")");
  cmd.add_option("--out", o.out, "run file written at the end")->capture_default_str();
  cmd.add_option("--checkpoint", o.checkpoint, "checkpoint file (default: the --out file)");
  addNumberOption(cmd, "--checkpoint-interval", o.checkpointSeconds, "seconds between checkpoints");
  cmd.add_option("--resume", o.resume, "continue the run in this checkpoint or run file");
  addNumberOption(cmd, "--max-chunk", o.maxChunkBlocks, "at most this many blocks between progress reports (0: adaptive)");
  addKernelOption(cmd, o.kernel);
  cmd.add_flag("--print-spec", o.printSpec, "print the run spec (JSON) these options make, and run nothing");
  cmd.add_flag("--quiet", o.quiet, "no progress bar or summary");
  cmd.add_option("--orbits", o.orbits,
                  "run only orbits [BEGIN, END) of the M (e.g. 0:400): one part of the run, for a scheduler array job; "
                  "`merge` joins the parts into the run file of the whole run");
  cmd.add_option("--seeds", o.seeds,
                  "a seed ensemble: one independent run per seed (e.g. 1..8 or 1,2,5..7, at most " +
                      std::to_string(limits::kSeeds) + "), written to NAME.seed-K.json for --out NAME.json; "
                      "`stats` combines the files");
}

}  // namespace archipelago::cli
