#include "core/stats/RunEnsemble.hpp"

#include <sstream>
#include <stdexcept>
#include <variant>

#include "core/stats/RunStatistics.hpp"

namespace archipelago {

namespace {
std::string text(const ParameterValue& v) {
  std::ostringstream out;
  out.precision(17);
  std::visit([&out](auto x) { out << x; }, v);
  return out.str();
}
}  // namespace

std::vector<TrappingHistogram> pooledSubsets(const Ensemble& e) {
  std::vector<TrappingHistogram> out;
  for (const EnsembleMember& m : e.members) out.insert(out.end(), m.subsets.begin(), m.subsets.end());
  return out;
}

std::vector<std::uint64_t> pooledOrbitsPerSubset(const Ensemble& e) {
  std::vector<std::uint64_t> out;
  for (const EnsembleMember& m : e.members) out.insert(out.end(), m.orbitsPerSubset.begin(), m.orbitsPerSubset.end());
  return out;
}

TrappingStatistics ensembleStatistics(const Ensemble& e) {
  if (e.members.empty()) throw std::invalid_argument("an ensemble needs at least one run");
  return computeStatistics(pooledSubsets(e), pooledOrbitsPerSubset(e), e.blocks, e.q);
}

Ensemble ensembleOf(const std::vector<TrappingState>& runs, const std::vector<std::string>& names) {
  if (runs.empty()) throw std::invalid_argument("an ensemble needs at least one run");
  const auto name = [&](std::size_t i) { return i < names.size() ? names[i] : "run " + std::to_string(i + 1); };
  const TrappingState& first = runs.front();
  Ensemble e;
  e.blocks = first.blocksDone;
  e.q = first.params.q;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const TrappingState& r = runs[i];
    const std::string pair = name(i) + " and " + name(0);
    for (const ParameterRule& rule : parameterRules()) {
      if (rule.key == "seed") continue;
      const ParameterValue a = parameterValue(r.params, rule.key), b = parameterValue(first.params, rule.key);
      if (a != b)
        throw std::invalid_argument(pair + " differ in " + std::string(rule.key) + " (" + text(a) + " and " + text(b) +
                                    "): runs combined must differ only in the seed");
    }
    if (r.orbitBegin != first.orbitBegin || r.orbitEnd != first.orbitEnd)
      throw std::invalid_argument(pair + " cover different orbits: runs combined must cover the same orbit range");
    if (r.blocksDone != first.blocksDone)
      throw std::invalid_argument(pair + " have done different numbers of blocks (" + std::to_string(r.blocksDone) +
                                  " and " + std::to_string(first.blocksDone) + "): finish both first");
    for (std::size_t j = 0; j < i; ++j)
      if (runs[j].params.seed == r.params.seed)
        throw std::invalid_argument(name(i) + " and " + name(j) + " have the same seed " +
                                    std::to_string(r.params.seed) + ": the same orbits would be counted twice");
    e.members.push_back({r.subsets, orbitsPerSubset(r), r.params.seed});
  }
  return e;
}

}  // namespace archipelago
