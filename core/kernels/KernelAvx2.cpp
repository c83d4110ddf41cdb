// The AVX2 path: 4 orbits per 256-bit vector (VectorKernels.hpp), X and Y iterated as integer-valued doubles.
//
// AVX2 multiplies integers only 32×32 → 64 bits, so the exact 52-bit map N⁻¹ (map/FixedPointMap.hpp) would
// need 11 vpmuludq per step.  Doubles hold every integer below 2^53 exactly, and FMA forms a·b + c exactly
// before its one rounding; with the rounding mode set to round toward −∞ that rounding is a floor:
//   for real v in [2^e, 2^(e+1)), where the spacing of doubles is 2^(e−52), RD(v) = ⌊v / 2^(e−52)⌋·2^(e−52).
// So an FMA whose result lands in a binade of spacing 2^s floors it to a multiple of 2^s, and every
// floor division of appendix B is one FMA.  Let T = 3·2^103 (in [2^104, 2^105): spacing 2^52); for an
// integer v with |v| < 2^103, (v + T) − T = ⌊v/2^52⌋·2^52 (the add rounds down, the subtraction is exact), so
// v − ((v + T) − T) = v mod 2^52 takes three adds.  With X, Y in [0, 2^52), m the map's shift (≤ 9):
//   s   = (X + 2^51) − Y                         in (−2^51, 3·2^51), exact
//   F   = (s + T) − T = ⌊s/2^52⌋·2^52,   X' = s − F                          (X ← X − Y + 2^51 mod 2^52)
//   x2b = fma(X', X', 2^104)    = 2^104 + ⌊X'²/2^52⌋·2^52                    (spacing 2^52)
//   ax  = fma(A·2^(m−104), x2b, (2^52 − A)·2^m) = (2^52 + ⌊A·x2/2^52⌋)·2^m   (spacing 2^m: the exact value
//         is 2^m (2^52 + A·x2/2^52) since A·2^(m−104)·x2b = 2^m (A + A·x2/2^52))
//   bx  = fma(B·2^(m−52), X', 2^(52+m)) = (2^52 + ⌊B·X'/2^52⌋)·2^m
//   G   = ax − (bx − C·2^m) = 2^m (⌊A x2/2^52⌋ − ⌊B X'/2^52⌋ + C)             exact (fixedPointG; 0 ≤ C < 2^52,
//         as MapParameters' validation makes c > 0, so bx − C·2^m = (2^52 + bx' − C)·2^m with 53 bits)
//   K   = (G + T) − T = k·2^52,  Gr = G − K = G mod 2^52   (|G| < 2^62)
//   u   = Y − Gr in (−2^52, 2^52),  U = (u + T) − T,  Y' = u − U             (Y ← Y − G mod 2^52)
// Every intermediate is a multiple of its spacing or the exact floor above, so X', Y' equal backwardStep()'s
// bit for bit.  The true Y − G is u − K, so the step wraps (backwardStep() returns true) exactly when F ≠ 0
// or U − K ≠ 0.  In round-down mode an exact zero difference is −0.0, so the wraps are accumulated as bit
// patterns (F | (U − K)) and tested with the sign bit masked off: every nonzero integer has exponent bits.
// X or Y may be −0.0; conversions to integers add 2^52 first, comparisons treat it as 0.
// N (forward) is the same in the other order: u = Y + Gr in [0, 2^53), Y' = u − ((u + T) − T), then
// s = (X − 2^51) + Y', X' = s − ((s + T) − T).  20 vector operations per step (18 without the wraps).
//
// The rounding mode: each exported function sets MXCSR to round down (RoundingDown, restoring the caller's
// MXCSR on return) and runs the loops in a [[gnu::noinline]] function, so no floating-point operation can be
// scheduled across the mode switch; all constants are exact (powers of two times integers below 2^53).
// The density kernel's pixel positions (RasterGrid::pixelOf) are products and sums rounded to nearest; they
// are computed lane by lane in x87 long double with the x87 precision set to 53 bits (X87Double), which
// rounds each operation to nearest double exactly as SSE does and is unaffected by MXCSR.
// The random draws, rare (only inside the randomizing zone), are done lane by lane in scalar code, since
// AVX2 has no 64-bit multiply for mix64.

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/kernels/FloatModes.hpp"
#include "core/kernels/VectorKernels.hpp"
#include "core/random/CounterRng.hpp"
#include "core/trapping/TrappingHistogram.hpp"

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC target("avx2,fma")
#endif

