#include "core/tail/TailResult.hpp"

#include <algorithm>
#include <cmath>

#include "core/stats/RunStatistics.hpp"

namespace archipelago {

TailResult tailResult(const TailState& s) {
  TailResult out;
  out.steps = static_cast<double>(s.steps);
  out.finished = s.finished();
  const TailRequest& r = s.request;
  const std::size_t R = s.replicas.size();
  std::size_t reached = SIZE_MAX;
  for (const TailReplica& x : s.replicas) reached = std::min(reached, x.levels.size());
  if (R == 0 || reached == SIZE_MAX) return out;
  std::vector<double> running(R, 0);
  // Σ_j (1 − p_j)/(n_j p_j) over the levels so far, pooled over the replicas: the relative variance of P if every
  // walker were independent (the binomial floor, TailResult.hpp); binomial[k] after level k, and per level.
  std::vector<double> binomial, binomialOfLevel;
  double relative = 0;
  for (std::size_t k = 0; k < reached; ++k) {
    TailLevelResult L;
    L.blocks = s.levels[k];
    L.t = static_cast<double>(s.levels[k]) * r.run.q;
    L.steps = k < s.stepsAtLevel.size() ? static_cast<double>(s.stepsAtLevel[k]) : out.steps;
    L.fewestAncestors = UINT64_MAX;
    std::uint64_t proposals = 0, accepted = 0;
    for (std::size_t rep = 0; rep < R; ++rep) {
      const TailLevelCount& c = s.replicas[rep].levels[k];
      const double fraction =
          c.population > 0 ? static_cast<double>(c.survivors) / static_cast<double>(c.population) : 0.0;
      running[rep] = k == 0 ? fraction : running[rep] * fraction;
      L.replicaP.push_back(running[rep]);
      L.population += c.population;
      L.survivors += c.survivors;
      L.ancestors += c.ancestors;
      L.fewestAncestors = std::min(L.fewestAncestors, c.ancestors);
      proposals += c.proposals;
      accepted += c.accepted;
    }
    double mean = 0;
    for (double p : L.replicaP) mean += p;
    mean /= static_cast<double>(R);
    L.P = mean;
    const double pooled = L.population > 0 ? static_cast<double>(L.survivors) / static_cast<double>(L.population) : 0;
    binomialOfLevel.push_back(pooled > 0 ? (1 - pooled) / (static_cast<double>(L.population) * pooled) : 0);
    relative += binomialOfLevel.back();
    binomial.push_back(relative);
    L.PErrorBinomial = mean * std::sqrt(relative);
    if (R > 1) {
      double ss = 0;
      for (double p : L.replicaP) ss += (p - mean) * (p - mean);
      L.PErrorReplicas = std::sqrt(ss / static_cast<double>(R - 1) / static_cast<double>(R));
    }
    L.PError = R > 1 ? std::max(L.PErrorReplicas, L.PErrorBinomial) : L.PErrorBinomial;
    L.reliable = R > 1 && L.ancestors >= r.minAncestors;
    if (proposals > 0) L.acceptance = static_cast<double>(accepted) / static_cast<double>(proposals);
    out.levels.push_back(std::move(L));
  }
  for (std::size_t k = 0; k + 1 < out.levels.size(); ++k) {
    const TailLevelResult& a = out.levels[k];
    const TailLevelResult& b = out.levels[k + 1];
    if (!a.reliable || !b.reliable || !(a.P > 0) || !(b.P > 0)) continue;
    TailExponent e;
    e.tFrom = a.t;
    e.tTo = b.t;
    e.t = std::sqrt(a.t * b.t);
    const double span = std::log(b.t / a.t);
    e.gamma = -(std::log(b.P) - std::log(a.P)) / span;
    if (R > 1) {
      double va = 0, vb = 0, cab = 0;
      for (std::size_t rep = 0; rep < R; ++rep) {
        va += (a.replicaP[rep] - a.P) * (a.replicaP[rep] - a.P);
        vb += (b.replicaP[rep] - b.P) * (b.replicaP[rep] - b.P);
        cab += (a.replicaP[rep] - a.P) * (b.replicaP[rep] - b.P);
      }
      const double norm = static_cast<double>(R) * static_cast<double>(R - 1);
      const double var = va / norm / (a.P * a.P) + vb / norm / (b.P * b.P) - 2 * cab / norm / (a.P * b.P);
      // The binomial floor of ln(P_b/P_a): the survival fraction of level b alone (the levels below are shared).
      e.gammaError = std::sqrt(std::max(var, binomialOfLevel[k + 1])) / span;
    }
    out.exponents.push_back(e);
  }
  return out;
}

TailResult runTailSampler(const TailRequest& request, const TailRunOptions& options, const TailObserver& observer,
                          std::stop_token stop) {
  return tailResult(runTail(startTail(request), options, observer, std::move(stop)));
}

Series reliableSurvival(const TailResult& result) {
  Series s;
  for (const TailLevelResult& L : result.levels) {
    if (!L.reliable) continue;
    s.x.push_back(L.t);
    s.value.push_back(L.P);
    s.error.push_back(L.PError);
  }
  return s;
}

Series reliableSurvivalIn(const TailResult& result, const TrappingState& run, const TrappingStatistics& shown,
                          double* factor) {
  const double own = statisticsOf(run).alpha;
  const double f = shown.splicedAt > 0 && own > 0 && std::isfinite(shown.alpha) ? shown.alpha / own : 1;
  if (factor) *factor = f;
  Series s = reliableSurvival(result);
  for (double& v : s.value) v *= f;
  for (double& e : s.error) e *= f;
  return s;
}

double largestReliableT(const TailResult& result) noexcept {
  double t = 0;
  for (const TailLevelResult& L : result.levels)
    if (L.reliable) t = std::max(t, L.t);
  return t;
}

}  // namespace archipelago
