// The AVX-512 IFMA orbit-measure kernel (MeasureKernels.hpp): the map and the accumulation fused in one loop,
// 8 orbits per 512-bit vector, 4 vectors per group (2 for the rotation measure).
//
// The step is N (forward) exactly as KernelAvx512Ifma.cpp computes it (vpmadd52huq gives ⌊a·b/2^52⌋ of 52-bit
// words, i.e. fixedPointG of FixedPointMap.hpp), with the wrap accumulated as ScalarStep::forward does:
//   u = Y + G(X),  Y ← u mod 2^52,  s = X + Y − 2^51,  X ← s mod 2^52,  wraps |= s | u.
// X and Y stay 64-bit integer vectors; each step they are converted to doubles (vcvtuqq2pd, exact below 2^52)
// for MeasureMath.inl's operations, one IEEE operation per lane as in the scalar kernel.  Products and sums are
// separate intrinsics (this module is compiled with -ffp-contract=off: no FMA contraction either).

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "core/measures/MeasureKernels.hpp"

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f,avx512ifma,avx512vl,avx512dq"))), apply_to = function)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC target("avx512f,avx512ifma,avx512vl,avx512dq")
// GCC 12's avx512fintrin.h shifts start from _mm512_undefined_epi32(), which -Wmaybe-uninitialized
// reports falsely once inlined (GCC bug 105593).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace archipelago::measures {
namespace {

#include "core/measures/MeasureMath.inl"

// The loop over the vectors of a step is unrolled, so that X and Y stay in registers.
#if defined(__clang__)
#define ARCHIPELAGO_UNROLL_STEP _Pragma("clang loop unroll(full)")
#else
#define ARCHIPELAGO_UNROLL_STEP _Pragma("GCC unroll 16")
#endif

struct Mask8 {
  __mmask8 m;
};

/// Eight doubles.
struct D8 {
  __m512d v;
  D8() = default;
  D8(__m512d a) : v(a) {}
  D8(double a) : v(_mm512_set1_pd(a)) {}
};

// Operations as free functions (found by argument-dependent lookup); hidden friends would miss the target
// attribute of this region with GCC 12.
inline D8 operator+(D8 a, D8 b) { return _mm512_add_pd(a.v, b.v); }
inline D8 operator-(D8 a, D8 b) { return _mm512_sub_pd(a.v, b.v); }
inline D8 operator*(D8 a, D8 b) { return _mm512_mul_pd(a.v, b.v); }
inline D8 operator/(D8 a, D8 b) { return _mm512_div_pd(a.v, b.v); }
inline Mask8 operator>(D8 a, D8 b) { return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_GT_OQ)}; }
inline Mask8 operator<(D8 a, D8 b) { return {_mm512_cmp_pd_mask(a.v, b.v, _CMP_LT_OQ)}; }
inline D8 absValue(D8 a) { return _mm512_abs_pd(a.v); }
inline D8 minValue(D8 a, D8 b) { return _mm512_min_pd(a.v, b.v); }  // a < b ? a : b
inline D8 maxValue(D8 a, D8 b) { return _mm512_max_pd(a.v, b.v); }  // a > b ? a : b
inline D8 select(Mask8 m, D8 a, D8 b) { return _mm512_mask_blend_pd(m.m, b.v, a.v); }
inline D8 negateWhere(Mask8 m, D8 a) {
  const __m512i bits = _mm512_castpd_si512(a.v);
  return _mm512_castsi512_pd(_mm512_mask_xor_epi64(bits, m.m, bits, _mm512_set1_epi64(INT64_MIN)));
}
inline Mask8 maskXor(Mask8 a, Mask8 b) { return {static_cast<__mmask8>(a.m ^ b.m)}; }
/// An index 0 … 15 per lane (MeasureMath.inl's offsetIndex).
struct Index8 {
  __m512i i;
};
inline Index8 offsetIndex(Mask8 mid, Mask8 far, Mask8 swapped, Mask8 cNegative) {
  const __m512i one = _mm512_set1_epi64(1);
  __m512i i = _mm512_maskz_mov_epi64(mid.m, one);
  i = _mm512_mask_add_epi64(i, far.m, i, one);
  i = _mm512_mask_or_epi64(i, swapped.m, i, _mm512_set1_epi64(4));
  return {_mm512_mask_or_epi64(i, cNegative.m, i, _mm512_set1_epi64(8))};
}
inline D8 lookup(Index8 index, const double (&table)[16]) {
  return _mm512_permutex2var_pd(_mm512_loadu_pd(table), index.i, _mm512_loadu_pd(table + 8));
}
/// For positive normal r: getexp gives ⌊log₂ r⌋, getmant the mantissa in [1, 2), both exact.
inline D8 splitExponent(D8 r, D8& mantissa) {
  mantissa = _mm512_getmant_pd(r.v, _MM_MANT_NORM_1_2, _MM_MANT_SIGN_src);
  return _mm512_getexp_pd(r.v);
}

