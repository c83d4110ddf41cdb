// KernelAvx512F.inl — the AVX-512F path's SIMD policy and loops (VectorKernels.hpp): the exact-double method of
// the AVX2 path (KernelAvx2.cpp's file comment: X and Y as integer-valued doubles, every floor division one FMA
// in round-toward-−∞ mode), 8 orbits per 512-bit vector, with AVX-512 Foundation instructions only (no IFMA, no
// DQ: Skylake-SP, Cascade Lake and Cooper Lake Xeons have AVX-512F without IFMA).
//
// Included twice, never compiled on its own:
//   - by KernelAvx512F.cpp, inside its target("avx512f") region, after <immintrin.h>: the path programs run;
//   - by tests/core/kernels/KernelAvx512FEmulated.cpp after SIMDe's <simde/x86/avx512.h> with native aliases,
//     which implements the same _mm512_* intrinsics with AVX2 + FMA halves: the test suite runs this very
//     source on CPUs without AVX-512 and compares it bit for bit with the others (every intrinsic used here
//     is one that SIMDe 0.7.4 implements, with a true fused multiply-add).
// The includer provides, before including it: <cmath>, <algorithm>, <array>, <cstdint>, VectorKernels.hpp,
// FloatModes.hpp, CounterRng.hpp, TrappingHistogram.hpp, and an enclosing anonymous namespace in archipelago.
//
// One step of N⁻¹ is the AVX2 path's 20 vector operations on 8 lanes instead of 4.  The wrap test ORs bit
// patterns with integer instructions (vorpd on zmm is AVX-512DQ).  The rare draws (randomizing zone) and the
// density kernel's pixel positions are computed lane by lane exactly as in the AVX2 path (scalar orbitDraw;
// RasterGrid::pixelOf in x87 long double at 53-bit precision).

struct Avx512F {
  using Vec = __m512i;
  static constexpr std::size_t kLanes = 8;
  using State = __m512d;

  struct Constants {
    State one, minusOne, half, minusHalf, T, two104, A, Aoffset, B, Boffset, C, randomizingX;
    Vec magnitude;  // all bits but the sign
    Constants(const MapCoefficients& k, std::uint64_t Xr)
        : one(_mm512_set1_pd(1.0)),
          minusOne(_mm512_set1_pd(-1.0)),
          half(_mm512_set1_pd(std::ldexp(1.0, 51))),
          minusHalf(_mm512_set1_pd(-std::ldexp(1.0, 51))),
          T(_mm512_set1_pd(std::ldexp(3.0, 103))),
          two104(_mm512_set1_pd(std::ldexp(1.0, 104))),
          A(_mm512_set1_pd(std::ldexp(static_cast<double>(k.A), k.m - 104))),
          Aoffset(_mm512_set1_pd(std::ldexp(static_cast<double>(fixedpoint::kOne - static_cast<std::uint64_t>(k.A)), k.m))),
          B(_mm512_set1_pd(std::ldexp(static_cast<double>(k.B), k.m - 52))),
          Boffset(_mm512_set1_pd(std::ldexp(1.0, 52 + k.m))),
          C(_mm512_set1_pd(std::ldexp(static_cast<double>(k.C), k.m))),
          randomizingX(_mm512_set1_pd(static_cast<double>(std::min(Xr, fixedpoint::kOne)))),
          magnitude(_mm512_set1_epi64(INT64_MAX)) {}
  };

  static Vec load(const std::uint64_t* p) { return _mm512_loadu_si512(p); }
  static void store(std::uint64_t* p, Vec v) { _mm512_storeu_si512(p, v); }
  static Vec zero() { return _mm512_setzero_si512(); }

  /// Integers below 2^52 to doubles: 2^52 + x has the bits of 2^52 with x in the mantissa.
  static State toState(Vec x) {
    const __m512d two52 = _mm512_set1_pd(0x1p52);
    return _mm512_sub_pd(_mm512_castsi512_pd(_mm512_or_si512(x, _mm512_castpd_si512(two52))), two52);
  }
  /// The inverse of toState(), for integer-valued doubles in [0, 2^52) (and −0.0).
  static Vec fromState(State x) {
    const __m512d two52 = _mm512_set1_pd(0x1p52);
    return _mm512_sub_epi64(_mm512_castpd_si512(_mm512_add_pd(x, two52)), _mm512_castpd_si512(two52));
  }
  static State loadState(const std::uint64_t* p) { return toState(load(p)); }
  static void storeState(std::uint64_t* p, State s) { store(p, fromState(s)); }
  static State noWraps() { return _mm512_setzero_pd(); }
  /// a | b on the bit patterns (integer instructions: vorpd on zmm needs AVX-512DQ).
  static State orBits(State a, State b) {
    return _mm512_castsi512_pd(_mm512_or_si512(_mm512_castpd_si512(a), _mm512_castpd_si512(b)));
  }

