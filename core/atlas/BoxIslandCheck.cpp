#include "core/atlas/BoxIslandCheck.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/atlas/Atlas.hpp"
#include "core/io/NumberText.hpp"
#include "core/measures/BirkhoffAverage.hpp"
#include "core/scan/ScanBox.hpp"

namespace archipelago {

namespace {

constexpr int kScanPoints = 64;  // points of S₂ from the centre to −2√K
constexpr int kBisections = 16;  // halvings of the outermost circle's bracket

/// The extent of the boundary circle's polygon.
CentralIslandExtent extentOf(const BoundaryCircle& circle, double K) {
  CentralIslandExtent e;
  e.found = true;
  e.K = K;
  e.crossing = static_cast<double>(circle.point.x);
  e.rotation = circle.rotation;
  e.xLeft = e.xRight = e.crossing;
  for (const PhysicalPoint& p : circle.curve) {
    e.xLeft = std::min(e.xLeft, static_cast<double>(p.x));
    e.xRight = std::max(e.xRight, static_cast<double>(p.x));
    e.yMax = std::max(e.yMax, static_cast<double>(std::fabs(p.y)));
  }
  return e;
}

/// The island's boundary circle by the atlas's method (centralBoundaryCircle) at the check's coarse resolution, in
/// the K scan's box, so that the island is measured on Q, not on the run's Q*.
CentralIslandExtent centralIsland(double K) {
  CentralIslandExtent none;
  none.K = K;
  if (!(K > 0 && K < 1)) return none;
  AtlasRequest r;
  r.map = scanBox(K);
  r.iterations = kDefaultIterations;
  r.digitsThreshold = kDefaultDigitsThreshold;
  r.scanPoints = kScanPoints;
  r.bisections = kBisections;
  const std::optional<BoundaryCircle> circle = centralBoundaryCircle(r, std::sqrt(static_cast<long double>(K)));
  return circle ? extentOf(*circle, K) : none;
}

std::string fixed(double v) { return io::formatC("%.3f", v); }

/// What the box's edges cut of the boundary circle (the check's cutLeft, cutRight, cutY), one phrase each.
std::vector<std::string> circleCuts(const BoxIslandCheck& c, const MapParameters& map) {
  std::vector<std::string> what;
  if (!c.island.found) return what;
  if (c.cutLeft > 0)
    what.push_back("the box's left edge xmin = " + io::shortestText(map.xmin) + " cuts its boundary circle by " +
                   fixed(c.cutLeft) + " in x");
  if (c.cutRight > 0)
    what.push_back("the box's right edge xmax = " + io::shortestText(map.xmax) + " cuts its boundary circle by " +
                   fixed(c.cutRight) + " in x");
  if (c.cutY > 0)
    what.push_back("the box's height L = " + fixed(map.xmax - map.xmin) + " cuts its boundary circle by " +
                   fixed(c.cutY) + " in y");
  return what;
}

/// The right edge inside the loop's hyperbolic point, when it does not already cut the circle.
void addLoopCutRight(const BoxIslandCheck& c, const MapParameters& map, std::vector<std::string>& what) {
  if (c.cutRight <= 0 && c.loopCutRight > 0)
    what.push_back("the box's right edge xmax = " + io::shortestText(map.xmax) + " lies " + fixed(c.loopCutRight) +
                   " inside the loop's hyperbolic point x = sqrt(K)");
}

std::string joined(const std::vector<std::string>& what) {
  std::string list;
  for (std::size_t i = 0; i < what.size(); ++i) list += (i == 0 ? "" : "; ") + what[i];
  return list;
}

std::string circleExtent(const CentralIslandExtent& I) {
  return I.found ? " (its boundary circle spans x in [" + fixed(I.xLeft) + ", " + fixed(I.xRight) + "], |y| <= " +
                       fixed(I.yMax) + ")"
                 : std::string();
}

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
  if (I.found) {
    c.zoneDepth = c.zoneEdge - I.xLeft;
    c.cutLeft = map.xmin - I.xLeft;
    c.cutRight = I.xRight - map.xmax;
    c.cutY = I.yMax - L / 2;
  }
  std::vector<std::string> what = circleCuts(c, map);
  if (c.zoneDepth > 0)
    what.insert(what.begin() + (c.cutLeft > 0 ? 1 : 0),
                "the randomizing zone (x <= xmin + Xr*L = " + fixed(c.zoneEdge) + ") reaches " + fixed(c.zoneDepth) +
                    " into its boundary circle in x");
  if (c.zoneDepth <= 0 && c.loopDepth > 0)
    what.push_back("the randomizing zone (x <= xmin + Xr*L = " + fixed(c.zoneEdge) + ") reaches " +
                   fixed(c.loopDepth) + " into the separatrix loop around it (" + fixed(c.loopLeft) +
                   " <= x <= " + fixed(c.loopRight) + ", eq. hamb)" +
                   (I.found ? ", within " + fixed(-c.zoneDepth) + " of its boundary circle" : std::string()));
  addLoopCutRight(c, map, what);
  if (what.empty()) return c;
  c.warning = "the box does not hold the central island at K = " + io::shortestText(map.K) + circleExtent(I) + ": " +
              joined(what) +
              ". Orbits trapped in or near the island are randomized or wrapped, so the run is not the paper's "
              "process (appendix B); a box holds it when xmin + Xr*L < " + fixed(c.loopLeft) + " and xmax > " +
              fixed(c.loopRight) + (I.found ? " and L/2 > " + fixed(I.yMax) : std::string()) +
              " (the K scan's box, xmin = -2*sqrt(K) - 0.2, xmax = sqrt(K) + 0.2, does).";
  return c;
}

std::optional<std::string> atlasBoxError(const MapParameters& map) {
  const BoxIslandCheck c = checkBoxAgainstIsland(map, 0);  // no randomizing zone: the atlas iterates Q* alone
  std::vector<std::string> what = circleCuts(c, map);
  if (c.cutLeft <= 0 && c.loopDepth > 0)
    what.push_back("the box's left edge xmin = " + io::shortestText(map.xmin) + " lies " + fixed(c.loopDepth) +
                   " inside the separatrix loop around it");
  addLoopCutRight(c, map, what);
  if (what.empty()) return std::nullopt;
  const MapParameters box = scanBox(map.K);
  return "the box does not hold the central island at K = " + io::shortestText(map.K) + circleExtent(c.island) +
         ": " + joined(what) + ". The atlas maps the island of Q and its chains out to the separatrix loop around it (" +
         fixed(c.loopLeft) + " <= x <= " + fixed(c.loopRight) + ", eq. hamb); in this box their orbits wrap round, "
         "and the circles and chains it would find are not Q's. The K scan's box (xmin = -2*sqrt(K) - 0.2 = " +
         fixed(box.xmin) + ", xmax = sqrt(K) + 0.2 = " + fixed(box.xmax) + ") holds it.";
}

}  // namespace archipelago
