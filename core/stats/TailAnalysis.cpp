/// \file TailAnalysis.cpp
/// \brief Bootstrap over segments, D's shares and D against steps, tail fits, what can be decided (see the
/// header for the definitions and the derivation of the steps needed).

#include "core/stats/TailAnalysis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/io/NumberText.hpp"
#include "core/stats/LogFits.hpp"
#include "core/stats/ReferenceSlopes.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

using Real = long double;

double standardDeviation(const std::vector<double>& values) {
  Real sum = 0, squares = 0;
  std::size_t n = 0;
  for (const double v : values)
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  if (n < 2) return kTailUndefined;
  const Real mean = sum / static_cast<Real>(n);
  for (const double v : values)
    if (std::isfinite(v)) squares += (v - mean) * (v - mean);
  return static_cast<double>(std::sqrt(squares / static_cast<Real>(n - 1)));
}

// One bin's segments as the statistics see them (TrappingStatistics.hpp): at s = q t̄ steps, each carrying
// ½ s² w/n of D, w = n/(M(T + 1 − t̄))/q.
struct Mass {
  double s;
  std::uint64_t n;
  Real perSegmentD;
};
std::vector<Mass> massesOf(const TrappingHistogram& h, std::uint64_t orbits, std::uint64_t blocks, std::uint32_t q) {
  std::vector<Mass> out;
  for (int i = 1; i < TrappingHistogram::kBins; ++i) {
    const std::uint64_t n = h.count(i);
    if (n == 0) continue;
    const Real mean = static_cast<Real>(h.lengthSum(i)) / static_cast<Real>(n);
    const Real s = q * mean;
    const Real wPerSegment = 1 / (static_cast<Real>(orbits) * (static_cast<Real>(blocks) + 1 - mean)) / q;
    out.push_back({static_cast<double>(s), n, s * s * wPerSegment / 2});
  }
  return out;  // sorted by s: bins are disjoint ranges
}

std::uint64_t segmentsBeyond(const std::vector<Mass>& masses, double t) {
  std::uint64_t n = 0;
  for (auto it = masses.rbegin(); it != masses.rend() && it->s > t; ++it) n += it->n;
  return n;
}

std::uint64_t sum(const std::vector<std::uint64_t>& v) {
  std::uint64_t n = 0;
  for (const auto x : v) n += x;
  return n;
}

std::string format(const char* f, double v) {
  const std::string buffer = io::formatC(f, v);
  return buffer;
}

/// The ensemble and the bootstrap's options, checked before any work.
void checkTailRequest(const Ensemble& e, const BootstrapOptions& bo) {
  if (e.members.empty()) throw std::invalid_argument("an ensemble needs at least one run");
  if (bo.replicates < 20 || bo.replicates > 100000)
    throw std::invalid_argument("a bootstrap needs 20 to 100000 replicates, not " + std::to_string(bo.replicates));
  if (auto error = realOpenIntervalError("confidence", bo.confidence, 0, 1)) throw std::invalid_argument(*error);
}

/// D over seeds: each member's D, their mean, median, range and standard error (an ensemble of several runs).
void addSeedSpread(TailAnalysis& a, const Ensemble& e) {
  for (const EnsembleMember& m : e.members) {
    a.seeds.push_back(m.seed);
    a.seedD.push_back(computeStatistics(m.subsets, m.orbitsPerSubset, e.blocks, e.q).D);
  }
  std::vector<double> sorted = a.seedD;
  std::sort(sorted.begin(), sorted.end());
  Real mean = 0;
  for (const double d : sorted) mean += d;
  a.seedMean = static_cast<double>(mean / static_cast<Real>(sorted.size()));
  a.seedMedian = percentile(sorted, 0.5);
  a.seedMin = sorted.front();
  a.seedMax = sorted.back();
  a.seedError = standardDeviation(sorted) / std::sqrt(static_cast<double>(sorted.size()));
}

