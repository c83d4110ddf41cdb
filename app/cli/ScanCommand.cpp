#include "ScanCommand.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stop_token>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "core/runfile/CheckpointedRun.hpp"
#include "core/scan/ScanHeatMap.hpp"
#include "core/scan/ScanRun.hpp"
#include "core/kernels/KernelDispatch.hpp"

namespace archipelago::cli {

namespace {

struct ScanOptions : SpecOptions {  // --preset, --spec, the parameters but K, xmin, xmax; --threads, --kernel
  std::string K;                    // --K FROM:TO:STEP or K1,K2,…
  std::string dir = "scan";
  double checkpointSeconds = 60;
  std::uint64_t maxChunkBlocks = 0;
  std::uint64_t b2Iterations = 0;   // 0: no b₂
  bool quiet = false;
};

/// --K: core's one reader of K lists (core/scan/ScanBox.hpp), its message naming the option.
std::vector<double> parseKList(const std::string& text) {
  try {
    return parseScanValues(text);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--K: ") + e.what());
  }
}

int scanCommand(const ScanOptions& o, const RunSpec& base, const std::vector<double>& Ks) {
  KScanRequest request;
  request.base = base;
  request.K = Ks;
  request.dir = o.dir;
  request.kernel = &selectKernel(o.kernel);
  request.checkpointSeconds = o.checkpointSeconds;
  request.maxChunkBlocks = o.maxChunkBlocks;
  request.b2Iterations = o.b2Iterations;
  const std::filesystem::path dir = o.dir;

  // The scan itself is core's (core/scan/ScanRun.hpp), shared with the GUI; here only its progress line.
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  auto lastLine = std::chrono::steady_clock::now() - std::chrono::seconds(60);
  bool lineOpen = false;
  KScanObserver observer;
  observer.progress = [&](const KScanProgress& p) {
    const auto now = std::chrono::steady_clock::now();
    if (o.quiet || (!tty && std::chrono::duration<double>(now - lastLine).count() < 10)) return;
    lastLine = now;
    std::fprintf(stderr, "%sscan: K = %s (%zu of %zu) %5.1f%%, whole scan %5.1f%%  %.3g steps/s  ETA %s   %s",
                 tty ? "\r" : "", scanKText(p.K).c_str(), p.index + 1, p.count, 100 * p.fractionK(),
                 100 * p.fractionScan(), p.stepsPerSecond, clockText(p.etaScan).c_str(), tty ? "" : "\n");
    std::fflush(stderr);
    lineOpen = tty;
  };
  observer.finished = [&](std::size_t, const ScanRunSummary&) {
    if (lineOpen) std::fputc('\n', stderr);
    lineOpen = false;
  };
  observer.warning = [&](const std::string& text) {
    if (lineOpen) std::fputc('\n', stderr);
    lineOpen = false;
    std::fprintf(stderr, "WARNING: %s\n", text.c_str());
  };
  const KScanOutcome outcome = runKScan(request, observer, interruptToken());  // Ctrl-C: the program's one stop
  if (lineOpen) std::fputc('\n', stderr);
  if (!outcome.finished) {
    std::fprintf(stderr, "interrupted: K = %s checkpointed in %s; run the same scan again to resume\n",
                 scanKText(Ks[outcome.stoppedIndex]).c_str(), outcome.stoppedFile.string().c_str());
    return 130;  // 128 + SIGINT
  }
  const std::vector<ScanRunSummary>& runs = outcome.runs;
  // The summaries, from the run files (all finished now) and, when asked, b₂ of every box.
  writeHeatMapPng(dir / "scan_local_exponent.png", localExponentHeatMap(runs), "K scan: local exponent over K and tau");
  std::printf("K, box xmin..xmax, D +- error (bootstrap over segments; 'dominated': the longest segments dominate "
              "D, no error), longest (steps), time in segments >= 1e4 steps%s\n",
              o.b2Iterations > 0 ? ", b2 (area), b2*D" : "");
  for (const ScanRunSummary& r : runs) {
    const ScanPoint& p = r.point;
    char error[32] = "dominated";
    if (std::isfinite(p.DError)) std::snprintf(error, sizeof error, "+- %.2g", p.DError);
    std::printf("%-6s %.4g..%.4g  %.4g %s  %llu  %.3f", scanKText(p.K).c_str(), p.box.xmin, p.box.xmax, p.D, error,
                static_cast<unsigned long long>(p.longestSteps), p.longFraction);
    if (p.boxInvariant) std::printf("  %.4f  %.4g", p.boxInvariant->b2.area, p.boxInvariant->b2D);
    std::printf("\n");
  }
  std::printf("wrote %s/{%s,%s,%s,scan_local_exponent.png} and a run file per K\n", dir.string().c_str(),
              scanFtCsvFileName, scanLocalExponentCsvFileName, scanSummaryCsvFileName);
  return 0;
}

}  // namespace

void addScanCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<ScanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "scan", "the K scan of sec. 5: a resumable run per K in its own box (xmin = -2 sqrt(K) - 0.2, xmax = sqrt(K) + 0.2), "
              "then summary CSVs over K");
  cmd->add_option("--K", o->K, "the K values: FROM:TO:STEP (e.g. 0.05:1.3:0.05) or K1,K2,...; each in [0, 4]")
      ->required();
  cmd->add_option("--dir", o->dir, "folder of the scan: a run file per K (K0.05.json, ...) and the summaries")
      ->capture_default_str();
  // The run's parameters but the map: K is the scan's, the box is the rule's (core/scan/ScanBox.hpp).
  addSpecOptions(*cmd, *o, {"K", "xmin", "xmax"});
  addNumberOption(*cmd, "--threads", o->threads, "OpenMP threads (0: all cores; at most " + std::to_string(kMaxThreads) + ")");
  addKernelOption(*cmd, o->kernel);
  addNumberOption(*cmd, "--checkpoint-interval", o->checkpointSeconds, "seconds between checkpoints of the K running");
  addNumberOption(*cmd, "--max-chunk", o->maxChunkBlocks, "at most this many blocks between progress reports (0: adaptive)");
  addNumberOption(*cmd, "--b2-iterations", o->b2Iterations,
                  "also compute b2 (the area of the sea, appendix A) of every box with this many steps, e.g. 134217728 "
                  "(0: not; recomputed on every invocation)");
  cmd->add_flag("--quiet", o->quiet, "no progress");
  cmd->callback([o, cmd, &status] {
    const std::vector<double> Ks = parseKList(o->K);
    if (auto e = checkpointIntervalError("--checkpoint-interval", o->checkpointSeconds)) throw std::invalid_argument(*e);
    if (cmd->count("--dir") > 0 && o->dir.empty()) throw std::invalid_argument("--dir is empty: give a folder");
    RunSpec base = resolveSpec(*o, *cmd);
    if (!o->kernel.empty() || base.kernel != "auto") o->kernel = base.kernel == "auto" ? std::string() : base.kernel;
    status = scanCommand(*o, base, Ks);
  });
}

}  // namespace archipelago::cli
