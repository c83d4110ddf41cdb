// The AVX-512 IFMA path: 8 orbits per 512-bit vector (VectorKernels.hpp).
//
// vpmadd52huq(acc, a, b) = acc + ⌊(a mod 2^52)(b mod 2^52) / 2^52⌋ exactly, which is the fixed-point product
// of appendix B on 52-bit words.  One step of N⁻¹, with s = X − Y + 2^51 and the inputs' low 52 bits used
// directly (so the multiplies need not wait for the masking of s):
//   x2 = madd52hi(0, s, s) = ⌊X²/2^52⌋,   t = madd52hi(C, A, x2) = ⌊A·x2/2^52⌋ + C,
//   bx = madd52hi(0, B, s) = ⌊B·X/2^52⌋,  G = (t − bx)·2^m,  u = Y − G,
// exactly FixedPointMap.hpp's fixedPointG/backwardStep.  A wrap is a bit ≥ 52 set in s or u (as unsigned
// 64-bit words); one vpternlogq ORs both into an accumulator that is tested once per block.

#include <immintrin.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "core/kernels/VectorKernels.hpp"
#include "core/random/CounterRng.hpp"

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

namespace archipelago {
namespace {

struct Avx512Ifma {
  using Vec = __m512i;
  static constexpr std::size_t kLanes = 8;

  struct Constants {
    Vec mask, notMask, half, A, B, C, randomizingX, one, golden, mixFirst, mixSecond;
    __m128i shift;
    Constants(const MapCoefficients& k, std::uint64_t Xr)
        : mask(_mm512_set1_epi64(static_cast<long long>(fixedpoint::kMask))),
          notMask(_mm512_set1_epi64(static_cast<long long>(~fixedpoint::kMask))),
          half(_mm512_set1_epi64(static_cast<long long>(fixedpoint::kHalf))),
          A(_mm512_set1_epi64(k.A)),
          B(_mm512_set1_epi64(k.B)),
          C(_mm512_set1_epi64(k.C)),
          randomizingX(_mm512_set1_epi64(static_cast<long long>(Xr))),
          one(_mm512_set1_epi64(1)),
          golden(_mm512_set1_epi64(static_cast<long long>(0x9E3779B97F4A7C15ULL))),
          mixFirst(_mm512_set1_epi64(static_cast<long long>(0xBF58476D1CE4E5B9ULL))),
          mixSecond(_mm512_set1_epi64(static_cast<long long>(0x94D049BB133111EBULL))),
          shift(_mm_cvtsi32_si128(k.m)) {}
  };

  static Vec load(const std::uint64_t* p) { return _mm512_loadu_si512(p); }
  static void store(std::uint64_t* p, Vec v) { _mm512_storeu_si512(p, v); }
  static Vec zero() { return _mm512_setzero_si512(); }
  // X and Y are iterated as the integers themselves.
  using State = Vec;
  static State loadState(const std::uint64_t* p) { return load(p); }
  static void storeState(std::uint64_t* p, State s) { store(p, s); }
  static State noWraps() { return zero(); }

  static void backward(const Constants& c, Vec& X, Vec& Y, Vec& wrapBits) {
    const Vec s = _mm512_add_epi64(_mm512_sub_epi64(X, Y), c.half);
    const Vec x2 = _mm512_madd52hi_epu64(_mm512_setzero_si512(), s, s);
    const Vec bx = _mm512_madd52hi_epu64(_mm512_setzero_si512(), c.B, s);
    const Vec t = _mm512_madd52hi_epu64(c.C, c.A, x2);
    const Vec u = _mm512_sub_epi64(Y, _mm512_sll_epi64(_mm512_sub_epi64(t, bx), c.shift));
    X = _mm512_and_si512(s, c.mask);
    Y = _mm512_and_si512(u, c.mask);
    wrapBits = _mm512_ternarylogic_epi64(wrapBits, s, u, 0xFE);  // wrapBits | s | u
  }

