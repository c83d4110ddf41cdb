// The AVX2 orbit-measure kernel (MeasureKernels.hpp): 4 orbits per 256-bit vector, 6 vectors per group.
//
// The AVX2 map kernel computes N on integer-valued doubles in round-toward-−∞ mode (KernelAvx2.cpp); the
// measures must be computed in round-to-nearest like the scalar reference, so the two cannot share a loop.
// Instead the unchanged orbit kernel iterateOrbitsAvx2 writes a trace of a chunk of kTraceRows steps (its
// states are bit for bit those of N), and the accumulation reads it back in round-to-nearest with 256-bit
// double arithmetic (MeasureMath.inl, one IEEE operation per lane as in the scalar kernel).
//
// Wraps (Dig and Rotation) are not in the trace, so they are recovered from consecutive points, exactly: with
// z = (X, Y) and z' = N(z),
//   - the second sum of the step wrapped  ⇔  X + Y' − 2^51 ≠ X'  (integers below 2^53: exact in double);
//   - the first sum Y + G(X) wrapped  ⇔  |Y + Ĝ − Y'| > 2^51, Ĝ = 2^52 g(x)/L in double, since Y' differs from
//     Y + G(X) by a multiple k·2^52 (k ≠ 0 exactly when it wrapped) and |Ĝ − G(X)| < 2^12 (G's coefficients
//     are rounded to 52 − m bits, m ≤ 9, and Ĝ's few roundings are relative 2^−52 of |G| < 2^62);
// the same flags as the exact carries the other paths test (tests/core/measures checks it).

#include <immintrin.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/kernels/VectorKernels.hpp"
#include "core/measures/MeasureKernels.hpp"

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC target("avx2")
#endif

namespace archipelago::measures {
namespace {

#include "core/measures/MeasureMath.inl"

struct Mask4 {
  __m256d m;  // all ones in the selected lanes
};

/// Four doubles.
struct D4 {
  __m256d v;
  D4() = default;
  D4(__m256d a) : v(a) {}
  D4(double a) : v(_mm256_set1_pd(a)) {}
};

// Operations as free functions (found by argument-dependent lookup); hidden friends would miss the target
// attribute of this region with GCC 12.
inline D4 operator+(D4 a, D4 b) { return _mm256_add_pd(a.v, b.v); }
inline D4 operator-(D4 a, D4 b) { return _mm256_sub_pd(a.v, b.v); }
inline D4 operator*(D4 a, D4 b) { return _mm256_mul_pd(a.v, b.v); }
inline D4 operator/(D4 a, D4 b) { return _mm256_div_pd(a.v, b.v); }
inline Mask4 operator>(D4 a, D4 b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_GT_OQ)}; }
inline Mask4 operator<(D4 a, D4 b) { return {_mm256_cmp_pd(a.v, b.v, _CMP_LT_OQ)}; }
inline D4 absValue(D4 a) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), a.v); }
inline D4 minValue(D4 a, D4 b) { return _mm256_min_pd(a.v, b.v); }  // a < b ? a : b
inline D4 maxValue(D4 a, D4 b) { return _mm256_max_pd(a.v, b.v); }  // a > b ? a : b
inline D4 select(Mask4 m, D4 a, D4 b) { return _mm256_blendv_pd(b.v, a.v, m.m); }
inline D4 negateWhere(Mask4 m, D4 a) { return _mm256_xor_pd(a.v, _mm256_and_pd(m.m, _mm256_set1_pd(-0.0))); }
inline Mask4 maskXor(Mask4 a, Mask4 b) { return {_mm256_xor_pd(a.m, b.m)}; }
/// An index 0 … 15 per lane (MeasureMath.inl's offsetIndex).
struct Index4 {
  __m256i i;
};
inline Index4 offsetIndex(Mask4 mid, Mask4 far, Mask4 swapped, Mask4 cNegative) {
  // A mask lane is −1 (all ones) or 0: 0 − mid − far is j.
  const __m256i j = _mm256_sub_epi64(_mm256_sub_epi64(_mm256_setzero_si256(), _mm256_castpd_si256(mid.m)),
                                     _mm256_castpd_si256(far.m));
  const __m256i q = _mm256_or_si256(_mm256_and_si256(_mm256_castpd_si256(swapped.m), _mm256_set1_epi64x(4)),
                                    _mm256_and_si256(_mm256_castpd_si256(cNegative.m), _mm256_set1_epi64x(8)));
  return {_mm256_or_si256(j, q)};
}
inline D4 lookup(Index4 index, const double (&table)[16]) { return _mm256_i64gather_pd(table, index.i, 8); }
/// For positive normal r: the exponent field minus 1023 and the mantissa with the exponent of 1.0 (exact).
inline D4 splitExponent(D4 r, D4& mantissa) {
  const __m256i bits = _mm256_castpd_si256(r.v);
  mantissa = _mm256_castsi256_pd(_mm256_or_si256(_mm256_and_si256(bits, _mm256_set1_epi64x(0x000FFFFFFFFFFFFFll)),
                                                 _mm256_set1_epi64x(0x3FF0000000000000ll)));
  // The biased exponent e (< 2^11) in the mantissa of 2^52: the double 2^52 + e, exactly.
  const __m256d two52 = _mm256_set1_pd(0x1p52);
  const __m256d biased =
      _mm256_sub_pd(_mm256_castsi256_pd(_mm256_or_si256(_mm256_srli_epi64(bits, 52), _mm256_castpd_si256(two52))), two52);
  return _mm256_sub_pd(biased, _mm256_set1_pd(1023.0));
}

