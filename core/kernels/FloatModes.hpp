#pragma once
/// \file FloatModes.hpp
/// \brief Core-internal: the floating-point modes the exact-double kernels (KernelAvx2.cpp, KernelAvx512F.inl)
/// set around their loops.  Generic code (SSE's MXCSR and the x87 control word exist on every x86-64 CPU).

#include <xmmintrin.h>

#include <cstdint>

namespace archipelago::kernels {

/// Sets MXCSR to round toward −∞ for its lifetime (the floors of the double-valued map need it), with every
/// floating-point exception masked (almost every step is inexact); the caller's MXCSR, flags included, comes back.
class RoundingDown {
 public:
  RoundingDown() : saved_(_mm_getcsr()) { _mm_setcsr((saved_ & ~_MM_ROUND_MASK) | _MM_ROUND_DOWN | _MM_MASK_MASK); }
  ~RoundingDown() { _mm_setcsr(saved_); }
  RoundingDown(const RoundingDown&) = delete;
  RoundingDown& operator=(const RoundingDown&) = delete;

 private:
  unsigned saved_;
};

/// Sets the x87 control word to round to nearest at 53-bit precision for its lifetime, so that long double
/// products and sums round exactly like double ones (the exponent range is wider, which changes nothing for
/// the normal values of RasterGrid::pixelOf).
class X87Double {
 public:
  X87Double() {
    __asm__ __volatile__("fnstcw %0" : "=m"(saved_));
    const std::uint16_t doubleNearest = static_cast<std::uint16_t>((saved_ & ~0x0F00u) | 0x0200u);
    __asm__ __volatile__("fldcw %0" : : "m"(doubleNearest));
  }
  ~X87Double() { __asm__ __volatile__("fldcw %0" : : "m"(saved_)); }
  X87Double(const X87Double&) = delete;
  X87Double& operator=(const X87Double&) = delete;

 private:
  std::uint16_t saved_ = 0;
};

}  // namespace archipelago::kernels