  /// v − ((v + T) − T) = v mod 2^52 for integer-valued v, |v| < 2^103; `multiple` receives ⌊v/2^52⌋·2^52.
  static State mod52(const Constants& c, State v, State& multiple) {
    multiple = _mm512_sub_pd(_mm512_add_pd(v, c.T), c.T);
    return _mm512_sub_pd(v, multiple);
  }
  /// G(X) (fixedPointG), exact, for X in [0, 2^52).
  static State G(const Constants& c, State X) {
    const State x2b = _mm512_fmadd_pd(X, X, c.two104);
    const State ax = _mm512_fmadd_pd(c.A, x2b, c.Aoffset);
    const State bx = _mm512_fmadd_pd(c.B, X, c.Boffset);
    return _mm512_sub_pd(ax, _mm512_fmadd_pd(c.C, c.minusOne, bx));
  }

  static void backward(const Constants& c, State& X, State& Y, State& wraps) {
    const State s = _mm512_sub_pd(_mm512_fmadd_pd(X, c.one, c.half), Y);
    State F, K, U;
    X = mod52(c, s, F);
    const State Gr = mod52(c, G(c, X), K);
    const State u = _mm512_sub_pd(Y, Gr);
    Y = mod52(c, u, U);
    wraps = orBits(wraps, orBits(F, _mm512_sub_pd(U, K)));
  }

  static void forward(const Constants& c, State& X, State& Y) {
    State K, U, F;
    const State Gr = mod52(c, G(c, X), K);
    Y = mod52(c, _mm512_add_pd(Y, Gr), U);
    X = mod52(c, _mm512_add_pd(_mm512_add_pd(X, c.minusHalf), Y), F);
  }

