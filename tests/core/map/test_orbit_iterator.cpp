// The one orbit loop (issue 35, item 4): the CLI's `orbit`, Python's orbit(), the GUI's launched orbits and the
// overlays iterate here, with the one length limit.  Checked against FixedPointMap's own steps, and N⁻¹ against N.
#include <gtest/gtest.h>

#include <vector>

#include "core/map/OrbitIterator.hpp"
#include "core/portrait/MapOverlays.hpp"

namespace archipelago {
namespace {

const MapParameters kPaperBox{0.1, -0.8, 0.5};

TEST(OrbitIterator, VisitsTheStartThenEachStepOfTheMap) {
  const OrbitRequest r = orbitRequestAt(kPaperBox, 0.3L, 0.01L, 5000);
  const FixedPointMap N(kPaperBox);
  UnitState z = r.start;
  std::uint64_t visits = 0, wraps = 0;
  iterateOrbit(r, [&](std::uint64_t step, const UnitState& s, bool wrapped) {
    EXPECT_EQ(step, visits);
    if (step > 0) {
      const bool w = N.forward(z);
      EXPECT_EQ(w, wrapped);
      wraps += w;
    } else {
      EXPECT_FALSE(wrapped);
    }
    EXPECT_EQ(s.X, z.X);
    EXPECT_EQ(s.Y, z.Y);
    ++visits;
  });
  EXPECT_EQ(visits, 5001u);
  EXPECT_GT(wraps, 0u);  // (0.3, 0.01) lies in the sea: the test sees the wrap flag
}

TEST(OrbitIterator, BackwardRetracesForward) {
  OrbitRequest r = orbitRequestAt(kPaperBox, -0.25L, 0.02L, 1000);
  UnitState end;
  iterateOrbit(r, [&](std::uint64_t, const UnitState& s, bool) { end = s; });
  OrbitRequest back = r;
  back.start = end;
  back.backward = true;
  UnitState start;
  iterateOrbit(back, [&](std::uint64_t, const UnitState& s, bool) { start = s; });
  EXPECT_EQ(start.X, r.start.X);
  EXPECT_EQ(start.Y, r.start.Y);
}

TEST(OrbitIterator, StopsWhenTheVisitSaysSo) {
  std::uint64_t visits = 0;
  iterateOrbit(orbitRequestAt(kPaperBox, 0, 0, 100), [&](std::uint64_t step, const UnitState&, bool) {
    ++visits;
    return step < 9;
  });
  EXPECT_EQ(visits, 10u);
}

TEST(OrbitIterator, TheOneLengthLimit) {
  OrbitRequest r = orbitRequestAt(kPaperBox, 0, 0, limits::kOrbitLength);
  EXPECT_EQ(validationError(r), std::nullopt);
  r.steps = limits::kOrbitLength + 1;
  EXPECT_EQ(validationError(r), "steps = 100000001 must lie in [0, 100000000]");
  EXPECT_THROW(iterateOrbit(r, [](std::uint64_t, const UnitState&, bool) {}), std::invalid_argument);
  EXPECT_THROW((void)traceOrbit(kPaperBox, 0, 0, limits::kOrbitLength + 1), std::invalid_argument);
  r.steps = 10;
  r.start.X = FixedPointMap::kOne;
  EXPECT_NE(validationError(r), std::nullopt);
}

TEST(OrbitIterator, TraceOrbitIsTheLoopInPhysicalCoordinates) {
  const FixedPointMap N(kPaperBox);
  const std::vector<PhysicalPoint> forward = traceOrbit(kPaperBox, -0.25L, 0.02L, 200);
  const std::vector<PhysicalPoint> backward = traceOrbit(kPaperBox, -0.25L, 0.02L, 200, true);
  ASSERT_EQ(forward.size(), 201u);
  ASSERT_EQ(backward.size(), 201u);
  EXPECT_EQ(forward[0].x, backward[0].x);
  UnitState z = N.toUnit(-0.25L, 0.02L);
  for (int i = 0; i < 200; ++i) N.backward(z);
  EXPECT_EQ(backward[200].x, N.toPhysical(z).x);
  EXPECT_EQ(backward[200].y, N.toPhysical(z).y);
}

}  // namespace
}  // namespace archipelago
