#include "ScanCommand.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommon.hpp"
#include "PngWriter.hpp"
#include "RunSession.hpp"
#include "core/export/ScanCsv.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/portrait/StochasticArea.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/theory/KScan.hpp"

namespace archipelago::cli {

namespace {

/// The b₂ computation of one K of the scan (--b2-iterations): the run's map, randomizing zone, q and seed.
StochasticAreaRequest b2Request(const TrappingParameters& p, std::uint64_t iterations, const KernelInfo& kernel) {
  StochasticAreaRequest r;
  r.map = p.map;
  r.Xr = p.Xr;
  r.q = p.q;
  r.seed = p.seed;
  r.iterations = iterations;
  r.firstCheckpoint = std::min<std::uint64_t>(r.firstCheckpoint, iterations);
  r.kernel = &kernel;
  return r;
}

struct ScanOptions : SpecOptions {  // --preset, --spec, the parameters but K, xmin, xmax; --threads, --kernel
  std::string K;                    // --K FROM:TO:STEP or K1,K2,…
  std::string dir = "scan";
  double checkpointSeconds = 60;
  std::uint64_t maxChunkBlocks = 0;
  std::uint64_t b2Iterations = 0;   // 0: no b₂
  bool quiet = false;
};

/// --K: "FROM:TO:STEP" (scanValues) or a comma-separated list; every K once, in [0, kScanMaxK].
std::vector<double> parseKList(const std::string& text) {
  std::vector<double> values;
  if (text.find(':') != std::string::npos) {
    const std::vector<double> r = parseNumbers<double>("--K", text, ':', 3, "FROM:TO:STEP, e.g. 0.05:1.3:0.05");
    values = scanValues(r[0], r[1], r[2]);
  } else {
    const std::size_t count = static_cast<std::size_t>(std::count(text.begin(), text.end(), ',')) + 1;
    values = parseNumbers<double>("--K", text, ',', count, "a list K1,K2,... or a range FROM:TO:STEP");
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    (void)scanBox(values[i]);  // the range of the box rule
    for (std::size_t j = 0; j < i; ++j)
      if (values[j] == values[i]) throw std::invalid_argument("--K lists K = " + formatNumber(values[i]) + " twice");
  }
  return values;
}

/// The run file of one K in the scan's folder: K0.05.json (the shortest text that reads back as K).
std::filesystem::path runFileOf(const std::filesystem::path& dir, double K) {
  return dir / ("K" + formatNumber(K) + ".json");
}

/// One K of the scan: its parameters, its file, and what is known of it before this session.
struct ScanItem {
  TrappingParameters params;
  std::filesystem::path file;
  std::uint64_t blocksDone = 0;
  bool finished = false;
};

double stepsOf(const TrappingParameters& p, std::uint64_t blocks) {
  return static_cast<double>(p.M) * static_cast<double>(blocks) * p.q;
}

/// The heat map of the local exponent as an image: a column of cells per K (left to right), log τ upwards at 30
/// rows per decade (each row the grid τ nearest in log τ); white (0) through orange to dark red (2 and more);
/// grey where undefined.
void writeHeatMapPng(const std::filesystem::path& path, const ScanHeatMap& map) {
  if (map.K.empty() || map.tau.empty() || !(map.tau.front() > 0)) return;
  constexpr int kRowsPerDecade = 30, cellH = 4;
  const double lo = std::log10(map.tau.front()), hi = std::log10(map.tau.back());
  const int rows = static_cast<int>(std::ceil((hi - lo) * kRowsPerDecade)) + 1;
  const int cellW = std::max(4, 480 / static_cast<int>(map.K.size()));
  const int width = cellW * static_cast<int>(map.K.size()), height = cellH * rows;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    const double logTau = hi - static_cast<double>(y / cellH) / kRowsPerDecade;  // large τ on top
    auto it = std::lower_bound(map.tau.begin(), map.tau.end(), std::pow(10.0, logTau));
    if (it == map.tau.end() || (it != map.tau.begin() && logTau - std::log10(*(it - 1)) < std::log10(*it) - logTau)) --it;
    const auto row = static_cast<std::size_t>(it - map.tau.begin());
    for (int x = 0; x < width; ++x) {
      const double v = map.value[row * map.K.size() + static_cast<std::size_t>(x / cellW)];
      std::uint8_t* px = &rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      if (std::isnan(v)) {
        px[0] = px[1] = px[2] = 160;
        continue;
      }
      const double s = std::clamp(v / 2, 0.0, 1.0);
      px[0] = static_cast<std::uint8_t>(255 - 115 * s * s);
      px[1] = static_cast<std::uint8_t>(255 * (1 - s));
      px[2] = static_cast<std::uint8_t>(255 * (1 - s) * (1 - s));
    }
  }
  writePng(path.string(), width, height, rgb);
}

int scanCommand(const ScanOptions& o, const RunSpec& base, const std::vector<double>& Ks) {
  const std::filesystem::path dir = o.dir;
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw std::runtime_error("cannot scan into " + dir.string() + ": it is not a folder");
  if (!std::filesystem::exists(dir, ec)) {
    io::checkWritableTarget(dir);  // its parent exists and is writable
    std::filesystem::create_directory(dir);
  }
  io::checkWritableTarget(dir / scanSummaryCsvFileName);
  // One scan per folder at a time: the summary's lock for the whole scan, each K's file while it runs.
  const io::FileLock scanLock = io::FileLock::acquire(dir / scanSummaryCsvFileName);
  const KernelInfo& kernel = selectKernel(o.kernel);

  // Every K checked before any work: its parameters, its b₂ request, and any run file already there.
  std::vector<ScanItem> items;
  for (const double K : Ks) {
    ScanItem item;
    item.params = base.parameters;
    item.params.map = scanBox(K);
    RunSpec spec = base;
    spec.parameters = item.params;
    if (auto e = validationError(spec)) throw std::invalid_argument("K = " + formatNumber(K) + ": " + *e);
    if (auto e = memoryError(item.params, base.threads)) throw std::runtime_error(*e);
    item.file = runFileOf(dir, K);
    if (std::filesystem::exists(item.file, ec)) {
      const TrappingState state = loadRunFile(item.file);
      if (!(state.params == item.params))
        throw std::runtime_error(item.file.string() + " holds a run of other parameters than this scan's K = " +
                                 formatNumber(K) + " (another --dir, or remove the file)");
      item.blocksDone = state.blocksDone;
      item.finished = state.finished();
    }
    if (o.b2Iterations > 0) {
      const StochasticAreaRequest r = b2Request(item.params, o.b2Iterations, kernel);
      if (auto e = validationError(r)) throw std::invalid_argument("--b2-iterations at K = " + formatNumber(K) + ": " + *e);
    }
    items.push_back(item);
  }

  // Progress of the whole scan: steps over every K, the rate of this session, its ETA.
  double totalSteps = 0, stepsBefore = 0;
  for (const ScanItem& item : items) {
    totalSteps += stepsOf(item.params, item.params.T);
    stepsBefore += stepsOf(item.params, item.blocksDone);
  }
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  const auto sessionStart = std::chrono::steady_clock::now();
  auto lastLine = sessionStart - std::chrono::seconds(60);
  double stepsFinishedThisSession = 0;  // whole K finished in this session (beyond what they had before)

  installInterruptHandlers();
  for (std::size_t k = 0; k < items.size(); ++k) {
    ScanItem& item = items[k];
    if (item.finished) continue;
    const std::string path = item.file.string();
    const std::vector<io::FileLock> locks = lockRunFiles(path, path, std::string());
    TrappingState state = item.blocksDone > 0 || std::filesystem::exists(item.file, ec) ? loadRunFile(item.file)
                                                                                     : startTrapping(item.params);
    if (!(state.params == item.params)) throw std::runtime_error(path + " changed during the scan");
    const std::uint64_t blocksAtStart = state.blocksDone;
    CheckpointedRunOptions options;
    options.run.kernel = &kernel;
    options.run.threads = base.threads;
    options.run.maxChunkBlocks = o.maxChunkBlocks;
    options.checkpoint = path;
    options.checkpointSeconds = o.checkpointSeconds;
    options.breakLineBeforeWarning = tty && !o.quiet;
    LastCheckpoint last{blocksAtStart > 0 ? path : std::string(), blocksAtStart};
    auto progress = [&](const TrappingState& s, const TrappingProgress&) {
      const auto now = std::chrono::steady_clock::now();
      if (o.quiet || (!tty && std::chrono::duration<double>(now - lastLine).count() < 10)) return;
      lastLine = now;
      const double thisSession = stepsFinishedThisSession + stepsOf(s.params, s.blocksDone - blocksAtStart);
      const double done = stepsBefore + thisSession;
      const double seconds = std::chrono::duration<double>(now - sessionStart).count();
      const double rate = seconds > 0 ? thisSession / seconds : 0;
      std::fprintf(stderr, "%sscan: K = %s (%zu of %zu) %5.1f%%, whole scan %5.1f%%  %.3g steps/s  ETA %s   %s",
                   tty ? "\r" : "", formatNumber(s.params.map.K).c_str(), k + 1, items.size(),
                   100.0 * static_cast<double>(s.blocksDone) / static_cast<double>(s.params.T), 100 * done / totalSteps,
                   rate, clockText(rate > 0 ? (totalSteps - done) / rate : -1).c_str(), tty ? "" : "\n");
      std::fflush(stderr);
    };
    state = runWithCheckpoints(std::move(state), options, last, progress);
    if (!o.quiet && tty) std::fputc('\n', stderr);
    saveRunFileOrSayWhere(path, state, last);
    if (!state.finished()) {
      std::fprintf(stderr, "interrupted: K = %s checkpointed in %s; run the same scan again to resume\n",
                   formatNumber(item.params.map.K).c_str(), path.c_str());
      return 130;  // 128 + SIGINT
    }
    stepsFinishedThisSession += stepsOf(item.params, state.blocksDone - blocksAtStart);
    item.finished = true;
  }

  // The summaries, from the run files (all finished now) and, when asked, b₂ of every box.
  std::vector<ScanRunSummary> runs;
  for (const ScanItem& item : items) {
    const TrappingState state = loadRunFile(item.file);
    const TrappingStatistics statistics = statisticsOf(state);
    std::optional<StochasticAreaValue> b2;
    if (o.b2Iterations > 0) {
      const StochasticAreaRequest r = b2Request(item.params, o.b2Iterations, kernel);
      b2 = stochasticAreaOf(r.map, computeStochasticArea(r).b2());
    }
    runs.push_back({state.params, scanPointOf(state, statistics, b2), statistics});
  }
  io::writeFileAtomically(dir / scanFtCsvFileName, scanFtCsv(runs));
  io::writeFileAtomically(dir / scanLocalExponentCsvFileName, scanLocalExponentCsv(runs));
  io::writeFileAtomically(dir / scanSummaryCsvFileName, scanSummaryCsv(runs));
  writeHeatMapPng(dir / "scan_local_exponent.png", localExponentHeatMap(runs));
  std::printf("K, box xmin..xmax, D +- error, longest (steps), time in segments >= 1e4 steps%s\n",
              o.b2Iterations > 0 ? ", b2 (area), b2*D" : "");
  for (const ScanRunSummary& r : runs) {
    const ScanPoint& p = r.point;
    std::printf("%-6s %.4g..%.4g  %.4g +- %.2g  %llu  %.3f", formatNumber(p.K).c_str(), p.box.xmin, p.box.xmax, p.D,
                p.DError, static_cast<unsigned long long>(p.longestSteps), p.longFraction);
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
  // The run's parameters but the map: K is the scan's, the box is the rule's (theory/KScan.hpp).
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
    if (!(o->checkpointSeconds >= 0)) throw std::invalid_argument("--checkpoint-interval must not be negative");
    if (cmd->count("--dir") > 0 && o->dir.empty()) throw std::invalid_argument("--dir is empty: give a folder");
    RunSpec base = resolveSpec(*o, *cmd);
    if (!o->kernel.empty() || base.kernel != "auto") o->kernel = base.kernel == "auto" ? std::string() : base.kernel;
    status = scanCommand(*o, base, Ks);
  });
}

}  // namespace archipelago::cli
