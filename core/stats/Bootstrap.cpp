#include "core/stats/Bootstrap.hpp"

#include <algorithm>
#include <cmath>

#include "core/random/CounterRng.hpp"
#include "core/random/Poisson.hpp"

namespace archipelago {

using Real = long double;

double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return kTailUndefined;
  const double at = p * static_cast<double>(sorted.size() - 1);
  const auto i = static_cast<std::size_t>(std::floor(at));
  if (i + 1 >= sorted.size()) return sorted.back();
  return sorted[i] + (at - static_cast<double>(i)) * (sorted[i + 1] - sorted[i]);
}

ConfidenceInterval percentileInterval(std::vector<double> values, double confidence) {
  const std::size_t all = values.size();
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }), values.end());
  if (values.empty() || static_cast<double>(values.size()) < 0.9 * static_cast<double>(all)) return {};
  std::sort(values.begin(), values.end());
  return {percentile(values, (1 - confidence) / 2), percentile(values, (1 + confidence) / 2)};
}

TrappingHistogram resampleHistogram(const TrappingHistogram& h, std::uint64_t seed, std::uint64_t replicate) {
  TrappingHistogram out;
  const std::uint64_t key = orbitKey(seed, replicate);
  std::uint64_t counter = 0;
  for (int i = 1; i < TrappingHistogram::kBins; ++i) {
    const std::uint64_t n = h.count(i);
    if (n == 0) continue;
    const std::uint64_t drawn = poissonVariate(static_cast<double>(n), key, counter);
    const Real lengths = static_cast<Real>(drawn) * static_cast<Real>(h.lengthSum(i)) / static_cast<Real>(n);
    out.setBin(i, drawn, toCount(std::round(lengths)));
  }
  return out;
}

}  // namespace archipelago
