// The orbit-measure kernels (core/measures/MeasureKernels.hpp): every instruction-set path gives the orbit
// points of the exact map N bit for bit, the exact wrap flags, and the same accumulators bit for bit; a
// measurement split into chunks equals one call.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/kernels/VectorKernels.hpp"
#include "core/measures/MeasureKernels.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/random/CounterRng.hpp"
#include "tests/core/kernels/KernelsUnderTest.hpp"

namespace archipelago {
namespace {

using measures::MeasureLane;
using measures::MeasureSetup;

const MapParameters kBox{0.1, -0.8, 0.5};

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

/// Every field, doubles by their bits (so that −0 and +0, or two NaNs, are told apart).
void expectSameLane(const MeasureLane& a, const MeasureLane& b, const std::string& what) {
  EXPECT_EQ(a.X, b.X) << what;
  EXPECT_EQ(a.Y, b.Y) << what;
  EXPECT_EQ(a.wrapped, b.wrapped) << what;
  for (auto field : {&MeasureLane::hi, &MeasureLane::lo, &MeasureLane::firstBlock, &MeasureLane::vx, &MeasureLane::vy,
                     &MeasureLane::rescale, &MeasureLane::maxNormSq, &MeasureLane::lnNorm, &MeasureLane::sumLn,
                     &MeasureLane::sumY})
    EXPECT_EQ(bits(a.*field), bits(b.*field)) << what << ": " << a.*field << " vs " << b.*field;
}

/// Starts spread over the whole box (sea, islands, and points that leave the box of Q at once), plus a few
/// hand-picked ones: the centre's neighbourhood, the six islands, the edges of the torus.
std::vector<UnitState> starts(std::size_t count) {
  std::vector<UnitState> z;
  const FixedPointMap map(kBox);
  z.push_back(map.toUnit(-0.31622776601683794L + 1e-7L, 0));  // next to the elliptic fixed point
  z.push_back(map.toUnit(0.0509024128L, 0.0L));                 // in one of the six islands
  z.push_back({0, 0});
  z.push_back({fixedpoint::kMask, fixedpoint::kMask});
  z.push_back(rotationCentreUnits(kBox).x > 0 ? UnitState{static_cast<std::uint64_t>(rotationCentreUnits(kBox).x),
                                                          fixedpoint::kHalf}
                                              : UnitState{});
  for (std::size_t i = z.size(); i < count; ++i)
    z.push_back({orbitDraw(0x5EED, 2 * i + 1), orbitDraw(0x5EED, 2 * i + 2)});
  return z;
}

MeasureSetup setupFor(IndicatorKind kind, std::uint64_t T, const BirkhoffWeights& w) {
  MeasureSetup s;
  s.kind = kind;
  s.coefficients = computeCoefficients(kBox);
  s.T = T;
  s.weights = w.g.data();
  s.xmin = kBox.xmin;
  s.unit = std::ldexp(kBox.width(), -FixedPointMap::kBits);
  s.K = kBox.K;
  const PhysicalPoint c = rotationCentreUnits(kBox);
  s.centreX = static_cast<double>(std::floor(c.x));
  s.centreY = static_cast<double>(std::floor(c.y));
  s.centreFracX = static_cast<double>(c.x - std::floor(c.x));
  s.centreFracY = static_cast<double>(c.y - std::floor(c.y));
  return s;
}

std::vector<MeasureLane> lanesFrom(const std::vector<UnitState>& z) {
  std::vector<MeasureLane> lanes(z.size());
  for (std::size_t i = 0; i < z.size(); ++i) {
    lanes[i].X = z[i].X;
    lanes[i].Y = z[i].Y;
  }
  return lanes;
}

constexpr IndicatorKind kAllKinds[] = {IndicatorKind::Dig, IndicatorKind::Rotation, IndicatorKind::Fli,
                                       IndicatorKind::Megno, IndicatorKind::Lyapunov};

TEST(MeasureKernels, EveryPathGivesTheScalarPointsAndSumsBitForBit) {
  constexpr std::uint64_t T = 300;
  const BirkhoffWeights w = birkhoffWeights(T);
  // 77 orbits: full groups of every path and a remainder that leaves vectors partly empty.
  const std::vector<UnitState> z = starts(77);
  for (IndicatorKind kind : kAllKinds) {
    const MeasureSetup setup = setupFor(kind, T, w);
    const MeasureSetup& s = setup;
    const std::uint64_t steps = measures::totalSteps(kind, T);
    std::vector<MeasureLane> reference = lanesFrom(z);
    measures::measureKernelScalar(s, reference, 0, steps);

    // The orbit points are N's: the plain scalar orbit kernel reaches the same states.
    std::vector<UnitState> plain = z;
    iterateOrbitsScalar(s.coefficients, MapDirection::forward, plain, steps, nullptr);
    std::size_t wrappedCount = 0;
    for (std::size_t i = 0; i < z.size(); ++i) {
      ASSERT_EQ(reference[i].X, plain[i].X);
      ASSERT_EQ(reference[i].Y, plain[i].Y);
      // The wrap flag (Dig and Rotation) is FixedPointMap::forward's.
      bool wrapped = false;
      UnitState q = z[i];
      for (std::uint64_t n = 0; n < steps; ++n) wrapped |= forwardStep(s.coefficients, q);
      EXPECT_EQ(reference[i].wrapped, isBirkhoffKind(kind) && wrapped ? 1u : 0u) << i;
      wrappedCount += wrapped;
    }
    EXPECT_GT(wrappedCount, 10u);           // the sample has escaping orbits …
    EXPECT_LT(wrappedCount, z.size() - 5);  // … and orbits that stay

    for (const KernelInfo& k : kerneltests::kernelsUnderTest()) {
      const measures::MeasurePath path = measures::measurePath(k.kind);
      MeasureSetup sk = setup;
      sk.trace = k.orbits;  // the path's own orbit kernel, as OrbitMeasurer gives it (the avx2 accumulation reads it)
      std::vector<MeasureLane> lanes = lanesFrom(z);
      path.kernel(sk, lanes, 0, steps);
      for (std::size_t i = 0; i < z.size(); ++i)
        expectSameLane(lanes[i], reference[i], std::string(k.name) + " " + std::string(toString(kind)) + " orbit " +
                                                   std::to_string(i));
      // In chunks that end anywhere, also across the end of the first block (step T).
      std::vector<MeasureLane> chunked = lanesFrom(z);
      for (std::uint64_t done = 0, chunk = 1; done < steps; chunk = chunk * 3 + 1) {
        const std::uint64_t n = std::min(chunk, steps - done);
        path.kernel(sk, chunked, done, n);
        done += n;
      }
      for (std::size_t i = 0; i < z.size(); ++i)
        expectSameLane(chunked[i], reference[i], std::string(k.name) + " chunked " + std::string(toString(kind)));
    }
  }
}

}  // namespace
}  // namespace archipelago
