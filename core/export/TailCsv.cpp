#include "core/export/TailCsv.hpp"

#include <cstdint>

#include "core/io/NumberText.hpp"
#include "core/stats/ReferenceSlopes.hpp"

namespace archipelago {

namespace {

std::string n(double v) { return csvNumber(v); }
std::string n(std::uint64_t v) { return std::to_string(v); }

void comment(std::string& out, const std::string& name, const std::string& value) {
  out += "# " + name + ": " + value + '\n';
}

void row(std::string& out, const std::string& quantity, double value, double lo = kTailUndefined,
         double hi = kTailUndefined) {
  out += quantity + ',' + n(value) + ',' + n(lo) + ',' + n(hi) + '\n';
}

std::string header(const TrappingState& state, const TailAnalysis& a) {
  return csvMetadataHeader(state) + ensembleNote(a);
}

std::string bootstrapLine(const TailAnalysis& a) {
  return std::to_string(a.bootstrap.replicates) + " replicates of the segments (Poisson per bin), seed " +
         std::to_string(a.bootstrap.seed) + ", percentile intervals at confidence " + n(a.bootstrap.confidence);
}

}  // namespace

std::string ensembleNote(const TailAnalysis& a) {
  if (a.seeds.size() < 2) return {};
  std::string seeds;
  for (const auto s : a.seeds) seeds += (seeds.empty() ? "" : " ") + std::to_string(s);
  return "# ensemble: " + std::to_string(a.seeds.size()) + " runs pooled, seeds " + seeds +
         " (the seed above is the first run's)\n";
}

std::vector<CsvFile> withNote(std::vector<CsvFile> files, const TrappingState& state, const std::string& note) {
  if (note.empty()) return files;
  const std::size_t at = csvMetadataHeader(state).size();
  for (CsvFile& f : files)
    if (f.text.size() >= at) f.text.insert(at, note);
  return files;
}

std::vector<CsvFile> tailCsvFiles(const TrappingState& state, const TailAnalysis& a, const Series& P) {
  std::vector<CsvFile> files;
  {
    std::string out = header(state, a);
    comment(out, "content", "D (eq. ddef) of the first k subsets of orbits (then the next seed's), each over the "
                            "whole record: steps = orbits x T x q; gamma_P_tail = -dlog P/dlog t over the tail "
                            "fit's window; longest = the longest segment so far (its bin's mean length, steps)");
    out += "steps,orbits,segments,D,gamma_P_tail,longest\n";
    for (const DPoint& p : a.DvsSteps)
      out += n(p.steps) + ',' + n(p.orbits) + ',' + n(p.segments) + ',' + n(p.D) + ',' + n(p.gammaTail) + ',' +
             n(p.longestSteps) + '\n';
    files.push_back({"D_vs_steps.csv", out});
  }
  {
    std::string out = header(state, a);
    comment(out, "content", "tail fits: least-squares slopes of log P_t and log C_tau on log t over each window "
                            "(steps), the tail fit [t_end/10, t_end] first; t_end = " + n(a.tailEnd) +
                            ", the largest t with at least 10 segments beyond");
    comment(out, "intervals", bootstrapLine(a));
    out += "from,to,points,gamma_P,gamma_P_lo,gamma_P_hi,exponent_C,exponent_C_lo,exponent_C_hi,"
           "segments_beyond_from,segments_beyond_to\n";
    for (const TailWindow& w : a.windows)
      out += n(w.from) + ',' + n(w.to) + ',' + n(static_cast<std::uint64_t>(w.points)) + ',' + n(w.gammaP) + ',' +
             n(w.gammaPInterval.lo) + ',' + n(w.gammaPInterval.hi) + ',' + n(w.exponentC) + ',' +
             n(w.exponentCInterval.lo) + ',' + n(w.exponentCInterval.hi) + ',' + n(w.segmentsBeyondFrom) + ',' +
             n(w.segmentsBeyondTo) + '\n';
    files.push_back({"tail_fit.csv", out});
  }
  {
    std::string out = header(state, a);
    comment(out, "content", "segments longer than t (a count from the histogram) and P_t, on P_t's grid: what "
                            "the data can decide about the tail beyond t");
    out += "t,P_t,segments\n";
    for (const SegmentsBeyond& b : a.beyond) out += n(b.t) + ',' + n(b.P) + ',' + n(b.segments) + '\n';
    files.push_back({"segments_beyond.csv", out});
  }
  {
    std::string out = header(state, a);
    comment(out, "content", "reference slopes t^-gamma anchored at P_t (stats/TailAnalysis.hpp, referenceSlopes)");
    out += "curve,t,P_t\n";
    for (const ReferenceSlope& r : referenceSlopes(P))
      for (std::size_t i = 0; i < r.line.x.size(); ++i)
        out += '"' + r.label + "\"," + n(r.line.x[i]) + ',' + n(r.line.value[i]) + '\n';
    files.push_back({"P_t.reference.csv", out});
  }
  {
    std::string out = header(state, a);
    comment(out, "content", "D's errors and the tail verdict (stats/TailAnalysis.hpp); lo and hi: intervals");
    comment(out, "intervals", bootstrapLine(a));
    const std::string message = dominanceMessage(a);
    comment(out, "verdict", message.empty() ? "the tail does not dominate D: the bootstrap error stands" : message);
    out += "quantity,value,lo,hi\n";
    // No interval, and no error, for a D its longest segments dominate (the verdict line says why).
    if (a.dominated()) row(out, "D", a.D);
    else row(out, "D", a.D, a.DInterval.lo, a.DInterval.hi);
    row(out, "D_bootstrap_error", a.dominated() ? kTailUndefined : a.DBootstrapError);
    row(out, "D_subset_error", a.dominated() ? kTailUndefined : a.DSubsetError);
    for (std::size_t i = 0; i < a.seedD.size(); ++i) row(out, "D_seed_" + std::to_string(a.seeds[i]), a.seedD[i]);
    if (!a.seedD.empty()) {
      row(out, "D_seed_median", a.seedMedian, a.seedMin, a.seedMax);
      row(out, "D_seed_mean", a.seedMean);
      row(out, "D_seed_error", a.dominated() ? kTailUndefined : a.seedError);
    }
    for (const LongestShare& s : a.shares) {
      row(out, "share_of_D_longest_" + std::to_string(s.k), s.share);
      row(out, "length_of_longest_" + std::to_string(s.k), s.shortestOfThem);
    }
    row(out, "dominated", a.dominated() ? 1 : 0);
    row(out, "dominated_by_share", a.shareDominates ? 1 : 0);
    row(out, "dominated_by_interval", a.intervalTooWide ? 1 : 0);
    row(out, "dominated_by_divergent_tail", a.tailDiverges ? 1 : 0);
    row(out, "tail_end", a.tailEnd);
    row(out, "gamma_P_tail", a.tailFit.gammaP, a.tailFit.gammaPInterval.lo, a.tailFit.gammaPInterval.hi);
    row(out, "exponent_C_tail", a.tailFit.exponentC, a.tailFit.exponentCInterval.lo, a.tailFit.exponentCInterval.hi);
    row(out, "tail_fit_from", a.tailFit.from);
    row(out, "tail_fit_to", a.tailFit.to);
    row(out, "steps_done", a.stepsDone);
    // The forward estimate (TailAnalysis.hpp): steps for N segments beyond t under P ∝ t^−γ past t_end.
    for (const TailForecast& f : a.forecast)
      row(out, "forecast_steps_" + std::to_string(static_cast<long long>(f.segments)) + "_beyond_" +
                   io::formatC("%g", f.target) + "_gamma_" + io::formatC("%g", f.gamma),
          f.steps);
    files.push_back({"tail_summary.csv", out});
  }
  return files;
}

}  // namespace archipelago