namespace archipelago {
namespace {

using kernels::RoundingDown;
using kernels::X87Double;

struct Avx2 {
  using Vec = __m256i;
  static constexpr std::size_t kLanes = 4;
  // X and Y are iterated as integer-valued doubles in [0, 2^52) (−0.0 for 0 at times), in round-down mode.
  using State = __m256d;

  struct Constants {
    State one, minusOne, half, minusHalf, T, two104, A, Aoffset, B, Boffset, C, randomizingX;
    Vec magnitude;  // all bits but the sign
    Constants(const MapCoefficients& k, std::uint64_t Xr)
        : one(_mm256_set1_pd(1.0)),
          minusOne(_mm256_set1_pd(-1.0)),
          half(_mm256_set1_pd(std::ldexp(1.0, 51))),
          minusHalf(_mm256_set1_pd(-std::ldexp(1.0, 51))),
          T(_mm256_set1_pd(std::ldexp(3.0, 103))),
          two104(_mm256_set1_pd(std::ldexp(1.0, 104))),
          A(_mm256_set1_pd(std::ldexp(static_cast<double>(k.A), k.m - 104))),
          Aoffset(_mm256_set1_pd(std::ldexp(static_cast<double>(fixedpoint::kOne - static_cast<std::uint64_t>(k.A)), k.m))),
          B(_mm256_set1_pd(std::ldexp(static_cast<double>(k.B), k.m - 52))),
          Boffset(_mm256_set1_pd(std::ldexp(1.0, 52 + k.m))),
          C(_mm256_set1_pd(std::ldexp(static_cast<double>(k.C), k.m))),
          randomizingX(_mm256_set1_pd(static_cast<double>(std::min(Xr, fixedpoint::kOne)))),
          magnitude(_mm256_set1_epi64x(INT64_MAX)) {}
  };

