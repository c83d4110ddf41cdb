// MeasureMath.inl — core-internal: the per-step arithmetic of the orbit measures, written once for every
// instruction set.
//
// Each file that uses it includes it inside an anonymous namespace (and the vector kernels inside their
// target-attribute region), after <bit> and <cstdint>: every function here is then compiled once per
// instruction set with internal linkage, so no AVX-512 copy of an inline function can be merged into generic
// code (the rule of kernels/SimdDriver.inl).  It includes nothing itself.
//
// The orbit measures (OrbitMeasures.hpp) add up, at every step of the exact map, an angle (rotation numbers),
// a logarithm (MEGNO) or a weighted coordinate (Birkhoff averages).  The scalar, AVX2 and AVX-512 paths must
// give the same sums bit for bit, so that a raster does not depend on the path; libm's atan2 and log cannot be
// vectorised identically, so this file defines its own, from +, −, ×, ÷, comparisons and exact bit
// operations only (each a correctly rounded IEEE operation, the same in every lane of every instruction set):
//   - clockwiseAngle(a, b): atan2(−(a × b), a · b) ∈ (−π, π], the clockwise angle from a to b;
//   - lnPositive(r): ln r for a positive normal r;
//   - twoSumAdd(hi, lo, p): compensated summation (Knuth's TwoSum: hi + lo is the sum with the rounding error of
//     every addition kept in lo), so that a Birkhoff sum of 10⁴–10⁷ terms keeps ~16 digits.
// Every template takes a number type V: double, or a SIMD vector of doubles, constructible from a double (a
// broadcast), whose operators and the functions absValue, minValue, maxValue, select, splitExponent,
// negateWhere, maskXor, offsetIndex and lookup (found by argument-dependent lookup on V, its mask type and its
// index type) act lane by lane with the same IEEE semantics as the double overloads below.
// No expression may be contracted into an FMA: core modules are compiled with -ffp-contract=off, and the vector
// types call separate multiply and add intrinsics.
//
// Accuracy (checked against long double in tests/core/measures, bounds derived there): clockwiseAngle within
// 3.75·10⁻¹⁶ rad of atan2 of its rounded arguments (5.75·10⁻¹⁶ before issue 41's table of offsets), lnPositive
// within 2.5 ulp.  Both are piecewise polynomials
// (after an exact-enough range reduction: a Taylor series for ln, a near-minimax polynomial for atan), smooth
// inside each piece, so a weighted Birkhoff average of them converges as fast as one of the true functions (the
// pieces meet within the same 10⁻¹⁶).
//
// References: the argument reductions are the textbook ones (e.g. J.-M. Muller, Elementary Functions, 3rd ed.,
// 2016, ch. 11; Cody & Waite's split constants for π and ln 2); TwoSum: D. E. Knuth, TAOCP vol. 2, §4.2.2.

// --- the double overloads (the reference, and the scalar path) ----------------------------------------------
/// |a| with the sign bit cleared (as vandpd does: |−0| = +0).
[[nodiscard]] inline double absValue(double a) noexcept {
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(a) & 0x7FFFFFFFFFFFFFFFull);
}
/// Like SSE/AVX min: a when a < b, else b.
[[nodiscard]] inline double minValue(double a, double b) noexcept { return a < b ? a : b; }
/// Like SSE/AVX max: a when a > b, else b.
[[nodiscard]] inline double maxValue(double a, double b) noexcept { return a > b ? a : b; }
[[nodiscard]] inline double select(bool m, double a, double b) noexcept { return m ? a : b; }
/// −a where m (the sign bit flipped: exact), else a.
[[nodiscard]] inline double negateWhere(bool m, double a) noexcept {
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(a) ^ (m ? 0x8000000000000000ull : 0));
}
[[nodiscard]] inline bool maskXor(bool a, bool b) noexcept { return a != b; }
/// atan2Portable's table index: j + 4·swapped + 8·cNegative, j = 2 where far, else 1 where mid, else 0.
[[nodiscard]] inline unsigned offsetIndex(bool mid, bool far, bool swapped, bool cNegative) noexcept {
  return (far ? 2u : mid ? 1u : 0u) + (swapped ? 4u : 0u) + (cNegative ? 8u : 0u);
}
[[nodiscard]] inline double lookup(unsigned index, const double (&table)[16]) noexcept { return table[index]; }
/// r = m·2^e with m in [1, 2), for a positive normal r; returns e (exactly) and sets m (exactly).
[[nodiscard]] inline double splitExponent(double r, double& mantissa) noexcept {
  const auto bits = std::bit_cast<std::uint64_t>(r);
  mantissa = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
  return static_cast<double>(static_cast<std::int64_t>(bits >> 52) - 1023);
}

// --- constants -----------------------------------------------------------------------------------------------
constexpr double kTanPi8 = 0x1.a827999fcef32p-2;  // tan(π/8) = √2 − 1, rounded
constexpr double kTanPi16 = 0x1.975f5e0553158p-3, kTan3Pi16 = 0x1.561b82ab7f990p-1;  // the reduction's thresholds
constexpr double kSqrt2 = 0x1.6a09e667f3bcdp+0;
// ln 2 split so that e·kLn2Hi is exact for |e| < 2^11 (fdlibm's constants).
constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;

