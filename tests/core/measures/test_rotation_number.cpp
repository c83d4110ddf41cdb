// Rotation numbers of exact orbits (core/measures/RotationNumber.hpp, OrbitMeasures.hpp) against two independent
// parts of the program and the paper:
//   - near the elliptic fixed point they tend to α/2π, cos α = 1 − 2√K (Karney 1983, §2);
//   - near an elliptic periodic orbit of period n, the rotation of Qⁿ tends to ν with R = sin²(πν), R the residue
//     that the periodic-orbit finder computes in quad precision from DQⁿ (core/periodic), not from any orbit;
//   - the Rotation indicator of a pixel is the level-0 measurement bit for bit.
// The nonlinear shift ω(d) − ν = c d² + O(d⁴) at a distance d is removed by Richardson extrapolation from d and
// 2d: ν ≈ ω(d) − (ω(2d) − ω(d))/3.  Tolerance: each average's error is estimated by the difference of its two
// blocks, 10^−digits; the extrapolation weighs them 4/3 and 1/3; four times that, plus 10⁻¹³ for the noise of the
// 52-bit grid (a unit is 2.9·10⁻¹⁶; at d = 10⁻⁵ the map's rounding perturbs each step by ~10⁻¹¹ relative, which
// the 2·10⁴ weighted steps average to ~10⁻¹³ in ω).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/measures/RotationNumber.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"
#include "tests/core/kernels/KernelsUnderTest.hpp"

