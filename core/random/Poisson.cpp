#include "core/random/Poisson.hpp"

#include <cmath>
#include <numbers>

#include "core/random/CounterRng.hpp"

namespace archipelago {

namespace {
double uniform(std::uint64_t key, std::uint64_t& counter) {
  return (static_cast<double>(orbitDraw(key, ++counter)) + 0.5) * 0x1p-52;  // in (0, 1)
}

}  // namespace

// A non-negative whole number as a count, clamped to [0, 2⁶⁴ − 2¹¹] (no undefined conversion for huge values).
std::uint64_t toCount(long double v) noexcept {
  constexpr long double kMax = 18446744073709549568.0L;  // the largest double below 2⁶⁴
  return v <= 0 ? 0 : v >= kMax ? static_cast<std::uint64_t>(kMax) : static_cast<std::uint64_t>(v);
}

std::uint64_t poissonVariate(double mean, std::uint64_t key, std::uint64_t& counter) {
  if (!(mean > 0)) return 0;
  if (mean < 10) {  // multiplication (Knuth): the number of uniforms whose product stays above e^−mean
    const double limit = std::exp(-mean);
    std::uint64_t k = 0;
    for (double product = uniform(key, counter); product > limit; product *= uniform(key, counter)) ++k;
    return k;
  }
  if (mean > 1e7) {  // normal limit (relative skewness 1/√mean < 3·10⁻⁴), Box–Muller
    const double u1 = uniform(key, counter), u2 = uniform(key, counter);
    const double z = std::sqrt(-2 * std::log(u1)) * std::cos(2 * std::numbers::pi * u2);
    return toCount(std::round(mean + std::sqrt(mean) * z));
  }
  // PTRS, transformed rejection with squeeze (W. Hörmann, Insurance: Math. Econ. 12, 39, 1993), mean ≥ 10.
  const double slam = std::sqrt(mean), loglam = std::log(mean);
  const double b = 0.931 + 2.53 * slam, a = -0.059 + 0.02483 * b;
  const double invalpha = 1.1239 + 1.1328 / (b - 3.4), vr = 0.9277 - 3.6224 / (b - 2);
  for (;;) {
    const double U = uniform(key, counter) - 0.5, V = uniform(key, counter);
    const double us = 0.5 - std::fabs(U);
    const double k = std::floor((2 * a / us + b) * U + mean + 0.43);
    if (us >= 0.07 && V <= vr) return static_cast<std::uint64_t>(k);
    if (k < 0 || (us < 0.013 && V > us)) continue;
    if (std::log(V) + std::log(invalpha) - std::log(a / (us * us) + b) <= -mean + k * loglam - std::lgamma(k + 1))
      return static_cast<std::uint64_t>(k);
  }
}

}  // namespace archipelago