/// atan u / u ≈ Σ_{k<8} kAtanCoefficients[k] u^{2k} for |u| ≤ tan(π/16): Chebyshev interpolation of atan u / u
/// in u² on [0, tan²(π/16)] at 8 nodes (near-minimax), computed at 60 digits by scripts/atan-coefficients.py and
/// rounded to double; with these rounded coefficients |u Σ c_k u^{2k} − atan u| < 3.5·10⁻¹⁸ on the range (the
/// 21 terms of the Taylor series that reached 3·10⁻¹⁸ on |u| ≤ tan(π/8) before issue 41 cost twice as much).
constexpr int kAtanTerms = 8;
constexpr double kAtanCoefficients[kAtanTerms] = {
    0x1.0000000000000p+0,  -0x1.5555555555333p-2, 0x1.999999990bbe4p-3,  -0x1.249248b4394c3p-3,
    0x1.c71c1a3a671a8p-4,  -0x1.744a82d0e4f2cp-4, 0x1.38e13ef8bb64cp-4,  -0x1.dbe17a0683168p-5,
};
/// The offsets K of atan2Portable, indexed by offsetIndex: j + 4·swapped + 8·(c < 0), j = 0, 1, 2 for α = 0, α₁,
/// π/4 (j = 3 is not used and repeats j = 2): α, π/2 − α, π − α and π/2 + α, each as a double (Hi) plus the
/// double nearest its rounding error (Lo), computed at 60 digits by scripts/atan-coefficients.py.
constexpr double kAngleOffsetHi[16] = {
    0x0.0p+0,              0x1.921fb54442d18p-2, 0x1.921fb54442d18p-1, 0x1.921fb54442d18p-1,
    0x1.921fb54442d18p+0,  0x1.2d97c7f3321d2p+0, 0x1.921fb54442d18p-1, 0x1.921fb54442d18p-1,
    0x1.921fb54442d18p+1,  0x1.5fdbbe9bba775p+1, 0x1.2d97c7f3321d2p+1, 0x1.2d97c7f3321d2p+1,
    0x1.921fb54442d18p+0,  0x1.f6a7a2955385ep+0, 0x1.2d97c7f3321d2p+1, 0x1.2d97c7f3321d2p+1,
};
constexpr double kAngleOffsetLo[16] = {
    0x0.0p+0,              0x1.c398861b78b55p-59, 0x1.1a62633145c07p-55, 0x1.1a62633145c07p-55,
    0x1.1a62633145c07p-54, 0x1.0c459f0069facp-54, 0x1.1a62633145c07p-55, 0x1.1a62633145c07p-55,
    0x1.1a62633145c07p-53, 0x1.13540118d7ddap-53, 0x1.a79394c9e8a0ap-54, 0x1.a79394c9e8a0ap-54,
    0x1.1a62633145c07p-54, 0x1.287f276221862p-54, 0x1.a79394c9e8a0ap-54, 0x1.a79394c9e8a0ap-54,
};
/// Terms of ln m = 2 s Σ s^{2k}/(2k+1), s = (m − 1)/(m + 1), |s| ≤ (√2 − 1)/(√2 + 1): s^{2·11}/23 < 10⁻¹⁸.
constexpr int kLogTerms = 11;

// --- the functions -------------------------------------------------------------------------------------------

/// Σ_{k<N} c[k] x^k by Estrin's scheme, with pow2[i] = x^(2^i): the low half (the largest power of two of terms
/// below N) plus x^half times the rest, recursively — a dependency chain of ⌈log₂ N⌉ multiply-adds instead of
/// Horner's N − 1, so that the vector kernels are not latency-bound; the recursion is resolved at compile time.
template <int N, class V>
[[nodiscard]] inline V estrinPart(const double* c, const V* pow2) noexcept {
  if constexpr (N == 1) {
    return V(c[0]);
  } else {
    constexpr int half = static_cast<int>(std::bit_floor(static_cast<unsigned>(N - 1)));
    constexpr int level = std::countr_zero(static_cast<unsigned>(half));
    return estrinPart<half>(c, pow2) + estrinPart<N - half>(c + half, pow2) * pow2[level];
  }
}

template <int N, class V>
[[nodiscard]] inline V estrin(V x, const double (&c)[N]) noexcept {
  constexpr int levels = N > 1 ? std::bit_width(static_cast<unsigned>(N - 1)) : 1;
  V pow2[levels];
  pow2[0] = x;
  for (int i = 1; i < levels; ++i) pow2[i] = pow2[i - 1] * pow2[i - 1];
  return estrinPart<N>(c, pow2);
}

