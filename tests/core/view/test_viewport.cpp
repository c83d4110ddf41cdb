// Viewport: exact centre, zoom and pan maths, and clear errors for bad views.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/view/DeepestZoom.hpp"
#include "core/view/Viewport.hpp"

namespace archipelago {
namespace {

const MapParameters kPaper{0.1, -0.8, 0.5};  // §5

std::string errorOf(const PhysicalRect& r) {
  try {
    (void)Viewport::fromPhysical(kPaper, r);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(Viewport, WholeBoxCoversTheBox) {
  const Viewport v;
  EXPECT_EQ(v.centre(), (UnitState{FixedPointMap::kHalf, FixedPointMap::kHalf}));
  const PhysicalRect r = v.physical(kPaper);
  EXPECT_NEAR(static_cast<double>(r.x0), -0.8, 1e-15);
  EXPECT_NEAR(static_cast<double>(r.x1), 0.5, 1e-15);
  EXPECT_NEAR(static_cast<double>(r.y0), -0.65, 1e-15);
  EXPECT_NEAR(static_cast<double>(r.y1), 0.65, 1e-15);
  EXPECT_EQ(Viewport::fromPhysical(kPaper, r), v);
}

TEST(Viewport, PhysicalBoundsRoundTripAtDeepZoom) {
  // A view 1e-10 wide: its bounds survive the trip through the exact centre to within a grid unit.
  const PhysicalRect r{-0.3395897609751681L, -0.3395897608751681L, 0.2624408178962272L, 0.2624408179962272L};
  const Viewport v = Viewport::fromPhysical(kPaper, r);
  const long double unit = std::ldexp(1.3L, -52);
  EXPECT_NEAR(static_cast<double>(v.widthUnits() * unit), static_cast<double>(r.x1 - r.x0), 1e-19);  // long double rounding of (x − xmin)/L
  const PhysicalRect back = v.physical(kPaper);
  EXPECT_LE(std::fabs(back.x0 - r.x0), unit);
  EXPECT_LE(std::fabs(back.x1 - r.x1), unit);
  EXPECT_LE(std::fabs(back.y0 - r.y0), unit);
  EXPECT_LE(std::fabs(back.y1 - r.y1), unit);
}

TEST(Viewport, BadViewsGiveClearErrors) {
  const long double nan = std::numeric_limits<long double>::quiet_NaN();
  EXPECT_NE(errorOf({0.1L, 0.1L, 0, 0.1L}).find("width x1 - x0 = 0 must be > 0"), std::string::npos);
  EXPECT_NE(errorOf({0.2L, 0.1L, 0, 0.1L}).find("width x1 - x0 = -0.1"), std::string::npos);
  EXPECT_NE(errorOf({0, 0.1L, 0.1L, 0.05L}).find("height y1 - y0"), std::string::npos);
  EXPECT_NE(errorOf({nan, 0.1L, 0, 0.1L}).find("x0 = nan must be a finite number"), std::string::npos);
  EXPECT_NE(errorOf({0, 0.1L, 0, std::numeric_limits<long double>::infinity()}).find("y1 = inf must be a finite"),
            std::string::npos);
  EXPECT_NE(errorOf({0.4L, 0.6L, 0, 0.1L}).find("is not inside the box"), std::string::npos);
  EXPECT_NE(errorOf({-0.9L, -0.7L, 0, 0.1L}).find("is not inside the box"), std::string::npos);
  EXPECT_NE(errorOf({0, 0.1L, 0.6L, 0.7L}).find("is not inside the box"), std::string::npos);
  EXPECT_NE(errorOf({0, 1e-14L, 0, 1e-14L}).find("below the resolution limit"), std::string::npos);
  EXPECT_EQ(errorOf({0, 0.1L, 0, 0.1L}), "");  // a valid view
  EXPECT_THROW((void)Viewport::fromUnits({FixedPointMap::kHalf, 10}, 4096, 4096), std::invalid_argument);
  EXPECT_THROW((void)Viewport::fromUnits({FixedPointMap::kHalf, FixedPointMap::kHalf}, 0, 4096),
               std::invalid_argument);
}

TEST(Viewport, ZoomAboutAPointKeepsItsPlace) {
  Viewport v;
  const long double dx = 0.3L * v.widthUnits(), dy = -0.2L * v.heightUnits();
  const long double px = static_cast<long double>(v.centre().X) + dx;
  const long double py = static_cast<long double>(v.centre().Y) + dy;
  for (int i = 0; i < 30; ++i) {  // 2^30 deep, the point stays at the same fraction of the view
    const long double fx = (px - static_cast<long double>(v.centre().X)) / v.widthUnits() + 0.5L;
    const long double fy = (py - static_cast<long double>(v.centre().Y)) / v.heightUnits() + 0.5L;
    v = v.zoomedAboutFraction(fx, fy, 2);
    const long double gx = (px - static_cast<long double>(v.centre().X)) / v.widthUnits() + 0.5L;
    EXPECT_NEAR(static_cast<double>(gx), 0.8, static_cast<double>(1 / v.widthUnits()) + 1e-12);
    const long double gy = (py - static_cast<long double>(v.centre().Y)) / v.heightUnits() + 0.5L;
    EXPECT_NEAR(static_cast<double>(gy), 0.3, static_cast<double>(1 / v.heightUnits()) + 1e-12);
  }
  EXPECT_EQ(v.widthUnits(), std::ldexp(1.0L, 22));
}

TEST(Viewport, ZoomAboutTheCentreKeepsItExactly) {
  const Viewport start = Viewport::fromUnits({1234567890123456, 2345678901234567}, 1e12L, 1e12L);
  Viewport v = start;
  for (int i = 0; i < 40; ++i) v = v.zoomedAbout(0, 0, 1.7L);
  EXPECT_EQ(v.centre(), start.centre());
  EXPECT_EQ(v.widthUnits(), Viewport::kMinSizeUnits);  // clamped at the resolution limit
}

TEST(Viewport, ZoomOutAndPanStayInsideTheBox) {
  const Viewport corner = Viewport::fromPhysical(kPaper, {0.4L, 0.5L, 0.55L, 0.65L});
  const Viewport out = corner.zoomedAbout(0, 0, 0.25L);
  const PhysicalRect r = out.physical(kPaper);
  const long double unit = std::ldexp(1.3L, -52);
  EXPECT_LE(r.x1, 0.5L + unit);
  EXPECT_LE(r.y1, 0.65L + unit);
  EXPECT_NEAR(static_cast<double>(r.x1 - r.x0), 0.4, 1e-12);
  const Viewport far = corner.panned(10, -0.5L);
  EXPECT_LE(far.physical(kPaper).x1, 0.5L + unit);
  EXPECT_NEAR(static_cast<double>(far.physical(kPaper).y0), 0.5, 1e-12);
  EXPECT_EQ(Viewport().zoomedAbout(0, 0, 0.5L), Viewport());  // cannot be larger than the box
  EXPECT_EQ(corner.zoomedAbout(0, 0, std::numeric_limits<long double>::quiet_NaN()), corner);
}

TEST(Viewport, CroppedToARubberBand) {
  const Viewport v;
  const Viewport c = v.cropped(0.25L, 0.75L, 0.5L, 0.625L);
  EXPECT_EQ(c.widthUnits(), v.widthUnits() / 2);
  EXPECT_EQ(c.heightUnits(), v.heightUnits() / 8);
  EXPECT_EQ(c.centre().X, FixedPointMap::kHalf);
  EXPECT_EQ(c.centre().Y, FixedPointMap::kHalf + FixedPointMap::kOne / 16);
  EXPECT_EQ(v.cropped(0.5L, 0.5L, 0, 1), v);  // empty: unchanged
}

TEST(Viewport, TheDeepestZoomIsKnownAndSaysWhy_Issue53Finding7) {
  const MapParameters map{0.1, -0.8, 0.5};
  Viewport v;
  EXPECT_FALSE(atDeepestZoom(v));
  for (int i = 0; i < 60; ++i) v = v.zoomedAboutFraction(0.5L, 0.5L, 2);
  EXPECT_TRUE(atDeepestZoom(v));
  EXPECT_EQ(v.zoomedAboutFraction(0.5L, 0.5L, 2), v);
  const std::string note = deepestZoomNote(map);
  EXPECT_NE(note.find("1024 grid cells (3e-13) wide"), std::string::npos) << note;
  EXPECT_NE(note.find("2^52"), std::string::npos) << note;
}

}  // namespace
}  // namespace archipelago