struct Avx512Ifma {
  using D = D8;
  static constexpr std::size_t kLanes = 8;
  static D load(const double* p) { return _mm512_loadu_pd(p); }
  static void store(double* p, D a) { _mm512_storeu_pd(p, a.v); }

  template <int V>
  class Stepper {
   public:
    Stepper(const MeasureSetup& s, const std::uint64_t* xs, const std::uint64_t* ys, std::uint64_t, bool trackWraps)
        : trackWraps_(trackWraps),
          mask_(_mm512_set1_epi64(static_cast<long long>(fixedpoint::kMask))),
          half_(_mm512_set1_epi64(static_cast<long long>(fixedpoint::kHalf))),
          A_(_mm512_set1_epi64(s.coefficients.A)),
          B_(_mm512_set1_epi64(s.coefficients.B)),
          C_(_mm512_set1_epi64(s.coefficients.C)),
          shift_(_mm_cvtsi32_si128(s.coefficients.m)) {
      for (int v = 0; v < V; ++v) {
        X_[v] = _mm512_loadu_si512(xs + 8 * v);
        Y_[v] = _mm512_loadu_si512(ys + 8 * v);
        wraps_[v] = _mm512_setzero_si512();
      }
    }
    void next() {
      ARCHIPELAGO_UNROLL_STEP
      for (int v = 0; v < V; ++v) {
        const __m512i X = X_[v];
        const __m512i x2 = _mm512_madd52hi_epu64(_mm512_setzero_si512(), X, X);
        const __m512i bx = _mm512_madd52hi_epu64(_mm512_setzero_si512(), B_, X);
        const __m512i t = _mm512_madd52hi_epu64(C_, A_, x2);
        const __m512i u = _mm512_add_epi64(Y_[v], _mm512_sll_epi64(_mm512_sub_epi64(t, bx), shift_));
        const __m512i Y = _mm512_and_si512(u, mask_);
        const __m512i s = _mm512_sub_epi64(_mm512_add_epi64(X, Y), half_);
        X_[v] = _mm512_and_si512(s, mask_);
        Y_[v] = Y;
        wraps_[v] = _mm512_ternarylogic_epi64(wraps_[v], s, u, 0xFE);  // wraps | s | u
      }
    }
    [[nodiscard]] D x(int v) const { return _mm512_cvtepu64_pd(X_[v]); }
    [[nodiscard]] D y(int v) const { return _mm512_cvtepu64_pd(Y_[v]); }
    void store(std::uint64_t* xs, std::uint64_t* ys, std::uint64_t* wraps) const {
      if (!trackWraps_) {
        for (int v = 0; v < V; ++v) {
          _mm512_storeu_si512(xs + 8 * v, X_[v]);
          _mm512_storeu_si512(ys + 8 * v, Y_[v]);
        }
        return;
      }
      const __m512i notMask = _mm512_set1_epi64(static_cast<long long>(~fixedpoint::kMask));
      for (int v = 0; v < V; ++v) {
        _mm512_storeu_si512(xs + 8 * v, X_[v]);
        _mm512_storeu_si512(ys + 8 * v, Y_[v]);
        const __mmask8 wrapped = _mm512_test_epi64_mask(wraps_[v], notMask);
        const __m512i old = _mm512_loadu_si512(wraps + 8 * v);
        _mm512_storeu_si512(wraps + 8 * v, _mm512_mask_mov_epi64(old, wrapped, _mm512_set1_epi64(1)));
      }
    }

   private:
    bool trackWraps_;
    __m512i mask_, half_, A_, B_, C_;
    __m128i shift_;
    __m512i X_[V], Y_[V], wraps_[V];
  };
};

#include "core/measures/MeasureDriver.inl"

// Four vectors (32 orbits): the step's latency chain (~13 cycles) is hidden by the other vectors' work and the
// accumulation, as in the trapping kernel (KernelAvx512Ifma.cpp).
constexpr int kVectors = 4;
// The rotation measure: two vectors (16 orbits).  Its atan2 per step and lane is long enough to hide the step, and
// with four vectors the loop's live values exceed the 32 zmm registers and spill every step; issue 41 measured two
// vectors 4 % faster on a Zen 5 (7 alternated runs of bench/run-benchmarks.sh's rotation line; three vectors no
// better than four).
constexpr int kRotationVectors = 2;

}  // namespace

void measureKernelAvx512Ifma(const MeasureSetup& setup, std::span<MeasureLane> lanes, std::uint64_t first,
                             std::uint64_t steps) {
  measureWith<Avx512Ifma, kVectors, kRotationVectors>(setup, lanes, first, steps);
}

}  // namespace archipelago::measures

#if defined(__clang__)
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif
