// The Markov model of Karney (1983), appendix C (core/markov): the 7-point example (eq. pex), the paper's
// statements about ε(τ) and the anti-correlation, and D by the matrix formula against eq. (dmark).  Reference
// values are the paper's matrix, hand computations from eq. (pex), closed forms derived from the model's rules
// (the characteristic polynomial of the lumped chain), and the dense N × N evaluation (DenseMarkovReference.hpp).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "DenseMarkovReference.hpp"
#include "core/markov/MarkovModel.hpp"

namespace archipelago::markov {
namespace {

// Random h with Σ h = 0 on N points (dense layout), optionally with prescribed values on some points.
std::vector<double> randomObservable(std::size_t N, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-2, 2);
  std::vector<double> h(N);
  double mean = 0;
  for (double& v : h) mean += (v = u(rng));
  mean /= static_cast<double>(N);
  for (double& v : h) v -= mean;
  return h;
}

// Σ_S h² in the dense layout (S = S′ ∪ pre-images = the points after the trapped ones).
double seaSquares(const std::vector<double>& h, std::int64_t m) {
  double s = 0;
  for (std::size_t i = static_cast<std::size_t>(m); i < h.size(); ++i) s += h[i] * h[i];
  return s;
}

// ---------------------------------------------------------------------------------------------------------
// The 7-point example

TEST(MarkovModel, SevenPointExampleIsEqPex) {
  const double c = 0.25;
  const dense::Matrix pex = {  // eq. (pex): column i is where point i goes
      {0, 0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 0, 0}, {0, 0, c, c, c, c, 0},
      {0, 0, c, c, c, c, 0}, {0, 0, c, c, c, c, 0}, {0, 0, c, c, c, c, 0}};
  EXPECT_EQ(dense::transitionMatrix({3}, 7), pex);
}

TEST(MarkovModel, SevenPointExampleByHand) {
  // h = [1, 1, 1, −1, 1, −3, 0] (appendix C): 1 on T, 0 on the pre-image (point 7), Σ h = 0.
  const std::vector<double> h = {1, 1, 1, -1, 1, -3, 0};
  const MarkovModel model{{3}, 7};
  const LumpedObservable lumped = dense::lump({3}, h);
  EXPECT_EQ(lumped.preImages, std::vector<double>{0});
  EXPECT_EQ(lumped.freeSeaSquares, 11);
  // By hand from eq. (pex): C(0) = Σh²/7 = 14/7; P h = [0, 1, 1, −½, −½, −½, −½] so C(1) = 3.5/7;
  // P² h = [−½, 0, 1, −⅛, −⅛, −⅛, −⅛] so C(2) = (−½ + 1 + ⅜)/7 = ⅞/7.
  const std::vector<double> C = correlation(model, lumped, 2);
  EXPECT_DOUBLE_EQ(C[0], 2.0);
  EXPECT_DOUBLE_EQ(C[1], 0.5);
  EXPECT_DOUBLE_EQ(C[2], 0.125);
  // eq. (dmark): (1/14)(Σ_{S′} h² + (h_q + Σ_T h)²) = (11 + 9)/14.
  EXPECT_DOUBLE_EQ(diffusionCoefficientDmark(model, lumped), 20.0 / 14);
  EXPECT_NEAR(diffusionCoefficient(model, lumped), 20.0 / 14, 1e-15);
  const dense::Matrix P = dense::transitionMatrix({3}, 7);
  EXPECT_NEAR(dense::diffusionCoefficient(P, h), 20.0 / 14, 1e-14);
  const std::vector<double> reference = dense::correlation(P, h, 40);
  const std::vector<double> lumpedC = correlation(model, lumped, 40);
  for (std::size_t t = 0; t <= 40; ++t) EXPECT_NEAR(lumpedC[t], reference[t], 1e-15) << t;
}

// ---------------------------------------------------------------------------------------------------------
// The lumped chain against the dense N × N evaluation

TEST(MarkovModel, LumpedChainMatchesDenseMatrices) {
  struct Case {
    std::vector<std::int64_t> lengths;
    std::size_t N;
  };
  for (const Case& c : {Case{{1}, 3}, Case{{3}, 5}, Case{{10}, 40}, Case{{20}, 200}, Case{{2, 5}, 12},
                        Case{{7, 3}, 60}, Case{{4, 4, 9}, 90}}) {
    const dense::Matrix P = dense::transitionMatrix(c.lengths, c.N);
    for (std::uint64_t seed : {1u, 2u}) {
      const std::vector<double> h = randomObservable(c.N, seed);
      const MarkovModel model{c.lengths, static_cast<std::int64_t>(c.N)};
      const LumpedObservable lumped = dense::lump(c.lengths, h);
      const std::vector<double> expected = dense::correlation(P, h, 3 * c.N);
      const std::vector<double> C = correlation(model, lumped, static_cast<std::int64_t>(3 * c.N));
      for (std::size_t t = 0; t < C.size(); ++t) ASSERT_NEAR(C[t], expected[t], 1e-13) << c.N << " τ = " << t;
      const double D = dense::diffusionCoefficient(P, h);
      EXPECT_NEAR(diffusionCoefficient(model, lumped), D, 1e-12 * (1 + std::fabs(D))) << c.N;
      EXPECT_NEAR(diffusionCoefficientDmark(model, lumped), D, 1e-12 * (1 + std::fabs(D))) << c.N;
    }
  }
}

TEST(MarkovModel, DmarkEqualsTheMatrixFormulaAtLargeN) {
  // Structured solve against eq. (dmark), and against ½C(0) + Σ_{τ≥1} C(τ) summed until it has converged.
  struct Case {
    std::vector<std::int64_t> lengths;
    std::int64_t N;
  };
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const Case& c : {Case{{10}, 100'000}, Case{{50}, 50'000'000}, Case{{13, 29}, 1'000'000}, Case{{5, 40}, 400}}) {
    const MarkovModel model{c.lengths, c.N};
    LumpedObservable h;
    for (std::int64_t mk : c.lengths) {
      h.trapped.emplace_back();
      for (std::int64_t i = 0; i < mk; ++i) h.trapped.back().push_back(u(rng));
      h.preImages.push_back(u(rng));
    }
    const long double sum = h.freeSeaSum();
    h.freeSeaSquares = static_cast<double>(sum * sum / static_cast<long double>(model.freeSeaPoints())) + 3.5;
    const double D = diffusionCoefficient(model, h);
    EXPECT_NEAR(diffusionCoefficientDmark(model, h), D, 1e-13 * std::fabs(D));
    if (c.N <= 1'000'000) {  // the series converges in a few (m/log n)·log(1e20) steps
      const std::vector<double> C = correlation(model, h, 20 * model.trappedPoints() + 2000);
      long double series = 0.5L * C[0];
      for (std::size_t t = 1; t < C.size(); ++t) series += C[t];
      EXPECT_NEAR(static_cast<double>(series), D, 1e-12 * std::fabs(D));
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// The paper's statements about ε(τ) (appendix C), one segment, h = 1 on T, 0 on the pre-image

struct Deviation {
  std::vector<double> C, eps;
};
Deviation deviation(std::int64_t m, std::int64_t N, std::int64_t tauMax) {
  const MarkovModel model{{m}, N};
  Deviation d;
  d.C = correlation(model, paperObservable(model), tauMax);
  d.eps = correlationDeviation(model, paperObservable(model), tauMax);
  return d;
}

TEST(MarkovModel, DeviationIsBoundedByMOverN) {
  // Paper: |ε(τ)| ≤ m/N for τ > 0, m = 10, 20, 50, N = 10m … 10⁶m.  The largest |ε| is at τ = 1, where
  // (by hand: P h = 0 on q, 1 on p⁽²⁾…p⁽ᵐ⁾, −(m − 1)/n on S) ε(1) = (m − 1)/(N − m) exactly.  That is ≤ m/N
  // iff N ≥ m², so the paper's bound fails slightly (by at most a factor 10(m − 1)/9m < 1.11) at N = 10m for
  // m = 20, 50; the bound that holds throughout is |ε(τ)| ≤ (m − 1)/(N − m).
  for (std::int64_t m : {10, 20, 50}) {
    for (std::int64_t factor : {10, 100, 1000, 10'000, 100'000, 1'000'000}) {
      const std::int64_t N = factor * m;
      const Deviation d = deviation(m, N, 20 * m);
      const double first = static_cast<double>(m - 1) / static_cast<double>(N - m);
      EXPECT_NEAR(d.eps[1], first, 1e-11 * first) << m << " " << N;
      const double bound = static_cast<double>(m) / static_cast<double>(N);
      for (std::size_t t = 1; t < d.eps.size(); ++t) {
        ASSERT_LE(std::fabs(d.eps[t]), first * (1 + 1e-11)) << m << " " << N << " τ = " << t;
        if (N >= m * m) {
          ASSERT_LE(std::fabs(d.eps[t]), bound * (1 + 1e-11)) << m << " " << N << " τ = " << t;
        }
      }
      if (N < m * m) {
        EXPECT_GT(std::fabs(d.eps[1]), bound) << "the paper's bound is exceeded (at τ = 1)";
      }
    }
  }
}

TEST(MarkovModel, DeviationSumsToZero) {
  // Appendix C: eq. (dmark) gives D − D_is = Σ_{S′}h²/2N = ½(C(0) − C_is(0)), so Σ_{τ≥1} ε(τ) = 0 exactly.
  for (std::int64_t m : {10, 20, 50}) {
    for (std::int64_t N : {10 * m, 1000 * m}) {
      const Deviation d = deviation(m, N, 40 * m);
      long double sum = 0, size = 0;
      for (std::size_t t = 1; t < d.eps.size(); ++t) {
        sum += d.eps[t];
        size += std::fabs(d.eps[t]);
      }
      EXPECT_LT(std::fabs(static_cast<double>(sum)), 1e-12 * static_cast<double>(size)) << m << " " << N;
    }
  }
}

// The nontrivial eigenvalue of largest modulus of the lumped chain, one segment.  Its eigenvectors are
// F(p⁽ⁱ⁾) = a λ⁻ⁱ, so λ^m w = 1 with w = n(λ − 1) + 1.  The root with θ = arg λ ∈ (π/m, 2π/m) is the fixed
// point of λ = |w|^(−1/m) exp(i(2π − arg w)/m) (a contraction, factor ≈ 1/(m|λ − 1|) < 1 here), started
// from the paper's estimate n^(−1/m) e^(iπ/m).
std::complex<long double> dominantRoot(std::int64_t m, std::int64_t N) {
  const long double n = static_cast<long double>(N - m), pi = std::numbers::pi_v<long double>;
  const long double mm = static_cast<long double>(m);
  std::complex<long double> z = std::polar(std::pow(n, -1 / mm), pi / mm);
  for (int it = 0; it < 2000; ++it) {
    const std::complex<long double> w = n * (z - 1.0L) + 1.0L;
    z = std::polar(std::pow(std::abs(w), -1 / mm), (2 * pi - std::arg(w)) / mm);
  }
  const std::complex<long double> residual = std::pow(z, static_cast<int>(m)) * (n * (z - 1.0L) + 1.0L) - 1.0L;
  EXPECT_LT(std::abs(residual), 1e-15L) << m << " " << N;
  return z;
}

TEST(MarkovModel, DeviationOscillatesWithHalfPeriodMAndDecaysAsNToTheMinusTauOverM) {
  // Paper: after a transient ε(τ) oscillates about 0 with half-period m and decays as n^(−τ/m) approximately.
  // Measured here from the zero crossings after τ = 3m (half-period: their mean spacing) and the peaks of |ε|
  // between them (decay: least-squares slope of log peak), while |ε| > 1e-33 (the long double recursion's
  // rounding floor is ~1e-40 here).
  // Exact: both come from the dominant root λ = r e^(iθ) (dominantRoot): half-period π/θ, decay −log r per
  // step; checked to 3% (integer grid of the crossings and peaks; subdominant roots, whose moduli differ by
  // factors (|λ₁ − 1|/|λ₂ − 1|)^(1/m), close to 1, still contribute after 3m).
  // The paper's approximations, from λ^m w = 1, w = n(λ − 1) + 1:
  //   decay: m log(1/r) = log|w| = log n + log|λ − 1 + 1/n|, so −log r = log(n)/m to a relative
  //     |log|λ − 1|| / log n (≤ 0.37 for N ≥ 10m, m ≤ 50);
  //   half-period: mθ = π + φ, φ = π − arg w ∈ (0, π), so π/θ = m π/(π + φ) < m; with 1 − r ≈ log(n)/m,
  //     φ ≈ π/log n to first order, and at most 1.5π/log n for the cases here (second-order terms matter at
  //     N = 10m, m = 50: π/θ = 40.2).  Tolerance: relative 1.5/log n.
  // Both plus the 3% measurement allowance.
  for (std::int64_t m : {10, 20, 50}) {
    for (std::int64_t factor : {10, 100, 1000}) {
      const std::int64_t N = factor * m;
      const Deviation d = deviation(m, N, 30 * m);
      std::vector<std::size_t> crossings;
      for (std::size_t t = static_cast<std::size_t>(3 * m); t + 1 < d.eps.size(); ++t) {
        if (std::fabs(d.eps[t]) < 1e-33) break;
        if ((d.eps[t] < 0) != (d.eps[t + 1] < 0)) crossings.push_back(t + 1);
      }
      ASSERT_GE(crossings.size(), 5u) << m << " " << N;
      std::vector<double> peaks;
      for (std::size_t j = 0; j + 1 < crossings.size(); ++j) {
        double peak = 0;
        for (std::size_t t = crossings[j]; t < crossings[j + 1]; ++t) peak = std::max(peak, std::fabs(d.eps[t]));
        peaks.push_back(peak);
      }
      const double halfPeriod = static_cast<double>(crossings.back() - crossings.front()) /
                                static_cast<double>(crossings.size() - 1);
      // Least-squares slope of log(peak) against the crossing that starts its half-period.
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      const double count = static_cast<double>(peaks.size());
      for (std::size_t j = 0; j < peaks.size(); ++j) {
        const double x = static_cast<double>(crossings[j]), y = std::log(peaks[j]);
        sx += x, sy += y, sxx += x * x, sxy += x * y;
      }
      const double rate = -(count * sxy - sx * sy) / (count * sxx - sx * sx);

      const std::complex<long double> lambda = dominantRoot(m, N);
      const double r = static_cast<double>(std::abs(lambda)), theta = static_cast<double>(std::arg(lambda));
      EXPECT_NEAR(halfPeriod, std::numbers::pi / theta, 0.03 * std::numbers::pi / theta) << m << " " << N;
      EXPECT_NEAR(rate, -std::log(r), 0.03 * -std::log(r)) << m << " " << N;

      const double logn = std::log(static_cast<double>(N - m));
      EXPECT_NEAR(halfPeriod, static_cast<double>(m), (1.5 / logn + 0.03) * static_cast<double>(m)) << m << " " << N;
      const double logGap = std::fabs(std::log(static_cast<double>(std::abs(lambda - 1.0L))));
      EXPECT_NEAR(rate * static_cast<double>(m) / logn, 1, logGap / logn + 0.03) << m << " " << N;
    }
  }
}

TEST(MarkovModel, AntiCorrelationBetweenMAnd2M) {
  // Appendix C: C(τ) < 0, "most pronounced for m ≲ τ ≲ 2m": the most negative C lies in [m, 2m].
  for (std::int64_t m : {10, 20, 50}) {
    for (std::int64_t factor : {10, 1000, 1'000'000}) {
      const Deviation d = deviation(m, factor * m, 10 * m);
      const auto lowest = std::min_element(d.C.begin() + 1, d.C.end());
      const auto at = static_cast<std::int64_t>(lowest - d.C.begin());
      EXPECT_LT(*lowest, 0) << m << " " << factor;
      EXPECT_GE(at, m) << m << " " << factor;
      EXPECT_LE(at, 2 * m) << m << " " << factor;
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// When the island part of D is D_is (appendix C, eq. after (dmark))

TEST(MarkovModel, IslandPartIsDisWhenHIsConstantOnTAndPreImagesBalance) {
  // Two segments m = (3, 5), N = 40: h = h₀ on T, Σ m_k h(q_k) = 3·5 + 5·(−3) = 0 ⇒ D = (Σ_S h² + h₀²Σm_k²)/2N.
  const std::vector<std::int64_t> lengths{3, 5};
  const std::size_t N = 40;
  const double h0 = 0.7;
  std::vector<double> h = randomObservable(N, 5);
  const dense::Layout L = dense::layout(lengths, N);
  for (const auto& T : L.segments)
    for (std::size_t i : T) h[i] = h0;
  h[L.preImages[0]] = 5;
  h[L.preImages[1]] = -3;
  auto rebalance = [&] {  // restore Σ h = 0 on S′
    double s = 0;
    for (double v : h) s += v;
    for (std::size_t i : L.freeSea) h[i] -= s / static_cast<double>(L.freeSea.size());
  };
  rebalance();
  const MarkovModel model{lengths, static_cast<std::int64_t>(N)};
  const double Dis = islandDiffusionCoefficient(model, h0);
  EXPECT_DOUBLE_EQ(Dis, 0.49 * (9 + 25) / 80);
  const dense::Matrix P = dense::transitionMatrix(lengths, N);
  const double islandPart = dense::diffusionCoefficient(P, h) - seaSquares(h, 8) / (2 * N);
  EXPECT_NEAR(islandPart, Dis, 1e-13);
  EXPECT_NEAR(diffusionCoefficient(model, dense::lump(lengths, h)) - seaSquares(h, 8) / (2 * N), Dis, 1e-13);

  // Violated: the pre-images do not balance (Σ m_k h(q_k) = 3·5 + 5·0 ≠ 0).  The island part is then
  // D_is + h₀ Σ_k m_k h(q_k) / N (from eq. (dmark)).
  h[L.preImages[1]] = 0;
  rebalance();
  const double unbalanced = dense::diffusionCoefficient(P, h) - seaSquares(h, 8) / (2 * N);
  EXPECT_NEAR(unbalanced, Dis + h0 * 15 / N, 1e-13);
  EXPECT_GT(std::fabs(unbalanced - Dis), 0.1);

  // Violated: h not constant on T (balanced pre-images again).
  h[L.preImages[1]] = -3;
  h[L.segments[1][2]] = -h0;
  rebalance();
  const double uneven = dense::diffusionCoefficient(P, h) - seaSquares(h, 8) / (2 * N);
  EXPECT_GT(std::fabs(uneven - islandDiffusionCoefficient(model, h0)), 1e-3);
  EXPECT_NEAR(diffusionCoefficientDmark(model, dense::lump(lengths, h)), dense::diffusionCoefficient(P, h), 1e-13);
}

TEST(MarkovModel, PaperObservableGivesDisAtLargeN) {
  // h = 1 on T, 0 on the pre-images (paperObservable): D = Σ_{S′}h²/2N + ½Σm_k²/N for any N.
  for (const std::vector<std::int64_t>& lengths : {std::vector<std::int64_t>{50}, std::vector<std::int64_t>{20, 7}}) {
    const MarkovModel model{lengths, 10'000'000};
    const LumpedObservable h = paperObservable(model);
    const double expected = h.freeSeaSquares / (2 * 1e7) + islandDiffusionCoefficient(model);
    EXPECT_NEAR(diffusionCoefficient(model, h), expected, 1e-15 * expected);
    EXPECT_NEAR(diffusionCoefficientDmark(model, h), expected, 1e-15 * expected);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Ranges

TEST(MarkovModel, InvalidModelsAreRejected) {
  EXPECT_THROW(validate(MarkovModel{{}, 10}), std::invalid_argument);
  EXPECT_THROW(validate(MarkovModel{{0}, 10}), std::invalid_argument);
  EXPECT_THROW(validate(MarkovModel{{3}, 4}), std::invalid_argument);  // no free sea point: a pure cycle
  EXPECT_NO_THROW(validate(MarkovModel{{3}, 5}));
  EXPECT_THROW(validate(MarkovModel{{MarkovModel::kMaxTrappedPoints + 1}, MarkovModel::kMaxPoints}), std::invalid_argument);
  EXPECT_THROW(validate(MarkovModel{{3}, MarkovModel::kMaxPoints + 1}), std::invalid_argument);
  const MarkovModel model{{3}, 7};
  LumpedObservable h = paperObservable(model);
  h.freeSeaSquares = 1;  // Σ_{S′} h = −3 over 3 points needs Σ h² ≥ 3
  EXPECT_THROW(validate(model, h), std::invalid_argument);
  h = paperObservable(model);
  h.trapped[0].pop_back();
  EXPECT_THROW(validate(model, h), std::invalid_argument);
  EXPECT_THROW((void)correlation(model, paperObservable(model), -1), std::invalid_argument);
  EXPECT_THROW((void)correlation(model, paperObservable(model), MarkovModel::kMaxWork), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago::markov