  static Vec load(const std::uint64_t* p) { return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)); }
  static void store(std::uint64_t* p, Vec v) { _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v); }
  static Vec zero() { return _mm256_setzero_si256(); }

  /// Integers below 2^52 to doubles: 2^52 + x has the bits of 2^52 with x in the mantissa.
  static State toState(Vec x) {
    const __m256d two52 = _mm256_set1_pd(0x1p52);
    return _mm256_sub_pd(_mm256_castsi256_pd(_mm256_or_si256(x, _mm256_castpd_si256(two52))), two52);
  }
  /// The inverse of toState(), for integer-valued doubles in [0, 2^52) (and −0.0).
  static Vec fromState(State x) {
    const __m256d two52 = _mm256_set1_pd(0x1p52);
    return _mm256_sub_epi64(_mm256_castpd_si256(_mm256_add_pd(x, two52)), _mm256_castpd_si256(two52));
  }
  static State loadState(const std::uint64_t* p) { return toState(load(p)); }
  static void storeState(std::uint64_t* p, State s) { store(p, fromState(s)); }
  static State noWraps() { return _mm256_setzero_pd(); }

  /// v − ((v + T) − T) = v mod 2^52 for integer-valued v, |v| < 2^103; `multiple` receives ⌊v/2^52⌋·2^52.
  static State mod52(const Constants& c, State v, State& multiple) {
    multiple = _mm256_sub_pd(_mm256_add_pd(v, c.T), c.T);
    return _mm256_sub_pd(v, multiple);
  }
  /// G(X) (fixedPointG), exact, for X in [0, 2^52).
  static State G(const Constants& c, State X) {
    const State x2b = _mm256_fmadd_pd(X, X, c.two104);
    const State ax = _mm256_fmadd_pd(c.A, x2b, c.Aoffset);
    const State bx = _mm256_fmadd_pd(c.B, X, c.Boffset);
    // bx − C·2^m as an FMA: adds run on two ports only, FMAs on two others' worth (p0, p1).
    return _mm256_sub_pd(ax, _mm256_fmadd_pd(c.C, c.minusOne, bx));
  }

  static void backward(const Constants& c, State& X, State& Y, State& wraps) {
    const State s = _mm256_sub_pd(_mm256_fmadd_pd(X, c.one, c.half), Y);  // X + 2^51 (off the chain) as an FMA
    State F, K, U;
    X = mod52(c, s, F);
    const State Gr = mod52(c, G(c, X), K);
    const State u = _mm256_sub_pd(Y, Gr);
    Y = mod52(c, u, U);
    wraps = _mm256_or_pd(wraps, _mm256_or_pd(F, _mm256_sub_pd(U, K)));
  }

  static void forward(const Constants& c, State& X, State& Y) {
    State K, U, F;
    const State Gr = mod52(c, G(c, X), K);
    Y = mod52(c, _mm256_add_pd(Y, Gr), U);
    X = mod52(c, _mm256_add_pd(_mm256_add_pd(X, c.minusHalf), Y), F);
  }

  /// The pixels lane by lane: RasterGrid::pixelOf in x87 long double at 53-bit precision (X87Double, set by
  /// binDensityAvx2), which rounds like double but not by MXCSR's round-down mode.
  struct Grid {
    RasterGrid grid;
    explicit Grid(const RasterGrid& g) : grid(g) {}
  };
  static unsigned pixels(const Grid& g, State X, State Y, std::uint64_t* out) {
    alignas(32) std::uint64_t xs[kLanes], ys[kLanes];
    storeState(xs, X);
    storeState(ys, Y);
    const RasterGrid& r = g.grid;
    unsigned inside = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const long double dx = static_cast<long double>(static_cast<std::int64_t>(xs[l] - r.cx));
      const long double dy = static_cast<long double>(static_cast<std::int64_t>(ys[l] - r.cy));
      const long double productX = dx * static_cast<long double>(r.sx);
      const long double productY = dy * static_cast<long double>(r.sy);
      const long double fx = productX + static_cast<long double>(r.hw);
      const long double fy = static_cast<long double>(r.hh) - productY;
      std::int64_t p = -1;
      if (fx >= 0 && fx < static_cast<long double>(r.w) && fy >= 0 && fy < static_cast<long double>(r.h)) {
        auto col = static_cast<std::int64_t>(fx), row = static_cast<std::int64_t>(fy);
        col = col < r.iw ? col : r.iw - 1;
        row = row < r.ih ? row : r.ih - 1;
        p = row * r.iw + col;
        inside |= 1u << l;
      }
      out[l] = static_cast<std::uint64_t>(p);
    }
    return inside;
  }

  static unsigned laneBits(Vec allOnesWhere) {
    return static_cast<unsigned>(_mm256_movemask_pd(_mm256_castsi256_pd(allOnesWhere)));
  }
  static unsigned atMost(const Constants& c, State X) {
    return static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(X, c.randomizingX, _CMP_LE_OQ)));
  }
  static unsigned wrapped(const Constants& c, State wraps) {
    const Vec bits = _mm256_and_si256(_mm256_castpd_si256(wraps), c.magnitude);
    return ~laneBits(_mm256_cmpeq_epi64(bits, _mm256_setzero_si256())) & 0xFu;
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
  /// The draws U are below 2^52 (orbitDraw), so Y + U < 2^53 is exact.
  static State addModMasked(const Constants& c, State Y, unsigned lanes, Vec U) {
    State multiple;
    return mod52(c, _mm256_add_pd(Y, toState(_mm256_and_si256(U, laneMask(lanes)))), multiple);
  }

  static Vec set1(std::uint64_t x) { return _mm256_set1_epi64x(static_cast<long long>(x)); }
  static Vec add(Vec a, Vec b) { return _mm256_add_epi64(a, b); }
  static Vec sub(Vec a, Vec b) { return _mm256_sub_epi64(a, b); }
  static unsigned below(unsigned lanes, Vec a, Vec b) { return lanes & laneBits(_mm256_cmpgt_epi64(b, a)); }
  static unsigned atLeast(unsigned lanes, Vec a, Vec b) { return lanes & ~laneBits(_mm256_cmpgt_epi64(b, a)); }
  /// All-ones in the 64-bit lanes whose bit is set in `lanes`.
  static Vec laneMask(unsigned lanes) {
    const Vec bit = _mm256_setr_epi64x(1, 2, 4, 8);
    return _mm256_cmpeq_epi64(_mm256_and_si256(_mm256_set1_epi64x(lanes), bit), bit);
  }
  static void storeMasked(std::uint64_t* p, unsigned lanes, Vec v) {
    _mm256_maskstore_epi64(reinterpret_cast<long long*>(p), laneMask(lanes), v);
  }
  static void storeStateMasked(std::uint64_t* p, unsigned lanes, State s) { storeMasked(p, lanes, fromState(s)); }
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

#include "core/kernels/SimdDriver.inl"

// Vectors in flight: a step is 20 operations on three 256-bit ports against a latency chain of ~35 cycles,
// so six vectors (24 orbits) keep the ports busy; they do not fit the 16 ymm registers with the constants, but
// the spilled X, Y and wraps cost less than a shorter queue (measured: 4 vectors ~20% slower, 8 or 12 no
// faster).
constexpr int kBlockVectors = 6;
static_assert(kBlockVectors * Avx2::kLanes == kAvx2BlockOrbits);
constexpr int kOrbitVectors = 6;

// The loops, called from the exported functions only after the rounding mode is set (never inlined into
// them, so that the compiler cannot move a floating-point operation across the switch).
[[gnu::noinline]] void advanceBlocksRoundingDown(const KernelSettings& settings, std::span<OrbitState> orbits,
                                                 std::uint64_t firstOrbit, std::uint64_t blocks, SegmentSink& sink) {
  advanceBlocksWith<Avx2, kBlockVectors>(settings, orbits, firstOrbit, blocks, sink);
}
[[gnu::noinline]] void iterateOrbitsRoundingDown(const MapCoefficients& coefficients, MapDirection direction,
                                                 std::span<UnitState> orbits, std::uint64_t steps, UnitState* trace) {
  iterateOrbitsWith<Avx2, kOrbitVectors>(coefficients, direction, orbits, steps, trace);
}
[[gnu::noinline]] std::uint64_t binDensityRoundingDown(const MapCoefficients& coefficients,
                                                       std::span<UnitState> orbits, std::uint64_t steps,
                                                       const RasterGrid& grid, std::uint8_t* counts,
                                                       std::vector<std::uint32_t>& carries) {
  return binDensityWith<Avx2, kOrbitVectors>(coefficients, orbits, steps, grid, counts, carries);
}

}  // namespace

void advanceBlocksAvx2(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                       std::uint64_t blocks, SegmentSink& sink) {
  // The histogram's bin edges are computed (in long double) on first use: not in round-down mode.
  (void)TrappingHistogram::binOf(TrappingHistogram::kExactMax + 1);
  const RoundingDown mode;
  advanceBlocksRoundingDown(settings, orbits, firstOrbit, blocks, sink);
}

void iterateOrbitsAvx2(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                       std::uint64_t steps, UnitState* trace) {
  const RoundingDown mode;
  iterateOrbitsRoundingDown(coefficients, direction, orbits, steps, trace);
}

std::uint64_t binDensityAvx2(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                             const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries) {
  const RoundingDown mode;
  const X87Double pixelRounding;
  return binDensityRoundingDown(coefficients, orbits, steps, grid, counts, carries);
}

}  // namespace archipelago

#if defined(__clang__)
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC pop_options
#endif
