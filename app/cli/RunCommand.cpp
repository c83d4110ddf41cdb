#include "RunCommand.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "CliCommon.hpp"
#include "kernels/KernelDispatch.hpp"
#include "periodic/IslandChain.hpp"
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

void runCommand(const RunOptions& o, const std::vector<std::string>& explicitParameters) {
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
    std::exit(130);
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
}

}  // namespace

void addRunCommand(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "trapping statistics: M orbits x T blocks of N^-q (paper section 3)");
  addMapOptions(*cmd, o->params.map);
  cmd->add_option("--Xr", o->params.Xr, "randomizing zone 0 <= X <= Xr (unit coordinates)")->capture_default_str();
  cmd->add_option("--q", o->params.q, "steps of N^-1 per block")->capture_default_str();
  cmd->add_option("--T", o->params.T, "blocks per orbit")->capture_default_str();
  cmd->add_option("--M", o->params.M, "number of orbits")->capture_default_str();
  cmd->add_option("--seed", o->params.seed, "random seed")->capture_default_str();
  cmd->add_option("--subsets", o->params.subsets, "orbit subsets for error estimates")->capture_default_str();
  cmd->add_option("--longest", o->params.longestKept, "longest segments kept for replay")->capture_default_str();
  cmd->add_option("--threads", o->threads, "OpenMP threads (0: all cores)")->capture_default_str();
  cmd->add_option("--out", o->out, "run file written at the end")->capture_default_str();
  cmd->add_option("--checkpoint", o->checkpoint, "checkpoint file (default: the --out file)");
  cmd->add_option("--checkpoint-interval", o->checkpointSeconds, "seconds between checkpoints")->capture_default_str();
  cmd->add_option("--resume", o->resume, "continue the run in this checkpoint or run file");
  cmd->add_option("--max-chunk", o->maxChunkBlocks, "at most this many blocks between progress reports (0: adaptive)");
  addKernelOption(*cmd, o->kernel);
  cmd->add_flag("--quiet", o->quiet, "no progress bar or summary");
  cmd->callback([o, cmd] {
    std::vector<std::string> given;
    for (const char* name : {"--K", "--xmin", "--xmax", "--Xr", "--q", "--T", "--M", "--seed", "--subsets", "--longest"})
      if (cmd->count(name) > 0) given.emplace_back(name);
    runCommand(*o, given);
  });
}

namespace {
struct ReplayOptions {
  std::string runFile;
  std::size_t segment = 0;
  std::string out;
  std::uint64_t stride = 1;
  bool identify = false;
};

void replayCommand(const ReplayOptions& o) {
  const TrappingState state = loadRunFile(o.runFile);
  const auto& items = state.longest.items();
  if (o.segment >= items.size())
    throw std::invalid_argument("--segment " + std::to_string(o.segment) + " is out of range: the run file keeps " +
                                std::to_string(items.size()) + " segments (0 is the longest)");
  if (o.stride == 0) throw std::invalid_argument("--stride must be >= 1");
  const SegmentRecord& rec = items[o.segment];
  std::ofstream out(o.out);
  if (!out) throw std::runtime_error("cannot write " + o.out);
  const FixedPointMap map(state.params.map);
  out << "step,x,y,X,Y\n";
  out.precision(17);
  const std::uint64_t lastStep = rec.length * state.params.q;
  std::vector<PhysicalPoint> points;  // for --identify: every step, in physical coordinates
  constexpr std::uint64_t kMaxIdentifyPoints = 20'000'000;
  const std::uint64_t length = replaySegment(state.params, rec, [&](std::uint64_t step, const UnitState& z) {
    const PhysicalPoint p = map.toPhysical(z);
    if (o.identify && step < kMaxIdentifyPoints) points.push_back(p);
    if (step % o.stride != 0 && step != lastStep) return;
    out << step << ',' << static_cast<double>(p.x) << ',' << static_cast<double>(p.y) << ',' << z.X << ',' << z.Y
        << '\n';
  });
  out.close();
  if (!out) throw std::runtime_error("cannot write " + o.out);
  if (length != rec.length)
    throw std::runtime_error("replay mismatch: the segment ended after " + std::to_string(length) +
                             " blocks, the run recorded " + std::to_string(rec.length));
  std::fprintf(stderr, "segment %zu: orbit %llu, %llu blocks (%llu steps), replayed bit for bit to %s\n", o.segment,
               static_cast<unsigned long long>(rec.orbit), static_cast<unsigned long long>(rec.length),
               static_cast<unsigned long long>(lastStep), o.out.c_str());
  if (o.identify) {
    // The segment iterates N⁻¹ (time reversed); the chain it sticks to is the same for Q.
    const IslandChain chain = identifyIslandChain(state.params.map.K, points);
    std::printf("# chain_period: %d\n# hierarchy:", chain.period);
    for (int level : chain.hierarchy) std::printf(" %d", level);
    std::printf("\n# member: %.12Lg,%.12Lg\n", chain.member.x, chain.member.y);
    if (chain.centre) {
      std::printf("# centre_orbit: period %d at %.12Lg,%.12Lg, residue %.9Lg (%s)\n", chain.centre->period,
                  chain.centre->points.front().x, chain.centre->points.front().y, chain.centre->residue,
                  chain.centre->stable() ? "stable" : "unstable");
    }
  }
}
}  // namespace

void addReplayCommand(CLI::App& app) {
  auto o = std::make_shared<ReplayOptions>();
  CLI::App* cmd = app.add_subcommand("replay", "replay a recorded long segment exactly; CSV of its points");
  cmd->add_option("run", o->runFile, "run file")->required();
  cmd->add_option("--segment", o->segment, "rank of the segment (0: the longest)")->capture_default_str();
  cmd->add_option("--out", o->out, "CSV file to write")->required();
  cmd->add_option("--stride", o->stride, "write every stride-th step")->capture_default_str();
  cmd->add_flag("--identify", o->identify, "identify the island chain the segment sticks to (period, centre orbit)");
  cmd->callback([o] { replayCommand(*o); });
}

}  // namespace archipelago::cli
