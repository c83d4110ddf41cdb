// The small-K theory of Karney (1983), §4: the paper's numbers, and checks of the closed forms against
// direct quadrature and finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/theory/SmallKTheory.hpp"

namespace archipelago::smallk {
namespace {

// Midpoint rule on θ ∈ (0, π/2) for ∫₀^∞ g(u) du with u = tan θ.  Each integrand below, written in θ, is a
// smooth function of sin²θ and cos²θ, hence π-periodic and even, so the midpoint rule converges
// geometrically; 4000 points are far more than enough for 1e-13.
template <class Integrand>
long double integrateHalfLine(Integrand g, int points = 4000) {
  const long double h = std::numbers::pi_v<long double> / 2 / points;
  long double sum = 0;
  for (int i = 0; i < points; ++i) {
    const long double theta = (i + 0.5L) * h;
    const long double c = std::cos(theta);
    sum += g(std::tan(theta)) / (c * c);
  }
  return sum * h;
}

// eq. (tneg) by quadrature, independent of the elliptic reduction: X = X0 + u² removes the endpoint
// singularity, and X³/3 + X − X0³/3 − X0 = (X − X0)(X² + X X0 + X0² + 3)/3 exactly.
double trappingTimeByQuadrature(double X0) {
  const long double x0 = X0;
  return static_cast<double>(integrateHalfLine([x0](long double u) {
    const long double X = x0 + u * u;
    return 2 / std::sqrt((X * X + X * x0 + x0 * x0 + 3) / 3);
  }));
}

// ---------------------------------------------------------------------------------------------------------
// K < 0: T(X0) and T'(X0)

TEST(SmallKTheory, TrappingTimeMatchesQuadratureOfEqTneg) {
  for (double X0 : {-1e4, -300.0, -10.0, -2.0, -0.5536, -0.1, 0.0, 0.3, 1.0, 7.5, 100.0, 1e4}) {
    const double expected = trappingTimeByQuadrature(X0);
    EXPECT_NEAR(negativeKTrappingTime(X0), expected, 1e-13 * expected) << "X0 = " << X0;
  }
}

TEST(SmallKTheory, TrappingTimeIsPositiveContinuousAndBounded) {
  const double Tmax = negativeKMaximum().T;
  std::vector<double> grid;
  for (double x = -20; x <= 20; x += 0.0625) grid.push_back(x);
  for (double x = 20; x <= 1e12; x *= 1.7) {
    grid.push_back(x);
    grid.push_back(-x);
  }
  for (double X0 : grid) {
    const double T = negativeKTrappingTime(X0);
    ASSERT_TRUE(std::isfinite(T)) << X0;
    EXPECT_GT(T, 0) << X0;
    EXPECT_LE(T, Tmax) << X0;
    // Continuity: |T(X0 + δ) − T(X0)| ≤ max|T'| δ with max|T'| < 2.
    const double delta = 1e-7 * std::max(1.0, std::abs(X0));
    EXPECT_LE(std::abs(negativeKTrappingTime(X0 + delta) - T), 2 * delta) << X0;
  }
  EXPECT_TRUE(std::isnan(negativeKTrappingTime(std::nan(""))));
  EXPECT_TRUE(std::isnan(negativeKTrappingTime(INFINITY)));
}

TEST(SmallKTheory, TrappingTimeApproachesTheZeroKLawFarOut) {
  // T(X0) → T_{K=0}(X0) with relative corrections O(X0⁻²).
  for (double X0 : {-1e6, -1e4, 1e4, 1e6}) {
    const double zeroK = zeroKTrappingTime(X0);
    EXPECT_NEAR(negativeKTrappingTime(X0), zeroK, 10 / (X0 * X0) * zeroK) << X0;
  }
}

TEST(SmallKTheory, DerivativeMatchesFiniteDifference) {
  for (double X0 : {-1000.0, -20.0, -3.0, -1.0, -0.6, -0.5536, -0.5, 0.0, 0.5, 2.0, 50.0, 1e4}) {
    // Richardson-extrapolated central difference: truncation O(h⁴), rounding ~ ε T/h.
    const double h = 1e-3 * std::max(1.0, std::abs(X0));
    auto central = [X0](double step) {
      return (negativeKTrappingTime(X0 + step) - negativeKTrappingTime(X0 - step)) / (2 * step);
    };
    const double difference = (4 * central(h) - central(2 * h)) / 3;
    const double derivative = negativeKTrappingTimeDerivative(X0);
    const double scale = negativeKTrappingTime(X0) / std::max(1.0, std::abs(X0));  // typical |T'|
    EXPECT_NEAR(derivative, difference, 1e-10 * scale) << "X0 = " << X0;
  }
}

// ---------------------------------------------------------------------------------------------------------
// K < 0: the maximum and F(T)

TEST(SmallKTheory, MaximumTrappingTimeIsThePapers) {
  const TrappingTimeMaximum& top = negativeKMaximum();
  EXPECT_NEAR(top.T, 5.1454, 1e-4);    // §4: Tmax = 5.1454
  EXPECT_NEAR(top.X0, -0.5536, 1e-4);  //      at X0 = −0.5536
  EXPECT_NEAR(negativeKTrappingTimeDerivative(top.X0), 0, 1e-15);
  EXPECT_DOUBLE_EQ(negativeKTrappingTime(top.X0), top.T);
  for (double dx : {-1e-2, -1e-4, 1e-4, 1e-2}) EXPECT_LT(negativeKTrappingTime(top.X0 + dx), top.T);
  // T(X0 ± δ) ≈ Tmax + ½T''δ²
  const double dx = 1e-3;
  const double second = (negativeKTrappingTime(top.X0 + dx) + negativeKTrappingTime(top.X0 - dx) - 2 * top.T) /
                        (dx * dx);
  EXPECT_NEAR(top.curvature, second, 1e-4);
  EXPECT_LT(top.curvature, 0);
}

TEST(SmallKTheory, UnscaledMaximum) {
  // K = −10⁻⁴: t_max = 5.1454 |K|^(−1/4) ≈ 51.5 ("about 50", §4), at x = −0.5536 √|K|.
  EXPECT_NEAR(negativeKMaximumTime(-1e-4), 51.454, 1e-3);
  EXPECT_NEAR(negativeKMaximumPosition(-1e-4), -0.005536, 1e-6);
  EXPECT_DOUBLE_EQ(negativeKMaximumTime(-1.0), negativeKMaximum().T);
  EXPECT_TRUE(std::isnan(negativeKMaximumTime(0.0)));
  EXPECT_TRUE(std::isnan(negativeKMaximumPosition(1e-4)));
}

TEST(SmallKTheory, InverseBranchesHitTheirTime) {
  const TrappingTimeMaximum& top = negativeKMaximum();
  for (double T : {1e-3, 0.05, 0.5, 1.0, 2.5, 4.0, 5.0, 5.14, top.T - 1e-6}) {
    const auto [left, right] = negativeKInverse(T);
    EXPECT_LT(left, top.X0) << T;
    EXPECT_GT(right, top.X0) << T;
    EXPECT_NEAR(negativeKTrappingTime(left), T, 4e-16 * top.T) << T;
    EXPECT_NEAR(negativeKTrappingTime(right), T, 4e-16 * top.T) << T;
  }
  EXPECT_TRUE(std::isnan(negativeKInverse(0.0).left));
  EXPECT_TRUE(std::isnan(negativeKInverse(top.T * 1.0001).right));
}

TEST(SmallKTheory, SegmentDensityForShortTimesIsThePapers) {
  // §4: F(T) ≈ 6.205·10⁵ T⁻⁷ for T ≪ Tmax (to the paper's 4 digits, 0.1 %), and the exact limit 112A⁶.
  EXPECT_NEAR(negativeKSmallTCoefficient(), 6.205e5, 6.205e2);
  for (double T : {0.01, 0.05, 0.1, 0.3}) {
    const double scaled = negativeKSegmentDensity(T) * std::pow(T, 7);
    EXPECT_NEAR(scaled, 6.205e5, 6.205e2) << T;
    // 1 + O(T⁴): the correction is measured to be −1.4e-4 T⁴.
    EXPECT_NEAR(scaled, negativeKSmallTCoefficient(), (3e-4 * std::pow(T, 4) + 1e-13) * scaled) << T;
  }
}

TEST(SmallKTheory, SegmentDensityNearTheCutoffIsThePapers) {
  // §4: F(T) ≈ 3.024 (Tmax − T)^(−1/2) for T ≈ Tmax; the relative correction is O(Tmax − T) (about 8(Tmax − T)).
  const double Tmax = negativeKMaximum().T;
  const double c = negativeKCutoffCoefficient();
  EXPECT_NEAR(c, 3.024, 3.024e-3);
  for (double delta : {1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
    const double scaled = negativeKSegmentDensity(Tmax - delta) * std::sqrt(delta);
    EXPECT_NEAR(scaled, 3.024, 3.024e-3) << delta;
    EXPECT_NEAR(scaled, c, (10 * delta + 1e-7) * c) << delta;
  }
}

TEST(SmallKTheory, SegmentDensityAgreesWithItsDefinitionAndDomain) {
  // Eq. (fneg) by hand at X0 = 3: the right branch's partner on the left has the same T.
  const double T = negativeKTrappingTime(3.0);
  const auto [left, right] = negativeKInverse(T);
  EXPECT_NEAR(right, 3.0, 1e-13);
  const double byHand = 2 * (3.0 * 3.0 + 1) / std::abs(negativeKTrappingTimeDerivative(3.0)) +
                        2 * (left * left + 1) / std::abs(negativeKTrappingTimeDerivative(left));
  EXPECT_NEAR(negativeKSegmentDensity(T), byHand, 1e-13 * byHand);
  // Domain: no trapping beyond Tmax; undefined for T ≤ 0.
  EXPECT_EQ(negativeKSegmentDensity(negativeKMaximum().T * 1.001), 0.0);
  EXPECT_EQ(negativeKSegmentDensity(negativeKMaximum().T), INFINITY);
  EXPECT_TRUE(std::isnan(negativeKSegmentDensity(0.0)));
  EXPECT_TRUE(std::isnan(negativeKSegmentDensity(-1.0)));
  // Unscaled shape: f_t ∝ F(|K|^(1/4) t).
  EXPECT_DOUBLE_EQ(negativeKSegmentShape(30.0, -1e-4), negativeKSegmentDensity(3.0));
  EXPECT_DOUBLE_EQ(segmentShape(30.0, -1e-4), negativeKSegmentDensity(3.0));
  EXPECT_TRUE(std::isnan(negativeKSegmentShape(30.0, 1e-4)));
}

TEST(SmallKTheory, CorrelationIsTheSecondIntegralOfTheDensity) {
  // C'' = F (C(Θ) = ∫_Θ (T − Θ) F dT), by Richardson-extrapolated central second differences (truncation
  // O(h⁴) with h well inside both the T⁻⁷ scale Θ and the cutoff scale Tmax − Θ).
  const double Tmax = negativeKMaximum().T;
  for (double Theta : {0.5, 1.5, 3.0, 4.5, 5.0}) {
    auto central = [Theta](double h) {
      return (negativeKCorrelation(Theta + h) - 2 * negativeKCorrelation(Theta) + negativeKCorrelation(Theta - h)) /
             (h * h);
    };
    const double h = 2e-3 * std::min(Theta, Tmax - Theta);
    const double second = (4 * central(h) - central(2 * h)) / 3;
    const double F = negativeKSegmentDensity(Theta);
    EXPECT_NEAR(second, F, 1e-5 * F) << Theta;
  }
  // Near Tmax: C ≈ (4/3) c (Tmax − Θ)^(3/2)  (§4: C_τ ~ (t_max − τ)^(3/2)).
  const double c = negativeKCutoffCoefficient();
  for (double delta : {1e-3, 1e-4, 1e-5}) {
    const double expected = 4.0 / 3 * c * std::pow(delta, 1.5);
    EXPECT_NEAR(negativeKCorrelation(Tmax - delta), expected, 20 * delta * expected) << delta;
  }
  // Short times: C ≈ (112A⁶/30) Θ⁻⁵.
  const double Theta = 0.02;
  const double shortTime = negativeKSmallTCoefficient() / 30 * std::pow(Theta, -5);
  EXPECT_NEAR(negativeKCorrelation(Theta), shortTime, 1e-3 * shortTime);
  EXPECT_EQ(negativeKCorrelation(Tmax), 0.0);
  EXPECT_TRUE(std::isnan(negativeKCorrelation(0.0)));
  EXPECT_DOUBLE_EQ(negativeKCorrelationShape(30.0, -1e-4), negativeKCorrelation(3.0));
  EXPECT_DOUBLE_EQ(correlationShape(30.0, -1e-4), negativeKCorrelation(3.0));
}

// ---------------------------------------------------------------------------------------------------------
// K = 0

TEST(SmallKTheory, ZeroKConstantIsThePapersAndMatchesQuadrature) {
  const double A = zeroKTimeConstant();
  EXPECT_NEAR(A, 4.207, 1e-3);  // §4: T = {1, √3} × 4.207 |X0|^(−1/2) for X0 ≷ 0
  // √3 ∫₁^∞ dZ/√(Z³ − 1), Z = 1 + u²:  Z³ − 1 = u²(Z² + Z + 1).
  const double positiveSide = static_cast<double>(
      std::sqrt(3.0L) * integrateHalfLine([](long double u) {
        const long double Z = 1 + u * u;
        return 2 / std::sqrt(Z * Z + Z + 1);
      }));
  // ∫_{−1}^∞ dZ/√(Z³ + 1), Z = −1 + u²:  Z³ + 1 = u²(Z² − Z + 1).
  const double negativeSide = static_cast<double>(integrateHalfLine([](long double u) {
    const long double Z = -1 + u * u;
    return 2 / std::sqrt(Z * Z - Z + 1);
  }));
  EXPECT_NEAR(A, positiveSide, 1e-14 * A);
  EXPECT_NEAR(A, negativeSide, 1e-14 * A);
}

TEST(SmallKTheory, ZeroKLaws) {
  const double A = zeroKTimeConstant();
  EXPECT_DOUBLE_EQ(zeroKTrappingTime(4.0), A / 2);
  EXPECT_DOUBLE_EQ(zeroKTrappingTime(-4.0), std::sqrt(3.0) * A / 2);
  EXPECT_EQ(zeroKTrappingTime(0.0), INFINITY);
  // f_t ∝ t⁻⁷ and C_τ ∝ τ⁻⁵: ratios over a factor 2.
  EXPECT_NEAR(zeroKSegmentShape(10.0) / zeroKSegmentShape(20.0), 128.0, 1e-12);
  EXPECT_NEAR(zeroKCorrelationShape(10.0) / zeroKCorrelationShape(20.0), 32.0, 1e-12);
  EXPECT_DOUBLE_EQ(segmentShape(10.0, 0.0), zeroKSegmentShape(10.0));
  EXPECT_DOUBLE_EQ(correlationShape(10.0, 0.0), zeroKCorrelationShape(10.0));
  EXPECT_TRUE(std::isnan(zeroKSegmentShape(0.0)));
}

// ---------------------------------------------------------------------------------------------------------
// K > 0

TEST(SmallKTheory, LyapunovNumberIsTheEigenvalueAtTheHyperbolicPoint) {
  for (double K : {1e-8, 1e-4, 1e-3, 1e-2, 0.1, 1.0}) {
    // Q linearised at (√K, 0): x' = (1 + 4√K) x + y, y' = 4√K x + y; trace 2 + 4√K, determinant 1.
    const double trace = 2 + 4 * std::sqrt(K);
    const double eigenvalue = (trace + std::sqrt(trace * trace - 4)) / 2;
    const double lambda = positiveKLyapunovNumber(K);
    EXPECT_NEAR(lambda, eigenvalue, 1e-14 * eigenvalue) << K;
    EXPECT_NEAR(lambda + 1 / lambda, trace, 1e-14 * trace) << K;
    EXPECT_NEAR(positiveKDecayRate(K), 0.5 * std::log(lambda), 1e-15) << K;
  }
  EXPECT_DOUBLE_EQ(positiveKLyapunovNumber(0.0), 1.0);
  EXPECT_TRUE(std::isnan(positiveKLyapunovNumber(-1e-4)));
}

TEST(SmallKTheory, DecayRateIsAboutKToTheQuarter) {
  // §4: for K = 10⁻⁴ the decay rate should be about 0.1.
  EXPECT_NEAR(positiveKDecayRate(1e-4), 0.1, 1e-3);
  // ½ log λ = K^(1/4) (1 − K^(1/2)/6 + …) → K^(1/4) as K → 0.
  for (double K : {1e-12, 1e-8, 1e-4}) {
    const double quarter = std::sqrt(std::sqrt(K));
    EXPECT_NEAR(positiveKDecayRate(K) / quarter, 1 - std::sqrt(K) / 6, std::sqrt(K)) << K;
  }
  const double rate = positiveKDecayRate(1e-4);
  EXPECT_NEAR(positiveKSegmentShape(10.0, 1e-4) / positiveKSegmentShape(20.0, 1e-4), std::exp(10 * rate), 1e-12);
  EXPECT_DOUBLE_EQ(segmentShape(10.0, 1e-4), std::exp(-10 * rate));
  EXPECT_DOUBLE_EQ(correlationShape(10.0, 1e-4), std::exp(-10 * rate));
}

// ---------------------------------------------------------------------------------------------------------
// Amplitude fit

TEST(SmallKTheory, AmplitudeFitRecoversTheFactor) {
  auto shape = [](double t) { return zeroKSegmentShape(t); };
  std::vector<double> t, f;
  for (int i = 1; i <= 200; ++i) {
    t.push_back(i);
    // Multiplicative noise e^{±0.1}, alternating, so its log-mean over an even count is zero.
    f.push_back(2.5 * shape(i) * std::exp(i % 2 == 0 ? 0.1 : -0.1));
  }
  f[99] = 0;    // t = 100, an empty bin: skipped (leaves 65 of each sign of the noise)
  f[10] = 1e9;  // t = 11, an outlier below tLow: skipped
  const AmplitudeFit fit = fitAmplitude(t, f, 20, 150, shape);  // t = 20..150 less t = 100: 130 points
  ASSERT_TRUE(fit.valid());
  EXPECT_EQ(fit.points, 130u);
  EXPECT_NEAR(fit.amplitude, 2.5, 1e-12);
  EXPECT_NEAR(fit.rmsLogResidual, 0.1, 1e-12);

  const AmplitudeFit none = fitAmplitude(t, f, 1000, 2000, shape);
  EXPECT_FALSE(none.valid());
  EXPECT_TRUE(std::isnan(none.amplitude));
  // A cutoff shape (K < 0, zero beyond t_max) drops the points it cannot describe.
  auto cutoff = [](double time) { return negativeKSegmentShape(time, -1e-4); };
  const AmplitudeFit cut = fitAmplitude(t, f, 1, 200, cutoff);
  EXPECT_EQ(cut.points, 51u);  // t = 1..51 < t_max = 51.45
  std::vector<double> shorter(3, 1.0);
  EXPECT_THROW((void)fitAmplitude(t, shorter, 0, 1, shape), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago::smallk