/// Integers below 2^52 to doubles, exactly: 2^52 + x has the bits of 2^52 with x in the mantissa.
__m256d toDouble(__m256i x) {
  const __m256d two52 = _mm256_set1_pd(0x1p52);
  return _mm256_sub_pd(_mm256_castsi256_pd(_mm256_or_si256(x, _mm256_castpd_si256(two52))), two52);
}

struct Avx2 {
  using D = D4;
  static constexpr std::size_t kLanes = 4;
  static D load(const double* p) { return _mm256_loadu_pd(p); }
  static void store(double* p, D a) { _mm256_storeu_pd(p, a.v); }

  template <int V>
  class Stepper {
   public:
    static constexpr std::size_t kOrbits = 4 * static_cast<std::size_t>(V);
    static constexpr std::uint64_t kTraceRows = 256;  // 256 steps × 24 orbits × 16 bytes = 96 KiB

    Stepper(const MeasureSetup& s, const std::uint64_t* xs, const std::uint64_t* ys, std::uint64_t steps,
            bool trackWraps)
        : coefficients_(s.coefficients), iterate_(s.trace ? s.trace : &iterateOrbitsAvx2), remaining_(steps), trackWraps_(trackWraps),
          xmin_(s.xmin), unit_(s.unit), K_(s.K), gScale_(2.0 / s.unit),
          trace_(static_cast<std::size_t>(std::min(steps, kTraceRows)) * kOrbits) {
      for (std::size_t l = 0; l < kOrbits; ++l) orbits_[l] = {xs[l], ys[l]};
      for (int v = 0; v < V; ++v) {
        X_[v] = lanes(xs, v);
        Y_[v] = lanes(ys, v);
        wraps_[v] = _mm256_setzero_pd();
      }
    }
    void next() {
      if (row_ == rows_) refill();
      const UnitState* row = trace_.data() + row_ * kOrbits;
      ++row_;
      for (int v = 0; v < V; ++v) {
        const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + 4 * v));      // X0 Y0 X1 Y1
        const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + 4 * v + 2));  // X2 Y2 X3 Y3
        const D4 X = toDouble(_mm256_permute4x64_epi64(_mm256_unpacklo_epi64(a, b), 0xD8));
        const D4 Y = toDouble(_mm256_permute4x64_epi64(_mm256_unpackhi_epi64(a, b), 0xD8));
        if (trackWraps_) {
          const D4 half(0x1p51);
          const Mask4 second = {_mm256_cmp_pd(((X_[v] + Y) - half).v, X.v, _CMP_NEQ_OQ)};
          const D4 x = D4(xmin_) + D4(unit_) * X_[v];
          const D4 G = (x * x - D4(K_)) * D4(gScale_);
          const Mask4 first = absValue((Y_[v] + G) - Y) > half;
          wraps_[v] = _mm256_or_pd(wraps_[v], _mm256_or_pd(first.m, second.m));
        }
        X_[v] = X;
        Y_[v] = Y;
      }
    }
    [[nodiscard]] D x(int v) const { return X_[v]; }
    [[nodiscard]] D y(int v) const { return Y_[v]; }
    void store(std::uint64_t* xs, std::uint64_t* ys, std::uint64_t* wraps) const {
      for (std::size_t l = 0; l < kOrbits; ++l) {
        xs[l] = orbits_[l].X;
        ys[l] = orbits_[l].Y;
      }
      for (int v = 0; v < V; ++v) {
        const int bits = _mm256_movemask_pd(wraps_[v]);
        for (int i = 0; i < 4; ++i)
          if (bits & (1 << i)) wraps[4 * static_cast<std::size_t>(v) + static_cast<std::size_t>(i)] = 1;
      }
    }

   private:
    static D4 lanes(const std::uint64_t* a, int v) {
      return toDouble(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(a + 4 * v)));
    }
    void refill() {
      rows_ = std::min(remaining_, kTraceRows);
      remaining_ -= rows_;
      row_ = 0;
      // The orbit kernel sets and restores the rounding mode itself; it advances orbits_ to the chunk's end.
      iterate_(coefficients_, MapDirection::forward, std::span<UnitState>(orbits_, kOrbits), rows_,
                        trace_.data());
    }

    MapCoefficients coefficients_;
    OrbitKernel iterate_;  // the path's orbit kernel (MeasureSetup::trace)
    std::uint64_t remaining_;
    bool trackWraps_;
    double xmin_, unit_, K_, gScale_;
    std::vector<UnitState> trace_;
    std::uint64_t rows_ = 0, row_ = 0;
    UnitState orbits_[kOrbits];
    D4 X_[V], Y_[V];
    __m256d wraps_[V];
  };
};

#include "core/measures/MeasureDriver.inl"

// Six vectors (24 orbits), as the AVX2 trapping kernel keeps in flight (kAvx2BlockOrbits).
constexpr int kVectors = 6;

}  // namespace

void measureKernelAvx2(const MeasureSetup& setup, std::span<MeasureLane> lanes, std::uint64_t first,
                       std::uint64_t steps) {
  measureWith<Avx2, kVectors>(setup, lanes, first, steps);
}

}  // namespace archipelago::measures

#if defined(__clang__)
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC pop_options
#endif