namespace archipelago {
namespace {

constexpr long double kPi = std::numbers::pi_v<long double>;

struct Extrapolated {
  long double value;
  long double tolerance;
};

/// ω at d and 2d (physical x offsets from `centre`), extrapolated to d → 0, with the tolerance above.
Extrapolated extrapolate(const MapParameters& box, PhysicalPoint centre, RotationCentre about, std::uint64_t power,
                         long double d) {
  const FixedPointMap map(box);
  RotationRequest r;
  r.map = box;
  r.centre = about;
  r.power = power;
  r.start = map.toUnit(centre.x + d, centre.y);
  const RotationMeasurement near = measureRotation(r);
  r.start = map.toUnit(centre.x + 2 * d, centre.y);
  const RotationMeasurement far = measureRotation(r);
  EXPECT_EQ(near.verdict, OrbitVerdict::Regular);
  EXPECT_EQ(far.verdict, OrbitVerdict::Regular);
  const long double value = near.rotation - (static_cast<long double>(far.rotation) - near.rotation) / 3;
  const long double noise = 4.0L / 3 * std::pow(10.0L, -near.digits) + 1.0L / 3 * std::pow(10.0L, -far.digits);
  return {value, 4 * noise + 1e-13L};
}

PhysicalPoint unitsOf(const MapParameters& box, PhysicalPoint p) {
  const long double L = static_cast<long double>(box.xmax) - box.xmin, one = FixedPointMap::kOne;
  return {(p.x - box.xmin) / L * one, (p.y + L / 2) / L * one};
}

/// A request about the central fixed point of `box` (clockwise), from the physical point (x, y).
RotationRequest aboutTheCentre(const MapParameters& box, long double x, long double y) {
  RotationRequest r;
  r.map = box;
  r.centre = centralFixedPoint(box);
  r.start = FixedPointMap(box).toUnit(x, y);
  return r;
}

TEST(RotationNumber, TendsToAlphaOverTwoPiNearTheEllipticFixedPoint) {
  for (double K : {0.01, 0.1, 0.5, 0.9}) {
    SCOPED_TRACE(K);
    const MapParameters box{K, -std::sqrt(K) - 0.5, 0.6};
    const long double alpha = std::acos(1 - 2 * std::sqrt(static_cast<long double>(K)));  // §2: cos α = 1 − 2√K
    const Extrapolated e = extrapolate(box, {-std::sqrt(static_cast<long double>(K)), 0}, centralFixedPoint(box), 1, 1e-5L);
    EXPECT_NEAR(static_cast<double>(e.value), static_cast<double>(alpha / (2 * kPi)), static_cast<double>(e.tolerance));
  }
  // The paper's value at K = 0.1: α/2π = 0.1900993 (to the 7 digits quoted).
  const MapParameters paper{0.1, -0.8, 0.5};
  const RotationRequest r = aboutTheCentre(paper, -std::sqrt(0.1L) + 1e-4L, 0);
  EXPECT_NEAR(measureRotation(r).rotation, 0.1900993, 5e-8);
}

/// The elliptic orbit of period n near `guess`, its member nearest the guess first.
PeriodicOrbit ellipticOrbit(int n, PhysicalPoint guess) {
  PeriodicOrbitSearch s;
  s.period = n;
  s.near = guess;
  s.stableOnly = true;
  PeriodicOrbit o = findPeriodicOrbit(0.1L, s);
  EXPECT_TRUE(o.stable());
  return o;
}

/// Clockwise (+1) when DQⁿ turns points about z clockwise (RotationNumber.hpp's convention), computed here
/// from the Jacobian product of the smooth map.
int senseOfLinearization(const PeriodicOrbit& o) {
  smooth::Matrix2<long double> m;
  (void)smooth::iterate(o.K, smooth::Point<long double>{o.points[0].x, o.points[0].y}, o.period, &m);
  return m.yx < 0 ? 1 : -1;
}

TEST(RotationNumber, AgreesWithTheResidueOfEllipticPeriodicOrbits) {
  const MapParameters box{0.1, -0.8, 0.5};
  // The six islands (§5) and the chain of order 6 × 23 = 138 (§6: a member near x + √K ≈ 0.352, y ≈ 0.034).
  struct Case {
    int period;
    PhysicalPoint guess;
    long double d;
  };
  for (const Case c : {Case{6, {0.0509L, 0.0974L}, 1e-6L}, Case{138, {0.0358L, 0.034L}, 1e-6L}}) {
    SCOPED_TRACE(c.period);
    const PeriodicOrbit o = ellipticOrbit(c.period, c.guess);
    const RotationCentre about{unitsOf(box, o.points[0]), senseOfLinearization(o)};
    const Extrapolated e = extrapolate(box, o.points[0], about, static_cast<std::uint64_t>(c.period), c.d);
    // R = sin²(πν): compare in ν (R's derivative 2π sin cos is of order 1 here).
    const long double nu = std::acos(1 - 2 * o.residue) / (2 * kPi);
    EXPECT_NEAR(static_cast<double>(e.value), static_cast<double>(nu), static_cast<double>(e.tolerance));
    EXPECT_NEAR(static_cast<double>(std::pow(std::sin(kPi * e.value), 2)), static_cast<double>(o.residue),
                static_cast<double>(3 * e.tolerance));
  }
}

TEST(RotationNumber, SensesOfTheLevelsOfThe138Chain) {
  // Q turns clockwise about (−√K, 0) (DQ there has lower-left element −4√K < 0); Q⁶ turns counter-clockwise
  // about its elliptic orbit; Q^138 clockwise again.  With each level's own sense the rotations are positive.
  const PeriodicOrbit six = ellipticOrbit(6, {0.0509L, 0.0974L});
  const PeriodicOrbit long138 = ellipticOrbit(138, {0.0358L, 0.034L});
  EXPECT_EQ(senseOfLinearization(six), -1);
  EXPECT_EQ(senseOfLinearization(long138), 1);
  const MapParameters box{0.1, -0.8, 0.5};
  const FixedPointMap map(box);
  RotationRequest r;
  r.map = box;
  r.start = map.toUnit(long138.points[0].x + 1e-6L, long138.points[0].y);
  r.centre = centralFixedPoint(box);
  const RotationMeasurement centre = measureRotation(r);
  EXPECT_NEAR(centre.rotation, 1.0 / 6, 1e-13);  // 23/138 turns per step about the centre
  r.centre = {unitsOf(box, six.points[0]), -1};
  r.power = 6;
  const RotationMeasurement island = measureRotation(r);
  EXPECT_NEAR(island.rotation, 2.0 / 23, 1e-13);  // 2 turns per 23 applications of Q⁶, counter-clockwise
  r.centre.sense = 1;
  EXPECT_EQ(measureRotation(r).rotation, -island.rotation);  // measured clockwise: the opposite sign, exactly
}

TEST(RotationNumber, ChaoticAndEscapingOrbitsGetNoNumber) {
  const MapParameters box{0.1, -0.8, 0.5};
  const FixedPointMap map(box);
  RotationRequest r = aboutTheCentre(box, 0.3L, 0.3L);  // the chaotic sea, soon out of the box
  const RotationMeasurement escaping = measureRotation(r);
  EXPECT_EQ(escaping.verdict, OrbitVerdict::Escaping);
  EXPECT_TRUE(std::isnan(escaping.rotation));
  EXPECT_LT(escaping.digits, 5);
  // A regular orbit of ~15 digits under a threshold of 16 is called chaotic: the verdict is the threshold's.
  r.start = map.toUnit(-0.3L, 0.0L);
  r.digitsThreshold = 16;
  const RotationMeasurement strict = measureRotation(r);
  EXPECT_EQ(strict.verdict, OrbitVerdict::Chaotic);
  EXPECT_TRUE(std::isnan(strict.rotation));
  EXPECT_GT(strict.digits, 12);
}

TEST(RotationNumber, TheRotationIndicatorIsTheLevelZeroMeasurementBitForBit) {
  const MapParameters box{0.1, -0.8, 0.5};
  const FixedPointMap map(box);
  MeasureSettings s;
  s.map = box;
  s.kind = IndicatorKind::Rotation;
  s.iterations = 2000;
  RotationRequest r;
  r.map = box;
  r.centre = centralFixedPoint(box);
  r.iterations = s.iterations;
  for (const KernelInfo& k : kerneltests::kernelsUnderTest()) {
    s.kernel = &k;
    const OrbitMeasurer measurer(s);
    for (long double x = -0.62L; x < 0.3L; x += 0.0713L) {
      r.start = map.toUnit(x, 0.01L);
      const OrbitMeasure pixel = measurer.measure(r.start);
      const RotationMeasurement single = measureRotation(r);
      EXPECT_EQ(pixel.verdict, single.verdict) << k.name << " x = " << x;
      EXPECT_EQ(std::isnan(pixel.value), std::isnan(single.rotation));
      if (!std::isnan(pixel.value)) {
        EXPECT_EQ(pixel.value, single.rotation) << k.name << " x = " << x;
      }
      EXPECT_EQ(pixel.digits, single.digits) << k.name << " x = " << x;
    }
  }
}

// A frame B (issue 50: a thin island's normal-form coordinates) changes the angles measured, not the rotation of an
// orbit whose steps do not fold: the identity and 2·1 (exact) give the same bits as no frame, a shear the same rotation
// within the two measurements' accuracies, a reflection its negative.  A frame that is not finite or not invertible is
// refused.
TEST(RotationNumber, AFrameChangesTheAnglesNotTheRotation) {
  const RotationRequest r = aboutTheCentre({0.1, -0.8, 0.5}, -std::sqrt(0.1L) + 0.05L, 0.01L);
  const RotationMeasurement plain = measureRotation(r);
  ASSERT_EQ(plain.verdict, OrbitVerdict::Regular);
  const auto framed = [&](std::array<double, 4> B) {
    RotationRequest f = r;
    f.frame = B;
    return measureRotation(f);
  };
  for (const std::array<double, 4> B : {std::array<double, 4>{1, 0, 0, 1}, std::array<double, 4>{2, 0, 0, 2}}) {
    const RotationMeasurement m = framed(B);
    EXPECT_EQ(m.rotation, plain.rotation);
    EXPECT_EQ(m.digits, plain.digits);
  }
  const RotationMeasurement sheared = framed({3, 1, 0, 0.5});
  ASSERT_EQ(sheared.verdict, OrbitVerdict::Regular);
  EXPECT_NEAR(sheared.rotation, plain.rotation, 2 * (sheared.difference + plain.difference));
  EXPECT_NEAR(framed({1, 0, 0, -1}).rotation, -plain.rotation, 2 * plain.difference);
  const double nan = std::nan(""), inf = HUGE_VAL;
  for (const std::array<double, 4> B : {std::array<double, 4>{nan, 0, 0, 1}, std::array<double, 4>{inf, 0, 0, 1},
                                        std::array<double, 4>{1, 2, 2, 4}, std::array<double, 4>{0, 0, 0, 0},
                                        std::array<double, 4>{1e300, 0, 0, 1e300}})
    EXPECT_THROW((void)framed(B), std::invalid_argument) << B[0] << " " << B[1] << " " << B[2] << " " << B[3];
}

TEST(RotationNumber, RejectsInvalidRequests) {
  RotationRequest r;
  r.power = 0;
  EXPECT_THROW((void)measureRotation(r), std::invalid_argument);
  r.power = 1;
  r.iterations = 3;
  EXPECT_THROW((void)measureRotation(r), std::invalid_argument);
  r.iterations = 100;
  r.centre.sense = 0;
  EXPECT_THROW((void)measureRotation(r), std::invalid_argument);
  r.centre.sense = 1;
  r.digitsThreshold = std::nan("");
  EXPECT_THROW((void)measureRotation(r), std::invalid_argument);
  r.digitsThreshold = 9;
  r.map.xmin = -0.2;  // xmin must be < −√K
  EXPECT_THROW((void)measureRotation(r), std::invalid_argument);
}

}  // namespace
}  // namespace archipelago
