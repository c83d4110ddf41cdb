// The exact fixed-point map N of docs/design.md, "Arithmetic contract" (Karney 1983, appendix B).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/map/FixedPointMap.hpp"
#include "core/map/ScalarStep.hpp"

namespace archipelago {
namespace {

constexpr std::uint64_t kOne = FixedPointMap::kOne;

// Parameter sets: the paper's K = 0.1 box, the small-K boxes of §4, and larger K and boxes (m up to 4).
const std::vector<MapParameters> kParameterSets = {
    {0.1, -0.8, 0.5}, {0.0, -0.05, 0.05}, {-1e-4, -0.05, 0.05}, {1e-4, -0.05, 0.05}, {0.5, -1.5, 1.5},
    {1.0, -2.0, 0.25},
};

// (A, B, C, m) derived by hand from the contract with exact rational arithmetic (Python's fractions).
struct CoefficientCase {
  MapParameters p;
  MapCoefficients expected;
};
const std::vector<CoefficientCase> kCoefficientTable = {
    {{0.1, -0.8, 0.5}, {2927339757790823, 3602879701896397, 935362999530796, 2}},
    {{0.0, -0.05, 0.05}, {900719925474099, 900719925474099, 225179981368525, 0}},
    {{-1e-4, -0.05, 0.05}, {900719925474099, 900719925474099, 234187180623266, 0}},
    {{1e-4, -0.05, 0.05}, {900719925474099, 900719925474099, 216172782113784, 0}},
    {{0.5, -1.5, 1.5}, {3377699720527872, 3377699720527872, 656774945658197, 3}},
    {{1.0, -2.0, 0.25}, {1266637395197952, 2251799813685248, 750599937895083, 4}},
};

TEST(FixedPointMap, CoefficientsEqualHandDerivedValues) {
  for (const auto& c : kCoefficientTable) {
    SCOPED_TRACE(testing::Message() << "K=" << c.p.K << " xmin=" << c.p.xmin << " xmax=" << c.p.xmax);
    EXPECT_EQ(computeCoefficients(c.p), c.expected);
    EXPECT_EQ(FixedPointMap(c.p).coefficients(), c.expected);
  }
}

UnitState randomState(std::mt19937_64& rng) { return {rng() >> 12, rng() >> 12}; }

// 10^7 random states in all, spread over the parameter sets: N⁻¹N = 1, J² = 1, JNJ = N⁻¹, bit for bit,
// and the wrap flag of N at z equals that of N⁻¹ at N(z).
TEST(FixedPointMap, IdentitiesHoldBitForBitOnTenMillionStates) {
  constexpr std::uint64_t kStates = 10'000'000;
  const std::uint64_t perSet = kStates / kParameterSets.size() + 1;
  std::uint64_t checked = 0;
  for (std::size_t set = 0; set < kParameterSets.size(); ++set) {
    const FixedPointMap map(kParameterSets[set]);
    std::mt19937_64 rng(20261122 + set);
    std::uint64_t failures = 0;
    for (std::uint64_t i = 0; i < perSet; ++i) {
      const UnitState z = randomState(rng);
      UnitState n = z;
      const bool forwardWrapped = map.forward(n);
      UnitState back = n;
      const bool backwardWrapped = map.backward(back);
      UnitState jj = z;
      FixedPointMap::involution(jj);
      FixedPointMap::involution(jj);
      UnitState jnj = z;
      FixedPointMap::involution(jnj);
      map.forward(jnj);
      FixedPointMap::involution(jnj);
      UnitState inverse = z;
      map.backward(inverse);
      const bool ok = back == z && forwardWrapped == backwardWrapped && jj == z && jnj == inverse &&
                      n.X < kOne && n.Y < kOne && inverse.X < kOne && inverse.Y < kOne;
      if (!ok && ++failures <= 3) ADD_FAILURE() << "identity broken at X=" << z.X << " Y=" << z.Y;
    }
    EXPECT_EQ(failures, 0u) << "parameter set " << set;
    checked += perSet;
  }
  EXPECT_GE(checked, kStates);
}

// An independent N⁻¹: the contract written with signed 128-bit integers and plain division.
UnitState referenceBackward(const MapCoefficients& k, UnitState z, bool& wrapped) {
  using i128 = int128;
  const i128 one = i128{1} << 52;
  const i128 s = i128(z.X) - i128(z.Y) + one / 2;
  const i128 X = ((s % one) + one) % one;
  const i128 G = ((i128(k.A) * ((X * X) / one)) / one - (i128(k.B) * X) / one + k.C) * (i128{1} << k.m);
  const i128 u = i128(z.Y) - G;
  const i128 Y = ((u % one) + one) % one;
  wrapped = s < 0 || s >= one || u < 0 || u >= one;
  return {static_cast<std::uint64_t>(X), static_cast<std::uint64_t>(Y)};
}

TEST(FixedPointMap, BackwardStepAndWrapFlagAgreeWithInt128Reference) {
  for (const auto& p : kParameterSets) {
    const FixedPointMap map(p);
    std::mt19937_64 rng(7);
    std::uint64_t wraps = 0;
    constexpr int kCount = 200'000;
    for (int i = 0; i < kCount; ++i) {
      UnitState z = randomState(rng);
      if (i % 4 == 0) z.X = rng() % 1024;                 // near the edges, where wraps happen
      if (i % 4 == 1) z.Y = kOne - 1 - rng() % 1024;
      bool expectedWrap = false;
      const UnitState expected = referenceBackward(map.coefficients(), z, expectedWrap);
      const bool wrapped = map.backward(z);
      ASSERT_EQ(z, expected);
      ASSERT_EQ(wrapped, expectedWrap);
      wraps += wrapped;
    }
    EXPECT_GT(wraps, 0u);       // both outcomes are exercised
    EXPECT_LT(wraps, kCount + 0u);
  }
}

// The scalar kernels' form of the map (ScalarStep.hpp: one high word per product) computes the same integers
// and the same wraps as fixedPointG/backwardStep/forwardStep, including an m = 9 box.
TEST(FixedPointMap, ScalarStepFormEqualsTheDefinition) {
  std::vector<MapParameters> sets = kParameterSets;
  sets.push_back({1.0, -100.0, 100.0});  // m = 9
  for (const auto& p : sets) {
    const FixedPointMap map(p);
    if (p.xmax == 100.0) {
      ASSERT_EQ(map.coefficients().m, 9);
    }
    const ScalarStep step(map.coefficients());
    std::mt19937_64 rng(11);
    std::uint64_t wraps = 0;
    for (int i = 0; i < 200'000; ++i) {
      UnitState z = randomState(rng);
      if (i % 4 == 0) z.X = rng() % 1024;
      if (i % 4 == 1) z.Y = kOne - 1 - rng() % 1024;
      ASSERT_EQ(step.G(z.X), static_cast<std::uint64_t>(map.G(z.X)));
      UnitState expected = z;
      const bool expectedWrap = map.backward(expected);
      std::uint64_t X = z.X, Y = z.Y, wrap = 0;
      step.backward(X, Y, wrap);
      ASSERT_EQ((UnitState{X, Y}), expected);
      ASSERT_EQ(wrap >= kOne, expectedWrap);
      wraps += expectedWrap;
      UnitState forward = z;
      const bool forwardWrap = map.forward(forward);
      X = z.X;
      Y = z.Y;
      step.forward(X, Y);
      ASSERT_EQ((UnitState{X, Y}), forward);
      X = z.X;
      Y = z.Y;
      wrap = 0;
      step.forward(X, Y, wrap);  // the form with the wrap flag (ScalarLanes.hpp, portraits' Orbits mode)
      ASSERT_EQ((UnitState{X, Y}), forward);
      ASSERT_EQ(wrap >= kOne, forwardWrap);
    }
    EXPECT_GT(wraps, 0u);
  }
}

// The fixed points (∓√K, 0) of Q map to themselves up to the error of the fixed-point G: the two floor
// divisions and the rounding of A, B, C to 52 − m bits lose at most 3.5 units of 2^(m−52) in G, and the
// start point is rounded to the grid; so the image lies within 4 units of the map's resolution 2^(m−52)·L.
TEST(FixedPointMap, FixedPointsMapToThemselvesWithinTheGridResolution) {
  for (const auto& p : kParameterSets) {
    if (p.K <= 0 || std::sqrt(p.K) >= p.xmax) continue;
    const FixedPointMap map(p);
    const long double resolution = std::ldexp(map.gridUnit(), map.coefficients().m);
    for (const long double x0 : {-std::sqrt(static_cast<long double>(p.K)), std::sqrt(static_cast<long double>(p.K))}) {
      for (const bool forward : {true, false}) {
        UnitState z = map.toUnit(x0, 0);
        forward ? map.forward(z) : map.backward(z);
        const PhysicalPoint q = map.toPhysical(z);
        EXPECT_LE(std::fabs(q.x - x0), 4 * resolution) << "K=" << p.K << " x0=" << static_cast<double>(x0);
        EXPECT_LE(std::fabs(q.y), 4 * resolution) << "K=" << p.K << " x0=" << static_cast<double>(x0);
      }
    }
  }
}

TEST(FixedPointMap, UnitAndPhysicalCoordinatesRoundTrip) {
  const FixedPointMap map({0.1, -0.8, 0.5});
  std::mt19937_64 rng(3);
  for (int i = 0; i < 100000; ++i) {
    const UnitState z = randomState(rng);
    const PhysicalPoint p = map.toPhysical(z);
    ASSERT_EQ(map.toUnit(p.x, p.y), z);
  }
  // The corners of the box, and periodic reduction of points outside it.
  EXPECT_EQ(map.toUnit(-0.8L, -0.65L), (UnitState{0, 0}));
  EXPECT_EQ(map.toUnit(-0.8L + 1.3L, -0.65L - 1.3L), (UnitState{0, 0}));
  EXPECT_EQ(map.toUnit(-0.15L, 0.0L), (UnitState{FixedPointMap::kHalf, FixedPointMap::kHalf}));
}

void expectInvalid(const MapParameters& p, const std::string& mention) {
  try {
    FixedPointMap map(p);
    ADD_FAILURE() << "accepted invalid parameters K=" << p.K << " xmin=" << p.xmin << " xmax=" << p.xmax;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what();
    EXPECT_EQ(mapError(p), std::optional<std::string>(e.what()));  // the one check requests start with
  }
  EXPECT_TRUE(validationError(p).has_value() || mention == "too large");
}

TEST(FixedPointMap, EveryInvalidParameterGivesItsError) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  expectInvalid({nan, -0.8, 0.5}, "K = nan must be a finite number");
  expectInvalid({inf, -0.8, 0.5}, "K = inf must be a finite number");
  expectInvalid({0.1, nan, 0.5}, "xmin = nan must be a finite number");
  expectInvalid({0.1, -0.8, -inf}, "xmax = -inf must be a finite number");
  expectInvalid({0.1, -0.8, -0.8}, "xmax = -0.8 must be > xmin = -0.8");
  expectInvalid({0.1, -0.8, -0.9}, "L = xmax − xmin must be > 0");
  expectInvalid({0.1, -0.2, 0.5}, "xmin = -0.2 must be < −√K = -0.31622776601683794");
  expectInvalid({0.1, -0.31622776601683794, 0.5}, "must be < −√K");
  expectInvalid({-1e-4, 0.0, 0.5}, "xmin = 0 must be < 0 when K < 0");
  expectInvalid({0.1, -1000.0, 0.5}, "too large");
  EXPECT_FALSE(validationError({0.1, -0.8, 0.5}).has_value());
  EXPECT_FALSE(validationError({-1e-4, -0.05, 0.05}).has_value());
  EXPECT_FALSE(mapError({0.1, -0.8, 0.5}).has_value());
  EXPECT_FALSE(mapError({1.0, -100.0, 100.0}).has_value());  // m = 9, the largest shift
}

// Issue 12, finding 1: computeCoefficients looped ++m forever (signed overflow, undefined behaviour) once 2L or
// 2(xmin² − K)/L overflowed to infinity: `orbit --K 0.1 --xmin=-1e300 --xmax 0.5`, `--K=-1e308`, `--xmax=1e308`.
TEST(FixedPointMap, HugeBoxOrKIsAnErrorNotAnEndlessLoop) {
  for (const MapParameters p : {MapParameters{0.1, -1e300, 0.5}, MapParameters{-1e308, -0.8, 0.5},
                                MapParameters{0.1, -0.8, 1e308}, MapParameters{0.1, -1.7e308, 1.7e308},
                                MapParameters{1e300, -1e151, 0.5}}) {
    try {
      (void)computeCoefficients(p);
      ADD_FAILURE() << "accepted K = " << p.K << ", xmin = " << p.xmin << ", xmax = " << p.xmax;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_TRUE(what.find("too large") != std::string::npos || what.find("finite") != std::string::npos) << what;
    }
  }
}


// Issue 53, finding 17: K = 1e300 marked xmin ("must be < −√K = -1e+150") though no xmin could do; K is named.
TEST(FixedPointMap, AKNoBoxHoldsIsKsError_Issue53) {
  for (const double K : {1e300, 16384.0}) {
    const std::vector<ParameterError> errors = mapErrors({K, -0.8, 0.5});
    ASSERT_EQ(errors.size(), 1u) << errors.front().message;
    EXPECT_EQ(errors[0].fields, std::vector<std::string>{"K"});
    EXPECT_NE(errors[0].message.find("K = " + shortestDecimal(K) + " is too large: it must be < 16384"), std::string::npos)
        << errors[0].message;
  }
  // Just below, a box holds it: xmin = −127.999 < −√K, and −4 xmin < 512.
  EXPECT_TRUE(mapErrors({16383.0, -127.999, 0.0}).empty()) << mapErrors({16383.0, -127.999, 0.0}).front().message;
  EXPECT_EQ(mapErrors({16383.0, -0.8, 0.5}).front().fields, std::vector<std::string>{"xmin"});
}

// Issue 13, finding 11: messages printed numbers with precision(17), so −0.8 showed as "-0.80000000000000004";
// they now print the shortest text that reads back as the same double.
TEST(FixedPointMap, MessagesPrintShortestRoundTripNumbers) {
  EXPECT_EQ(shortestDecimal(-0.8), "-0.8");
  EXPECT_EQ(shortestDecimal(0.1), "0.1");
  EXPECT_EQ(shortestDecimal(1e30), "1e+30");
  EXPECT_EQ(shortestDecimal(0.30000000000000004), "0.30000000000000004");  // 0.1 + 0.2 is not 0.3
  EXPECT_EQ(std::stod(shortestDecimal(-0.31622776601683794)), -0.31622776601683794);
  EXPECT_EQ(shortestDecimal(std::numeric_limits<double>::infinity()), "inf");
  const auto e = validationError(MapParameters{0.1, -0.8, -0.8});
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->find("0000"), std::string::npos) << *e;
}