  /// The pixels lane by lane, as the AVX2 path: RasterGrid::pixelOf in x87 long double at 53-bit precision
  /// (X87Double, set by the density kernel), which rounds like double but not by MXCSR's round-down mode.
  struct Grid {
    RasterGrid grid;
    explicit Grid(const RasterGrid& g) : grid(g) {}
  };
  static unsigned pixels(const Grid& g, State X, State Y, std::uint64_t* out) {
    alignas(64) std::uint64_t xs[kLanes], ys[kLanes];
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

  static unsigned atMost(const Constants& c, State X) {
    return static_cast<unsigned>(_mm512_cmp_pd_mask(X, c.randomizingX, _CMP_LE_OQ));
  }
  static unsigned wrapped(const Constants& c, State wraps) {
    return static_cast<unsigned>(_mm512_test_epi64_mask(_mm512_castpd_si512(wraps), c.magnitude));
  }

  static void refreshDraws(const Constants&, unsigned lanes, const std::uint64_t* key, Vec D, std::uint64_t* next) {
    alignas(64) std::uint64_t d[kLanes], u[kLanes];
    store(d, D);
    store(u, load(next));
    for (unsigned bits = lanes; bits; bits &= bits - 1) {
      const int l = __builtin_ctz(bits);
      u[l] = orbitDraw(key[l], d[l] + 1);
    }
    store(next, load(u));  // one full store, which a later vector load can forward from
  }
  static Vec select(unsigned lanes, Vec a, Vec b) { return _mm512_mask_mov_epi64(b, static_cast<__mmask8>(lanes), a); }
  /// The draws U are below 2^52 (orbitDraw), so Y + U < 2^53 is exact.
  static State addModMasked(const Constants& c, State Y, unsigned lanes, Vec U) {
    State multiple;
    return mod52(c, _mm512_add_pd(Y, toState(_mm512_maskz_mov_epi64(static_cast<__mmask8>(lanes), U))), multiple);
  }

  static Vec set1(std::uint64_t x) { return _mm512_set1_epi64(static_cast<long long>(x)); }
  static Vec add(Vec a, Vec b) { return _mm512_add_epi64(a, b); }
  static Vec sub(Vec a, Vec b) { return _mm512_sub_epi64(a, b); }
  // Unmasked compares and the lane mask in a general register (the masked forms' SIMDe aliases are missing or
  // take other arguments in 0.7.4).
  static unsigned below(unsigned lanes, Vec a, Vec b) {
    return lanes & ~static_cast<unsigned>(_mm512_cmpge_epu64_mask(a, b));
  }
  static unsigned atLeast(unsigned lanes, Vec a, Vec b) {
    return lanes & static_cast<unsigned>(_mm512_cmpge_epu64_mask(a, b));
  }
  /// A blend into the kLanes words at p, which the driver's per-lane arrays always hold (SIMDe 0.7.4 lacks
  /// the masked store).
  static void storeMasked(std::uint64_t* p, unsigned lanes, Vec v) {
    store(p, _mm512_mask_mov_epi64(load(p), static_cast<__mmask8>(lanes), v));
  }
  static void storeStateMasked(std::uint64_t* p, unsigned lanes, State s) { storeMasked(p, lanes, fromState(s)); }
  /// Packs the selected lanes to the front and stores all eight words (the register form and a full store: the
  /// memory form of vpcompressq is slow on Intel cores).
  static void compressStore(std::uint64_t* p, unsigned lanes, Vec v) {
    store(p, _mm512_maskz_compress_epi64(static_cast<__mmask8>(lanes), v));
  }
};

#include "core/kernels/SimdDriver.inl"

// Vectors in flight: the AVX2 path's chain of ~35 cycles per step, now on two 512-bit FMA/add ports (Skylake-SP
// and Cascade Lake fuse ports 0 and 1 and use port 5's FMA unit for 512-bit work): four vectors (32 orbits)
// keep them busy and, with the constants, fit the 32 zmm registers.
constexpr int kAvx512FBlockVectors = 4;
static_assert(kAvx512FBlockVectors * Avx512F::kLanes == kAvx512FBlockOrbits);
constexpr int kAvx512FOrbitVectors = 4;

// The loops, called only after the rounding mode is set (never inlined into their callers, so that the
// compiler cannot move a floating-point operation across the switch).
[[gnu::noinline]] void advanceBlocksAvx512FRoundingDown(const KernelSettings& settings, std::span<OrbitState> orbits,
                                                        std::uint64_t firstOrbit, std::uint64_t blocks,
                                                        SegmentSink& sink) {
  advanceBlocksWith<Avx512F, kAvx512FBlockVectors>(settings, orbits, firstOrbit, blocks, sink);
}
[[gnu::noinline]] void iterateOrbitsAvx512FRoundingDown(const MapCoefficients& coefficients, MapDirection direction,
                                                        std::span<UnitState> orbits, std::uint64_t steps,
                                                        UnitState* trace) {
  iterateOrbitsWith<Avx512F, kAvx512FOrbitVectors>(coefficients, direction, orbits, steps, trace);
}
[[gnu::noinline]] std::uint64_t binDensityAvx512FRoundingDown(const MapCoefficients& coefficients,
                                                              std::span<UnitState> orbits, std::uint64_t steps,
                                                              const RasterGrid& grid, std::uint8_t* counts,
                                                              std::vector<std::uint32_t>& carries) {
  return binDensityWith<Avx512F, kAvx512FOrbitVectors>(coefficients, orbits, steps, grid, counts, carries);
}

// The entry points' bodies (the includer names the exported functions).
void advanceBlocksAvx512FBody(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                              std::uint64_t blocks, SegmentSink& sink) {
  // The histogram's bin edges are computed (in long double) on first use: not in round-down mode.
  (void)TrappingHistogram::binOf(TrappingHistogram::kExactMax + 1);
  const kernels::RoundingDown mode;
  advanceBlocksAvx512FRoundingDown(settings, orbits, firstOrbit, blocks, sink);
}
void iterateOrbitsAvx512FBody(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                              std::uint64_t steps, UnitState* trace) {
  const kernels::RoundingDown mode;
  iterateOrbitsAvx512FRoundingDown(coefficients, direction, orbits, steps, trace);
}
std::uint64_t binDensityAvx512FBody(const MapCoefficients& coefficients, std::span<UnitState> orbits,
                                    std::uint64_t steps, const RasterGrid& grid, std::uint8_t* counts,
                                    std::vector<std::uint32_t>& carries) {
  const kernels::RoundingDown mode;
  const kernels::X87Double pixelRounding;
  return binDensityAvx512FRoundingDown(coefficients, orbits, steps, grid, counts, carries);
}
