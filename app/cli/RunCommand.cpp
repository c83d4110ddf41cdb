#include "RunCommand.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "CliCommon.hpp"
#include "kernels/KernelDispatch.hpp"
#include "runfile/RunFile.hpp"
#include "trapping/TrappingRun.hpp"

namespace archipelago::cli {

namespace {

volatile std::sig_atomic_t gInterrupted = 0;
extern "C" void onInterrupt(int) { gInterrupted = 1; }

struct RunOptions {
  TrappingParameters params;
  std::string out = "run.json";
  std::string checkpoint;  // empty: the output file
  double checkpointSeconds = 60;
  std::string resume;
  int threads = 0;
  std::uint64_t maxChunkBlocks = 0;
  std::string kernel;  // empty: $ARCHIPELAGO_KERNEL, else the fastest the CPU supports
  bool quiet = false;
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

int runCommand(const RunOptions& o, const std::vector<std::string>& explicitParameters) {
  TrappingState state;
  if (!o.resume.empty()) {
    if (!explicitParameters.empty())
      throw std::invalid_argument("--resume takes the parameters from the run file; do not also give " +
                                  explicitParameters.front());
    state = loadRunFile(o.resume);
    if (state.finished()) throw std::invalid_argument(o.resume + " is already finished (" +
                                                      std::to_string(state.blocksDone) + " of T blocks)");
  } else {
    state = startTrapping(o.params);
  }
  const std::string checkpoint = o.checkpoint.empty() ? o.out : o.checkpoint;
  const bool tty = ::isatty(STDERR_FILENO) != 0;

  std::stop_source stopper;
  std::signal(SIGINT, onInterrupt);
  std::signal(SIGTERM, onInterrupt);
  const KernelInfo& kernel = selectKernel(o.kernel);
  TrappingRunOptions options;
  options.kernel = &kernel;
  options.threads = o.threads;
  options.maxChunkBlocks = o.maxChunkBlocks;
  auto lastCheckpoint = std::chrono::steady_clock::now();
  auto lastLine = lastCheckpoint;
  auto observer = [&](const TrappingState& s, const TrappingProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (gInterrupted) stopper.request_stop();
    if (std::chrono::duration<double>(now - lastCheckpoint).count() >= o.checkpointSeconds && !s.finished()) {
      saveRunFile(checkpoint, s);
      lastCheckpoint = now;
    }
    // A progress bar on a terminal; on a pipe or file, a line every 10 s.
    if (!o.quiet && (tty || std::chrono::duration<double>(now - lastLine).count() >= 10)) {
      drawProgress(p, std::string(kernel.name));
      if (!tty) std::fputc('\n', stderr);
      lastLine = now;
    }
  };
  state = runTrapping(std::move(state), options, observer, stopper.get_token());
  if (!o.quiet && tty) std::fputc('\n', stderr);
  if (!state.finished()) {
    saveRunFile(checkpoint, state);
    std::fprintf(stderr, "interrupted: checkpoint written to %s (resume with --resume %s)\n", checkpoint.c_str(),
                 checkpoint.c_str());
    return 130;  // 128 + SIGINT, as a shell reports a process stopped by Ctrl-C
  }
  saveRunFile(o.out, state);
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

}  // namespace

void addRunCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "trapping statistics: M orbits x T blocks of N^-q (paper section 3)");
  addMapOptions(*cmd, o->params.map);
  addNumberOption(*cmd, "--Xr", o->params.Xr, "randomizing zone 0 <= X <= Xr (unit coordinates)");
  addNumberOption(*cmd, "--q", o->params.q, "steps of N^-1 per block");
  addNumberOption(*cmd, "--T", o->params.T, "blocks per orbit");
  addNumberOption(*cmd, "--M", o->params.M, "number of orbits");
  addNumberOption(*cmd, "--seed", o->params.seed, "random seed");
  addNumberOption(*cmd, "--subsets", o->params.subsets, "orbit subsets for error estimates");
  addNumberOption(*cmd, "--longest", o->params.longestKept, "longest segments kept for replay");
  addNumberOption(*cmd, "--threads", o->threads, "OpenMP threads (0: all cores)");
  cmd->add_option("--out", o->out, "run file written at the end")->capture_default_str();
  cmd->add_option("--checkpoint", o->checkpoint, "checkpoint file (default: the --out file)");
  addNumberOption(*cmd, "--checkpoint-interval", o->checkpointSeconds, "seconds between checkpoints");
  cmd->add_option("--resume", o->resume, "continue the run in this checkpoint or run file");
  addNumberOption(*cmd, "--max-chunk", o->maxChunkBlocks, "at most this many blocks between progress reports (0: adaptive)");
  addKernelOption(*cmd, o->kernel);
  cmd->add_flag("--quiet", o->quiet, "no progress bar or summary");
  cmd->callback([o, cmd, &status] {
    std::vector<std::string> given;
    for (const char* name : {"--K", "--xmin", "--xmax", "--Xr", "--q", "--T", "--M", "--seed", "--subsets", "--longest"})
      if (cmd->count(name) > 0) given.emplace_back(name);
    status = runCommand(*o, given);
  });
}

}  // namespace archipelago::cli
