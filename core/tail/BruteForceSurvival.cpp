#include "core/tail/BruteForceSurvival.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/stats/RunStatistics.hpp"
#include "core/trapping/TrappingHistogram.hpp"

namespace archipelago {

namespace {
using Real = long double;  // as core/stats

struct Survival {
  Real P = std::numeric_limits<Real>::quiet_NaN();
  std::uint64_t beyond = 0;
};

// P(length > L) of one histogram of `orbits` orbits × `blocks` blocks, the estimator of TrappingStatistics.hpp.
Survival survivalOf(const TrappingHistogram& h, std::uint64_t orbits, std::uint64_t blocks, std::uint64_t L) {
  Survival out;
  if (h.segments() == 0 || orbits == 0) return out;  // no segment: P has no value (as core/stats)
  Real all = 0, above = 0;
  for (int i = 1; i < TrappingHistogram::kBins; ++i) {
    const std::uint64_t n = h.count(i);
    if (n == 0) continue;
    const Real meanBlocks = static_cast<Real>(h.lengthSum(i)) / static_cast<Real>(n);
    const Real w = static_cast<Real>(n) / (static_cast<Real>(orbits) * (static_cast<Real>(blocks) + 1 - meanBlocks));
    all += w;
    if (TrappingHistogram::binLower(i) > L) {
      above += w;
      out.beyond += n;
    }
  }
  out.P = above / all;
  return out;
}

bool sameProcess(const TrappingParameters& a, const TrappingParameters& b) {
  return a.map == b.map && a.Xr == b.Xr && a.q == b.q;
}
}  // namespace

bool isHistogramEdgeLevel(std::uint64_t L) noexcept {
  const std::uint64_t e = L + 1;
  if (e <= static_cast<std::uint64_t>(TrappingHistogram::kExactMax) + 1) return true;
  return TrappingHistogram::binLower(TrappingHistogram::binOf(e)) == e;
}

std::vector<BruteForceLevel> bruteForceSurvival(const std::vector<TrappingState>& runs,
                                                const std::vector<std::uint64_t>& levels) {
  if (runs.empty()) throw std::invalid_argument("brute-force survival needs at least one run");
  for (const TrappingState& r : runs) {
    TrappingParameters a = r.params, b = runs.front().params;
    a.seed = b.seed;
    if (!(a == b)) throw std::invalid_argument("the runs compared must share every parameter but the seed");
    if (r.blocksDone != runs.front().blocksDone)
      throw std::invalid_argument("the runs compared must have done the same number of blocks");
  }
  std::vector<TrappingHistogram> subsets;
  std::vector<std::uint64_t> orbits;
  TrappingHistogram total;
  std::uint64_t allOrbits = 0;
  for (const TrappingState& r : runs) {
    const std::vector<std::uint64_t> per = orbitsPerSubset(r);
    for (std::size_t i = 0; i < r.subsets.size(); ++i) {
      subsets.push_back(r.subsets[i]);
      orbits.push_back(per[i]);
      total.merge(r.subsets[i]);
      allOrbits += per[i];
    }
  }
  const std::uint64_t blocks = runs.front().blocksDone;
  const std::uint32_t q = runs.front().params.q;
  std::vector<BruteForceLevel> out;
  for (const std::uint64_t L : levels) {
    BruteForceLevel b;
    b.t = static_cast<double>(L) * q;
    const Survival s = survivalOf(total, allOrbits, blocks, L);
    b.segmentsBeyond = s.beyond;
    if (!isHistogramEdgeLevel(L) || std::isnan(s.P)) {
      out.push_back(b);
      continue;
    }
    b.P = static_cast<double>(s.P);
    Real sum = 0, squares = 0;
    std::size_t n = 0;
    std::vector<Real> parts;
    for (std::size_t i = 0; i < subsets.size(); ++i) {
      const Survival p = survivalOf(subsets[i], orbits[i], blocks, L);
      if (std::isnan(p.P)) continue;
      parts.push_back(p.P);
      sum += p.P;
      ++n;
    }
    if (n >= 2) {
      const Real mean = sum / static_cast<Real>(n);
      for (const Real v : parts) squares += (v - mean) * (v - mean);
      b.PError = static_cast<double>(std::sqrt(squares / static_cast<Real>(n - 1)) / std::sqrt(static_cast<Real>(n)));
    }
    out.push_back(b);
  }
  return out;
}

std::optional<std::string> tailRunMismatch(const TailRequest& request, const TrappingState& run) {
  const TrappingParameters& a = request.run;
  const TrappingParameters& b = run.params;
  if (!(a.map == b.map)) return std::string("the map (K, xmin, xmax) differs");
  if (a.Xr != b.Xr) return std::string("Xr differs");
  if (a.q != b.q) return std::string("q differs");
  if (!sameProcess(a, b)) return std::string("the process differs");
  return std::nullopt;
}

TailComparison compareWithRuns(const TailState& state, const TailResult& result, const std::vector<TrappingState>& runs) {
  TailComparison out;
  std::vector<std::uint64_t> levels;
  for (const TailLevelResult& L : result.levels) levels.push_back(L.blocks);
  const std::vector<BruteForceLevel> brute = bruteForceSurvival(runs, levels);
  for (const TrappingState& r : runs) out.bruteSteps += r.stepsDone();
  // α = 1/Σ w per step: the pooled runs' segments per step of record.
  TrappingHistogram total;
  std::uint64_t allOrbits = 0;
  for (const TrappingState& r : runs) {
    total.merge(r.total());
    allOrbits += r.orbitEnd - r.orbitBegin;
  }
  {
    Real all = 0;
    for (int i = 1; i < TrappingHistogram::kBins; ++i) {
      const std::uint64_t n = total.count(i);
      if (n == 0) continue;
      const Real meanBlocks = static_cast<Real>(total.lengthSum(i)) / static_cast<Real>(n);
      all += static_cast<Real>(n) /
             (static_cast<Real>(allOrbits) * (static_cast<Real>(runs.front().blocksDone) + 1 - meanBlocks));
    }
    out.alpha = all > 0 ? static_cast<double>(state.request.run.q / all) : 0;
  }
  for (std::size_t k = 0; k < result.levels.size(); ++k) {
    const TailLevelResult& L = result.levels[k];
    const BruteForceLevel& b = brute[k];
    TailComparisonLevel c;
    c.t = L.t;
    c.P = L.P;
    c.PError = L.PError;
    c.reliable = L.reliable;
    c.bruteP = b.P;
    c.bruteError = b.PError;
    c.bruteSegments = b.segmentsBeyond;
    c.tailSteps = L.steps;
    c.replicaP = L.replicaP;
    const double both = std::hypot(L.PError, b.PError);
    if (b.segmentsBeyond > 0 && std::isfinite(both) && both > 0) c.z = (L.P - b.P) / both;
    const double r = L.PError / L.P;
    if (std::isfinite(r) && r > 0) {
      if (b.segmentsBeyond > 0 && b.PError > 0 && b.P > 0) {
        const double rb = b.PError / b.P;
        c.bruteStepsSameError = out.bruteSteps * (rb / r) * (rb / r);
        c.bruteStepsMeasured = true;
      } else if (L.P > 0 && out.alpha > 0) {
        c.bruteStepsSameError = out.alpha / (L.P * r * r);
      }
    }
    out.levels.push_back(c);
  }
  return out;
}

TailPooledBias pooledBias(const TailComparison& comparison, std::uint64_t minSegments) {
  TailPooledBias out;
  std::vector<const TailComparisonLevel*> used;
  for (const TailComparisonLevel& l : comparison.levels) {
    const bool finite = std::isfinite(l.P) && std::isfinite(l.PError) && std::isfinite(l.bruteP) &&
                        std::isfinite(l.bruteError);
    if (!l.reliable || l.bruteSegments < minSegments || !finite || !(l.P > 0 && l.bruteP > 0 && l.PError > 0 &&
                                                                     l.bruteError > 0))
      continue;
    used.push_back(&l);
  }
  const std::size_t n = used.size();
  out.levels = n;
  if (n == 0) return out;
  out.tFrom = used.front()->t;
  out.tTo = used.back()->t;
  // The replicas' correlation of P_r(t_i) and P_r(t_j): 1 where it cannot be measured (the conservative bound).
  const auto rho = [&](const TailComparisonLevel& a, const TailComparisonLevel& b) {
    const std::size_t R = a.replicaP.size();
    if (&a == &b) return 1.0;
    if (R < 3 || b.replicaP.size() != R) return 1.0;
    double ma = 0, mb = 0;
    for (std::size_t r = 0; r < R; ++r) ma += a.replicaP[r], mb += b.replicaP[r];
    ma /= static_cast<double>(R), mb /= static_cast<double>(R);
    double saa = 0, sbb = 0, sab = 0;
    for (std::size_t r = 0; r < R; ++r) {
      saa += (a.replicaP[r] - ma) * (a.replicaP[r] - ma);
      sbb += (b.replicaP[r] - mb) * (b.replicaP[r] - mb);
      sab += (a.replicaP[r] - ma) * (b.replicaP[r] - mb);
    }
    if (!(saa > 0 && sbb > 0)) return 1.0;
    return std::clamp(sab / std::sqrt(saa * sbb), -1.0, 1.0);
  };
  std::vector<double> C(n * n), d(n), w(n);
  for (std::size_t i = 0; i < n; ++i) {
    const TailComparisonLevel& a = *used[i];
    d[i] = std::log(a.P / a.bruteP);
    for (std::size_t j = 0; j < n; ++j) {
      const TailComparisonLevel& b = *used[j];
      const double sampler = rho(a, b) * (a.PError / a.P) * (b.PError / b.P);
      const TailComparisonLevel& earlier = a.t <= b.t ? a : b;
      const double runs = (earlier.bruteError / earlier.bruteP) * (earlier.bruteError / earlier.bruteP);
      C[i * n + j] = sampler + runs;
    }
  }
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) sum += w[i] = 1 / C[i * n + i];
  double b = 0, var = 0;
  for (std::size_t i = 0; i < n; ++i) {
    w[i] /= sum;
    b += w[i] * d[i];
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) var += w[i] * C[i * n + j] * w[j];
  if (!(var > 0)) {  // a correlation set to 1 beside measured ones can leave C short of positive: the bound ρ = 1
    double bound = 0;
    for (std::size_t i = 0; i < n; ++i) bound += w[i] * std::sqrt(C[i * n + i]);
    var = bound * bound;
  }
  out.logRatio = b;
  out.logRatioError = std::sqrt(var);
  out.z = b / out.logRatioError;
  out.detectable = std::expm1(5 * out.logRatioError);
  out.detectableHalf = std::expm1(3 * out.logRatioError);
  return out;
}

}  // namespace archipelago