  static void forward(const Constants& c, Vec& X, Vec& Y) {
    const Vec x2 = _mm512_madd52hi_epu64(_mm512_setzero_si512(), X, X);
    const Vec bx = _mm512_madd52hi_epu64(_mm512_setzero_si512(), c.B, X);
    const Vec t = _mm512_madd52hi_epu64(c.C, c.A, x2);
    const Vec u = _mm512_add_epi64(Y, _mm512_sll_epi64(_mm512_sub_epi64(t, bx), c.shift));
    Y = _mm512_and_si512(u, c.mask);
    X = _mm512_and_si512(_mm512_sub_epi64(_mm512_add_epi64(X, Y), c.half), c.mask);
  }

  /// RasterGrid broadcast; the products and sums use explicit rounding (never fused into an FMA), as the
  /// scalar RasterGrid::pixelOf rounds them.
  struct Grid {
    Vec cx, cy, iwLast, ihLast, iw;
    __m512d sx, sy, hw, hh, w, h, zero;
    explicit Grid(const RasterGrid& g)
        : cx(_mm512_set1_epi64(static_cast<long long>(g.cx))),
          cy(_mm512_set1_epi64(static_cast<long long>(g.cy))),
          iwLast(_mm512_set1_epi64(g.iw - 1)),
          ihLast(_mm512_set1_epi64(g.ih - 1)),
          iw(_mm512_set1_epi64(g.iw)),
          sx(_mm512_set1_pd(g.sx)),
          sy(_mm512_set1_pd(g.sy)),
          hw(_mm512_set1_pd(g.hw)),
          hh(_mm512_set1_pd(g.hh)),
          w(_mm512_set1_pd(g.w)),
          h(_mm512_set1_pd(g.h)),
          zero(_mm512_setzero_pd()) {}
  };
  static unsigned pixels(const Grid& g, Vec X, Vec Y, std::uint64_t* out) {
    constexpr int kRound = _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC;
    const __m512d dx = _mm512_cvtepi64_pd(_mm512_sub_epi64(X, g.cx));  // exact: |X − cx| < 2^53
    const __m512d dy = _mm512_cvtepi64_pd(_mm512_sub_epi64(Y, g.cy));
    const __m512d fx = _mm512_add_round_pd(_mm512_mul_round_pd(dx, g.sx, kRound), g.hw, kRound);
    const __m512d fy = _mm512_sub_round_pd(g.hh, _mm512_mul_round_pd(dy, g.sy, kRound), kRound);
    __mmask8 inside = _mm512_cmp_pd_mask(fx, g.zero, _CMP_GE_OQ);
    inside = _mm512_mask_cmp_pd_mask(inside, fx, g.w, _CMP_LT_OQ);
    inside = _mm512_mask_cmp_pd_mask(inside, fy, g.zero, _CMP_GE_OQ);
    inside = _mm512_mask_cmp_pd_mask(inside, fy, g.h, _CMP_LT_OQ);
    const Vec col = _mm512_min_epi64(_mm512_cvttpd_epi64(fx), g.iwLast);
    const Vec row = _mm512_min_epi64(_mm512_cvttpd_epi64(fy), g.ihLast);
    // Inside, 0 ≤ row < 2^14 and iw ≤ 2^14: the 32×32-bit product is exact.
    store(out, _mm512_add_epi64(_mm512_mul_epu32(row, g.iw), col));
    return inside;
  }

  static unsigned atMost(const Constants& c, Vec X) { return _mm512_cmple_epu64_mask(X, c.randomizingX); }
  static unsigned wrapped(const Constants& c, Vec wrapBits) { return _mm512_test_epi64_mask(wrapBits, c.notMask); }

  static Vec mix64(const Constants& c, Vec z) {  // random/CounterRng.hpp, with vpmullq
    z = _mm512_xor_si512(z, _mm512_srli_epi64(z, 30));
    z = _mm512_mullo_epi64(z, c.mixFirst);
    z = _mm512_xor_si512(z, _mm512_srli_epi64(z, 27));
    z = _mm512_mullo_epi64(z, c.mixSecond);
    return _mm512_xor_si512(z, _mm512_srli_epi64(z, 31));
  }

