#include "core/measures/BirkhoffAverage.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace archipelago {
namespace {
#include "core/measures/MeasureMath.inl"
}  // namespace

double birkhoffWeight(double s) noexcept {
  if (!(s > 0 && s < 1)) return 0;
  return std::exp(-1 / (s * (1 - s)));
}

BirkhoffWeights birkhoffWeights(std::uint64_t T, std::stop_token stop) {
  if (T < kMinIterations || T > kMaxIterations)
    throw std::invalid_argument("iterations = " + std::to_string(T) + " must be " + std::to_string(kMinIterations) +
                                " ... " + std::to_string(kMaxIterations));
  BirkhoffWeights w;
  w.g.resize(static_cast<std::size_t>(T));
  double hi = 0, lo = 0;
  for (std::uint64_t n = 0; n < T; ++n) {
    if (n % 65536 == 0 && stop.stop_requested()) return w;
    w.g[n] = birkhoffWeight(static_cast<double>(n) / static_cast<double>(T));
    twoSumAdd(hi, lo, w.g[n]);
  }
  w.sum = hi + lo;
  return w;
}

double convergenceDigits(double a, double b) noexcept {
  if (std::isnan(a) || std::isnan(b)) return std::nan("");
  const double d = std::fabs(a - b);
  if (!(d > 0)) return kMaxDigits;
  const double digits = -std::log10(d);
  return digits < kMaxDigits ? digits : kMaxDigits;
}

double weightedBirkhoffAverage(std::span<const double> f) {
  const BirkhoffWeights w = birkhoffWeights(f.size());
  double hi = 0, lo = 0;
  for (std::size_t n = 0; n < f.size(); ++n) twoSumAdd(hi, lo, w.g[n] * f[n]);
  return (hi + lo) / w.sum;
}

}  // namespace archipelago