/// The longest segments' share of D: the 1, 2, 3, 5 and 10 longest (a bin's segments at its mean), longest first.
std::vector<LongestShare> longestShares(const std::vector<Mass>& masses) {
  Real DofMasses = 0;
  for (const Mass& m : masses) DofMasses += m.perSegmentD * static_cast<Real>(m.n);
  std::vector<const Mass*> top;  // the ten longest segments, longest first (a bin's segments at its mean)
  for (auto it = masses.rbegin(); it != masses.rend() && top.size() < 10; ++it)
    for (std::uint64_t j = 0; j < it->n && top.size() < 10; ++j) top.push_back(&*it);
  std::vector<LongestShare> shares;
  Real carried = 0;
  for (std::size_t k = 1; k <= top.size(); ++k) {
    carried += top[k - 1]->perSegmentD;
    if (k == 1 || k == 2 || k == 3 || k == 5 || k == 10)
      shares.push_back({k, static_cast<double>(std::min<Real>(1, carried / DofMasses)), top[k - 1]->s});
  }
  return shares;
}

/// Segments beyond each t, the tail's end (the last t with minTailSegments beyond it), and the windows of the
/// running exponents up to it with their fits of P and C.
void addTailWindows(TailAnalysis& a, const TrappingStatistics& stats, const std::vector<Mass>& masses,
                    const TailOptions& options, double lowest) {
  for (std::size_t g = 0; g < stats.P.x.size(); ++g) {
    const std::uint64_t n = segmentsBeyond(masses, stats.P.x[g]);
    a.beyond.push_back({stats.P.x[g], stats.P.value[g], n});
    if (n >= options.minTailSegments) a.tailEnd = stats.P.x[g];
  }
  for (const LogWindow& window : runningExponentWindows(a.tailEnd, lowest)) {
    TailWindow w;
    w.from = window.from;
    w.to = window.to;
    w.gammaP = fitLogSlope(stats.P, w.from, w.to, &w.points);
    w.exponentC = fitLogSlope(stats.C, w.from, w.to);
    w.segmentsBeyondFrom = segmentsBeyond(masses, w.from);
    w.segmentsBeyondTo = segmentsBeyond(masses, w.to);
    a.windows.push_back(w);
  }
}

/// The bootstrap over segments: D and every window's exponents in each replicate, their spreads and intervals.
void addBootstrap(TailAnalysis& a, const TrappingHistogram& total, const RecordShape& shape,
                  const BootstrapOptions& bo) {
  std::vector<double> Ds(bo.replicates);
  std::vector<std::vector<double>> gP(a.windows.size(), std::vector<double>(bo.replicates)), gC = gP;
  double windowsFrom = kTailUndefined, windowsTo = kTailUndefined;  // the range every window lies in
  for (const TailWindow& w : a.windows) {
    windowsFrom = std::isnan(windowsFrom) ? w.from : std::min(windowsFrom, w.from);
    windowsTo = std::isnan(windowsTo) ? w.to : std::max(windowsTo, w.to);
  }
  for (std::uint32_t r = 0; r < bo.replicates; ++r) {
    const TrappingStatistics s = computeStatistics(resampleHistogram(total, bo.seed, r), shape);
    Ds[r] = s.D;
    const LogSeries P(s.P, windowsFrom, windowsTo), C(s.C, windowsFrom, windowsTo);  // logarithms once for all windows
    for (std::size_t w = 0; w < a.windows.size(); ++w) {
      gP[w][r] = fitLogSlope(P, a.windows[w].from, a.windows[w].to);
      gC[w][r] = fitLogSlope(C, a.windows[w].from, a.windows[w].to);
    }
  }
  a.DBootstrapError = standardDeviation(Ds);
  a.DInterval = percentileInterval(Ds, bo.confidence);
  for (std::size_t w = 0; w < a.windows.size(); ++w) {
    a.windows[w].gammaPInterval = percentileInterval(gP[w], bo.confidence);
    a.windows[w].exponentCInterval = percentileInterval(gC[w], bo.confidence);
  }
}

/// D against the steps sampled: the union of the first k subsets (seed after seed), with the tail fit's exponent.
std::vector<DPoint> DAgainstSteps(const TailAnalysis& a, const std::vector<TrappingHistogram>& subsets,
                                  const std::vector<std::uint64_t>& orbitsPerSubset, const Ensemble& e) {
  std::vector<DPoint> points;
  TrappingHistogram prefix;
  std::uint64_t prefixOrbits = 0;
  for (std::size_t i = 0; i < subsets.size(); ++i) {
    prefix.merge(subsets[i]);
    prefixOrbits += orbitsPerSubset[i];
    if (prefix.segments() == 0) continue;
    const TrappingStatistics s = computeStatistics(prefix, {prefixOrbits, e.blocks, e.q});
    DPoint p;
    p.orbits = prefixOrbits;
    p.steps = static_cast<double>(prefixOrbits) * static_cast<double>(e.blocks) * e.q;
    p.segments = s.segments;
    p.D = s.D;
    if (!a.windows.empty()) p.gammaTail = fitLogSlope(s.P, a.tailFit.from, a.tailFit.to);
    p.longestSteps = s.f.x.empty() ? 0 : s.f.x.back();
    points.push_back(p);
  }
  return points;
}

