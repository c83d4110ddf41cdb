// Trapping statistics from histograms (Karney 1983, §3 eqs. pdef, cdef, ddef, spreaddef; §5; appendices A–B).
// Synthetic histograms are built as exact expectations N_t = M(T + 1 − t) f_t of a known f, so that every
// statistic has an analytic or brute-force value to compare with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {
namespace {

using Real = long double;

// A point mass in steps, as the header defines it: s = q·t̄, w = n/(M(T + 1 − t̄))/q.  Recomputed here
// independently of the implementation, for the brute-force sums.
struct Mass {
  Real s, w;
};
std::vector<Mass> masses(const TrappingHistogram& h, std::uint64_t M, std::uint64_t T, std::uint32_t q) {
  std::vector<Mass> out;
  for (int i = 1; i < TrappingHistogram::kBins; ++i) {
    if (h.count(i) == 0) continue;
    const Real mean = static_cast<Real>(h.lengthSum(i)) / static_cast<Real>(h.count(i));
    out.push_back({q * mean, static_cast<Real>(h.count(i)) / (static_cast<Real>(M) * (T + 1 - mean)) / q});
  }
  return out;
}
// eq. (cdef) for point masses, at integer τ.
Real bruteC(const std::vector<Mass>& ms, Real tau) {
  Real c = 0;
  for (const auto& m : ms) c += m.w * std::max<Real>(0, m.s - tau);
  return c;
}
// eq. (spreaddef) by its definition: the loop over τ that the implementation avoids.
Real bruteS(const std::vector<Mass>& ms, std::uint64_t t) {
  Real s = static_cast<Real>(t) * bruteC(ms, 0);
  for (std::uint64_t tau = 1; tau <= t; ++tau)
    s += 2 * static_cast<Real>(t - tau) * bruteC(ms, static_cast<Real>(tau));
  return s;
}

// Geometric f_t = 2^−(t+1) (so Σ t f_t = 1, α = 2, D = 3/2 for the untruncated law), exact bins t ≤ 50,
// with M = 2^51 so that N_t = (T + 1 − t) 2^(50−t) is an integer.
constexpr std::uint64_t kGeometricOrbits = std::uint64_t{1} << 51;
constexpr std::uint64_t kGeometricBlocks = 1000;
TrappingHistogram geometricHistogram() {
  TrappingHistogram h;
  for (std::uint64_t t = 1; t <= 50; ++t) {
    const std::uint64_t n = (kGeometricBlocks + 1 - t) << (50 - t);
    h.setBin(static_cast<int>(t), n, n * t);
  }
  return h;
}

// Power law f_t = A t^−(2+a) for 1 ≤ t ≤ tmax blocks, A normalising Σ t f_t = 1, M = 1, T = 10^18 (so that
// T + 1 − t ≈ T and counts stay below 2^63).  Each bin gets the rounded expectation of its count and length
// sum; above 10^4 the sum over a bin is replaced by its midpoint-rule integral (Euler–Maclaurin error
// ~ p²/t² relative, below 10^-7).  Returns the histogram and the exact f it is the expectation of.
constexpr std::uint64_t kPowerBlocks = 1000000000000000000ULL;
struct PowerLaw {
  TrappingHistogram h;
  Real A = 0, sumF = 0, sumTF = 0, sumT2F = 0;  // A, and the moments of f over 1..tmax
};
PowerLaw powerLawHistogram(Real a, std::uint64_t tmax) {
  const Real p = 2 + a;
  // ∫_{lo−½}^{hi−½} t^−k dt, or the exact sum for short ranges: Σ_{t=lo}^{hi−1} t^−k.
  const auto powerSum = [](std::uint64_t lo, std::uint64_t hi, Real k) {
    if (hi - lo <= 2000 || lo < 10000) {
      Real s = 0;
      for (std::uint64_t t = lo; t < hi; ++t) s += std::pow(static_cast<Real>(t), -k);
      return s;
    }
    const Real l = static_cast<Real>(lo) - 0.5L, u = static_cast<Real>(hi) - 0.5L;
    return (std::pow(u, 1 - k) - std::pow(l, 1 - k)) / (1 - k);
  };
  PowerLaw law;
  struct Bin {
    int i;
    Real n, sum;  // Σ t^−p and Σ t^(1−p) over the bin
  };
  std::vector<Bin> bins;
  for (int i = 1;; ++i) {
    const std::uint64_t lo = TrappingHistogram::binLower(i);
    if (lo > tmax) break;
    const std::uint64_t hi = std::min(TrappingHistogram::binUpper(i), tmax + 1);
    bins.push_back({i, powerSum(lo, hi, p), powerSum(lo, hi, p - 1)});
    law.sumF += bins.back().n;
    law.sumTF += bins.back().sum;
    law.sumT2F += powerSum(lo, hi, p - 2);
  }
  law.A = 1 / law.sumTF;
  law.sumF *= law.A;
  law.sumT2F *= law.A;
  law.sumTF = 1;
  const Real records = static_cast<Real>(kPowerBlocks);  // M (T + 1 − t) ≈ T: error t/T ≤ 10^-10
  for (const auto& b : bins)
    law.h.setBin(b.i, static_cast<std::uint64_t>(std::llround(records * law.A * b.n)),
                 static_cast<std::uint64_t>(std::llround(records * law.A * b.sum)));
  return law;
}

std::size_t indexOf(const Series& s, double x) {
  const auto it = std::find(s.x.begin(), s.x.end(), x);
  EXPECT_NE(it, s.x.end()) << "grid lacks " << x;
  return static_cast<std::size_t>(it - s.x.begin());
}

TEST(TrappingStatistics, GeometricExactBinsMatchAnalyticValues) {
  const auto stats = computeStatistics(geometricHistogram(), {kGeometricOrbits, kGeometricBlocks, 1});
  // Truncating the law at t = 50 changes Σ f, Σ t f and Σ t² f by < 10^-12.
  EXPECT_NEAR(stats.sumTf, 1.0, 1e-12);
  EXPECT_NEAR(stats.alpha, 2.0, 1e-12);
  EXPECT_NEAR(stats.D, 1.5, 1e-11);
  EXPECT_EQ(stats.longestBlocks, 50u);
  ASSERT_EQ(stats.f.x.size(), 50u);
  for (std::size_t k = 0; k < 50; ++k) {
    const double t = static_cast<double>(k + 1);
    EXPECT_EQ(stats.f.x[k], t);
    EXPECT_DOUBLE_EQ(stats.f.value[k], std::ldexp(1.0, -static_cast<int>(k) - 2));
    EXPECT_NEAR(stats.p.value[k], 2 * stats.f.value[k], 1e-15);
  }
  ASSERT_FALSE(stats.C.x.empty());
  EXPECT_EQ(stats.C.x[0], 0.0);
  EXPECT_NEAR(stats.C.value[0], 1.0, 1e-12);
  EXPECT_NEAR(stats.P.value[0], 1.0, 1e-12);
  EXPECT_EQ(stats.S.value[0], 0.0);
  // P_t = Σ_{τ>t} p_τ = 2^−t for the geometric law.
  for (int t = 0; t <= 40; ++t) EXPECT_NEAR(stats.P.value[indexOf(stats.P, t)], std::ldexp(1.0, -t), 1e-14);
  // Grid: every integer to 50 q, then up to 2 × 50 blocks.
  for (int t = 0; t <= 50; ++t) EXPECT_EQ(stats.C.x[static_cast<std::size_t>(t)], t);
  EXPECT_EQ(stats.C.x.back(), 100.0);
}

TEST(TrappingStatistics, ClosedFormsEqualBruteForceSums) {
  for (const std::uint32_t q : {1u, 16u}) {
    SCOPED_TRACE(testing::Message() << "q=" << q);
    const auto h = geometricHistogram();
    const auto stats = computeStatistics(h, {kGeometricOrbits, kGeometricBlocks, q});
    const auto ms = masses(h, kGeometricOrbits, kGeometricBlocks, q);
    for (std::size_t g = 0; g < stats.C.x.size(); ++g) {
      const auto t = static_cast<std::uint64_t>(stats.C.x[g]);
      ASSERT_EQ(static_cast<double>(t), stats.C.x[g]) << "grid points are integers";
      const double c = static_cast<double>(bruteC(ms, static_cast<Real>(t)));
      EXPECT_NEAR(stats.C.value[g], c, 1e-14 * (1 + c)) << "tau=" << t;
      const double s = static_cast<double>(bruteS(ms, t));
      EXPECT_NEAR(stats.S.value[g], s, 1e-13 * (1 + s)) << "t=" << t;
    }
    // eq. (spreaddef): S_1 = C_0.
    EXPECT_NEAR(stats.S.value[1], stats.C.value[0], 1e-15);
  }
}

TEST(TrappingStatistics, PowerLawAcrossLogBins) {
  const Real a = 0.5;
  const auto law = powerLawHistogram(a, 1000000);
  const auto stats = computeStatistics(law.h, {1, kPowerBlocks, 1});
  // The first moment survives the binning (rounding of counts ~10^-10 relative).
  EXPECT_NEAR(stats.sumTf, 1.0, 1e-8);
  EXPECT_NEAR(stats.C.value[0], stats.sumTf, 1e-15);
  EXPECT_NEAR(stats.P.value[0], 1.0, 1e-12);
  EXPECT_NEAR(stats.alpha, static_cast<double>(1 / law.sumF), 1e-8 * stats.alpha);
  // D: the point mass at the bin mean drops the within-bin variance, (width/t)²/12 ≈ 5·10^-4 at most,
  // and always from below.
  const double D = static_cast<double>(law.sumT2F / 2);
  EXPECT_LT(stats.D, D);
  EXPECT_NEAR(stats.D, D, 6e-4 * D);
  // Log bins: f is the bin's density per unit length, i.e. close to A t̄^−(2+a) at the bin mean.
  for (std::size_t k = 0; k < stats.f.x.size(); ++k) {
    const Real t = stats.f.x[k];
    if (t < 100 || t > 1e5) continue;
    // The bin average of t^−p differs from its value at the mean by p(p+1)/2 · var/t² ≲ 2.3·10^-3.
    EXPECT_NEAR(stats.f.value[k] / static_cast<double>(law.A * std::pow(t, -(2 + a))), 1.0, 2.5e-3) << "t=" << t;
  }
  // Closed forms against brute force for the same point masses, up to t = 2·10^4.
  const auto ms = masses(law.h, 1, kPowerBlocks, 1);
  std::vector<Real> C(20001);
  for (std::size_t tau = 0; tau < C.size(); ++tau) C[tau] = bruteC(ms, static_cast<Real>(tau));
  int checked = 0;
  for (std::size_t g = 0; g < stats.C.x.size() && stats.C.x[g] < 20000; ++g) {
    const auto t = static_cast<std::size_t>(stats.C.x[g]);
    EXPECT_NEAR(stats.C.value[g], static_cast<double>(C[t]), 1e-13 * static_cast<double>(C[t])) << "tau=" << t;
    Real s = static_cast<Real>(t) * C[0];
    for (std::size_t tau = 1; tau <= t; ++tau) s += 2 * static_cast<Real>(t - tau) * C[tau];
    EXPECT_NEAR(stats.S.value[g], static_cast<double>(s), 1e-12 * static_cast<double>(s)) << "t=" << t;
    if (t > 50) ++checked;
  }
  EXPECT_GT(checked, 50);  // reaches well into the log bins
}

TEST(TrappingStatistics, DtTendsToDForShortTailedF) {
  const auto stats = computeStatistics(geometricHistogram(), {kGeometricOrbits, kGeometricBlocks, 1});
  const auto ms = masses(geometricHistogram(), kGeometricOrbits, kGeometricBlocks, 1);
  // For t ≥ the longest segment and integer s, S_t/2t = D − Σ w (s³ − s)/(6t) exactly (sum the
  // polynomials of eq. spreaddef); so D_t rises to D as 1/t.
  Real third = 0;
  for (const auto& m : ms) third += m.w * (m.s * m.s * m.s - m.s);
  double previous = 0;
  for (std::size_t g = 0; g < stats.Dt.x.size(); ++g) {
    const double t = stats.Dt.x[g];
    EXPECT_GT(stats.Dt.value[g], previous) << "t=" << t;
    previous = stats.Dt.value[g];
    if (t < 50) continue;
    EXPECT_NEAR(stats.Dt.value[g], stats.D - static_cast<double>(third / (6 * t)), 1e-13) << "t=" << t;
  }
  EXPECT_NEAR(stats.Dt.value.back(), stats.D, 0.021);  // Σ w(s³−s)/600 = 12/600 at t = 100
  EXPECT_EQ(stats.Dt.x.front(), 1.0);
  EXPECT_NEAR(stats.Dt.value.front(), 0.5 * stats.sumTf, 1e-15);  // D_1 = S_1/2 = C_0/2
}

TEST(TrappingStatistics, LocalExponentOfPowerLaw) {
  // f ~ t^−(2+a) gives C_τ ~ τ^−a for 1 ≪ τ ≪ tmax.  The cut-off at tmax raises the exponent by about
  // a(1+a)(τ/tmax)^a (0.0075 at τ = 10^4 for a = ½, tmax = 10^8), the discreteness changes it by O(1/τ).
  struct Case {
    Real a;
    std::uint64_t tmax;
    double from, to, tolerance;
  };
  for (const Case c : {Case{0.5, 100000000, 300, 1e4, 0.01}, Case{1.5, 1000000, 300, 1e4, 0.005}}) {
    SCOPED_TRACE(testing::Message() << "a=" << static_cast<double>(c.a));
    const auto stats = computeStatistics(powerLawHistogram(c.a, c.tmax).h, {1, kPowerBlocks, 1});
    const auto& e = stats.localExponent;
    ASSERT_EQ(e.x.size(), e.value.size());
    int checked = 0;
    for (std::size_t k = 0; k < e.x.size(); ++k) {
      if (e.x[k] < c.from || e.x[k] > c.to) continue;
      EXPECT_NEAR(e.value[k], static_cast<double>(c.a), c.tolerance) << "tau=" << e.x[k];
      ++checked;
    }
    EXPECT_EQ(checked, 16);  // the log grid: 10 points per decade, 10^2.5 … 10^4 both included (issue #26)
    // Beyond the longest segment C = 0 and the exponent is left out.
    EXPECT_LT(e.x.back(), 1.1 * static_cast<double>(c.tmax));
  }
}

// Issue #26: the local exponent of an exact power law is exact on the log grid (C_τ is evaluated at each grid τ,
// not interpolated), and a run of q = 100 shows no kink at τ = q (5.41 on the old integer grid).
TEST(TrappingStatistics, LocalExponentOnTheLogGrid_Issue26) {
  // Masses at every integer t with w ∝ t^−(2+a)(1 + 1/t)…: build C_τ = τ^−a exactly by the masses' second
  // difference; simpler and exact: a single mass at s gives C_τ = w (s − τ) for τ < s, whose local exponent at τ is
  // τ/(s − τ) — the centred difference on the log grid reproduces it to the grid's O(h²).
  TrappingHistogram h;
  h.setBin(TrappingHistogram::binOf(1000), 1, 1000);  // one segment of 1000 blocks
  const auto stats = computeStatistics(h, {1, 2000, 1});
  const auto& e = stats.localExponent;
  ASSERT_FALSE(e.x.empty());
  for (std::size_t k = 0; k < e.x.size(); ++k) {
    const double tau = e.x[k];
    EXPECT_NEAR(std::log10(tau) * 10, std::round(std::log10(tau) * 10), 1e-9) << "a log-grid point";
    // exact: −(log C(τ₊) − log C(τ₋))/(log τ₊ − log τ₋) with C = s − τ
    const double a = std::pow(10.0, 0.1), s = static_cast<double>(stats.f.x.front());
    const double expected = -(std::log(s - tau * a) - std::log(s - tau / a)) / (2 * std::log(a));
    EXPECT_NEAR(e.value[k], expected, 1e-9 * std::max(1.0, expected)) << "tau=" << tau;
  }
  // q = 100: masses at multiples of 100 only.  The exponent near τ = 100 stays within the range of its neighbours.
  TrappingHistogram g;
  for (std::uint64_t t = 1; t <= 50; ++t) g.setBin(static_cast<int>(t), 1000 / t, 1000 / t * t);
  const auto blocks = computeStatistics(g, {1, 100000, 100});
  double nearQ = 0, largest = 0;
  for (std::size_t k = 0; k < blocks.localExponent.x.size(); ++k) {
    const double tau = blocks.localExponent.x[k], v = blocks.localExponent.value[k];
    if (tau >= 50 && tau <= 200) nearQ = std::max(nearQ, v);
    if (tau >= 200 && tau <= 2000) largest = std::max(largest, v);
  }
  EXPECT_LT(nearQ, 1.5) << "no spike at tau = q";
  EXPECT_EQ(blocks.blockAffectedBelow, 1000) << "10 q";
  EXPECT_EQ(computeStatistics(g, {1, 100000, 1}).blockAffectedBelow, 0);
}

TEST(TrappingStatistics, QConversionScalesTimeAndDensity) {
  // Appendix B: t_steps = q t_blocks and f_t = F/q²; hence α and D scale by q, C and P are functions of t/q.
  const auto h = geometricHistogram();
  const auto one = computeStatistics(h, {kGeometricOrbits, kGeometricBlocks, 1});
  const auto sixteen = computeStatistics(h, {kGeometricOrbits, kGeometricBlocks, 16});
  ASSERT_EQ(one.f.x.size(), sixteen.f.x.size());
  for (std::size_t k = 0; k < one.f.x.size(); ++k) {
    EXPECT_EQ(sixteen.f.x[k], 16 * one.f.x[k]);
    EXPECT_NEAR(sixteen.f.value[k], one.f.value[k] / 256, 1e-15 * one.f.value[k]);
    EXPECT_NEAR(sixteen.p.value[k], one.p.value[k] / 16, 1e-15 * one.p.value[k]);
  }
  EXPECT_NEAR(sixteen.alpha, 16 * one.alpha, 1e-13);
  EXPECT_NEAR(sixteen.D, 16 * one.D, 1e-12);
  EXPECT_NEAR(sixteen.sumTf, one.sumTf, 1e-15);
  EXPECT_EQ(sixteen.longestBlocks, one.longestBlocks);
  EXPECT_EQ(sixteen.C.x.back(), 16 * one.C.x.back());
  for (int t = 0; t <= 50; ++t) {
    EXPECT_NEAR(sixteen.C.value[indexOf(sixteen.C, 16.0 * t)], one.C.value[indexOf(one.C, t)], 1e-15);
    EXPECT_NEAR(sixteen.P.value[indexOf(sixteen.P, 16.0 * t)], one.P.value[indexOf(one.P, t)], 1e-15);
  }
}

TEST(TrappingStatistics, LogBinDensityDividesByBinWidth) {
  // A flat f_t = c over every length of one logarithmic bin must come back as c per block (F_i of
  // appendix B), and as c/q² per step.
  const int bin = 70;
  const std::uint64_t lo = TrappingHistogram::binLower(bin), hi = TrappingHistogram::binUpper(bin);
  ASSERT_GT(hi - lo, 10u);
  const std::uint64_t M = 3, T = 1000000;
  std::uint64_t n = 0, sum = 0;
  for (std::uint64_t t = lo; t < hi; ++t) {
    n += M * (T + 1 - t) * 1000;  // N_t = M (T + 1 − t) f_t with f_t = 1000
    sum += t * M * (T + 1 - t) * 1000;
  }
  TrappingHistogram h;
  h.setBin(bin, n, sum);
  for (const std::uint32_t q : {1u, 16u}) {
    const auto stats = computeStatistics(h, {M, T, q});
    ASSERT_EQ(stats.f.x.size(), 1u);
    EXPECT_NEAR(stats.f.x[0], q * 0.5 * static_cast<double>(lo + hi - 1), 1e-4 * q);  // N-weighted mean
    // T + 1 − t varies by 10^-4 across the bin: the estimator at the mean is exact to ~10^-9.
    EXPECT_NEAR(stats.f.value[0] * q * q, 1000.0, 1e-5);
  }
}

TEST(TrappingStatistics, IdenticalSubsetsHaveZeroError) {
  const auto law = powerLawHistogram(0.5, 100000);
  // Scale down so that four copies still fit: the statistics depend on counts only through N/M.
  TrappingHistogram part;
  for (int i = 1; i < TrappingHistogram::kBins; ++i) part.setBin(i, law.h.count(i) / 8, law.h.lengthSum(i) / 8);
  const std::vector<TrappingHistogram> subsets(4, part);
  const auto stats = computeStatistics(subsets, {5, 5, 5, 5}, kPowerBlocks, 16);
  TrappingHistogram total;
  for (const auto& s : subsets) total.merge(s);
  const auto single = computeStatistics(total, {20, kPowerBlocks, 16});
  EXPECT_EQ(stats.alphaError, 0.0);
  EXPECT_EQ(stats.DError, 0.0);
  EXPECT_NEAR(stats.alpha, single.alpha, 1e-14 * single.alpha);
  EXPECT_NEAR(stats.D, single.D, 1e-14 * single.D);
  for (const Series* s : {&stats.f, &stats.p, &stats.P, &stats.C, &stats.localExponent, &stats.S, &stats.Dt}) {
    ASSERT_FALSE(s->x.empty());
    ASSERT_EQ(s->error.size(), s->x.size());
    for (const double e : s->error) EXPECT_EQ(e, 0.0);
  }
  EXPECT_EQ(stats.C.x, single.C.x);
  for (std::size_t g = 0; g < stats.C.x.size(); ++g)
    EXPECT_NEAR(stats.C.value[g], single.C.value[g], 1e-14 * single.C.value[g] + 1e-300);
}

TEST(TrappingStatistics, DifferingSubsetsGiveStandardErrorOfMean) {
  // Three small records, T = 100 blocks, q = 1; every value worked out by hand from the estimator.
  const std::uint64_t T = 100;
  TrappingHistogram a, b, c;
  a.setBin(1, 10, 10);                      // ten segments of length 1, M = 1
  b.setBin(2, 5, 10);                       // five of length 2, M = 1
  c.setBin(1, 4, 4);                        // four of length 1 and two of 3, M = 2
  c.setBin(3, 2, 6);
  // w for each: n/(M(T + 1 − t)).
  const double wa1 = 10.0 / 100, wb2 = 5.0 / 99, wc1 = 4.0 / (2 * 100), wc3 = 2.0 / (2 * 98);
  const double alphas[3] = {1 / wa1, 1 / wb2, 1 / (wc1 + wc3)};
  const double Ds[3] = {0.5 * wa1, 0.5 * 4 * wb2, 0.5 * (wc1 + 9 * wc3)};
  const double C1[3] = {0, wb2, 2 * wc3};                                  // C at τ = 1
  const double S2[3] = {2 * wa1, 2 * 2 * wb2 + 2 * wb2, 2 * (wc1 + 3 * wc3) + 2 * 2 * wc3};  // S at t = 2
  const double f1[3] = {wa1, 0, wc1};                                      // f at t = 1
  const auto standardError = [](const double (&x)[3]) {
    const double mean = (x[0] + x[1] + x[2]) / 3;
    double ss = 0;
    for (const double v : x) ss += (v - mean) * (v - mean);
    return std::sqrt(ss / 2) / std::sqrt(3.0);
  };
  const auto stats = computeStatistics({a, b, c}, {1, 1, 2}, T, 1);
  // Values from the union, M = 4.
  const double w1 = 14.0 / (4 * 100), w2 = 5.0 / (4 * 99), w3 = 2.0 / (4 * 98);
  EXPECT_NEAR(stats.alpha, 1 / (w1 + w2 + w3), 1e-12);
  EXPECT_NEAR(stats.D, 0.5 * (w1 + 4 * w2 + 9 * w3), 1e-15);
  EXPECT_NEAR(stats.alphaError, standardError(alphas), 1e-12);
  EXPECT_NEAR(stats.DError, standardError(Ds), 1e-15);
  EXPECT_GT(stats.alphaError, 1.0);
  const std::size_t g1 = indexOf(stats.C, 1), g2 = indexOf(stats.S, 2);
  EXPECT_NEAR(stats.C.value[g1], w2 + 2 * w3, 1e-15);
  EXPECT_NEAR(stats.C.error[g1], standardError(C1), 1e-15);
  EXPECT_NEAR(stats.S.error[g2], standardError(S2), 1e-15);
  EXPECT_NEAR(stats.Dt.error[indexOf(stats.Dt, 2)], standardError(S2) / 4, 1e-15);
  ASSERT_EQ(stats.f.x[0], 1.0);
  EXPECT_NEAR(stats.f.error[0], standardError(f1), 1e-15);
}

TEST(TrappingStatistics, EmptyAndInvalidInputs) {
  const auto empty = computeStatistics(TrappingHistogram{}, {});
  EXPECT_TRUE(empty.f.x.empty());
  EXPECT_TRUE(empty.C.x.empty());
  EXPECT_EQ(empty.alpha, 0.0);
  EXPECT_EQ(empty.segments, 0u);

  TrappingHistogram h;
  h.setBin(5, 2, 10);
  EXPECT_NO_THROW((void)computeStatistics(h, {1, 5, 1}));
  EXPECT_THROW((void)computeStatistics(h, {1, 4, 1}), std::invalid_argument);  // mean 5 > T = 4 blocks
  EXPECT_THROW((void)computeStatistics(h, {0, 100, 1}), std::invalid_argument);
  EXPECT_THROW((void)computeStatistics(h, {1, 100, 0}), std::invalid_argument);
  EXPECT_THROW((void)computeStatistics(std::vector<TrappingHistogram>{}, {}, 100, 1), std::invalid_argument);
  EXPECT_THROW((void)computeStatistics({h, h}, {1}, 100, 1), std::invalid_argument);
  // An empty subset counts as zero f, C, S, D and leaves α to the others.
  const auto withEmpty = computeStatistics({h, TrappingHistogram{}}, {1, 1}, 100, 1);
  EXPECT_EQ(withEmpty.alphaError, 0.0);
  EXPECT_GT(withEmpty.DError, 0.0);
}

}  // namespace
}  // namespace archipelago
