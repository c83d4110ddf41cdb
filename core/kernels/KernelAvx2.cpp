// The AVX2 path: 4 orbits per 256-bit vector (VectorKernels.hpp).
//
// AVX2 multiplies only 32×32 → 64 bits (vpmuludq, which reads the low 32 bits of each lane).  For a, b < 2^52
// split as a = a1·2^32 + a0 (a1 < 2^20):
//   ⌊a·b/2^52⌋ = a1·b1·2^12 + ⌊(a1·b0 + a0·b1 + ⌊a0·b0/2^32⌋) / 2^20⌋,
// exact because a·b = a1b1·2^64 + 2^32·(a1b0 + a0b1 + ⌊a0b0/2^32⌋) + (a0b0 mod 2^32) and nested floor
// divisions of non-negative integers compose.  The middle sum is < 2^54,
// so nothing overflows.  ⌊X²/2^52⌋ needs three products (the cross term twice), A·x2 and B·X four each.
// The random draws, rare (only inside the randomizing zone), are done lane by lane in scalar code, since
// AVX2 has no 64-bit multiply for mix64.

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>

#include "kernels/VectorKernels.hpp"
#include "random/CounterRng.hpp"

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2"))), apply_to = function)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC target("avx2")
#endif

namespace archipelago {
namespace {

struct Avx2 {
  using Vec = __m256i;
  static constexpr std::size_t kLanes = 4;

  struct Constants {
    Vec mask, notMask, half, A, A1, B, B1, C, randomizingX;
    __m128i shift;
    Constants(const MapCoefficients& k, std::uint64_t Xr)
        : mask(_mm256_set1_epi64x(static_cast<long long>(fixedpoint::kMask))),
          notMask(_mm256_set1_epi64x(static_cast<long long>(~fixedpoint::kMask))),
          half(_mm256_set1_epi64x(static_cast<long long>(fixedpoint::kHalf))),
          A(_mm256_set1_epi64x(k.A)),
          A1(_mm256_set1_epi64x(k.A >> 32)),
          B(_mm256_set1_epi64x(k.B)),
          B1(_mm256_set1_epi64x(k.B >> 32)),
          C(_mm256_set1_epi64x(k.C)),
          randomizingX(_mm256_set1_epi64x(static_cast<long long>(Xr))),
          shift(_mm_cvtsi32_si128(k.m)) {}
  };

  static Vec load(const std::uint64_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
  static void store(std::uint64_t* p, Vec v) { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v); }
  static Vec zero() { return _mm256_setzero_si256(); }
  // X and Y are iterated as the integers themselves.
  using State = Vec;
  static State loadState(const std::uint64_t* p) { return load(p); }
  static void storeState(std::uint64_t* p, State s) { store(p, s); }
  static State noWraps() { return zero(); }

  /// ⌊a·b/2^52⌋ for a, b < 2^52, given a1 = a >> 32 and b1 = b >> 32.
  static Vec mulHigh52(Vec a, Vec a1, Vec b, Vec b1) {
    const Vec low = _mm256_mul_epu32(a, b);
    const Vec middle = _mm256_add_epi64(_mm256_mul_epu32(a1, b), _mm256_mul_epu32(a, b1));
    const Vec high = _mm256_mul_epu32(a1, b1);
    return _mm256_add_epi64(_mm256_slli_epi64(high, 12),
                            _mm256_srli_epi64(_mm256_add_epi64(middle, _mm256_srli_epi64(low, 32)), 20));
  }
  /// ⌊x²/2^52⌋ for x < 2^52, given x1 = x >> 32.
  static Vec squareHigh52(Vec x, Vec x1) {
    const Vec low = _mm256_mul_epu32(x, x);
    const Vec cross = _mm256_mul_epu32(x1, x);
    const Vec high = _mm256_mul_epu32(x1, x1);
    return _mm256_add_epi64(
        _mm256_slli_epi64(high, 12),
        _mm256_srli_epi64(_mm256_add_epi64(_mm256_add_epi64(cross, cross), _mm256_srli_epi64(low, 32)), 20));
  }
  /// G(X)·… : (⌊A·⌊X²/2^52⌋/2^52⌋ − ⌊B·X/2^52⌋ + C)·2^m for X < 2^52.
  static Vec G(const Constants& c, Vec X) {
    const Vec X1 = _mm256_srli_epi64(X, 32);
    const Vec x2 = squareHigh52(X, X1);
    const Vec ax2 = mulHigh52(c.A, c.A1, x2, _mm256_srli_epi64(x2, 32));
    const Vec bx = mulHigh52(c.B, c.B1, X, X1);
    return _mm256_sll_epi64(_mm256_sub_epi64(_mm256_add_epi64(ax2, c.C), bx), c.shift);
  }

  static void backward(const Constants& c, Vec& X, Vec& Y, Vec& wrapBits) {
    const Vec s = _mm256_add_epi64(_mm256_sub_epi64(X, Y), c.half);
    X = _mm256_and_si256(s, c.mask);
    const Vec u = _mm256_sub_epi64(Y, G(c, X));
    Y = _mm256_and_si256(u, c.mask);
    wrapBits = _mm256_or_si256(wrapBits, _mm256_or_si256(s, u));
  }

