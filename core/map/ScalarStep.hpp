#pragma once
/// \file ScalarStep.hpp
/// \brief N and N⁻¹ (FixedPointMap.hpp) in the form the scalar kernels compute them.
///
/// For a, b < 2^52, ⌊a·b/2^52⌋ = ⌊(a·2^12)·b/2^64⌋ is the high word of one 64×64-bit product (mul/mulx, no
/// double-word shift), so with A·2^12 and B·2^12 precomputed a step is three such products.  The integers are
/// those of fixedPointG/backwardStep/forwardStep exactly (the same floor divisions of the same products);
/// tests/core/map checks them against each other.  The scalar kernels interleave several orbits, since the
/// three products of a step form one long dependency chain.

#include <cstdint>

#include "core/map/FixedPointMap.hpp"

// Loops over interleaved orbits must be unrolled so that their products overlap (GCC does not unroll them at
// -O2 by itself).
#if defined(__clang__)
#define ARCHIPELAGO_UNROLL_LANES _Pragma("clang loop unroll(full)")
#else
#define ARCHIPELAGO_UNROLL_LANES _Pragma("GCC unroll 8")
#endif

namespace archipelago {

class ScalarStep {
 public:
  explicit ScalarStep(const MapCoefficients& c) noexcept
      : A12_(static_cast<std::uint64_t>(c.A) << 12), B12_(static_cast<std::uint64_t>(c.B) << 12),
        C_(static_cast<std::uint64_t>(c.C)), m_(c.m) {}

  /// G(X) as a 64-bit word (fixedPointG), for X < 2^52.
  [[nodiscard]] std::uint64_t G(std::uint64_t X) const noexcept {
    const std::uint64_t x2 = mulHigh(X << 12, X);  // ⌊X²/2^52⌋
    return (mulHigh(A12_, x2) - mulHigh(B12_, X) + C_) << m_;
  }

  /// One step of N⁻¹ (backwardStep); ORs into `wrap` a word with a bit ≥ 52 set when the step wrapped.
  void backward(std::uint64_t& X, std::uint64_t& Y, std::uint64_t& wrap) const noexcept {
    using namespace fixedpoint;
    const std::uint64_t s = X - Y + kHalf;
    const std::uint64_t x = s & kMask;
    const std::uint64_t u = Y - G(x);
    X = x;
    Y = u & kMask;
    wrap |= s | u;
  }

  /// One step of N (forwardStep), wraps not reported.
  void forward(std::uint64_t& X, std::uint64_t& Y) const noexcept {
    using namespace fixedpoint;
    Y = (Y + G(X)) & kMask;
    X = (X + Y - kHalf) & kMask;
  }

  /// One step of N (forwardStep); ORs into `wrap` a word with a bit ≥ 52 set when the step wrapped.
  void forward(std::uint64_t& X, std::uint64_t& Y, std::uint64_t& wrap) const noexcept {
    using namespace fixedpoint;
    const std::uint64_t u = Y + G(X);
    Y = u & kMask;
    const std::uint64_t s = X + Y - kHalf;
    X = s & kMask;
    wrap |= s | u;
  }

 private:
  static std::uint64_t mulHigh(std::uint64_t a, std::uint64_t b) noexcept {
    return static_cast<std::uint64_t>((uint128{a} * b) >> 64);
  }

  std::uint64_t A12_, B12_, C_;
  int m_;
};

}  // namespace archipelago