/// The coefficients 1/(2k + 1) of atanh s / s in powers of s² (and (−1)^k/(2k + 1) of atan u / u with
/// kAlternating), each correctly rounded (the compiler folds the divisions exactly).
template <int N, bool kAlternating>
struct OddSeries {
  double c[N];
  constexpr OddSeries() : c() {
    for (int k = 0; k < N; ++k) c[k] = (kAlternating && k % 2 ? -1.0 : 1.0) / (2 * k + 1);
  }
};
constexpr OddSeries<kLogTerms, false> kAtanhSeries;

/// atan u for |u| ≤ tan(π/16) (and a little beyond): u · Σ c_k u^{2k} (kAtanCoefficients).
template <class V>
[[nodiscard]] inline V atanReduced(V u) noexcept {
  return u * estrin(u * u, kAtanCoefficients);
}

/// atan2(s, c) in (−π, π]: 0 for s = c = 0.  The octant is reduced exactly (absolute values, min, max) to the
/// angle β = atan(t) ∈ [0, π/4], t = min/max; then β − α for the nearest α of 0, α₁ = atan(τ), τ = kTanPi8, and
/// π/4, as tan(β − α) = (t − tan α)/(1 + t tan α) = (min − max·tan α)/(max + min·tan α) with tan α = 0, τ or 1
/// (exact products for 0 and 1), so one division brings every argument into |u| ≤ tan(π/16) (issue 41: eight
/// polynomial terms instead of 21).  For α₁ the product max·τ adds half an ulp of 0.42·max to the numerator:
/// 0.21ε in u, less than the 3ε|u| ≤ 1.24ε that the ratio's other roundings cost at the old bound |u| ≤ tan(π/8).
/// The angle is then K ± a, a = atan u, with K = B ± α one of twelve constants (B = 0, π/2 or π from the quadrant
/// and the swap of s and c; kAngleOffsetHi/Lo, as a double plus its rounding error) and the sign of a flipped
/// where exactly one of "swapped" and "c < 0" holds; the sign of the whole where s < 0.  One rounding of
/// (K_lo ± a) + K_hi instead of the three additions of α, π/2 and π before issue 41's third part: the table
/// lookup and the sign flips cost fewer operations and a shorter dependency chain than three selects.
template <class V>
[[nodiscard]] inline V atan2Portable(V s, V c) noexcept {
  const V as = absValue(s), ac = absValue(c);
  const V hi = maxValue(as, ac), lo = minValue(as, ac);
  const auto far = lo > hi * kTan3Pi16;  // β > 3π/16: about π/4
  const auto mid = lo > hi * kTanPi16;   // β > π/16: about α₁ (unless far)
  const auto swapped = as > ac;          // the angle from the y axis was reduced
  const auto cNegative = c < V(0.0);
  const V tanAlpha = select(far, V(1.0), select(mid, V(kTanPi8), V(0.0)));
  const V num = lo - hi * tanAlpha;
  const V den = select(hi > V(0.0), hi + lo * tanAlpha, V(1.0));
  const V a = atanReduced(num / den);
  const auto index = offsetIndex(mid, far, swapped, cNegative);
  const V angle = (lookup(index, kAngleOffsetLo) + negateWhere(maskXor(swapped, cNegative), a)) +
                  lookup(index, kAngleOffsetHi);
  return negateWhere(s < V(0.0), angle);
}

/// The clockwise angle from the vector (ax, ay) to (bx, by), in (−π, π]: atan2(−(a × b), a · b).  Clockwise is
/// the sense in which Q turns about its elliptic fixed point (RotationNumber.hpp).
template <class V>
[[nodiscard]] inline V clockwiseAngle(V ax, V ay, V bx, V by) noexcept {
  const V sine = ay * bx - ax * by;    // −(a × b)
  const V cosine = ax * bx + ay * by;  // a · b
  return atan2Portable(sine, cosine);
}

/// ln r for a positive normal double r (not 0, subnormal, inf or NaN): r = m·2^e with m in [√½, √2), then
/// ln r = e·ln 2 + 2 atanh((m − 1)/(m + 1)); m − 1 and e·kLn2Hi are exact.
template <class V>
[[nodiscard]] inline V lnPositive(V r) noexcept {
  V m = r;
  V e = splitExponent(r, m);
  const auto big = m > kSqrt2;
  m = select(big, m * 0.5, m);
  e = select(big, e + 1.0, e);
  const V s = (m - 1.0) / (m + 1.0);
  const V s2 = s * s;
  V p = V(kAtanhSeries.c[kLogTerms - 1]);  // Horner: Estrin's order rounds ln r near 1 up to 4 ulps
  for (int k = kLogTerms - 2; k >= 0; --k) p = p * s2 + kAtanhSeries.c[k];
  const V lnm = (s + s) * p;
  return e * kLn2Hi + (e * kLn2Lo + lnm);
}

/// hi + lo ← hi + lo + p with the rounding error of the addition kept in lo (TwoSum, six operations, no branch).
template <class V>
inline void twoSumAdd(V& hi, V& lo, V p) noexcept {
  const V t = hi + p;
  const V z = t - hi;
  const V e = (hi - (t - z)) + (p - z);
  hi = t;
  lo = lo + e;
}
