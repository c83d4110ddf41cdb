#include "core/stats/RunStatistics.hpp"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/io/NumberText.hpp"

namespace archipelago {

std::vector<std::uint64_t> orbitsPerSubset(const TrappingState& state) {
  const std::uint64_t n = state.params.subsets;
  std::vector<std::uint64_t> counts(n, 0);
  for (std::uint64_t i = state.orbitBegin; i < state.orbitEnd; ++i) counts[i % n] += 1;
  return counts;
}

TrappingStatistics statisticsOf(const TrappingState& state) {
  return computeStatistics(state.subsets, orbitsPerSubset(state), state.blocksDone, state.params.q);
}

namespace {
/// f of `s` at x by linear interpolation of log f in log x between its neighbouring positive points, with the
/// interpolated relative error; nothing outside its positive range.
std::optional<std::pair<double, double>> logInterpolate(const Series& s, double x) {
  std::size_t below = s.x.size();
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!(s.value[i] > 0)) continue;
    if (s.x[i] <= x) below = i;
    if (s.x[i] >= x && below != s.x.size()) {
      const double x0 = s.x[below], x1 = s.x[i];
      const double w = x1 > x0 ? (std::log(x) - std::log(x0)) / (std::log(x1) - std::log(x0)) : 0;
      const double lv = (1 - w) * std::log(s.value[below]) + w * std::log(s.value[i]);
      const double re = (1 - w) * s.error[below] / s.value[below] + w * s.error[i] / s.value[i];
      const double v = std::exp(lv);
      return std::pair{v, re * v};
    }
  }
  return std::nullopt;
}
}  // namespace

double spliceCrossover(const TrappingStatistics& run, const TrappingStatistics& companion, std::uint32_t q) {
  const double from = kBlockAffectedBlocks * q;
  for (std::size_t i = 0; i < run.f.x.size(); ++i) {
    const double x = run.f.x[i];
    if (x < from || !(run.f.value[i] > 0)) continue;
    const auto c = logInterpolate(companion.f, x);
    if (!c) break;  // beyond the companion's data
    const double sigma = std::sqrt(run.f.error[i] * run.f.error[i] + c->second * c->second);
    if (std::fabs(run.f.value[i] - c->first) <= 2 * sigma) return x;
  }
  throw std::invalid_argument("the run's f_t and its q = 1 companion's agree nowhere beyond 10 q = " +
                              io::shortestText(from) + " steps within the companion's data: a longer companion is needed");
}

TrappingStatistics splicedStatisticsOf(const TrappingState& run, const TrappingState& companion) {
  const TrappingParameters& a = run.params;
  const TrappingParameters& b = companion.params;
  const auto differ = [](const std::string& what) {
    throw std::invalid_argument("not a run and its q = 1 companion: " + what);
  };
  if (!(a.map == b.map)) differ("their maps (K, xmin, xmax) differ");
  if (a.Xr != b.Xr) differ("their randomizing zones Xr differ");
  if (a.subsets != b.subsets) differ("their numbers of subsets differ");
  if (a.q <= 1) differ("the run has q = 1 (it needs no companion)");
  if (b.q != 1) differ("the companion has q = " + std::to_string(b.q) + ", not 1");
  if (run.orbitEnd - run.orbitBegin != companion.orbitEnd - companion.orbitBegin) differ("their numbers of orbits differ");
  const double crossover = spliceCrossover(statisticsOf(run), statisticsOf(companion), a.q);
  SplicedRecord r;
  r.longSubsets = run.subsets;
  r.longOrbits = orbitsPerSubset(run);
  r.longBlocks = run.blocksDone;
  r.longQ = a.q;
  r.shortSubsets = companion.subsets;
  r.shortOrbits = orbitsPerSubset(companion);
  r.shortBlocks = companion.blocksDone;
  r.shortQ = 1;
  r.crossover = crossover;
  return computeSplicedStatistics(r);
}

}  // namespace archipelago
