#include "core/tail/TailResult.hpp"

#include <algorithm>
#include <cmath>

#include "core/stats/LogFits.hpp"
#include "core/stats/RunStatistics.hpp"

namespace archipelago {

namespace {

/// A level's (1 − p)/(n p), p its survivors over its population pooled over the replicas (n walkers): the relative
/// variance of its survival fraction if every walker were independent (the binomial floor's term).
double binomialTerm(const TailLevelResult& L) {
  const double pooled = L.population > 0 ? static_cast<double>(L.survivors) / static_cast<double>(L.population) : 0;
  return pooled > 0 ? (1 - pooled) / (static_cast<double>(L.population) * pooled) : 0;
}

/// Level k pooled over the replicas: each replica's P the running product of its survival fractions (`running`,
/// carried from level to level), P their mean, its errors (TailResult.hpp).  `relative` receives the sum of the
/// levels' binomialTerm() so far: the relative variance of P if every walker were independent (the binomial floor).
TailLevelResult pooledLevel(const TailState& s, std::size_t k, double stepsNow, std::vector<double>& running,
                            double& relative) {
  const TailRequest& r = s.request;
  const std::size_t R = s.replicas.size();
  TailLevelResult L;
  L.blocks = s.levels[k];
  L.t = static_cast<double>(s.levels[k]) * r.run.q;
  L.steps = k < s.stepsAtLevel.size() ? static_cast<double>(s.stepsAtLevel[k]) : stepsNow;
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
  relative += binomialTerm(L);
  L.PErrorBinomial = mean * std::sqrt(relative);
  if (R > 1) {
    double ss = 0;
    for (double p : L.replicaP) ss += (p - mean) * (p - mean);
    L.PErrorReplicas = std::sqrt(ss / static_cast<double>(R - 1) / static_cast<double>(R));
  }
  L.PError = R > 1 ? std::max(L.PErrorReplicas, L.PErrorBinomial) : L.PErrorBinomial;
  L.reliable = R > 1 && L.ancestors >= r.minAncestors;
  if (proposals > 0) L.acceptance = static_cast<double>(accepted) / static_cast<double>(proposals);
  return L;
}

/// The fit over window w is linear in ln P at the levels: γ = −Σ_j w_j ln P_j, w_j the fitted slope of ln y = [point j].
std::vector<double> fitWeights(const Series& P, const LogWindow& w) {
  std::vector<double> weight(P.x.size());
  for (std::size_t j = 0; j < P.x.size(); ++j) {
    Series unit = P;
    for (std::size_t i = 0; i < unit.value.size(); ++i) unit.value[i] = i == j ? std::exp(1.0) : 1.0;
    weight[j] = logLogSlope(unit, w.from, w.to).slope;
  }
  return weight;
}

/// The error of γ = −Σ_j w_j ln P_j over R > 1 replicas: the replicas' covariance of ln P_i and ln P_j, to first order
/// C_ij/(P_i P_j); and the binomial floor: ln P_j is the sum of ln p over the levels up to j, independent binomial
/// terms of variance b_k, so var = Σ_k b_k (Σ_{j: level(j) ≥ k} w_j)².  levelOf[j]: the level of point j.
double exponentError(const TailResult& out, std::size_t R, const std::vector<std::size_t>& levelOf,
                     const std::vector<double>& weight, const std::vector<double>& binomialOfLevel) {
  const std::size_t points = levelOf.size();
  const double norm = static_cast<double>(R) * static_cast<double>(R - 1);
  double var = 0;
  for (std::size_t i = 0; i < points; ++i)
    for (std::size_t j = 0; j < points; ++j) {
      if (weight[i] == 0 || weight[j] == 0) continue;
      const TailLevelResult& a = out.levels[levelOf[i]];
      const TailLevelResult& b = out.levels[levelOf[j]];
      double c = 0;
      for (std::size_t rep = 0; rep < R; ++rep) c += (a.replicaP[rep] - a.P) * (b.replicaP[rep] - b.P);
      var += weight[i] * weight[j] * c / norm / (a.P * b.P);
    }
  double floor = 0;
  for (std::size_t k = 0; k < binomialOfLevel.size(); ++k) {
    double later = 0;
    for (std::size_t j = 0; j < points; ++j)
      if (levelOf[j] >= k) later += weight[j];
    floor += binomialOfLevel[k] * later * later;
  }
  return std::sqrt(std::max(var, floor));
}

/// The reliable levels as the fit sees them: P, the level of each point, and every level's binomialTerm().
struct ReliablePoints {
  Series P;
  std::vector<std::size_t> levelOf;
  std::vector<double> binomialOfLevel;
};

ReliablePoints reliablePoints(const TailResult& out) {
  ReliablePoints r{reliableSurvival(out), {}, {}};
  for (std::size_t k = 0; k < out.levels.size(); ++k) {
    if (out.levels[k].reliable) r.levelOf.push_back(k);
    r.binomialOfLevel.push_back(binomialTerm(out.levels[k]));
  }
  return r;
}

/// γ over window w (TailResult.hpp): fitLogSlope() of P at the reliable levels, its error with R > 1 replicas.
TailExponent exponentOver(const TailResult& out, const ReliablePoints& points, const LogWindow& w) {
  TailExponent e;
  e.tFrom = w.from;
  e.tTo = w.to;
  e.t = std::sqrt(w.from * w.to);
  e.gamma = fitLogSlope(points.P, w.from, w.to, &e.points);
  const std::size_t R = out.levels.empty() ? 0 : out.levels.front().replicaP.size();
  if (std::isfinite(e.gamma) && R > 1)
    e.gammaError = exponentError(out, R, points.levelOf, fitWeights(points.P, w), points.binomialOfLevel);
  return e;
}

/// The running exponent γ(t) (TailResult.hpp): over the windows of the statistics' own (runningExponentWindows),
/// fitLogSlope() of P at the reliable levels.
std::vector<TailExponent> runningExponents(const TailResult& out, std::uint32_t q) {
  std::vector<TailExponent> exponents;
  const ReliablePoints points = reliablePoints(out);
  if (points.P.x.empty()) return exponents;
  const double lowest = std::max({points.P.x.front(), 10.0, 2.0 * q});
  for (const LogWindow& w : runningExponentWindows(points.P.x.back(), lowest)) {
    TailExponent e = exponentOver(out, points, w);
    if (std::isfinite(e.gamma)) exponents.push_back(e);
  }
  return exponents;
}

}  // namespace

TailResult tailResult(const TailState& s) {
  TailResult out;
  out.steps = static_cast<double>(s.steps);
  out.finished = s.finished();
  const std::size_t R = s.replicas.size();
  std::size_t reached = SIZE_MAX;
  for (const TailReplica& x : s.replicas) reached = std::min(reached, x.levels.size());
  if (R == 0 || reached == SIZE_MAX) return out;
  std::vector<double> running(R, 0);
  double relative = 0;
  for (std::size_t k = 0; k < reached; ++k) out.levels.push_back(pooledLevel(s, k, out.steps, running, relative));
  out.exponents = runningExponents(out, s.request.run.q);
  return out;
}

TailExponent tailExponentOver(const TailResult& result, double from, double to) {
  return exponentOver(result, reliablePoints(result), LogWindow{from, to});
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