// Issue 13, finding 11: a form showed one error at a time because core reported only the first.  Every rule
// is reported, each naming the fields it is about.
TEST(FixedPointMap, EveryViolatedRuleIsReportedWithItsFields) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<ParameterError> errors = mapErrors({inf, 0.6, 0.5});
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].fields, std::vector<std::string>{"K"});
  EXPECT_EQ(errors[1].fields, (std::vector<std::string>{"xmax", "xmin"}));
  // xmin = 0.6 > xmax = 0.5 at K = 0.1: xmin breaks its own rule too, so it is marked with its reason.
  const std::vector<ParameterError> box = validationErrors(MapParameters{0.1, 0.6, 0.5});
  ASSERT_EQ(box.size(), 2u);
  EXPECT_EQ(box[0].fields, std::vector<std::string>{"xmin"});  // first: the rule about xmin alone
  EXPECT_NE(box[0].message.find("xmin = 0.6 must be < −√K"), std::string::npos) << box[0].message;
  EXPECT_EQ(box[1].fields, (std::vector<std::string>{"xmax", "xmin"}));
  EXPECT_TRUE(mapErrors({0.1, -0.8, 0.5}).empty());
  EXPECT_EQ(mapErrors({0.1, -1000.0, 0.5}).size(), 1u);  // the box-size limit, once the rules hold
}
}  // namespace
}  // namespace archipelago