  static void forward(const Constants& c, Vec& X, Vec& Y) {
    Y = _mm256_and_si256(_mm256_add_epi64(Y, G(c, X)), c.mask);
    X = _mm256_and_si256(_mm256_sub_epi64(_mm256_add_epi64(X, Y), c.half), c.mask);
  }

  /// AVX2 has no 64-bit integer to double conversion: the pixels are found lane by lane.
  struct Grid {
    RasterGrid grid;
    explicit Grid(const RasterGrid& g) : grid(g) {}
  };
  static unsigned pixels(const Grid& g, Vec X, Vec Y, std::uint64_t* out) {
    alignas(32) std::uint64_t xs[kLanes], ys[kLanes];
    store(xs, X);
    store(ys, Y);
    unsigned inside = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const std::int64_t p = g.grid.pixelOf({xs[l], ys[l]});
      out[l] = static_cast<std::uint64_t>(p);
      inside |= p >= 0 ? 1u << l : 0u;
    }
    return inside;
  }

  static unsigned laneBits(Vec allOnesWhere) {
    return static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(allOnesWhere)));
  }
  // X and Xr are < 2^63, so the signed comparison is the unsigned one.
  static unsigned atMost(const Constants& c, Vec X) { return ~laneBits(_mm256_cmpgt_epi64(X, c.randomizingX)) & 0xFu; }
  static unsigned wrapped(const Constants& c, Vec wrapBits) {
    return ~laneBits(_mm256_cmpeq_epi64(_mm256_and_si256(wrapBits, c.notMask), _mm256_setzero_si256())) & 0xFu;
  }

  static void refreshDraws(const Constants&, unsigned lanes, const std::uint64_t* key, Vec D, std::uint64_t* next) {
    alignas(32) std::uint64_t d[kLanes], u[kLanes];
    store(d, D);
    store(u, load(next));
    for (unsigned bits = lanes; bits; bits &= bits - 1) {
      const int l = __builtin_ctz(bits);
      u[l] = orbitDraw(key[l], d[l] + 1);
    }
    store(next, load(u));  // one full store, which a later vector load can forward from
  }
  static Vec select(unsigned lanes, Vec a, Vec b) {
    return _mm256_castpd_si256(
        _mm256_blendv_pd(_mm256_castsi256_pd(b), _mm256_castsi256_pd(a), _mm256_castsi256_pd(laneMask(lanes))));
  }
  static Vec addModMasked(const Constants& c, Vec Y, unsigned lanes, Vec U) {
    return _mm256_and_si256(_mm256_add_epi64(Y, _mm256_and_si256(U, laneMask(lanes))), c.mask);
  }

  static Vec set1(std::uint64_t x) { return _mm256_set1_epi64x(static_cast<long long>(x)); }
  static Vec add(Vec a, Vec b) { return _mm256_add_epi64(a, b); }
  static Vec sub(Vec a, Vec b) { return _mm256_sub_epi64(a, b); }
  static unsigned atLeast(unsigned lanes, Vec a, Vec b) { return lanes & ~laneBits(_mm256_cmpgt_epi64(b, a)); }
  /// All-ones in the 64-bit lanes whose bit is set in `lanes`.
  static Vec laneMask(unsigned lanes) {
    const Vec bit = _mm256_setr_epi64x(1, 2, 4, 8);
    return _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(lanes), bit), bit);
  }
  static void storeMasked(std::uint64_t* p, unsigned lanes, Vec v) {
    _mm256_maskstore_epi64(reinterpret_cast<long long*>(p), laneMask(lanes), v);
  }
  static void storeStateMasked(std::uint64_t* p, unsigned lanes, State s) { storeMasked(p, lanes, s); }
  /// Packs the selected lanes to the front (a permutation from a 16-entry table) and stores all four.
  static void compressStore(std::uint64_t* p, unsigned lanes, Vec v) {
    store(p, _mm256_permutevar8x32_epi32(v, load(kCompress[lanes].data())));
  }
  static constexpr auto kCompress = [] {
    std::array<std::array<std::uint64_t, kLanes>, 16> table{};
    for (unsigned m = 0; m < 16; ++m) {
      std::size_t out = 0;
      for (unsigned l = 0; l < kLanes; ++l)
        if (m & (1u << l)) table[m][out++] = (2 * l) | (std::uint64_t{2 * l + 1} << 32);  // two 32-bit indices
    }
    return table;
  }();
};

#include "kernels/SimdDriver.inl"

// Three vectors (12 orbits) in flight: a step is ~40 operations on three 256-bit ports against a ~25-cycle
// latency chain; more would spill the 16 ymm registers.
constexpr int kBlockVectors = 3;
constexpr int kOrbitVectors = 3;

}  // namespace

void advanceBlocksAvx2(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                       std::uint64_t blocks, SegmentSink& sink) {
  advanceBlocksWith<Avx2, kBlockVectors>(settings, orbits, firstOrbit, blocks, sink);
}

void iterateOrbitsAvx2(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                       std::uint64_t steps, UnitState* trace) {
  iterateOrbitsWith<Avx2, kOrbitVectors>(coefficients, direction, orbits, steps, trace);
}

std::uint64_t binDensityAvx2(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                             const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries) {
  return binDensityWith<Avx2, kOrbitVectors>(coefficients, orbits, steps, grid, counts, carries);
}

}  // namespace archipelago

#if defined(__clang__)
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC pop_options
#endif
