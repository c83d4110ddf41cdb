#include "StatsCommand.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <memory>
#include <optional>
#include <utility>

#include "CliCommon.hpp"
#include "core/export/ScanCsv.hpp"
#include "core/export/StatisticsCsv.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/theory/TheoryCurves.hpp"

namespace archipelago::cli {

namespace {
struct StatsOptions {
  std::string runFile;
  std::string csvDir;
  bool allowModified = false;
  double b2 = -1;  // --b2 AREA; negative: not given
};

/// --b2 AREA: b₂ as an area in the run's box (appendix A), its fraction of L², the box-invariant b₂·D (eq. A3)
/// and the §6 figures; box_invariant.csv beside the other files with --csv.
StochasticAreaValue checkedStochasticArea(const MapParameters& map, double area) {
  const double boxArea = map.width() * map.width();
  if (!(area > 0 && area <= boxArea))
    throw std::invalid_argument("--b2 = " + formatNumber(area) + " must be an area in (0, L^2 = " +
                                formatNumber(boxArea) + "] of the run's box (stochastic-area prints it)");
  return stochasticAreaOf(map, area / boxArea);
}

void printBoxInvariant(const MapParameters& map, const StochasticAreaValue& b2, const TrappingStatistics& s) {
  const BoxInvariantQuantities q = boxInvariantQuantities(b2, s.D, s.DError);
  std::printf("b2          %s\n", stochasticAreaText(map, b2).c_str());
  std::printf("b2*D        %.6g +- %.2g   (box-invariant, eq. A3; the paper: 0.693 x 6400 = %.3g)\n", q.b2D, q.b2DError,
              kPaperStochasticArea * kPaperDiffusion);
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

int statsCommand(const StatsOptions& o) {
  if (!o.csvDir.empty()) checkCsvFolder(o.csvDir);
  const TrappingState state = loadRunFile(o.runFile, {.allowModified = o.allowModified});
  std::optional<StochasticAreaValue> b2;
  if (o.b2 >= 0) b2 = checkedStochasticArea(state.params.map, o.b2);
  if (o.allowModified) std::fprintf(stderr, "warning: --allow-modified: a file edited after it was written is read\n");
  const TrappingStatistics s = statisticsOf(state);
  const TrappingParameters& p = state.params;
  std::printf("run         %s (%s)\n", o.runFile.c_str(), state.finished() ? "finished" : "in progress");
  std::printf("map         K = %.17g, xmin = %.17g, xmax = %.17g;  A = %lld, B = %lld, C = %lld, m = %d\n", p.map.K,
              p.map.xmin, p.map.xmax, static_cast<long long>(state.coefficients.A),
              static_cast<long long>(state.coefficients.B), static_cast<long long>(state.coefficients.C),
              state.coefficients.m);
  std::printf("run        Xr = %.17g, q = %u, T = %llu (done %llu), M = %llu, seed = %llu, subsets = %u\n", p.Xr, p.q,
              static_cast<unsigned long long>(p.T), static_cast<unsigned long long>(state.blocksDone),
              static_cast<unsigned long long>(p.M), static_cast<unsigned long long>(p.seed), p.subsets);
  std::printf("segments    %llu\n", static_cast<unsigned long long>(s.segments));
  std::printf("alpha       %.6g +- %.2g   (mean segment length, steps)\n", s.alpha, s.alphaError);
  std::printf("D           %.6g +- %.2g   (eq. ddef)\n", s.D, s.DError);
  std::printf("sum t f_t   %.9f           (should be close to 1)\n", s.sumTf);
  if (b2) printBoxInvariant(p.map, *b2, s);
  std::printf("longest:    rank, length (steps), orbit, start block\n");
  const auto& items = state.longest.items();
  for (std::size_t i = 0; i < items.size() && i < 10; ++i)
    std::printf("            %zu, %llu, %llu, %llu\n", i, static_cast<unsigned long long>(items[i].length * p.q),
                static_cast<unsigned long long>(items[i].orbit), static_cast<unsigned long long>(items[i].start.block));
  if (!o.csvDir.empty()) {
    // The same files, byte for byte, as the GUI's "Export all" (export/StatisticsCsv.hpp).
    for (const auto& path : writeStatisticsCsv(o.csvDir, state, s, theoryCurves(p, s)))
      std::printf("wrote       %s\n", path.string().c_str());
    if (b2) {
      for (const auto& [name, text] : {std::pair{boxInvariantCsvFileName, boxInvariantCsv(state, s, *b2)},
                                       std::pair{boxInvariantFtCsvFileName, boxInvariantFtCsv(state, s, *b2)}}) {
        const std::filesystem::path path = std::filesystem::path(o.csvDir) / name;
        io::writeFileAtomically(path, text);
        std::printf("wrote       %s\n", path.string().c_str());
      }
    }
  }
  return 0;
}
}  // namespace

void addStatsCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<StatsOptions>();
  CLI::App* cmd = app.add_subcommand("stats", "statistics of a run file: f_t, P_t, C_tau, D, S_t, D_t with errors");
  cmd->add_option("run", o->runFile, "run file")->required();
  cmd->add_flag("--allow-modified", o->allowModified,
                "read a run file whose checksum does not match (edited by hand; forensic use); it is still validated");
  cmd->add_option("--csv", o->csvDir, "write every series, its small-K theory curves and a summary as CSV into this folder");
  addNumberOption(*cmd, "--b2", o->b2,
                  "b2 as an AREA in the run's box (appendix A; stochastic-area prints it): adds b2*D (eq. A3) and "
                  "the sec. 6 figures, and box_invariant.csv, b2_f_t.csv with --csv")->default_str("");
  cmd->callback([o, cmd, &status] {
    if (cmd->count("--b2") > 0 && o->b2 < 0) throw std::invalid_argument("--b2 must be a positive area");
    status = statsCommand(*o);
  });
}

}  // namespace archipelago::cli