  static void refreshDraws(const Constants& c, unsigned lanes, const std::uint64_t* key, Vec D, std::uint64_t* next) {
    const Vec k = _mm512_add_epi64(D, c.one);
    const Vec U = _mm512_srli_epi64(mix64(c, _mm512_add_epi64(load(key), _mm512_mullo_epi64(k, c.golden))), 12);
    store(next, _mm512_mask_mov_epi64(load(next), static_cast<__mmask8>(lanes), U));  // a full store forwards
  }
  static Vec select(unsigned lanes, Vec a, Vec b) { return _mm512_mask_mov_epi64(b, static_cast<__mmask8>(lanes), a); }
  /// Left unreduced (SimdDriver.inl): backward() uses only the low 52 bits of X − Y + 2^51 and of Y − G.
  static Vec addModMasked(const Constants&, Vec Y, unsigned lanes, Vec U) {
    return _mm512_mask_add_epi64(Y, static_cast<__mmask8>(lanes), Y, U);
  }

  static Vec set1(std::uint64_t x) { return _mm512_set1_epi64(static_cast<long long>(x)); }
  static Vec add(Vec a, Vec b) { return _mm512_add_epi64(a, b); }
  static Vec sub(Vec a, Vec b) { return _mm512_sub_epi64(a, b); }
  static unsigned below(unsigned lanes, Vec a, Vec b) {
    return _mm512_mask_cmplt_epu64_mask(static_cast<__mmask8>(lanes), a, b);
  }
  static unsigned atLeast(unsigned lanes, Vec a, Vec b) {
    return _mm512_mask_cmpge_epu64_mask(static_cast<__mmask8>(lanes), a, b);
  }
  static void storeMasked(std::uint64_t* p, unsigned lanes, Vec v) {
    _mm512_mask_storeu_epi64(p, static_cast<__mmask8>(lanes), v);
  }
  static void storeStateMasked(std::uint64_t* p, unsigned lanes, State s) { storeMasked(p, lanes, s); }
  /// Packs the selected lanes to the front and stores all eight words.
  static void compressStore(std::uint64_t* p, unsigned lanes, Vec v) {
    // The register form and a full store: the memory form of vpcompressq is slow on Intel cores.
    _mm512_storeu_si512(p, _mm512_maskz_compress_epi64(static_cast<__mmask8>(lanes), v));
  }
};

#include "core/kernels/SimdDriver.inl"

// Four vectors (32 orbits) per group: a step is 11 vector operations on two 512-bit ports against a
// latency chain of ~13 cycles, so three or more independent vectors keep the ports busy.
constexpr int kBlockVectors = 4;
static_assert(kBlockVectors * Avx512Ifma::kLanes == kAvx512IfmaBlockOrbits);
constexpr int kOrbitVectors = 6;
constexpr int kDensityVectors = 4;

}  // namespace

void advanceBlocksAvx512Ifma(const KernelSettings& settings, std::span<OrbitState> orbits,
                             std::uint64_t firstOrbit, std::uint64_t blocks, SegmentSink& sink) {
  advanceBlocksWith<Avx512Ifma, kBlockVectors>(settings, orbits, firstOrbit, blocks, sink);
}

void iterateOrbitsAvx512Ifma(const MapCoefficients& coefficients, MapDirection direction,
                             std::span<UnitState> orbits, std::uint64_t steps, UnitState* trace) {
  iterateOrbitsWith<Avx512Ifma, kOrbitVectors>(coefficients, direction, orbits, steps, trace);
}

std::uint64_t binDensityAvx512Ifma(const MapCoefficients& coefficients, std::span<UnitState> orbits,
                                   std::uint64_t steps, const RasterGrid& grid, std::uint8_t* counts,
                                   std::vector<std::uint32_t>& carries) {
  return binDensityWith<Avx512Ifma, kDensityVectors>(coefficients, orbits, steps, grid, counts, carries);
}

}  // namespace archipelago

#if defined(__clang__)
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif
