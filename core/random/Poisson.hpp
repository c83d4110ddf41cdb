#pragma once
/// \file Poisson.hpp
/// \brief Poisson variates from the counter-based stream of CounterRng.hpp: the bootstrap over segments
/// (core/stats/Bootstrap.hpp) draws every bin's count from them, reproducibly from a seed.
///
/// The k-th uniform of a stream `key` is (orbitDraw(key, k) + ½)/2⁵², in (0, 1).  Means below 10 by
/// multiplication (Knuth), up to 10⁷ by Hörmann's transformed rejection with squeeze (PTRS, Insurance: Math.
/// Econ. 12, 39, 1993), above by the normal limit (relative skewness 1/√mean < 3·10⁻⁴).

#include <cstdint>

namespace archipelago {

/// A Poisson variate of mean `mean` ≥ 0 (finite), drawn from the counter stream `key`, whose draw counter
/// `counter` is advanced.
[[nodiscard]] std::uint64_t poissonVariate(double mean, std::uint64_t key, std::uint64_t& counter);

/// A non-negative whole number as a count, clamped to [0, 2⁶⁴ − 2¹¹] (no undefined conversion for huge values).
[[nodiscard]] std::uint64_t toCount(long double v) noexcept;

}  // namespace archipelago
