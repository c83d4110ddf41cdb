#pragma once
/// \file CounterRng.hpp
/// \brief Counter-based random numbers: every orbit's k-th draw is a pure function of (seed, orbit, k).
///
/// This replaces the Cray's sequential generator (appendix B, step 6.2) so that each orbit is reproducible
/// alone, whichever thread, rank or resumed checkpoint computes it (docs/design.md, "arithmetic contract"):
///   mix64(z)   = SplitMix64's finaliser,
///   key(orbit) = mix64(seed ^ mix64(orbit + 1)),
///   U_k        = mix64(key + k·0x9E3779B97F4A7C15) >> 12   (k = 1, 2, …), a 52-bit fraction of the unit.

#include <cstdint>

namespace archipelago {

/// SplitMix64's output finaliser (Steele, Lea & Flood 2014), a bijection of 64-bit words.
[[nodiscard]] constexpr std::uint64_t mix64(std::uint64_t z) noexcept {
  z ^= z >> 30;
  z *= 0xBF58476D1CE4E5B9ULL;
  z ^= z >> 27;
  z *= 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return z;
}

/// The per-orbit key.
[[nodiscard]] constexpr std::uint64_t orbitKey(std::uint64_t seed, std::uint64_t orbit) noexcept {
  return mix64(seed ^ mix64(orbit + 1));
}

/// The k-th draw (k ≥ 1) of the orbit with key `key`: a uniform integer in [0, 2^52).
[[nodiscard]] constexpr std::uint64_t orbitDraw(std::uint64_t key, std::uint64_t k) noexcept {
  return mix64(key + k * 0x9E3779B97F4A7C15ULL) >> 12;
}

}  // namespace archipelago
