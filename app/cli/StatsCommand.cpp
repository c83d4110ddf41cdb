#include "StatsCommand.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "CliCommon.hpp"
#include "core/export/BoxInvariantCsv.hpp"
#include "core/export/StatisticsCsv.hpp"
#include "core/export/TailCsv.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunEnsemble.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/stats/RunSummary.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/stats/ReferenceSlopes.hpp"
#include "core/stats/TailAnalysis.hpp"
#include "core/theory/TheoryCurves.hpp"

namespace archipelago::cli {

namespace {
struct StatsOptions {
  std::vector<std::string> runFiles;  // one run, or a seed ensemble (same parameters but the seed)
  std::string csvDir;
  std::string tailCsvDir;             // --tail-csv: D's errors and the tail (export/TailCsv.hpp)
  bool allowModified = false;
  BootstrapOptions bootstrap;         // --bootstrap, --bootstrap-seed
  double b2 = 0;                      // --b2 AREA
  bool b2Given = false;               // core's rule checks it when given (any value)
  std::string shortRun;               // --short: the run's q = 1 companion (issue #26)
};

/// --b2 AREA: b₂ as an area in the run's box (appendix A), its fraction of L², the box-invariant b₂·D (eq. A3)
/// and the §6 figures; box_invariant.csv beside the other files with --csv.
StochasticAreaValue checkedStochasticArea(const MapParameters& map, double area) {
  if (auto e = stochasticAreaError("--b2", map, area)) throw std::invalid_argument(*e);
  return stochasticAreaOf(map, area / (map.width() * map.width()));
}

void printBoxInvariant(const MapParameters& map, const StochasticAreaValue& b2, const RunSummary& summary) {
  // b₂·D carries D's error as core's run summary gives it (issue 35), and none when the tail dominates D.
  const bool errorKnown = std::isfinite(summary.DError);
  const BoxInvariantQuantities q = boxInvariantQuantities(b2, summary.D, errorKnown ? summary.DError : 0);
  std::printf("b2          %s\n", stochasticAreaText(map, b2).c_str());
  const std::string paperB2D = io::formatC("the paper: %.3g x %.4g = %.3g", kPaperStochasticArea, kPaperDiffusion,
                                           kPaperStochasticArea * kPaperDiffusion);
  if (errorKnown)
    std::printf("b2*D        %.6g +- %.2g   (box-invariant, eq. A3; %s)\n", q.b2D, q.b2DError, paperB2D.c_str());
  else
    std::printf("b2*D        %.6g   (box-invariant, eq. A3; no error: see D above; %s)\n", q.b2D, paperB2D.c_str());
  std::printf("sec. 6      (8/pi^2) b2 = %.4g (paper: 0.56); D_island/D_ql = %.4g/n^2 (paper: at least 360/n^2)\n",
              q.acceleratorFactor, q.enhancementN1);
}

/// --csv DIR before any work: an existing folder must take the files, a missing one must be creatable.
void checkCsvFolder(const std::filesystem::path& dir) {
  std::error_code ec;
  const auto status = std::filesystem::status(dir, ec);
  if (std::filesystem::is_directory(status))
    io::checkWritableTarget(dir / summaryCsvFileName);
  else if (std::filesystem::exists(status))
    throw std::runtime_error("cannot write into " + dir.string() + ": it is not a folder");
  else
    io::checkWritableTarget(dir);  // its parent folder exists and is writable
}

void writeCsvFiles(const std::string& dir, const std::vector<CsvFile>& files) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create folder " + dir + ": " + ec.message());
  for (const CsvFile& f : files) {
    const std::filesystem::path path = std::filesystem::path(dir) / f.name;
    io::writeFileAtomically(path, f.text);
    std::printf("wrote       %s\n", path.string().c_str());
  }
}

// ---- D's honest error and the tail (issue #14, items 2 and 7): stats/TailAnalysis.hpp -------------------

std::string g(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", v);
  return buffer;
}
std::string interval(const ConfidenceInterval& i) { return "[" + g(i.lo) + ", " + g(i.hi) + "]"; }

/// The D line: with the bootstrap error when the tail does not dominate, with no error (and why) when it does.
void printD(const TailAnalysis& a, const TrappingStatistics& s, const char* label) {
  const std::string replicates = std::to_string(a.bootstrap.replicates) + " replicates, seed " +
                                 std::to_string(a.bootstrap.seed);
  const int percent = static_cast<int>(std::lround(100 * a.bootstrap.confidence));
  if (!a.dominated())
    std::printf("%s%.6g +- %.2g   (eq. ddef; one sigma of a bootstrap over segments, %s; %d%% interval %s; "
                "the subsets give +- %.2g)\n", label, a.D, a.DBootstrapError, replicates.c_str(), percent,
                interval(a.DInterval).c_str(), s.DError);
  else
    std::printf("%s%.6g   (eq. ddef; no error: %s)\n", label, a.D, dominanceMessage(a).c_str());
  if (!a.seedD.empty()) {
    std::string values;
    for (std::size_t i = 0; i < a.seedD.size(); ++i)
      values += (i ? ", " : "") + g(a.seedD[i]) + " (seed " + std::to_string(a.seeds[i]) + ")";
    std::printf("D per seed  %s\n", values.c_str());
    std::printf("            median %s, range [%s, %s], mean %s", g(a.seedMedian).c_str(), g(a.seedMin).c_str(),
                g(a.seedMax).c_str(), g(a.seedMean).c_str());
    if (!a.dominated())
      std::printf(" +- %s (standard error over %zu seeds)\n", g(a.seedError).c_str(), a.seedD.size());
    else
      std::printf(" (no error: the tail dominates)\n");
  }
  std::string shares;
  for (const LongestShare& l : a.shares)
    shares += (shares.empty() ? "" : ", ") + std::to_string(l.k) + ": " + g(100 * l.share) + "%";
  if (!a.shares.empty())
    std::printf("D share     of the longest k segments: %s (the longest is %s steps)\n", shares.c_str(),
                g(a.shares.front().shortestOfThem).c_str());
  // D against the steps sampled, at most 8 lines (every point is in D_vs_steps.csv).
  const std::size_t n = a.DvsSteps.size(), stride = n > 8 ? (n + 7) / 8 : 1;
  for (std::size_t i = 0; i < n; ++i) {
    if (i % stride != 0 && i + 1 != n) continue;
    const DPoint& p = a.DvsSteps[i];
    std::printf("%s %.3g steps (%llu orbits): D = %s, longest %s steps\n", i == 0 ? "D vs steps " : "           ",
                p.steps, static_cast<unsigned long long>(p.orbits), g(p.D).c_str(), g(p.longestSteps).c_str());
  }
}

/// The tail: its end, the running exponent over log-spaced windows with intervals, the literature's asymptotic
/// exponents, and the forward estimate of what more data would cost (issue #26).
void printTail(const TailAnalysis& a) {
  const int percent = static_cast<int>(std::lround(100 * a.bootstrap.confidence));
  if (a.windows.empty()) {
    std::printf("tail        %s\n", std::string(kNoTailFit).c_str());
    return;
  }
  const TailWindow& f = a.tailFit;
  std::printf("tail end    t_end = %s steps: %llu segments are longer; beyond it the data decide nothing\n",
              g(a.tailEnd).c_str(), static_cast<unsigned long long>(f.segmentsBeyondTo));
  std::printf("gamma_P     %s (P_t ~ t^-gamma; %d%% bootstrap interval, %llu segments beyond %s)\n",
              gammaPText(f).c_str(), percent, static_cast<unsigned long long>(f.segmentsBeyondFrom), g(f.from).c_str());
  std::printf("exponent_C  %s %s over the same window (-dlog C/dlog tau; gamma_P - 1 for a power law)\n",
              g(f.exponentC).c_str(), interval(f.exponentCInterval).c_str());
  std::printf("windows:    from, to, gamma_P [interval], exponent_C [interval], segments beyond from, beyond to\n");
  for (const TailWindow& w : a.windows)
    std::printf("            %s, %s, %s %s, %s %s, %llu, %llu\n", g(w.from).c_str(), g(w.to).c_str(),
                g(w.gammaP).c_str(), interval(w.gammaPInterval).c_str(), g(w.exponentC).c_str(),
                interval(w.exponentCInterval).c_str(), static_cast<unsigned long long>(w.segmentsBeyondFrom),
                static_cast<unsigned long long>(w.segmentsBeyondTo));
  // The literature's exponents are asymptotic (t → ∞): set beside the running exponent, never judged by one window.
  std::string literature;
  for (const ReferenceExponent& r : referenceExponents())
    literature += (literature.empty() ? "" : ", ") + g(r.gamma) + " (" + r.source + ")";
  std::printf("literature  asymptotic exponents (t -> infinity): %s; the windows above are finite t\n", literature.c_str());
  std::printf("forecast    steps for %g segments beyond t if P_t ~ t^-gamma past t_end (this sample: %.3g steps):\n",
              a.forecast.empty() ? 100.0 : a.forecast.front().segments, a.stepsDone);
  for (const TailForecast& forecast : a.forecast)
    std::printf("            t = %s, gamma = %s: %.2g steps\n", g(forecast.target).c_str(), g(forecast.gamma).c_str(),
                forecast.steps);
}

void printVerdict(const TailAnalysis& a) { std::printf("verdict     %s\n", tailVerdictText(a).c_str()); }

/// --csv: the same files, byte for byte, as the GUI's "Export all" (export/StatisticsCsv.hpp) for one run; an
/// ensemble's carry a note naming its seeds.  --tail-csv: the tail's files (export/TailCsv.hpp), in a folder of their
/// own so that --csv stays the GUI's set.
void writeStatsCsv(const StatsOptions& o, const TrappingState& state, const TrappingStatistics& s,
                   const TailAnalysis& tail, const RunSummary& summary, const std::optional<StochasticAreaValue>& b2) {
  if (!o.csvDir.empty())
    writeCsvFiles(o.csvDir, withNote(statisticsCsvFiles(state, s, theoryCurves(state.params, s), summary), state,
                                     ensembleNote(tail)));
  if (!o.csvDir.empty() && b2) {
    for (const auto& [name, text] : {std::pair{boxInvariantCsvFileName, boxInvariantCsv(state, s, *b2, summary.DError)},
                                     std::pair{boxInvariantFtCsvFileName, boxInvariantFtCsv(state, s, *b2)}}) {
      const std::filesystem::path path = std::filesystem::path(o.csvDir) / name;
      io::writeFileAtomically(path, text);
      std::printf("wrote       %s\n", path.string().c_str());
    }
  }
  if (!o.tailCsvDir.empty()) writeCsvFiles(o.tailCsvDir, tailCsvFiles(state, tail, s.P));
}

int statsCommand(const StatsOptions& o) {
  std::vector<io::CommandFile> files{{"--short", o.shortRun, io::FileUse::Input}};
  for (const std::string& file : o.runFiles) files.push_back({"run", file, io::FileUse::Input});
  io::checkCommandFiles(files);  // a run given twice would be pooled twice
  if (!o.csvDir.empty()) checkCsvFolder(o.csvDir);
  if (!o.tailCsvDir.empty()) checkCsvFolder(o.tailCsvDir);
  std::vector<TrappingState> states;
  for (const std::string& file : o.runFiles) states.push_back(loadRunFile(file, {.allowModified = o.allowModified, .allowModifiedName = "--allow-modified"}));
  std::optional<StochasticAreaValue> b2;
  if (o.b2Given) b2 = checkedStochasticArea(states.front().params.map, o.b2);
  if (o.allowModified) std::fprintf(stderr, "warning: --allow-modified: a file edited after it was written is read\n");
  const Ensemble ensemble = ensembleOf(states, o.runFiles);  // one run, or seeds checked to differ only in the seed
  const TrappingState& state = states.front();
  // With its q = 1 companion the short times are the q = 1 process's (issue #26): composite statistics.
  std::optional<TrappingState> companion;
  if (!o.shortRun.empty()) {
    if (states.size() > 1) throw std::invalid_argument("--short splices one run with its companion, not an ensemble");
    companion = loadRunFile(o.shortRun, {.allowModified = o.allowModified, .allowModifiedName = "--allow-modified"});
  }
  const TrappingStatistics s = companion ? splicedStatisticsOf(state, *companion) : ensembleStatistics(ensemble);
  TailOptions tailOptions;
  tailOptions.bootstrap = o.bootstrap;
  const TailAnalysis tail = analyseTail(ensemble, tailOptions);
  // D and its error as every front end gives them: the D lines, b₂·D, summary.csv and box_invariant.csv (issue 51).
  const RunSummary summary = summarizeRun(s, s.segments > 0 ? &tail : nullptr, "no segment yet");
  const TrappingParameters& p = state.params;
  for (std::size_t i = 0; i < states.size(); ++i)
    std::printf("run         %s (%s)\n", o.runFiles[i].c_str(), states[i].finished() ? "finished" : "in progress");
  std::printf("map         K = %s, xmin = %s, xmax = %s;  A = %lld, B = %lld, C = %lld, m = %d\n",
              io::shortestText(p.map.K).c_str(), io::shortestText(p.map.xmin).c_str(),
              io::shortestText(p.map.xmax).c_str(), static_cast<long long>(state.coefficients.A),
              static_cast<long long>(state.coefficients.B), static_cast<long long>(state.coefficients.C),
              state.coefficients.m);
  std::printf("run        Xr = %s, q = %u, T = %llu (done %llu), M = %llu, seed = %llu, subsets = %u\n", io::shortestText(p.Xr).c_str(), p.q,
              static_cast<unsigned long long>(p.T), static_cast<unsigned long long>(state.blocksDone),
              static_cast<unsigned long long>(p.M), static_cast<unsigned long long>(p.seed), p.subsets);
  if (states.size() > 1) {
    std::string seeds;
    for (const TrappingState& r : states) seeds += (seeds.empty() ? "" : " ") + std::to_string(r.params.seed);
    std::printf("ensemble    %zu runs pooled (seeds %s): %llu orbits\n", states.size(), seeds.c_str(),
                static_cast<unsigned long long>(p.M * states.size()));
  }
  if (companion)
    std::printf("spliced     with the q = 1 companion %s (T = %llu steps): f_t below t = %.6g steps is the companion's, "
                "at and above it the run's (the first point >= 10 q where both agree within 2 sigma)\n",
                o.shortRun.c_str(), static_cast<unsigned long long>(companion->blocksDone), s.splicedAt);
  else if (s.blockAffectedBelow > 0)
    std::printf("blocks      below t = 10 q = %.6g steps the statistics are those of blocks of q steps, not of the "
                "paper's q = 1 process (marked in the CSV files; a q = 1 companion, --short, splices them)\n",
                s.blockAffectedBelow);
  std::printf("segments    %llu%s\n", static_cast<unsigned long long>(s.segments),
              companion ? "   (the run's and the companion's)" : "");
  std::printf("alpha       %.6g +- %.2g   (mean segment length, steps)\n", s.alpha, s.alphaError);
  // Spliced, D is the composite statistics' with the error core's run summary gives it (the subsets' of the spliced
  // statistics); the tail below is the run's own: the longest segments, which carry D's error, are the run's.
  if (companion) {
    if (std::isfinite(summary.DError))
      std::printf("D           %.6g +- %.2g   (eq. ddef, %s; the run alone below)\n", summary.D, summary.DError,
                  summary.DErrorNote.c_str());
    else
      std::printf("D           %.6g   (eq. ddef, spliced; %s)\n", summary.D, summary.DErrorNote.c_str());
  }
  if (s.segments > 0) printD(tail, companion ? statisticsOf(state) : s, companion ? "D (run)     " : "D           ");
  else std::printf("D           0   (no segment yet)\n");
  std::printf("sum t f_t   %.9f           (should be close to 1)\n", s.sumTf);
  if (b2) printBoxInvariant(p.map, *b2, summary);
  if (s.segments > 0) {
    printTail(tail);
    printVerdict(tail);
  }
  std::printf("longest:    rank, length (steps), orbit, start block%s\n", states.size() > 1 ? ", seed" : "");
  std::vector<std::pair<SegmentRecord, std::uint64_t>> longest;  // with its run's seed
  for (const TrappingState& r : states)
    for (const SegmentRecord& item : r.longest.items()) longest.emplace_back(item, r.params.seed);
  std::stable_sort(longest.begin(), longest.end(), [](const auto& a, const auto& b) { return a.first.length > b.first.length; });
  for (std::size_t i = 0; i < longest.size() && i < 10; ++i) {
    const SegmentRecord& item = longest[i].first;
    std::printf("            %zu, %llu, %llu, %llu", i, static_cast<unsigned long long>(item.length * p.q),
                static_cast<unsigned long long>(item.orbit), static_cast<unsigned long long>(item.start.block));
    if (states.size() > 1) std::printf(", %llu", static_cast<unsigned long long>(longest[i].second));
    std::printf("\n");
  }
  io::OutputBatch outputs;  // every CSV or none (issue 36, class 5)
  writeStatsCsv(o, state, s, tail, summary, b2);
  outputs.commit();
  return 0;
}
}  // namespace

void addStatsCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<StatsOptions>();
  CLI::App* cmd = app.add_subcommand("stats", "statistics of a run file: f_t, P_t, C_tau, D, S_t, D_t with errors");
  cmd->add_option("run", o->runFiles,
                  "run file; several: a seed ensemble (same parameters but the seed), pooled, with D's spread over "
                  "seeds")->required();
  cmd->add_flag("--allow-modified", o->allowModified,
                "read a run file whose checksum does not match (edited by hand; forensic use); it is still validated");
  cmd->add_option("--short", o->shortRun,
                  "the run's q = 1 companion (run writes NAME.short.json when its spec asks for one): the statistics "
                  "below a crossover >= 10 q come from it, the rest from the run (issue #26)");
  cmd->add_option("--csv", o->csvDir, "write every series, its small-K theory curves and a summary as CSV into this folder");
  cmd->add_option("--tail-csv", o->tailCsvDir,
                  "write D's errors and the tail (tail_summary, D_vs_steps, tail_fit, segments_beyond, "
                  "P_t.reference) as CSV into this folder");
  addNumberOption(*cmd, "--bootstrap", o->bootstrap.replicates,
                  "replicates of the bootstrap over segments for D's error and the tail fits (at least 20)");
  addNumberOption(*cmd, "--bootstrap-seed", o->bootstrap.seed, "seed of the bootstrap (printed with its results)");
  addNumberOption(*cmd, "--b2", o->b2,
                  "b2 as an AREA in the run's box (appendix A; stochastic-area prints it): adds b2*D (eq. A3) and "
                  "the sec. 6 figures, and box_invariant.csv, b2_f_t.csv with --csv")->default_str("");
  cmd->callback([o, cmd, &status] {
    o->b2Given = cmd->count("--b2") > 0;
    status = statsCommand(*o);
  });
}

}  // namespace archipelago::cli
