#include "core/scan/ScanSummary.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>
#include <numbers>

#include "core/export/StatisticsCsv.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/scan/ScanHeatMap.hpp"

namespace archipelago {

namespace {

/// As every CSV file writes numbers (csvNumber); empty for NaN (an undefined cell).
std::string number(double v) { return std::isnan(v) ? std::string() : csvNumber(v); }

std::string number(std::uint64_t v) { return std::to_string(v); }

/// The shortest text that reads back as v (K and the box: 0.05, not 0.050000000000000003).
std::string shortest(double v) { return shortestDecimal(v); }

void line(std::string& out, std::string_view name, const std::string& value) { csvMetadataLine(out, name, value); }

/// What every scan file opens with: the program, the box rule and the settings the K share.
std::string scanHeader(const std::vector<ScanRunSummary>& runs) {
  std::string out;
  line(out, "program", programDescription());
  line(out, "scan", "trapping statistics over K (Karney 1983, sec. 5); box of each K: xmin = -2 sqrt(K) - " +
                        shortest(kScanBoxMargin) + ", xmax = sqrt(K) + " + shortest(kScanBoxMargin));
  if (!runs.empty()) {
    const TrappingParameters& p = runs.front().params;
    line(out, "settings", "Xr = " + shortest(p.Xr) + ", q = " + std::to_string(p.q) + ", T = " + number(p.T) +
                              ", M = " + number(p.M) + ", seed = " + number(p.seed) +
                              ", subsets = " + std::to_string(p.subsets));
  }
  return out;
}

}  // namespace

std::string scanFtCsv(const std::vector<ScanRunSummary>& runs) {
  std::string out = scanHeader(runs);
  line(out, "statistic", "f_t: distribution of trapping times (Karney 1983, figs. 3, 6(a)), every K");
  // Every K shares q: the column is there when one K's statistics have it (then all have).
  const auto marked = std::find_if(runs.begin(), runs.end(),
                                   [](const ScanRunSummary& r) { return hasBlocksAffectedColumn(r.statistics); });
  line(out, "columns", "K; t (steps); f_t (per step); f_t_error (one sigma over the subsets)" +
                           (marked != runs.end() ? blocksAffectedColumnNote(marked->statistics) : std::string()));
  out += std::string("K,t,f_t,f_t_error") + (marked != runs.end() ? ",blocks_affected" : "") + "\n";
  for (const ScanRunSummary& r : runs) {
    const Series& f = r.statistics.f;
    for (std::size_t i = 0; i < f.x.size(); ++i)
      out += shortest(r.point.K) + ',' + number(f.x[i]) + ',' + number(f.value[i]) + ',' + number(f.error[i]) +
             (marked != runs.end() ? blocksAffectedCell(marked->statistics, f.x[i]) : std::string()) + '\n';
  }
  return out;
}

std::string scanLocalExponentCsv(const std::vector<ScanRunSummary>& runs) {
  const ScanHeatMap map = localExponentHeatMap(runs);
  std::string out = scanHeader(runs);
  line(out, "statistic", "local exponent -dlog C_tau/dlog tau (Karney 1983, fig. 6(d)): rows tau (steps), columns K; "
                         "empty where C_tau = 0");
  out += "tau";
  for (const double K : map.K) out += ',' + shortest(K);
  out += '\n';
  for (std::size_t row = 0; row < map.tau.size(); ++row) {
    out += number(map.tau[row]);
    for (std::size_t c = 0; c < map.K.size(); ++c) out += ',' + number(map.value[row * map.K.size() + c]);
    out += '\n';
  }
  return out;
}

std::string scanSummaryCsv(const std::vector<ScanRunSummary>& runs) {
  std::string out = scanHeader(runs);
  line(out, "columns", "K; box xmin, xmax; blocks done of T; segments; D (eq. ddef) and its one-sigma bootstrap error "
                       "over segments (empty when the longest segments dominate D); longest segment (steps); fraction of the time in segments >= 1e4 steps; b2 as an "
                       "area and as a fraction of the box (appendix A), b2*D and its error (eq. A3; empty when b2 "
                       "was not computed)");
  out += "K,xmin,xmax,blocks_done,T,segments,D,D_error,longest_steps,time_fraction_ge_1e4,b2_area,b2_fraction,b2_D,"
         "b2_D_error\n";
  for (const ScanRunSummary& r : runs) {
    const ScanPoint& p = r.point;
    out += shortest(p.K) + ',' + shortest(p.box.xmin) + ',' + shortest(p.box.xmax) + ',' + number(p.blocksDone) + ',' +
           number(p.blocksTotal) + ',' + number(p.segments) + ',' + number(p.D) + ',' + number(p.DError) + ',' +
           number(p.longestSteps) + ',' + number(p.longFraction) + ',';
    if (p.boxInvariant) {
      const BoxInvariantQuantities& b = *p.boxInvariant;
      out += number(b.b2.area) + ',' + number(b.b2.fraction) + ',' + number(b.b2D) + ',' + number(b.b2DError);
    } else {
      out += ",,,";
    }
    out += '\n';
  }
  return out;
}

}  // namespace archipelago