/// The forward estimate (the header): steps for N segments beyond each target under each literature exponent, at
/// the rate of segments beyond the tail's end (none without a tail's end).
std::vector<TailForecast> forecasts(const TailAnalysis& a, const TailOptions& options) {
  std::vector<TailForecast> out;
  if (!std::isfinite(a.tailEnd)) return out;
  std::uint64_t beyondEnd = 0;
  for (const SegmentsBeyond& b : a.beyond)
    if (b.t == a.tailEnd) beyondEnd = b.segments;
  const double rate = beyondEnd > 0 ? static_cast<double>(beyondEnd) / a.stepsDone : 0;
  for (const double target : {1e8, 1e9, 1e10})
    for (const ReferenceExponent& r : referenceExponents()) {
      TailForecast f;
      f.target = target;
      f.gamma = r.gamma;
      f.segments = options.forecastSegments;
      if (rate > 0 && target > a.tailEnd) f.steps = f.segments / rate * std::pow(target / a.tailEnd, r.gamma);
      out.push_back(f);
    }
  return out;
}

}  // namespace

TailAnalysis analyseTail(const Ensemble& e, const TailOptions& options) {
  const BootstrapOptions& bo = options.bootstrap;
  checkTailRequest(e, bo);
  TailAnalysis a;
  a.bootstrap = bo;
  const std::vector<TrappingHistogram> subsets = pooledSubsets(e);
  const std::vector<std::uint64_t> orbitsPerSubset = pooledOrbitsPerSubset(e);
  const TrappingStatistics stats = computeStatistics(subsets, orbitsPerSubset, e.blocks, e.q);
  TrappingHistogram total;
  for (const auto& h : subsets) total.merge(h);
  const std::uint64_t orbits = sum(orbitsPerSubset);
  a.D = stats.D;
  a.DSubsetError = stats.DError;
  if (stats.segments == 0) return a;

  if (e.members.size() > 1) addSeedSpread(a, e);
  const std::vector<Mass> masses = massesOf(total, orbits, e.blocks, e.q);
  a.shares = longestShares(masses);
  addTailWindows(a, stats, masses, options, std::max(10.0, 2.0 * e.q));
  addBootstrap(a, total, RecordShape{orbits, e.blocks, e.q}, bo);
  if (!a.windows.empty()) a.tailFit = a.windows.front();
  a.DvsSteps = DAgainstSteps(a, subsets, orbitsPerSubset, e);
  a.stepsDone = static_cast<double>(orbits) * static_cast<double>(e.blocks) * e.q;
  a.forecast = forecasts(a, options);

  // The verdict.
  a.shareDominates = !a.shares.empty() && a.shares.front().share > options.dominanceShare;
  a.intervalTooWide = std::isfinite(a.DInterval.lo) && a.DInterval.hi - a.DInterval.lo > a.D;
  a.tailDiverges = std::isfinite(a.tailFit.gammaPInterval.hi) && a.tailFit.gammaPInterval.hi < 2;
  return a;
}

double supportedDError(const TailAnalysis& a) noexcept {
  return !a.dominated() && std::isfinite(a.DBootstrapError) ? a.DBootstrapError : kTailUndefined;
}

std::string dominanceMessage(const TailAnalysis& a) {
  if (!a.dominated()) return {};
  std::string why;
  const auto add = [&why](const std::string& reason) { why += (why.empty() ? "" : "; ") + reason; };
  if (a.shareDominates)
    add("the longest segment alone carries " + format("%.0f", 100 * a.shares.front().share) + "% of D");
  if (a.intervalTooWide) add("the bootstrap interval of D is wider than D");
  if (a.tailDiverges)
    add("P_t decays as t^-" + format("%.2f", a.tailFit.gammaP) + " < t^-2 at the tail's end, so D = sum t^2 f_t / 2 "
        "grows with the steps sampled if the tail goes on");
  return "D is dominated by its longest segments; its error cannot be estimated from this run (" + why + ")";
}

}  // namespace archipelago
