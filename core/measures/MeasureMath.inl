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
// broadcast), whose operators and the functions absValue, minValue, maxValue, select, splitExponent (found by
// argument-dependent lookup) act lane by lane with the same IEEE semantics as the double overloads below.
// No expression may be contracted into an FMA: core modules are compiled with -ffp-contract=off, and the vector
// types call separate multiply and add intrinsics.
//
// Accuracy (checked against long double in tests/core/measures, bounds derived there): clockwiseAngle within
// 5.75·10⁻¹⁶ rad of atan2 of its rounded arguments, lnPositive within 2.5 ulp.  Both are piecewise polynomials (a Taylor series after an exact-enough range reduction), smooth
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
/// r = m·2^e with m in [1, 2), for a positive normal r; returns e (exactly) and sets m (exactly).
[[nodiscard]] inline double splitExponent(double r, double& mantissa) noexcept {
  const auto bits = std::bit_cast<std::uint64_t>(r);
  mantissa = std::bit_cast<double>((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
  return static_cast<double>(static_cast<std::int64_t>(bits >> 52) - 1023);
}

// --- constants -----------------------------------------------------------------------------------------------
// π/4, π/2 and π as a double plus its rounding error (Cody–Waite), so that π/2 − a keeps the bits of a.
constexpr double kPi4Hi = 0x1.921fb54442d18p-1, kPi4Lo = 0x1.1a62633145c07p-55;
constexpr double kPi2Hi = 0x1.921fb54442d18p+0, kPi2Lo = 0x1.1a62633145c07p-54;
constexpr double kPiHi = 0x1.921fb54442d18p+1, kPiLo = 0x1.1a62633145c07p-53;
constexpr double kTanPi8 = 0x1.a827999fcef32p-2;  // tan(π/8) = √2 − 1, rounded
constexpr double kSqrt2 = 0x1.6a09e667f3bcdp+0;
// ln 2 split so that e·kLn2Hi is exact for |e| < 2^11 (fdlibm's constants).
constexpr double kLn2Hi = 6.93147180369123816490e-01, kLn2Lo = 1.90821492927058770002e-10;

/// Terms of the Taylor series of atan u = u Σ (−1)^k u^{2k}/(2k+1) used for |u| ≤ tan(π/8): u^{2·21}/43 < 3·10⁻¹⁸.
constexpr int kAtanTerms = 21;
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

/// The coefficients (−1)^k/(2k + 1) of atan u / u in powers of u², and 1/(2k + 1) of atanh s / s in powers of
/// s², each correctly rounded (the compiler folds the divisions exactly).
template <int N, bool kAlternating>
struct OddSeries {
  double c[N];
  constexpr OddSeries() : c() {
    for (int k = 0; k < N; ++k) c[k] = (kAlternating && k % 2 ? -1.0 : 1.0) / (2 * k + 1);
  }
};
constexpr OddSeries<kAtanTerms, true> kAtanSeries;
constexpr OddSeries<kLogTerms, false> kAtanhSeries;

/// atan u for |u| ≤ tan(π/8): u · Σ (−1)^k u^{2k}/(2k + 1).
template <class V>
[[nodiscard]] inline V atanReduced(V u) noexcept {
  return u * estrin(u * u, kAtanSeries.c);
}

/// atan2(s, c) in (−π, π]: 0 for s = c = 0.  The octant is reduced exactly (absolute values, min, max); the
/// ratio min/max above tan(π/8) becomes (min − max)/(min + max) = tan(atan(min/max) − π/4), so one division
/// brings every argument into |u| ≤ tan(π/8).
template <class V>
[[nodiscard]] inline V atan2Portable(V s, V c) noexcept {
  const V as = absValue(s), ac = absValue(c);
  const V hi = maxValue(as, ac), lo = minValue(as, ac);
  const auto reduce = lo > hi * kTanPi8;
  const V num = select(reduce, lo - hi, lo);
  const V den = select(hi > 0.0, select(reduce, lo + hi, hi), V(1.0));
  V a = atanReduced(num / den);
  a = select(reduce, (a + kPi4Lo) + kPi4Hi, a);
  a = select(as > ac, (kPi2Lo - a) + kPi2Hi, a);
  a = select(c < 0.0, (kPiLo - a) + kPiHi, a);
  return select(s < 0.0, -a, a);
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
