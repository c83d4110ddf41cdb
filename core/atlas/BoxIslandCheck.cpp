#include "core/atlas/BoxIslandCheck.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/io/NumberText.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/map/OrbitIterator.hpp"
#include "core/measures/BirkhoffAverage.hpp"
#include "core/measures/ChainIdentification.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/measures/RotationNumber.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/scan/ScanBox.hpp"

namespace archipelago {

namespace {

constexpr int kScanPoints = 64;          // points of S₂ from the centre to −2√K
constexpr int kBisections = 16;          // halvings of the outermost circle's bracket
constexpr std::size_t kOrbitPoints = 4096;  // points of the circle's orbit for its extent
constexpr std::int64_t kCircleDenominator = 2000;  // as the atlas's classification (Atlas.cpp)

/// Whether the orbit through (x, 0) lies on an invariant circle about the centre.
bool isCircle(const MapParameters& box, const FixedPointMap& N, double x) {
  RotationRequest r;
  r.map = box;
  r.start = N.toUnit(x, 0);
  r.centre = centralFixedPoint(box);
  r.iterations = kDefaultIterations;
  r.digitsThreshold = kDefaultDigitsThreshold;
  const RotationMeasurement m = measureRotation(r);
  if (m.verdict != OrbitVerdict::Regular) return false;
  return !rationalOfRotation(m.rotation, m.difference, kCircleDenominator);
}

/// The extent of the orbit through (x, 0), or nothing when it leaves the separatrix's box (a sticky chaotic orbit).
std::optional<CentralIslandExtent> extentOf(const MapParameters& box, const FixedPointMap& N, double x) {
  const double rootK = std::sqrt(box.K);
  CentralIslandExtent e;
  e.found = true;
  e.K = box.K;
  e.crossing = x;
  e.xLeft = e.xRight = x;
  const auto extend = [&](std::uint64_t, const UnitState& z) {
    const PhysicalPoint p = N.toPhysical(z);
    e.xLeft = std::min(e.xLeft, static_cast<double>(p.x));
    e.xRight = std::max(e.xRight, static_cast<double>(p.x));
    e.yMax = std::max(e.yMax, static_cast<double>(std::fabs(p.y)));
    return true;
  };
  if (iteratePower(N, N.toUnit(x, 0), 1, kOrbitPoints, extend) == PowerOrbitEnd::wrapped) return std::nullopt;
  if (e.xLeft < -2 * rootK || e.xRight > rootK) return std::nullopt;  // outside the separatrix (eq. hamb)
  return e;
}

CentralIslandExtent centralIsland(double K) {
  CentralIslandExtent none;
  none.K = K;
  if (!(K > 0 && K < 1)) return none;
  const MapParameters box = scanBox(K);
  const FixedPointMap N(box);
  const double rootK = std::sqrt(K);
  const double step = rootK / kScanPoints;  // from −√K to −2√K
  std::vector<char> circle(kScanPoints + 1, 0);
  parallelFor(kScanPoints, [&](std::size_t i, int) {
    circle[i + 1] = isCircle(box, N, -rootK - step * static_cast<double>(i + 1)) ? 1 : 0;
  });
  for (int last = kScanPoints; last >= 1; --last) {
    if (!circle[static_cast<std::size_t>(last)]) continue;
    double in = -rootK - step * last, out = in - step;
    for (int b = 0; b < kBisections && last < kScanPoints; ++b) {
      const double mid = (in + out) / 2;
      (isCircle(box, N, mid) ? in : out) = mid;
    }
    if (const auto e = extentOf(box, N, in)) return *e;
  }
  return none;
}

std::string fixed(double v) { return io::formatC("%.3f", v); }

}  // namespace

BoxIslandCheck checkBoxAgainstIsland(const MapParameters& map, double Xr) {
  BoxIslandCheck c;
  if (mapError(map) || !(std::isfinite(Xr) && Xr >= 0 && Xr < 1)) return c;  // refused by the parameters' rules
  if (!(map.K > 0 && map.K < 1)) return c;                                       // no elliptic fixed point
  const double rootK = std::sqrt(map.K);
  const double L = map.xmax - map.xmin;
  c.zoneEdge = map.xmin + Xr * L;
  c.loopLeft = -2 * rootK;
  c.loopRight = rootK;
  c.loopDepth = c.zoneEdge - c.loopLeft;
  c.loopCutRight = c.loopRight - map.xmax;
  c.island = centralIsland(map.K);
  const CentralIslandExtent& I = c.island;
  std::vector<std::string> what;
  if (I.found) {
    c.zoneDepth = c.zoneEdge - I.xLeft;
    c.cutLeft = map.xmin - I.xLeft;
    c.cutRight = I.xRight - map.xmax;
    c.cutY = I.yMax - L / 2;
    if (c.cutLeft > 0)
      what.push_back("the box's left edge xmin = " + io::shortestText(map.xmin) + " cuts its boundary circle by " +
                     fixed(c.cutLeft) + " in x");
    if (c.zoneDepth > 0)
      what.push_back("the randomizing zone (x <= xmin + Xr*L = " + fixed(c.zoneEdge) + ") reaches " +
                     fixed(c.zoneDepth) + " into its boundary circle in x");
    if (c.cutRight > 0)
      what.push_back("the box's right edge xmax = " + io::shortestText(map.xmax) + " cuts its boundary circle by " +
                     fixed(c.cutRight) + " in x");
    if (c.cutY > 0)
      what.push_back("the box's height L = " + fixed(L) + " cuts its boundary circle by " + fixed(c.cutY) + " in y");
  }
  if (c.zoneDepth <= 0 && c.loopDepth > 0)
    what.push_back("the randomizing zone (x <= xmin + Xr*L = " + fixed(c.zoneEdge) + ") reaches " +
                   fixed(c.loopDepth) + " into the separatrix loop around it (" + fixed(c.loopLeft) +
                   " <= x <= " + fixed(c.loopRight) + ", eq. hamb)" +
                   (I.found ? ", within " + fixed(-c.zoneDepth) + " of its boundary circle" : std::string()));
  if (c.cutRight <= 0 && c.loopCutRight > 0)
    what.push_back("the box's right edge xmax = " + io::shortestText(map.xmax) + " lies " + fixed(c.loopCutRight) +
                   " inside the loop's hyperbolic point x = sqrt(K)");
  if (what.empty()) return c;
  std::string list;
  for (std::size_t i = 0; i < what.size(); ++i)
    list += (i == 0 ? "" : "; ") + what[i];
  const std::string circle =
      I.found ? " (its boundary circle spans x in [" + fixed(I.xLeft) + ", " + fixed(I.xRight) + "], |y| <= " +
                    fixed(I.yMax) + ")"
              : std::string();
  c.warning = "the box does not hold the central island at K = " + io::shortestText(map.K) + circle + ": " + list +
              ". Orbits trapped in or near the island are randomized or wrapped, so the run is not the paper's "
              "process (appendix B); a box holds it when xmin + Xr*L < " + fixed(c.loopLeft) + " and xmax > " +
              fixed(c.loopRight) + (I.found ? " and L/2 > " + fixed(I.yMax) : std::string()) +
              " (the K scan's box, xmin = -2*sqrt(K) - 0.2, xmax = sqrt(K) + 0.2, does).";
  return c;
}

}  // namespace archipelago
