#include "core/atlas/Atlas.hpp"
#include "core/atlas/AtlasCantori.hpp"
#include "core/atlas/BoxIslandCheck.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <numeric>
#include <tuple>
#include <numbers>
#include <span>
#include <stdexcept>

#include "core/limits/Limits.hpp"
#include "core/manifolds/HyperbolicOrbit.hpp"
#include "core/manifolds/MmpFlux.hpp"
#include "core/manifolds/ManifoldParameterization.hpp"
#include "core/manifolds/PolygonRegion.hpp"
#include "core/manifolds/TurnstileFlux.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/map/OrbitIterator.hpp"
#include "core/measures/BirkhoffAverage.hpp"
#include "core/measures/OrbitMeasures.hpp"
#include "core/measures/RotationNumber.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/periodic/FloquetFrame.hpp"
#include "core/periodic/HyperbolicPartner.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"

namespace archipelago {

namespace {

enum class PointKind { Circle, Chain, Outside };

/// The largest denominator a scan point's rotation is named by (ChainIdentification.hpp's accuracy): an invariant
/// circle's rotation lies within 8 × 10^−digits of such a rational with a probability of a few 10^−3 at 10 digits.
constexpr std::int64_t kClassifyDenominator = 2000;
/// The largest denominator a boundary circle's rotation is proven irrational to (Classifier::rotationProven): at 4 T
/// iterates a circle's rotation is known to ~10⁻¹⁴, and the rationals of denominator ≤ 10⁴ lie ~10⁻⁸ apart, so an
/// invariant circle is taken for one of them with a probability of ~10⁻⁵.
constexpr std::int64_t kProofDenominator = 10000;
/// The largest q of the chains p/q about an island enumerated by their rotation (AtlasBuilder::addFareyChains), the
/// largest period n·q of those about a chain's island (the search's cost grows as q² n: about the island of 13 at
/// K = 0.1, q ≤ 50 took more than 20 minutes), and the spacing of that search along the lines (the MMP code's: it
/// brackets the roots of the chains to period 729).
constexpr std::uint64_t kFareyPeriod = 50;
constexpr std::uint64_t kFareyChainPeriod = 300;
constexpr long double kFareySpacing = 1e-6L;

/// Fundamental domains searched for a chain's primary heteroclinic points (TurnstileRequest::maxDomains): the search
/// of a long chain that has none near its orbit went on for minutes through the automatic limit (a period-150 chain
/// about the island of six); a flux not found within these is reported as such.
constexpr int kFluxDomains = 25;
/// The longest chain whose flux the atlas computes: the search for the primary points costs ~n²·domains² steps of the
/// map (a point of domain k is carried from the series over k·n steps), minutes for n ~ 1000; below the manifolds'
/// own limit.
constexpr int kMaxFluxPeriod = 400;
static_assert(kMaxFluxPeriod <= kMaxManifoldPeriod);
/// A flux is accepted when its two methods agree to this many digits and the lobe is below this share of the area
/// its barrier encloses (the measured ones: 10⁻² at the centre's loop, below 10⁻³ for the chains).
constexpr int kFluxDigits = 6;
constexpr long double kMaxLobeShare = 0.1L;

struct ScanPoint {
  PhysicalPoint point;
  PointKind kind = PointKind::Outside;
  double rotation = 0;
  double digits = 0;
  Rational rational;
};

/// An island to scan: the member c of an elliptic orbit of period n, on a symmetry line.
struct Island {
  PhysicalPoint centre;
  std::uint64_t n = 1;
  int sense = 1;
  smooth::SymmetryLine line = smooth::SymmetryLine::S2;
  long double range = 0;  ///< R: how far along the line (in x) to scan on each side
  long double reach = 0;  ///< how far from c a circle about c may reach (half the distance to the chain's next point)
  std::optional<FloquetFrame> frame;  ///< a thin island's normal-form frame at c (thinIslandFrame), else none
};

/// A thin island's angles are taken in its normal-form frame (issue 50) when the linear map's largest step of the
/// angle of z − c lies within this of half a turn (FloquetFrame::foldMargin): a little way out, where the circles are
/// no longer the eigen-ellipses, steps fold (the margin below which the chains' labels call a step folded,
/// kUnfoldedTurn).  At K = 0.1 about the 2/13 chain's member on S₁ (axis ratio 54, ν = 0.4025) the margin is 0.0019
/// turn and the scan's rotation numbers were garbage beyond 6·10⁻⁵ of c (the island reaches ~10⁻³ there); about its
/// member on S₂ (axis ratio 4.9) 0.021; about the island of six 0.35 and 0.14 (0.0089 and 0.0029 at K = 0.13, residue
/// 0.96); about the centre 0.21 (it is scanned as it was: its angles never fold).
constexpr long double kFrameFoldMargin = 0.05L;

/// The frame at the member c of an elliptic orbit of period n when the island is thin by that measure, else none.
std::optional<FloquetFrame> thinIslandFrame(long double K, PhysicalPoint c, std::uint64_t n) {
  std::optional<FloquetFrame> f = floquetFrame(K, c, static_cast<long>(n));
  if (f && f->foldMargin < kFrameFoldMargin) return f;
  return std::nullopt;
}

class Classifier {
 public:
  Classifier(const AtlasRequest& r, const Island& island)
      : request_(r), island_(island), map_(r.map), centre_(rotationCentreAt(r.map, island.centre, island.sense)) {}

  [[nodiscard]] PhysicalPoint at(long double x) const {
    const auto p = smooth::onLine(island_.line, static_cast<long double>(request_.map.K), x);
    return {p.x, p.y};
  }

  [[nodiscard]] ScanPoint classify(PhysicalPoint p, std::stop_token stop) const {
    ScanPoint s;
    s.point = p;
    if (boxPointError("p", request_.map, s.point)) return s;  // outside the box: outside every island
    RotationRequest m;
    m.map = request_.map;
    m.start = map_.toUnit(s.point.x, s.point.y);
    m.centre = centre_;
    m.power = island_.n;
    m.iterations = request_.iterations;
    m.digitsThreshold = request_.digitsThreshold;
    const RotationMeasurement r = rotation(m, stop);
    s.rotation = r.rotation;
    s.digits = r.digits;
    if (r.verdict != OrbitVerdict::Regular) return s;
    // Rationals up to kClassifyDenominator name chain points whatever the period limit (an orbit of a chain of long
    // period must not pass for a circle); only chains within maxPeriod are followed.
    const auto maxQ = std::max<std::int64_t>(static_cast<std::int64_t>(request_.maxPeriod / island_.n), kClassifyDenominator);
    const std::optional<Rational> q = rationalOfRotation(r.rotation, r.difference, maxQ);
    if (!q) {
      s.kind = PointKind::Circle;
    } else if (q->p != 0) {
      s.kind = PointKind::Chain;
      s.rational = *q;
    }
    return s;
  }

  /// The proof of a circle point's rotation (issue 50): measured again with 4 T iterates per block, it must be regular,
  /// agree with `s`'s within their accuracies, and name no rational of denominator ≤ kProofDenominator within its
  /// own accuracy (an orbit of a chain of long period, or a sticky one, converges slowly to a rational or not at all:
  /// at K = 0.12 an orbit of the 25/143 chain passed the scan's test at T).
  [[nodiscard]] bool rotationProven(const ScanPoint& s, std::stop_token stop) const {
    RotationRequest m;
    m.map = request_.map;
    m.start = map_.toUnit(s.point.x, s.point.y);
    m.centre = centre_;
    m.power = island_.n;
    m.iterations = std::min<std::uint64_t>(4 * request_.iterations, kMaxIterations);
    m.digitsThreshold = request_.digitsThreshold;
    const RotationMeasurement r = rotation(m, stop);
    if (r.verdict != OrbitVerdict::Regular) return false;
    if (std::fabs(r.rotation - s.rotation) > rotationAccuracy(r.difference) + rotationAccuracy(std::pow(10.0, -s.digits)))
      return false;
    return !rationalOfRotation(r.rotation, r.difference, kProofDenominator);
  }

  /// Whether the orbit of p is proven to leave the island: within 2 T applications of Qⁿ it leaves the box or goes
  /// farther from c than the nearest other member of c's orbit (no island of the chain reaches another's centre; at
  /// the centre, twice the distance 2√K to the hyperbolic fixed point).  An orbit that stays is not proven inside: it
  /// may be a sticky orbit of the layer.
  [[nodiscard]] bool leavesIsland(PhysicalPoint p, std::stop_token stop) const {
    if (boxPointError("p", request_.map, p)) return true;
    if (stop.stop_requested()) return false;
    // In unit coordinates (the grid is square): the offset's integer parts subtracted exactly, as measureRotation does.
    const PhysicalPoint c = centre_.units;
    const long double cx = std::floor(c.x), cy = std::floor(c.y);
    const double ix = static_cast<double>(cx), iy = static_cast<double>(cy);
    const double fx = static_cast<double>(c.x - cx), fy = static_cast<double>(c.y - cy);
    const auto far = static_cast<double>(2 * island_.reach / map_.gridUnit());
    const double far2 = far * far;
    bool left = false;
    const PowerOrbitEnd end =
        iteratePower(map_, map_.toUnit(p.x, p.y), island_.n, 2 * request_.iterations, [&](std::uint64_t k, const UnitState& z) {
          if ((k & 1023) == 0 && stop.stop_requested()) return false;
          const double dx = (static_cast<double>(z.X) - ix) - fx, dy = (static_cast<double>(z.Y) - iy) - fy;
          left = dx * dx + dy * dy > far2;
          return !left;
        });
    return end == PowerOrbitEnd::wrapped || left;
  }

  [[nodiscard]] const FixedPointMap& map() const { return map_; }

 private:
  /// The rotation about c under Qⁿ (measureRotation), in a thin island's normal-form frame where it has one.
  [[nodiscard]] RotationMeasurement rotation(RotationRequest m, std::stop_token stop) const {
    if (island_.frame) {
      const auto& B = island_.frame->toNormal;
      m.frame = {static_cast<double>(B.xx), static_cast<double>(B.xy), static_cast<double>(B.yx), static_cast<double>(B.yy)};
    }
    return measureRotation(m, stop);
  }

  const AtlasRequest& request_;
  Island island_;
  FixedPointMap map_;
  RotationCentre centre_;
};

/// The area enclosed by the invariant circle through `start` (Green's theorem on its orbit under Qⁿ ordered by
/// k·ω mod 1), with half the points for the error; wrapped or not winding about the centre: nothing.
struct CircleArea {
  long double area = 0;
  long double error = 0;            ///< |area − area with every other point|
  long double perimeterChange = 0;  ///< |perimeter − perimeter with every other point|, relative
  int points = 0;
  std::vector<PhysicalPoint> curve;  ///< the ordered polygon
};

long double shoelace(const std::vector<PhysicalPoint>& p, std::size_t stride) {
  // About the first vertex, in long double (the areas here are ≥ 1e−12 and the coordinates ≤ 1).
  long double twice = 0;
  const std::size_t m = p.size() / stride;
  for (std::size_t i = 0; i < m; ++i) {
    const PhysicalPoint& a = p[i * stride];
    const PhysicalPoint& b = p[((i + 1) % m) * stride];
    twice += (a.x - p[0].x) * (b.y - p[0].y) - (b.x - p[0].x) * (a.y - p[0].y);
  }
  return std::fabs(twice) / 2;
}

long double perimeter(const std::vector<PhysicalPoint>& p, std::size_t stride) {
  long double sum = 0;
  const std::size_t m = p.size() / stride;
  for (std::size_t i = 0; i < m; ++i) {
    const PhysicalPoint& a = p[i * stride];
    const PhysicalPoint& b = p[((i + 1) % m) * stride];
    sum += std::hypot(b.x - a.x, b.y - a.y);
  }
  return sum;
}

std::optional<CircleArea> circleArea(const FixedPointMap& N, const Island& island, PhysicalPoint start, double omega,
                                     int log2Points) {
  const std::size_t m = std::size_t{1} << log2Points;
  std::vector<std::pair<long double, PhysicalPoint>> points;
  points.reserve(m);
  const auto record = [&](std::size_t k, const UnitState& z) {
    const long double turns = static_cast<long double>(k) * static_cast<long double>(omega);
    points.emplace_back(turns - std::floor(turns), N.toPhysical(z));
  };
  const UnitState z0 = N.toUnit(start.x, start.y);
  record(0, z0);
  // Points 1 … m − 1, and the m-th application's wrap checked as well (an orbit that leaves is not a circle).
  if (iteratePower(N, z0, island.n, m, [&](std::uint64_t k, const UnitState& z) {
        if (k < m) record(k, z);
        return true;
      }) == PowerOrbitEnd::wrapped)
    return std::nullopt;
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<PhysicalPoint> curve;
  curve.reserve(m);
  for (const auto& p : points) curve.push_back(p.second);
  if (clockwiseTurns(curve, island.centre.x, island.centre.y) == 0) return std::nullopt;
  for (const PhysicalPoint& p : curve)  // an island lies within half the distance to the next island of its chain
    if (std::hypot(p.x - island.centre.x, p.y - island.centre.y) > island.reach) return std::nullopt;
  CircleArea a;
  a.area = shoelace(curve, 1);
  a.error = std::fabs(a.area - shoelace(curve, 2));
  const long double length = perimeter(curve, 1);
  a.perimeterChange = std::fabs(length - perimeter(curve, 2)) / length;
  a.points = static_cast<int>(m);
  a.curve = std::move(curve);
  return a;
}

/// The central island on `line`: the elliptic fixed point `centre` (−√K, 0), scanned to 2√K (its distance to the
/// hyperbolic fixed point (√K, 0), whose loop encloses the island).
Island centreIsland(PhysicalPoint centre, long double K, smooth::SymmetryLine line) {
  const long double rootK = std::sqrt(K);
  return {centre, 1, 1, line, 2 * rootK, 2 * rootK, std::nullopt};
}

/// One side of the scan: the classified points, the boundary's bracket and the chains beyond it.
struct SideScan {
  std::vector<ScanPoint> points;
  int lastCircle = -1;  ///< index of the outermost circle point (−1: none)
};

/// A stretch of a ray outwards from an island's centre, scanned for circles (scanSide, provenCircle): its point at
/// parameter s (on a symmetry line s is x, on a straight ray of a thin island's frame the distance from c), from
/// s = `origin` over `range` in the sense of `direction`.
struct ScanRay {
  std::function<PhysicalPoint(long double)> at;
  long double origin = 0, range = 0;
  int direction = 1;
};

/// The ray along the island's line from its centre towards `direction`, over its range.
ScanRay lineScanRay(const Classifier& c, const Island& island, int direction) {
  return {[&c](long double x) { return c.at(x); }, island.centre.x, island.range, direction};
}

/// Step 1 on one ray: `points` points outwards from the ray's origin over its range, classified in parallel.
SideScan scanSide(const Classifier& c, const ScanRay& ray, int points, std::stop_token stop, int threads) {
  SideScan s;
  const auto n = static_cast<std::size_t>(points);
  s.points.resize(n);
  parallelFor(
      n,
      [&](std::size_t i, int) {
        const long double x =
            ray.origin + ray.direction * ray.range * static_cast<long double>(i + 1) / static_cast<long double>(n);
        s.points[i] = c.classify(ray.at(x), stop);
      },
      stop, threads);
  for (std::size_t i = 0; i < n; ++i)
    if (s.points[i].kind == PointKind::Circle) s.lastCircle = static_cast<int>(i);
  return s;
}

/// Candidate circles tried inwards on a ray before giving up, and the largest relative change of the area between
/// 4096 and 8192 points that a circle's polygon may show (a converged invariant circle changes by ~1e−9).
constexpr int kBoundaryTries = 8;
constexpr long double kQuickTolerance = 1e-2L;
constexpr long double kCircleTolerance = 1e-4L;

/// A candidate that is not a circle after all: marked outside; the next circle inwards (or −1).
int dropCircle(SideScan& s, int candidate) {
  s.points[static_cast<std::size_t>(candidate)].kind = PointKind::Outside;
  do --candidate;
  while (candidate >= 0 && s.points[static_cast<std::size_t>(candidate)].kind != PointKind::Circle);
  s.lastCircle = candidate;
  return candidate;
}

/// A ray's boundary circle (step 2 of the header): the circle point, its polygon and the bisection's bracket.
struct ProvenCircle {
  ScanPoint point;          ///< the bisection's inner end, a proven circle point
  CircleArea polygon;       ///< its orbit's polygon (8192 points)
  long double x = 0;        ///< the point's parameter on its ray (on a symmetry line its x)
  long double bracket = 0;  ///< the bisection's last step, signed
  bool lastPoint = false;   ///< circles to the end of the ray: no bracket
};

/// Step 2 on one ray: the outermost circle point of `s` (the scan of `ray`), bisected `bisections` times against its
/// outer neighbour, whose orbit closes into a converged curve about the centre and whose rotation is proven (a sticky
/// chaotic orbit that passed for regular does not: it is marked outside in `s` and the next circle inwards tried,
/// kBoundaryTries times at most); or nothing.
std::optional<ProvenCircle> provenCircle(const Classifier& c, const Island& island, const ScanRay& ray, SideScan& s,
                                         int bisections, std::stop_token stop) {
  const int direction = ray.direction;
  const auto step = ray.range / static_cast<long double>(s.points.size());
  for (int candidate = s.lastCircle, tries = 0; candidate >= 0 && tries < kBoundaryTries;) {
    // A quick look first (1024 points: a circle's polygon is already within 1e−5 of its area there): sticky
    // chaotic orbits beyond the island that passed for regular are dropped without a bisection.
    const ScanPoint& at = s.points[static_cast<std::size_t>(candidate)];
    if (const auto quick = circleArea(c.map(), island, at.point, at.rotation, 10);
        !quick || quick->error > kQuickTolerance * quick->area) {
      candidate = dropCircle(s, candidate);
      continue;
    }
    ++tries;
    long double lo = ray.origin + direction * step * (candidate + 1);
    long double hi = lo + direction * step;
    ScanPoint inner = s.points[static_cast<std::size_t>(candidate)];
    const bool lastPoint = candidate + 1 == static_cast<int>(s.points.size());  // circles to the end of the ray: no bracket
    for (int b = 0; b < bisections && !lastPoint && !stop.stop_requested(); ++b) {
      const long double mid = (lo + hi) / 2;
      const ScanPoint p = c.classify(ray.at(mid), stop);
      if (p.kind == PointKind::Circle) {
        lo = mid;
        inner = p;
      } else {
        hi = mid;
      }
    }
    std::optional<CircleArea> a = circleArea(c.map(), island, inner.point, inner.rotation, 13);
    if (!a || a->error > kCircleTolerance * a->area || a->perimeterChange > kCircleTolerance ||
        !c.rotationProven(inner, stop)) {
      candidate = dropCircle(s, candidate);  // not a circle after all
      continue;
    }
    s.lastCircle = candidate;
    return ProvenCircle{inner, std::move(*a), lo, hi - lo, lastPoint};
  }
  return std::nullopt;
}

std::string number(long double v) { return shortestDecimal(v); }

/// The member of `orbit` on a symmetry line nearest to p (offset below 1e−9), or nothing.
std::optional<std::pair<std::size_t, smooth::SymmetryLine>> memberOnLine(const PeriodicOrbit& orbit, PhysicalPoint p) {
  std::optional<std::pair<std::size_t, smooth::SymmetryLine>> best;
  long double bestDistance = 0;
  for (std::size_t i = 0; i < orbit.points.size(); ++i) {
    const smooth::Point<long double> z{orbit.points[i].x, orbit.points[i].y};
    for (smooth::SymmetryLine line : {smooth::SymmetryLine::S2, smooth::SymmetryLine::S1}) {
      if (std::fabs(smooth::offsetFromLine(line, orbit.K, z)) > 1e-9L) continue;
      const long double d = std::hypot(z.x - p.x, z.y - p.y);
      if (!best || d < bestDistance) {
        best = std::pair{i, line};
        bestDistance = d;
      }
    }
  }
  return best;
}

/// Half the distance from point i of the orbit to the nearest other point.
long double halfSpacing(const PeriodicOrbit& orbit, std::size_t i) {
  long double d = std::numeric_limits<long double>::infinity();
  for (std::size_t j = 0; j < orbit.points.size(); ++j)
    if (j != i) d = std::min(d, std::hypot(orbit.points[j].x - orbit.points[i].x, orbit.points[j].y - orbit.points[i].y));
  return d / 2;
}

long double distance(PhysicalPoint a, PhysicalPoint b) { return std::hypot(a.x - b.x, a.y - b.y); }

/// A ray outwards from an island's centre for the escape search: its point at parameter s (on a symmetry line s is x,
/// on a ray of a thin island's frame the distance from c), s from `from` (the circle's crossing) to `end` in the
/// sense of `direction`, and the first offset tried.
struct EscapeRay {
  std::function<PhysicalPoint(long double)> at;
  long double from = 0, end = 0, firstStep = 0;
  int direction = 1;
};

/// The ray along the island's line from the circle point at x = `circle` towards `direction`, to the line's range.
EscapeRay lineEscapeRay(const Classifier& c, const Island& island, int direction, long double circle) {
  return {lineScanRay(c, island, direction).at, circle, island.centre.x + direction * island.range,
          island.range * 0x1p-20L, direction};
}

/// The straight ray from c along the unit vector `heading`: its point at distance t from c.
std::function<PhysicalPoint(long double)> straightRay(PhysicalPoint c, PhysicalPoint heading) {
  return [c, heading](long double t) { return PhysicalPoint{c.x + t * heading.x, c.y + t * heading.y}; };
}

/// The ray of a thin island's frame along `heading` (frameHeading) from the circle's crossing at distance `crossing`
/// from c to the island's reach.
EscapeRay frameEscapeRay(const Island& island, PhysicalPoint heading, long double crossing) {
  return {straightRay(island.centre, heading), crossing, island.reach, island.reach * 0x1p-20L, 1};
}

/// The nearest point beyond the circle on a ray whose orbit is proven to leave the island (Classifier::leavesIsland):
/// offsets doubling from the ray's first step (2^−20 of its range) until one leaves (the ray's end, the island's
/// reach by construction, if none does), the stretch up to it sampled at kEscapeSamples points (in parallel) for the
/// innermost that leaves, then bisected (kEscapeBisections) against its inner neighbour.  Its distance from the
/// island's centre.
constexpr int kEscapeSamples = 64;
/// The rays of a thin island's area interval, equally spaced in angle in its frame (AtlasBuilder::widestFrameBracket).
constexpr int kFrameRays = 16;
/// Of those, the rays on which circles are sought (AtlasBuilder::seekFrameCircles): every other one.  At K = 0.1,
/// depth 1, periods ≤ 60 (`atlas --K 0.1 --depth 1 --max-period 60`, one run each on shared cores): 80 CPU-s against
/// 110 with all 16 and 69 with 4 (48.5 without the search); the 2/13 island's lower end 6.1399e-5 against 6.1442e-5
/// with 16 and 6.1154e-5 with 4 (the independent circle's area 6.1408e-5, scripts/atlas-validate.py).
constexpr int kFrameCircleRays = 8;
constexpr int kEscapeBisections = 12;
long double escapeRadius(const Classifier& c, const Island& island, const EscapeRay& ray, std::stop_token stop,
                         int threads) {
  const long double circle = ray.from, end = ray.end;
  const int direction = ray.direction;
  long double reach = (end - circle) * direction;
  for (long double d = ray.firstStep; d < reach; d *= 2) {
    if (stop.stop_requested()) break;
    if (c.leavesIsland(ray.at(circle + direction * d), stop)) {
      reach = d;
      break;
    }
  }
  std::vector<char> leaves(kEscapeSamples, 0);
  parallelFor(
      leaves.size(),
      [&](std::size_t i, int) {
        leaves[i] = c.leavesIsland(
            ray.at(circle + direction * reach * static_cast<long double>(i + 1) / kEscapeSamples), stop);
      },
      stop, threads);
  const auto first = std::find(leaves.begin(), leaves.end(), 1);
  const long double k = static_cast<long double>(first - leaves.begin());  // samples inside before it
  long double inside = circle + direction * reach * k / kEscapeSamples;
  long double outside = first == leaves.end() ? end : circle + direction * reach * (k + 1) / kEscapeSamples;
  for (int b = 0; b < kEscapeBisections && first != leaves.end() && !stop.stop_requested(); ++b) {
    const long double mid = (inside + outside) / 2;
    (c.leavesIsland(ray.at(mid), stop) ? outside : inside) = mid;
  }
  return distance(ray.at(outside), island.centre);
}

/// The unit vector along the k-th of kFrameRays directions equally spaced in angle in a thin island's normal-form
/// frame: the image of the frame's direction 2πk / kFrameRays.
PhysicalPoint frameHeading(const FloquetFrame& frame, int k) {
  const long double phi = 2 * std::numbers::pi_v<long double> * k / kFrameRays;
  const PhysicalPoint d = frame.physical({std::cos(phi), std::sin(phi)});
  const long double length = std::hypot(d.x, d.y);
  return {d.x / length, d.y / length};
}

/// Where the ordered polygon `curve` crosses the straight ray from c along the unit vector `heading`: the distance
/// from c of the crossing nearest c (the polygon's edges interpolated; a vertex on the ray counted once, as
/// crossingX does), or nothing.
std::optional<long double> crossingAlong(const std::vector<PhysicalPoint>& curve, PhysicalPoint c, PhysicalPoint heading) {
  const auto side = [&](PhysicalPoint p) { return heading.x * (p.y - c.y) - heading.y * (p.x - c.x); };
  std::optional<long double> best;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const PhysicalPoint a = curve[i], b = curve[(i + 1) % curve.size()];
    const long double fa = side(a), fb = side(b);
    if ((fa > 0) == (fb > 0)) continue;
    const long double w = fa / (fa - fb);
    const long double t = (a.x - c.x + w * (b.x - a.x)) * heading.x + (a.y - c.y + w * (b.y - a.y)) * heading.y;
    if (t > 0 && (!best || t < *best)) best = t;
  }
  return best;
}

/// Where the ordered polygon `curve` crosses the ray from c along `line` towards `direction`: the x of the crossing
/// nearest c (the polygon's edges interpolated), or nothing.
std::optional<long double> crossingX(const std::vector<PhysicalPoint>& curve, long double K, smooth::SymmetryLine line,
                                     PhysicalPoint c, int direction) {
  std::optional<long double> best;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const PhysicalPoint a = curve[i], b = curve[(i + 1) % curve.size()];
    const long double fa = smooth::offsetFromLine(line, K, smooth::Point<long double>{a.x, a.y});
    const long double fb = smooth::offsetFromLine(line, K, smooth::Point<long double>{b.x, b.y});
    if ((fa > 0) == (fb > 0) || fa == fb) continue;
    const long double x = a.x + (b.x - a.x) * fa / (fa - fb);
    if ((x - c.x) * direction <= 0) continue;
    if (!best || std::fabs(x - c.x) < std::fabs(*best - c.x)) best = x;
  }
  return best;
}

/// The island's area as an interval that holds the truth (issue 50): from below, the proven circle's polygon less its
/// convergence; from above, that circle scaled about the centre by the widest ratio, over the rays, of the nearest
/// escaping point's distance to the ray's own outermost circle's (the boundary lies between the two on every ray;
/// the scaled circle holds it where the island's shape between the rays follows its circles').
void settleAreaInterval(AtlasNode& node, long double widest) {
  node.areaLower = std::max<long double>(node.circleArea - node.polygonError, 0);
  node.areaUpper = node.areaUpperRays = widest * widest * node.circleArea + node.polygonError;
  node.area = node.circleArea;
  node.areaError = std::max(node.area - node.areaLower, node.areaUpper - node.area);
}

}  // namespace

std::optional<long double> atlasEyeArea(const AtlasFlux& f, std::uint64_t n) {
  if (!f.found || !f.inner.found || n == 0) return std::nullopt;
  const auto disagreement = [](long double zone, long double digits) {
    return std::isfinite(digits) ? zone * std::pow(10.0L, -digits) : 0.0L;
  };
  const long double band = f.zoneArea - f.inner.zoneArea + disagreement(f.zoneArea, f.zoneDigits) +
                           disagreement(f.inner.zoneArea, f.inner.zoneDigits);
  return band / static_cast<long double>(n);
}

// Settled with the layers (settleLayers), from the separatrices found then.
void capAreaByEye(AtlasNode& node) {
  if (!node.boundaryFound || !(node.areaUpperRays >= node.area)) return;  // NaN: a file from before the interval
  node.areaUpper = node.areaUpperRays;
  const std::optional<long double> eye = atlasEyeArea(node.flux, node.period);
  if (eye && *eye >= node.areaLower && *eye < node.areaUpper) node.areaUpper = std::max(*eye, node.area);
  node.areaError = std::max(node.area - node.areaLower, node.areaUpper - node.area);
}

namespace {

/// The closed curves of a chain's two separatrices' zones (TurnstileFlux::zoneBoundary), for the layers.
struct BarrierZones {
  std::vector<std::vector<PhysicalPoint>> outer, inner;
};

/// `zone`: where the zone's closed curves go (TurnstileFlux::zoneBoundary), for the layers (settleLayers).
/// One separatrix's turnstile (side `side` of the partner's manifolds, or the fixed point's loop), checked: the two
/// methods agree and the lobe is a small part of what it encloses (a partner whose primary points were found far
/// along its manifolds gave a "flux" of half the zone per step).  No silent wrong answer: a failure says why.
SeparatrixFlux separatrixFlux(long double K, const std::optional<PeriodicOrbit>& partner, BranchSide side,
                              std::stop_token stop, std::vector<std::vector<PhysicalPoint>>& zone) {
  SeparatrixFlux f;
  try {
    TurnstileRequest t;
    t.K = K;
    t.orbit = partner;
    t.side = side;
    t.maxDomains = kFluxDomains;
    const TurnstileFlux flux = computeTurnstileFlux(t, {}, stop);
    f.flux = flux.lobeArea;
    f.zoneArea = flux.zoneArea;
    f.fluxDigits = flux.lobeDigits();
    f.zoneDigits = flux.zoneDigits();
    zone = flux.zoneBoundary;
    if (!(f.flux > 0)) f.failure = "zero lobe area";
    else if (f.fluxDigits < kFluxDigits || f.zoneDigits < kFluxDigits)
      f.failure = "the action and the polygon agree to " + number(std::min(f.fluxDigits, f.zoneDigits)) +
                  " digits only (fewer than " + std::to_string(kFluxDigits) + ")";
    else if (!(f.flux < kMaxLobeShare * f.zoneArea))
      f.failure = "lobe area " + number(f.flux) + " is not small against the area it encloses, " + number(f.zoneArea);
    f.found = f.failure.empty();
  } catch (const std::exception& e) {
    f.failure = e.what();
  }
  return f;
}

/// The flux into a chain's resonance zone through its separatrices (issue 50): both sides of the partner's manifolds
/// are computed and the **outer** separatrix is the one that encloses the larger zone about the parent — decided by
/// the zones, not by the label "outward" (at K = 0.12 the 11/63 chain's "outward" side gave the inner separatrix's
/// lobe, zone 0.343767, and "inward" the outer one, zone 0.344536, with a lobe 2.5 times larger).  Where only one
/// side is found it is taken with its label (`outerByZone` false).  At the centre the barrier is the fixed point's
/// loop (no inner side).  `zone`: where the outer and inner zones' closed curves go (TurnstileFlux::zoneBoundary),
/// for the layers (settleLayers).
AtlasFlux chainFlux(long double K, const std::optional<PeriodicOrbit>& chain, std::stop_token stop,
                    BarrierZones& zone) {
  AtlasFlux f;
  SeparatrixFlux outer;
  if (!chain) {
    outer = separatrixFlux(K, std::nullopt, defaultSide(true), stop, zone.outer);
  } else {
    if (chain->period > kMaxFluxPeriod) {
      f.failure = "not computed: period " + std::to_string(chain->period) + " above the atlas's flux limit " +
                  std::to_string(kMaxFluxPeriod) + " (the flux of that chain alone, computed on its own, has no such limit)";
      return f;
    }
    f.partner = findHyperbolicPartner(*chain);
    if (!f.partner) {
      f.failure = "no hyperbolic partner found between the islands";
      return f;
    }
    std::vector<std::vector<PhysicalPoint>> outwardZone, inwardZone;
    SeparatrixFlux outward = separatrixFlux(K, f.partner, BranchSide::Outward, stop, outwardZone);
    SeparatrixFlux inward = separatrixFlux(K, f.partner, BranchSide::Inward, stop, inwardZone);
    f.outerByZone = outward.found && inward.found;
    const bool swap = f.outerByZone ? inward.zoneArea > outward.zoneArea : !outward.found && inward.found;
    outer = swap ? inward : outward;
    f.inner = swap ? outward : inward;
    zone.outer = swap ? inwardZone : outwardZone;
    zone.inner = swap ? outwardZone : inwardZone;
  }
  f.found = outer.found;
  f.failure = outer.failure;
  f.flux = outer.flux;
  f.zoneArea = outer.zoneArea;
  f.fluxDigits = outer.fluxDigits;
  f.zoneDigits = outer.zoneDigits;
  f.layerArea = f.zoneArea;  // until settleLayers subtracts the islands inside
  f.residence = f.found ? static_cast<double>(f.zoneArea / f.flux) : 0;
  return f;
}

/// Rescans of an island's rays near its centre (AtlasBuilder::zoomForBoundary), and the fewest steps of a ray its
/// circles must span for the scan to be taken as resolved.
constexpr int kZooms = 2;
constexpr int kMinCircleSteps = 8;
/// The regions of the barriers' zones, by node (built once: a zone of a long chain has ~10⁵ vertices).
struct ZoneRegions {
  std::map<int, PolygonRegion> outer, inner;
  void add(int node, const BarrierZones& z, const AtlasFlux& f) {
    if (f.found && !z.outer.empty()) outer.emplace(node, PolygonRegion(z.outer));
    if (f.inner.found && !z.inner.empty()) inner.emplace(node, PolygonRegion(z.inner));
  }
  void erase(int node) {
    outer.erase(node);
    inner.erase(node);
  }
};

/// Each barrier's layer: its zone less the atlas's islands inside its curves, and the residence time layer / flux;
/// the same for each chain's inner separatrix (issue 50: the band between it and the next barrier inwards).
void settleLayers(Atlas& atlas, const ZoneRegions& zones) {
  for (const auto& [index, zone] : zones.outer) {
    AtlasFlux& f = atlas.nodes[static_cast<std::size_t>(index)].flux;
    std::tie(f.enclosedIslands, f.enclosedCount) = atlasIslandsInside(atlas, zone);
    f.layerArea = f.zoneArea - f.enclosedIslands;
    f.residence = static_cast<double>(f.layerArea / f.flux);
    refuseEmptyLayer(f);
  }
  for (const auto& [index, zone] : zones.inner) {
    SeparatrixFlux& f = atlas.nodes[static_cast<std::size_t>(index)].flux.inner;
    std::tie(f.enclosedIslands, f.enclosedCount) = atlasIslandsInside(atlas, zone);
    f.layerArea = f.zoneArea - f.enclosedIslands;
    refuseEmptyLayer(f);
  }
  for (AtlasNode& node : atlas.nodes) capAreaByEye(node);
}

constexpr int kMaxScanPoints = 10000;

/// The angle of z − c in `sense` (+1: clockwise), radians.
long double angleAbout(PhysicalPoint z, PhysicalPoint c, int sense) {
  return -sense * std::atan2(z.y - c.y, z.x - c.x);
}

/// Rational{p, q} in lowest terms, or nothing (a cycle of q images that turns p times with gcd(p, q) > 1 is no chain).
std::optional<Rational> chainRational(std::int64_t p, std::int64_t q) {
  if (std::gcd(p, q) != 1) return std::nullopt;
  return Rational{p, q};
}

/// The images' rotation by their order about c (issue 50): a chain p/q is well ordered, z_{kn} the (k·p mod q)-th from
/// z_0 in the sense of the rotation, in any coordinates; p in (−q/2, q/2] (the rotation nearest 0 mod 1, as rotations
/// are measured).  Nothing when two images lie on one ray, they are not well ordered, or (q ≥ 3) they leave a gap of
/// half a turn or more (they do not surround c).
std::optional<Rational> orderRotation(std::span<const PhysicalPoint> images, PhysicalPoint c, int sense) {
  const std::size_t q = images.size();
  const long double twoPi = 2 * std::numbers::pi_v<long double>;
  const long double start = angleAbout(images[0], c, sense);
  std::vector<std::pair<long double, std::size_t>> angles;  // from z_0, in [0, 2π), and k
  for (std::size_t k = 0; k < q; ++k) {
    const long double a = angleAbout(images[k], c, sense) - start;
    angles.emplace_back(a - twoPi * std::floor(a / twoPi), k);
  }
  std::sort(angles.begin(), angles.end());
  std::vector<std::size_t> position(q);
  for (std::size_t r = 0; r < q; ++r) {
    const long double next = r + 1 < q ? angles[r + 1].first : angles[0].first + twoPi;
    const long double gap = next - angles[r].first;
    if (gap == 0 || (q >= 3 && gap >= twoPi / 2)) return std::nullopt;
    position[angles[r].second] = r;
  }
  const std::size_t shift = position[1];
  for (std::size_t k = 0; k < q; ++k)
    if ((position[(k + 1) % q] + q - position[k]) % q != shift) return std::nullopt;
  const auto p = static_cast<std::int64_t>(shift), qq = static_cast<std::int64_t>(q);
  return chainRational(2 * p > qq ? p - qq : p, qq);
}

/// An increment of an angle about an island larger than this (turns) may be a fold: one of more than half a turn
/// read backwards (at K = 0.13 the 2/5 chain's 0.504 about a member of the six, read as −0.496).
constexpr long double kUnfoldedTurn = 0.45L;

/// The images' rotation by the sum of their angles' increments about c over the cycle z_0 → z_n → … → z_0, each taken
/// in (−½, ½] turn; nothing when one of them lies within 1/2 − kUnfoldedTurn of half a turn (it may be folded).
std::optional<Rational> incrementRotation(std::span<const PhysicalPoint> images, PhysicalPoint c, int sense) {
  const std::size_t q = images.size();
  const long double twoPi = 2 * std::numbers::pi_v<long double>;
  long double turns = 0;
  for (std::size_t k = 0; k < q; ++k) {
    const long double step =
        std::remainder(angleAbout(images[(k + 1) % q], c, sense) - angleAbout(images[k], c, sense), twoPi) / twoPi;
    if (std::fabs(step) > kUnfoldedTurn) return std::nullopt;
    turns += step;
  }
  return chainRational(std::llround(turns), static_cast<std::int64_t>(q));
}

/// The rotation p/q about an island's member c of the images z_0, z_n, …, z_{(q−1)n} of a chain of period n·q (Qⁿ fixes
/// c), in `sense` (+1: clockwise; issue 50).  By the images' order about c (orderRotation) and by the sum of their
/// angles' increments (incrementRotation): the increments fold about a long, thin island — at K = 0.13 (the six's
/// residue 0.96) the 2/5 chain about the island of six turns by 0.41, 0.48, 0.49, 0.43 and 0.20 of a turn, twice in
/// five steps, about one member of the six, and by 0.23, 0.48, −0.50, 0.48 and 0.30 about another (a step of 0.504
/// read as −0.496): once, and the scan, whose rotation numbers are such sums, named it 1/5 — while the order is not
/// decided where the chain is not star-shaped about c (the 4/29 chain about the centre at K = 0.1, far out, turns by
/// 0.02 … 0.38 of a turn, four times, but out of order).  Either decides; both must agree.  Nothing — the rotation is
/// not decided here — when neither does, they disagree, or an image is farther than `reach` from c.
std::optional<Rational> rotationAbout(std::span<const PhysicalPoint> images, PhysicalPoint c, int sense,
                                      long double reach) {
  if (images.size() < 2) return std::nullopt;
  for (const PhysicalPoint& z : images)
    if (std::hypot(z.x - c.x, z.y - c.y) > reach || (z.x == c.x && z.y == c.y)) return std::nullopt;
  const std::optional<Rational> byOrder = orderRotation(images, c, sense);
  const std::optional<Rational> byTurns = incrementRotation(images, c, sense);
  if (byOrder && byTurns && *byOrder != *byTurns) return std::nullopt;
  return byOrder ? byOrder : byTurns;
}

/// The images z_0, z_n, …, z_{(q−1)n} under Qⁿ of the member of `chain` (period n·q) nearest c.
std::vector<PhysicalPoint> imagesNear(const PeriodicOrbit& chain, PhysicalPoint c, std::uint64_t n) {
  const std::size_t size = chain.points.size(), first = chain.nearestIndex(c);
  std::vector<PhysicalPoint> images;
  for (std::size_t k = 0; k < size / n; ++k) images.push_back(chain.points[(first + k * n) % size]);
  return images;
}

/// A node as its parent's expansion made it (before its own expansion, stopped midway, filled part of it).
AtlasNode unmeasured(const AtlasNode& n) {
  AtlasNode m;
  m.parent = n.parent;
  m.level = n.level;
  m.period = n.period;
  m.aboutParent = n.aboutParent;
  m.orbit = n.orbit;
  m.centre = n.centre;
  m.onS1 = n.onS1;
  m.sense = n.sense;
  return m;
}

class AtlasBuilder {
 public:
  AtlasBuilder(const AtlasRequest& r, const AtlasProgress& progress, std::stop_token stop)
      : r_(r), progress_(progress), stop_(std::move(stop)), K_(static_cast<long double>(r.map.K)) {}

  Atlas build(const Atlas* resume) {
    const auto started = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(); };
    Atlas atlas;
    atlas.request = r_;
    std::deque<int> queue;
    int done = 0;
    if (resume) {
      // The measured islands are kept; their barriers' zones (not in the files) are computed again for the layers.
      atlas.nodes = resume->nodes;
      atlas.cantori = resume->cantori;
      for (std::size_t i = 0; i < atlas.nodes.size(); ++i) {
        AtlasNode& node = atlas.nodes[i];
        // A file keeps each chain's measured member only: the orbit is found again from it (Newton in __float128).
        if (i == 0) {
          node.orbit = analysePeriodicOrbit(K_, 1, static_cast<quad>(-std::sqrt(K_)), 0, OrbitSymmetry::LineS2);
        } else if (node.orbit.points.size() != node.period) {
          PeriodicOrbitSearch search;
          search.period = static_cast<int>(node.period);
          search.near = node.centre;
          PeriodicOrbit found = findPeriodicOrbit(K_, search, stop_);
          if (found.distanceTo(node.centre) > 1e-9L)
            throw std::invalid_argument("the atlas to resume: node " + std::to_string(i) + "'s orbit (period " +
                                        std::to_string(node.period) + ") is not found again from its centre");
          node.orbit = found.rotatedToStart(found.nearestIndex(node.centre));
        }
        if (!node.measured) {
          queue.push_back(static_cast<int>(i));
          continue;
        }
        ++done;
        if (!node.flux.found) continue;
        BarrierZones zone;
        const AtlasFlux again =
            chainFlux(K_, i == 0 ? std::nullopt : std::optional<PeriodicOrbit>(node.orbit), stop_, zone);
        if (stop_.stop_requested()) break;
        zones_.add(static_cast<int>(i), zone, again);
      }
    } else {
      // The central island: the elliptic fixed point (−√K, 0), on both lines; scanned along S₂.
      AtlasNode root;
      root.orbit = analysePeriodicOrbit(K_, 1, static_cast<quad>(-std::sqrt(K_)), 0, OrbitSymmetry::LineS2);
      root.centre = {-std::sqrt(K_), 0};
      root.sense = 1;
      atlas.nodes.push_back(root);
      queue.push_back(0);
    }
    const int doneBefore = done;
    while (!queue.empty()) {
      // The budget is checked between islands, after at least one: every computation (a resumed one too) progresses.
      if (r_.timeBudget > 0 && done > doneBefore && elapsed() >= r_.timeBudget)
        atlas.stopReason = "time budget of " + shortestDecimal(r_.timeBudget) + " s reached";
      if (stop_.stop_requested()) atlas.stopReason = "stopped";
      if (!atlas.stopReason.empty()) break;
      const int i = queue.front();
      if (progress_) {
        settleLayers(atlas, zones_);
        progress_(atlas, done, "island " + atlasPath(atlas, i));
      }
      std::vector<AtlasNode> children = expand(atlas, i);
      if (stop_.stop_requested()) {
        atlas.stopReason = "stopped";
        atlas.nodes[static_cast<std::size_t>(i)] = unmeasured(atlas.nodes[static_cast<std::size_t>(i)]);
        zones_.erase(i);
        break;
      }
      queue.pop_front();
      atlas.nodes[static_cast<std::size_t>(i)].measured = true;
      for (AtlasNode& child : children) {
        atlas.nodes[static_cast<std::size_t>(i)].children.push_back(static_cast<int>(atlas.nodes.size()));
        atlas.nodes.push_back(std::move(child));
        queue.push_back(static_cast<int>(atlas.nodes.size()) - 1);
      }
      ++done;
    }
    atlas.cancelled = !queue.empty();
    if (atlas.cancelled && atlas.stopReason.empty()) atlas.stopReason = "stopped";
    settleLayers(atlas, zones_);
    if (!atlas.cancelled && r_.cantori) addCantori(atlas, done);
    atlas.seconds = (resume ? resume->seconds : 0) + elapsed();  // every part of a resumed atlas
    if (progress_) progress_(atlas, done, atlas.cancelled ? atlas.stopReason : "done");
    return atlas;
  }

 private:
  /// Points a side: at the last level boundaryPoints (only the boundary is wanted there), else the request's or as
  /// many as `scanSteps` steps of the map allow over all sides, up to kMaxScanPoints: the chains around an island of
  /// short period can be narrow (the 138-chain's islands cross S₁ over 4·10⁻⁵ around the island of six).
  [[nodiscard]] int scanPoints(const AtlasNode& node, std::size_t sides) const {
    if (node.level >= r_.depth) return boundaryPoints(node, sides);
    return static_cast<int>(std::clamp(r_.scanSteps / stepsPerPoint(node, sides), static_cast<double>(r_.scanPoints),
                                       static_cast<double>(kMaxScanPoints)));
  }

  /// Points a side where only the boundary is wanted (the last level's scan, a thin island's frame rays): a quarter of
  /// the request's, fewer, down to 16, where `scanSteps` is short for a long period.
  [[nodiscard]] int boundaryPoints(const AtlasNode& node, std::size_t sides) const {
    const double quarter = std::max(16.0, r_.scanPoints / 4.0);
    return static_cast<int>(r_.scanSteps > 0 ? std::clamp(r_.scanSteps / stepsPerPoint(node, sides), 16.0, quarter)
                                             : quarter);
  }

  /// Steps of the map a point of the scan costs over all `sides` of the island (2 T applications of Qⁿ each).
  [[nodiscard]] double stepsPerPoint(const AtlasNode& node, std::size_t sides) const {
    return 2.0 * static_cast<double>(r_.iterations) * static_cast<double>(node.period) *
           static_cast<double>(std::max<std::size_t>(sides, 1));
  }

  /// The lines an island is scanned along: at the centre S₂ and S₁ (both pass through it), else every member of the
  /// chain's orbit on a symmetry line (its islands are images of each other: any of them is the island).
  std::vector<Island> scanOrigins(const AtlasNode& node, int index) const {
    std::vector<Island> out;
    if (index == 0) {
      for (smooth::SymmetryLine line : {smooth::SymmetryLine::S2, smooth::SymmetryLine::S1})
        out.push_back(centreIsland(node.centre, K_, line));
      return out;
    }
    for (std::size_t i = 0; i < node.orbit.points.size(); ++i) {
      const PhysicalPoint z = node.orbit.points[i];
      for (smooth::SymmetryLine line : {smooth::SymmetryLine::S2, smooth::SymmetryLine::S1})
        if (std::fabs(smooth::offsetFromLine(line, K_, smooth::Point<long double>{z.x, z.y})) <= 1e-9L)
          out.push_back({z, node.period, rotationSense(K_, z, node.period), line, halfSpacing(node.orbit, i),
                         halfSpacing(node.orbit, i), thinIslandFrame(K_, z, node.period)});
    }
    return out;
  }

  /// One ray of an island's scan: its line and direction, its classified points, its outermost proven circle.
  struct Ray {
    Island island;
    int direction = 1;
    SideScan scan;
    std::optional<long double> circleX;  ///< x of the ray's outermost proven circle point
  };
  using RunStart = std::pair<std::size_t, int>;  // (ray, index of the run's first point)
  using OutsideChains = std::map<std::pair<std::int64_t, std::int64_t>, std::vector<RunStart>>;  // p/q → its runs

  /// Fills the island's boundary circle, area and flux, and returns the chains outside it as children: the five steps
  /// of the header (scan, boundary, area, flux, chains).
  std::vector<AtlasNode> expand(Atlas& atlas, int index) {
    AtlasNode& node = atlas.nodes[static_cast<std::size_t>(index)];
    const std::vector<Island> origins = scanOrigins(node, index);
    const int points = scanPoints(node, 2 * origins.size());
    std::vector<Ray> rays = scanRays(origins, points);
    if (stop_.stop_requested()) return {};
    for (const Ray& ray : rays) node.scanRange = std::max(node.scanRange, ray.island.range);
    std::vector<PhysicalPoint> kept;  // the boundary circle's polygon
    findBoundary(rays, node, kept);  // the circles found false are outside for the chains too
    const std::vector<Ray> zoomRays = zoomForBoundary(rays, points, node, kept);
    if (stop_.stop_requested()) return {};
    if (node.boundaryFound) {
      // The lower end first: the upper end is measured against the circle kept.
      seekFrameCircles(rays, boundaryPoints(node, 2 * origins.size()), node, kept);
      settleAreaInterval(node, widestBracket(rays, zoomRays, node, kept));
    }
    measureFlux(node, index);
    if (!node.boundaryFound) {
      node.boundaryFailure = "no invariant circle about the centre within the scan's first step: the island is below "
                             "the scan's resolution";
      node.note = "not followed: no boundary circle";
      return {};
    }
    const OutsideChains outside = sortChains(node, rays);
    if (node.level >= r_.depth) {
      node.note = outside.empty() ? "" : "not followed: depth " + std::to_string(r_.depth) + " reached";
      return {};
    }
    if (node.area < r_.minArea) {
      node.note = "not followed: area below " + number(r_.minArea);
      return {};
    }
    std::vector<AtlasNode> children = chainsOutside(atlas, index, rays, outside);
    if (!stop_.stop_requested()) addFareyChains(atlas, index, rays, children);
    return children;
  }

  /// Step 1: every origin's two rays, scanned.
  std::vector<Ray> scanRays(const std::vector<Island>& origins, int points) {
    std::vector<Ray> rays;
    for (const Island& island : origins)
      for (int direction : {+1, -1}) {
        const Classifier c(r_, island);
        rays.push_back({island, direction, scanSide(c, lineScanRay(c, island, direction), points, stop_, r_.threads),
                        std::nullopt});
        if (stop_.stop_requested()) return rays;
      }
    return rays;
  }

  /// Step 2: the boundary circle on each ray (provenCircle); of all rays the largest area is the outermost circle,
  /// kept in `node`.
  void findBoundary(std::vector<Ray>& set, AtlasNode& node, std::vector<PhysicalPoint>& kept) {
    for (Ray& ray : set) {
      const Classifier c(r_, ray.island);
      if (const auto circle =
              provenCircle(c, ray.island, lineScanRay(c, ray.island, ray.direction), ray.scan, r_.bisections, stop_)) {
        ray.circleX = circle->x;
        if (!node.boundaryFound || circle->polygon.area > node.circleArea) keepBoundary(node, kept, ray.island, *circle);
      }
      if (stop_.stop_requested()) return;
    }
  }

  /// The proven circle found on a ray about `island`'s centre becomes the node's boundary circle.
  void keepBoundary(AtlasNode& node, std::vector<PhysicalPoint>& kept, const Island& island,
                    const ProvenCircle& circle) const {
    const ScanPoint& inner = circle.point;
    const CircleArea& a = circle.polygon;
    kept = a.curve;
    node.boundaryFound = true;
    node.centre = island.centre;  // the member whose island holds the circle, z₀ of the orbit
    node.orbit = node.orbit.rotatedToStart(node.orbit.nearestIndex(island.centre));
    node.boundaryPoint = inner.point;
    node.boundaryRotation = inner.rotation;
    node.boundaryDigits = inner.digits;
    node.gap = circle.lastPoint ? 0 : std::fabs(circle.bracket);
    node.circleArea = a.area;
    node.polygonError = a.error;
    node.areaPoints = a.points;
    if (circle.lastPoint) node.note = "the island reaches the end of the scan (" + number(island.range) + ")";
    else node.note.clear();
  }

  /// Step 2b: an island narrower than the scan's first step shows no circle (or only false ones, orbits of the layer
  /// that passed for regular): the rays are scanned again over their first two steps, up to kZooms times, for its
  /// boundary (the chains outside come from the full rays).  So is an island whose circles span fewer than
  /// kMinCircleSteps steps of every ray: its outermost circles lie between two points (the 138-chain's island:
  /// 3.9·10⁻⁷ at 1000 points a side, 7.7·10⁻⁷ looked at closer); the larger area is kept.  Returns the last zoom's rays.
  std::vector<Ray> zoomForBoundary(const std::vector<Ray>& rays, int points, AtlasNode& node,
                                   std::vector<PhysicalPoint>& kept) {
    auto coarse = [](const std::vector<Ray>& set) {
      return std::all_of(set.begin(), set.end(), [](const Ray& r) { return r.scan.lastCircle + 1 < kMinCircleSteps; });
    };
    std::vector<Ray> zoomRays = rays;
    for (int zoom = 0; zoom < kZooms && (!node.boundaryFound || coarse(zoomRays)) && !stop_.stop_requested(); ++zoom) {
      for (Ray& ray : zoomRays) {
        ray.island.range = 2 * ray.island.range / static_cast<long double>(ray.scan.points.size());
        const Classifier c(r_, ray.island);
        ray.scan = scanSide(c, lineScanRay(c, ray.island, ray.direction), points, stop_, r_.threads);
      }
      findBoundary(zoomRays, node, kept);
    }
    return zoomRays;
  }

  /// Step 3: the bracket's widest ratio over the rays (the kept circle's crossing; on another member's ray the crossing
  /// of the kept circle's image there, keptImageAbout, or that ray's own outermost circle where it lies further out;
  /// and the nearest escaping point beyond); for a
  /// thin island over rays equally spaced in its normal-form frame instead (widestFrameBracket).
  long double widestBracket(const std::vector<Ray>& rays, const std::vector<Ray>& zoomRays, const AtlasNode& node,
                            const std::vector<PhysicalPoint>& kept) {
    if (const auto thin = thinFrame(rays, node))
      if (const auto widest = widestFrameBracket(thin->first, thin->second, kept)) return *widest;
    long double widest = 1;
    std::vector<std::tuple<smooth::SymmetryLine, int, long double, long double>> done;  // line, direction, c.x, c.y
    for (const std::vector<Ray>* set : {&rays, &zoomRays})
      for (const Ray& ray : *set) {
        if (!ray.circleX) continue;
        const auto key = std::tuple{ray.island.line, ray.direction, ray.island.centre.x, ray.island.centre.y};
        if (std::find(done.begin(), done.end(), key) != done.end()) continue;
        done.push_back(key);
        const Classifier c(r_, ray.island);
        long double x = *ray.circleX;
        if (distance(ray.island.centre, node.centre) == 0) {
          if (const auto cross = crossingX(kept, K_, ray.island.line, node.centre, ray.direction)) x = *cross;
        } else if (const auto image = keptImageAbout(kept, node, ray.island)) {
          if (const auto cross = crossingX(*image, K_, ray.island.line, ray.island.centre, ray.direction))
            if (distance(c.at(*cross), ray.island.centre) > distance(c.at(x), ray.island.centre)) x = *cross;
        }
        const long double circle = distance(c.at(x), ray.island.centre);
        const long double escape = escapeRadius(c, ray.island, lineEscapeRay(c, ray.island, ray.direction, x), stop_, r_.threads);
        widest = std::max(widest, escape / circle);
      }
    return widest;
  }

  /// The kept circle about the node's member c, carried to another member `island` of its orbit: Q^j of each of its
  /// points (the smooth map in long double), j the first power that carries c there; nothing when none below the
  /// period does.  Another member's own outermost circle on the lines can lie deep inside the boundary's image there
  /// (issue 50: at K = 0.1, depth 1, the six's upper end was 8.53·10⁻³ against its rays' own circles and is 7.88·10⁻³
  /// against the image, the independent area 6.95·10⁻³); the image is the boundary itself, crossing the line where
  /// the island's circle does.
  std::optional<std::vector<PhysicalPoint>> keptImageAbout(const std::vector<PhysicalPoint>& kept, const AtlasNode& node,
                                                           const Island& island) const {
    const long double tolerance = 1e-6L * island.reach;
    const auto at = [&](smooth::Point<long double> z) {
      return std::hypot(z.x - island.centre.x, z.y - island.centre.y) < tolerance;
    };
    smooth::Point<long double> c{node.centre.x, node.centre.y};
    std::uint64_t power = 0;
    while (!at(c) && ++power < node.period) c = smooth::step(K_, c);
    if (power == node.period) return std::nullopt;
    std::vector<PhysicalPoint> image;
    image.reserve(kept.size());
    for (const PhysicalPoint& p : kept) {
      smooth::Point<long double> z{p.x, p.y};
      for (std::uint64_t j = 0; j < power; ++j) z = smooth::step(K_, z);
      image.push_back({z.x, z.y});
    }
    return image;
  }

  /// Step 3 for a thin island (issue 50; thin about one of its scanned members at least, thinIslandFrame): kFrameRays
  /// straight rays from the kept circle's member c, equally spaced in angle in the normal-form frame at c (each the
  /// image of a direction of that frame), from the kept circle's crossing to the island's reach: the widest ratio of
  /// the nearest escaping point's distance to the crossing's.
  /// Along the lines the rays meet a thin island at two angles of its frame only, and about its other members at
  /// their own outermost circles, which the folded angles kept deep inside (at K = 0.1 the 2/13 island's circle on
  /// S₁ at 6·10⁻⁵ of c, the first escaping point beyond the zoomed ray's end: a ratio of 13).  Nothing when a ray does
  /// not cross the circle within the reach (the lines' rays decide then).
  std::optional<long double> widestFrameBracket(const Island& island, const FloquetFrame& frame,
                                                const std::vector<PhysicalPoint>& kept) {
    const Classifier c(r_, island);
    long double widest = 1;
    for (int k = 0; k < kFrameRays && !stop_.stop_requested(); ++k) {
      const PhysicalPoint heading = frameHeading(frame, k);
      const std::optional<long double> crossing = crossingAlong(kept, island.centre, heading);
      if (!crossing || !(*crossing < island.reach)) return std::nullopt;
      const EscapeRay ray = frameEscapeRay(island, heading, *crossing);
      widest = std::max(widest, escapeRadius(c, island, ray, stop_, r_.threads) / *crossing);
    }
    return widest;
  }

  /// A thin island's kept circle's member (the island of one of its rays) and the normal-form frame there, when one of
  /// the island's scanned members is thin (thinIslandFrame; the frame is taken at the kept member whether it is thin
  /// there or not); else nothing.
  std::optional<std::pair<Island, FloquetFrame>> thinFrame(const std::vector<Ray>& rays, const AtlasNode& node) const {
    const auto thin = [](const Ray& ray) { return ray.island.frame.has_value(); };
    const auto home = [&](const Ray& ray) { return distance(ray.island.centre, node.centre) == 0; };
    const auto homeRay = std::find_if(rays.begin(), rays.end(), home);  // a ray of the kept circle's member
    if (homeRay == rays.end() || std::none_of(rays.begin(), rays.end(), thin)) return std::nullopt;
    const auto frame = floquetFrame(K_, node.centre, static_cast<long>(node.period));
    if (!frame) return std::nullopt;
    return std::pair{homeRay->island, *frame};
  }

  /// Step 2c for a thin island (issue 50): circles beyond the kept one sought on kFrameCircleRays of the kFrameRays
  /// straight rays of its frame (widestFrameBracket's, every other one): on each, `points` points (boundaryPoints: only the boundary is wanted) from the kept
  /// circle's crossing out to the nearest escaping point (escapeRadius: no circle about c lies beyond it), the
  /// outermost circle point bisected and proven as on the lines (provenCircle); one whose polygon encloses more than
  /// the kept circle's becomes the boundary.
  /// Along the lines the bisection stops inside a thin island's boundary (at K = 0.1 the 2/13 island's circle was 27 %
  /// below the independent one: the lines meet it at two angles of its frame per member, and the folded angles keep
  /// the member on S₁'s circles deep inside).  The upper end is measured afterwards, against the circle kept.
  void seekFrameCircles(const std::vector<Ray>& rays, int points, AtlasNode& node, std::vector<PhysicalPoint>& kept) {
    const auto thin = thinFrame(rays, node);
    if (!thin) return;
    const Island& island = thin->first;
    const Classifier c(r_, island);
    for (int k = 0; k < kFrameRays && !stop_.stop_requested(); k += kFrameRays / kFrameCircleRays) {
      const PhysicalPoint heading = frameHeading(thin->second, k);
      const std::optional<long double> crossing = crossingAlong(kept, island.centre, heading);
      if (!crossing || !(*crossing < island.reach)) continue;
      const long double escape =
          escapeRadius(c, island, frameEscapeRay(island, heading, *crossing), stop_, r_.threads);
      if (!(escape > *crossing)) continue;
      const ScanRay ray{straightRay(island.centre, heading), *crossing, escape - *crossing, 1};
      SideScan s = scanSide(c, ray, points, stop_, r_.threads);
      if (const auto circle = provenCircle(c, island, ray, s, r_.bisections, stop_);
          circle && circle->polygon.area > node.circleArea)
        keepBoundary(node, kept, island, *circle);
    }
  }

  /// Step 6 (issue 50): the cantori about each island (AtlasCantori.hpp), once every island is measured (their
  /// layers need the islands inside); kept from a resumed atlas that has them.  A stop leaves the atlas unfinished
  /// (cancelled): a resume computes them.
  void addCantori(Atlas& atlas, int done) {
    // A file from before the islands' and boundary cantori (2026-12-07) holds only the centre's: computed again.
    if (std::any_of(atlas.cantori.begin(), atlas.cantori.end(), [](const AtlasCantorus& c) { return c.boundary; })) return;
    if (progress_) progress_(atlas, done, "cantori about the islands");
    try {
      atlas.cantori = atlasCantori(atlas, stop_);
    } catch (const OperationStopped&) {
      atlas.cantori.clear();
    }
    if (stop_.stop_requested()) {
      atlas.cantori.clear();
      atlas.cancelled = true;
      atlas.stopReason = "stopped";
    }
  }

  /// Step 4: the flux through the chain's separatrix (at the centre: the fixed point (√K, 0)'s loop).  Its zone
  /// encloses the islands of the parent (one per closed curve) or, at the centre, the central island: the layer
  /// between is what an orbit that crossed the barrier moves in.
  void measureFlux(AtlasNode& node, int index) {
    BarrierZones zone;
    node.flux = chainFlux(K_, index == 0 ? std::nullopt : std::optional<PeriodicOrbit>(node.orbit), stop_, zone);
    zones_.add(index, zone, node.flux);
  }

  /// Step 5a: the rationals the rays crossed.  Those inside a ray's last circle, or whose rotation is not beyond the
  /// boundary circle's (counted from the centre's linear rotation ν₀, R = sin²(πν₀): the twist carries the rotation
  /// from ν₀ through the boundary's, so a chain between the two lies inside the boundary even where a ray's own last
  /// circle is further in), are internal chains, listed in the node; those beyond it are returned: the chains outside,
  /// each with the starts of its runs of points (its first point beyond, then each later run, in the rays' order).
  OutsideChains sortChains(AtlasNode& node, const std::vector<Ray>& rays) const {
    OutsideChains outside;
    for (std::size_t k = 0; k < rays.size(); ++k) {
      const SideScan& s = rays[k].scan;
      for (std::size_t i = 0; i < s.points.size(); ++i) {
        const ScanPoint& p = s.points[i];
        if (p.kind != PointKind::Chain || p.rational.q < 2) continue;
        // A chain about c turns in the sense its circles do (an orbit of a ring that encloses c, around the parent,
        // turns the other way about c).
        if ((p.rational.p > 0) != (node.boundaryRotation > 0)) continue;
        if (node.period * static_cast<std::uint64_t>(p.rational.q) > r_.maxPeriod) continue;  // beyond the tree's periods
        if (static_cast<int>(i) < s.lastCircle || !beyondBoundary(node, p.rational)) {
          addInternal(node, p.rational);
        } else {
          std::vector<RunStart>& runs = outside[{p.rational.p, p.rational.q}];
          if (runs.empty() || i == 0 || !sameChainPoint(s.points[i - 1], p)) runs.emplace_back(k, static_cast<int>(i));
        }
      }
    }
    return outside;
  }

  /// Lists `r` among the node's internal rationals (in the order of q, then p) unless it is there.
  static void addInternal(AtlasNode& node, const Rational& r) {
    auto before = [](const Rational& a, const Rational& b) { return a.q != b.q ? a.q < b.q : a.p < b.p; };
    const auto at = std::lower_bound(node.internal.begin(), node.internal.end(), r, before);
    if (at == node.internal.end() || *at != r) node.internal.insert(at, r);
  }

  /// Whether `a` is a chain point of the chain point `b`'s rational (the two in one run).
  static bool sameChainPoint(const ScanPoint& a, const ScanPoint& b) {
    return a.kind == PointKind::Chain && a.rational == b.rational;
  }

  /// The index of the last point of the run of chain points that starts at `first`.
  static int runEnd(const SideScan& s, int first) {
    int last = first;
    while (last + 1 < static_cast<int>(s.points.size()) && sameChainPoint(s.points[last + 1], s.points[first])) ++last;
    return last;
  }

  /// The runs a rational's orbit is sought from, in turn: its first run, then its longest other one.  The first can be
  /// a sticky orbit of the chaotic layer about the chain's islands that passed for regular at T (issue 50: at K = 0.13
  /// the first 1/6 point beyond the centre's boundary on S₁, x = 0.12684, 9.1 digits, a run of one, leaves the island
  /// of six within 3000 steps of Q⁶; the island's own run starts two points further out).
  static std::vector<RunStart> runsToTry(const std::vector<Ray>& rays, const std::vector<RunStart>& runs) {
    std::vector<RunStart> out{runs.front()};
    auto length = [&](const RunStart& r) { return runEnd(rays[r.first].scan, r.second) - r.second; };
    const auto longest = std::max_element(runs.begin() + 1, runs.end(),
                                          [&](const RunStart& a, const RunStart& b) { return length(a) < length(b); });
    if (longest != runs.end()) out.push_back(*longest);
    return out;
  }

  /// The linear rotation ν₀ at the island's centre, in turns per Qⁿ: R = sin²(πν₀).
  static long double linearRotation(const AtlasNode& node) {
    return std::asin(std::sqrt(std::clamp(node.orbit.residue, 0.0L, 1.0L))) / std::numbers::pi_v<long double>;
  }

  /// Whether the rotation p/q about the node's island lies beyond its boundary circle's, counted from the centre's
  /// linear rotation ν₀ (R = sin²(πν₀)) in the sense of the twist; true where no twist is measurable (the rays decide).
  static bool beyondBoundary(const AtlasNode& node, const Rational& r) {
    const long double centreRotation = linearRotation(node);
    const long double boundaryRotation = std::fabs(static_cast<long double>(node.boundaryRotation));
    const long double outwards = boundaryRotation - centreRotation;  // the sign of the twist, outwards
    if (!(std::fabs(outwards) > 1e-9L)) return true;
    const long double rotation = std::fabs(static_cast<long double>(r.p) / static_cast<long double>(r.q));
    return (rotation - boundaryRotation) * outwards > 0;
  }

  /// The rotation of `chain` (period n·q) about the island of period n (issue 50): rotationAbout at the member c of
  /// each ray whose cell holds the chain (its points within twice the ray's reach of c), where it is decided; nothing
  /// when it is decided about none, or two members disagree.
  static std::optional<Rational> chainRotation(const PeriodicOrbit& chain, const std::vector<Ray>& rays,
                                               std::uint64_t n) {
    std::optional<Rational> rotation;
    for (const Ray& ray : rays) {
      const PhysicalPoint c = ray.island.centre;
      const long double reach = 2 * ray.island.reach;
      if (chain.distanceTo(c) > reach) continue;  // the chain lies about another member
      const std::optional<Rational> about = rotationAbout(imagesNear(chain, c, n), c, ray.island.sense, reach);
      if (!about) continue;
      if (rotation && *rotation != *about) return std::nullopt;
      rotation = about;
    }
    return rotation;
  }

  /// Step 5b: the chains outside: the middle of a rational's run of points (runsToTry: its first, else its longest)
  /// gives its elliptic orbit, kept when it is a symmetric chain about this island beyond the boundary not already in
  /// the atlas.  A chain whose own rotation is not beyond the boundary's lies inside the boundary circle: its rotation
  /// is listed as internal (issue 50: at K = 0.1, depth 2, the island of six's run named 1/25 gives the 3/25 chain of
  /// period 150, inside the six's boundary, dropped unlisted before) and the rational's next run is tried.
  std::vector<AtlasNode> chainsOutside(Atlas& atlas, int index, const std::vector<Ray>& rays,
                                       const OutsideChains& outside) {
    AtlasNode& node = atlas.nodes[static_cast<std::size_t>(index)];
    std::vector<AtlasNode> children;
    for (const auto& [pq, runs] : outside)
      for (const auto& [k, first] : runsToTry(rays, runs)) {
        if (stop_.stop_requested()) return {};
        auto found = chainFromRun(node, index, rays, rays[k].scan, first, pq);
        if (!found) continue;
        if (!beyondBoundary(node, *found->first.aboutParent)) {
          addInternal(node, *found->first.aboutParent);
          continue;
        }
        addChain(atlas, std::move(found->first), found->second, children);
        break;
      }
    return children;
  }

  /// The chain about the island that the run of `s` from `first` (named p/q) gives, with the line its member lies on:
  /// the elliptic orbit of period n·q from the run's middle point, when it is a symmetric chain about this island
  /// (beyond the boundary or not: chainsOutside decides).
  using ChainFound = std::optional<std::pair<AtlasNode, smooth::SymmetryLine>>;
  ChainFound chainFromRun(const AtlasNode& node, int index, const std::vector<Ray>& rays, const SideScan& s, int first,
                          const std::pair<std::int64_t, std::int64_t>& pq) const {
    const PhysicalPoint start = s.points[static_cast<std::size_t>((first + runEnd(s, first)) / 2)].point;
    const std::uint64_t period = node.period * static_cast<std::uint64_t>(pq.second);
    AtlasNode child;
    child.parent = index;
    child.level = node.level + 1;
    child.period = period;
    const FixedPointMap N(r_.map);
    const EllipticOrbitGuess guess = ellipticOrbitAround(r_.map, N.toUnit(start.x, start.y), period, r_.iterations);
    // Not an island chain (a chaotic band's mean, a saddle, a sticky orbit that left the island).
    if (!guess.orbit || !guess.orbit->stable()) return std::nullopt;
    const auto member = memberOnLine(*guess.orbit, start);
    if (!member) return std::nullopt;  // not symmetric: the scan cannot measure it (docs/atlas.md)
    child.orbit = guess.orbit->rotatedToStart(member->first);
    child.centre = child.orbit.points.front();
    // The orbit must be a chain about this island: its points in the island's cell, Qⁿ-images of each other, well
    // ordered about the island's member and surrounding it (a chaotic band's elliptic orbit of the period the scan
    // named does not), turning in the sense the scan's points did; its label is its own
    // rotation, not the scan's (issue 50: the scan's increments fold about a long island, chainRotation).  And it
    // must not be a chain already in the atlas (addChain: the same period-247 orbit was named 2/19 and 7/19 about the
    // island of 13 and 1/13 about the island of 19).
    child.aboutParent = chainRotation(child.orbit, rays, node.period);
    const std::optional<Rational>& turned = child.aboutParent;
    if (!turned || (turned->p > 0) != (pq.first > 0)) return std::nullopt;
    return std::pair{std::move(child), member->second};
  }

  /// Adds `child` (its orbit and centre set, its member on `line`) to `children` unless the same chain (its period and
  /// an orbit through its centre) is already in the atlas or among them; whether it was added.
  bool addChain(const Atlas& atlas, AtlasNode child, smooth::SymmetryLine line, std::vector<AtlasNode>& children) const {
    auto same = [&](const AtlasNode& other) {
      return other.period == child.period && other.orbit.distanceTo(child.centre) < 1e-9L;
    };
    if (std::any_of(atlas.nodes.begin(), atlas.nodes.end(), same) || std::any_of(children.begin(), children.end(), same))
      return false;
    child.onS1 = line == smooth::SymmetryLine::S1;
    child.sense = rotationSense(K_, child.centre, child.period);
    children.push_back(std::move(child));
    return true;
  }

  /// Every symmetric chain p/q about the island, q ≤ kFareyPeriod (and period n·q ≤ kFareyChainPeriod about a chain's
  /// island), whose rotation about it lies between the boundary circle's and the barrier's (fareyInterval, issue 50):
  /// for each q the symmetric orbits of period n·q on the lines beyond the boundary (fareyWindows) are found once for
  /// the interval's Farey rationals p/q not yet found (fareyRationals), and each p/q's first that is elliptic and a
  /// chain about the island (its Qⁿ-images turn p times about the member c, well ordered about it) is kept.  At
  /// K = 0.1 the scan stepped over the 4/25 chain about the centre (islands ≈ 7·10⁻⁵ wide along S₁, the scan's step).
  void addFareyChains(const Atlas& atlas, int index, const std::vector<Ray>& rays, std::vector<AtlasNode>& children) {
    const AtlasNode& node = atlas.nodes[static_cast<std::size_t>(index)];
    const auto [lo, hi] = fareyInterval(node);
    if (!(lo < hi)) return;
    const std::vector<LineWindow> windows = fareyWindows(node, index, rays);
    if (windows.empty()) return;
    const std::uint64_t maxPeriod = index == 0 ? r_.maxPeriod : std::min(r_.maxPeriod, kFareyChainPeriod);
    const std::uint64_t maxQ = std::min<std::uint64_t>(kFareyPeriod, maxPeriod / node.period);
    for (std::int64_t q = 2; q <= static_cast<std::int64_t>(maxQ) && !stop_.stop_requested(); ++q) {
      const std::vector<Rational> sought = fareyRationals(index, q, lo, hi, children);
      if (sought.empty()) continue;
      std::vector<PeriodicOrbit> orbits;
      try {
        orbits = findSymmetricPeriodicOrbitsIn(
            K_, static_cast<int>(node.period * static_cast<std::uint64_t>(q)), windows, kFareySpacing, stop_,
            index == 0 ? std::function<bool(PhysicalPoint)>{}
                       : [&](PhysicalPoint z) { return mayBeChainAbout(z, rays, node.period, sought); });
      } catch (const OperationStopped&) {
        return;
      }
      for (const Rational& pq : sought)
        for (const PeriodicOrbit& orbit : orbits)
          if (orbit.stable() && addFareyChain(atlas, index, rays, orbit, pq, children))
            break;  // one elliptic orbit per p/q: its images are the chain
    }
  }

  /// The rotations about the island the Farey step searches (issue 50): from the boundary circle's outwards to the
  /// barrier's, where the windows end (the fixed point (√K, 0) about the centre, the chain's separatrix about a
  /// chain's island).  Outwards is the side the twist leads to, measured from the centre's linear rotation ν₀ to the
  /// boundary's (beyondBoundary); the barrier's orbit is a fixed point of Qⁿ, and the orbits beside it turn ever more
  /// slowly about c — to 0 turns per Qⁿ where the rotation falls outwards (the centre and every island at K = 0.1),
  /// to ½ (a reflection) where it rises.  Not the farthest rotation the scan measured: at K = 0.1 the island of 13's
  /// regular points end at the 7/19 chain on S₁, while its 4/11 chain lies further out, and its rays along S₂ cross
  /// the centre's circles, whose "rotations" about c (0.105, 0.111) are not turns about it.  Empty without a twist.
  static std::pair<long double, long double> fareyInterval(const AtlasNode& node) {
    const long double boundary = std::fabs(static_cast<long double>(node.boundaryRotation));
    const long double outwards = boundary - linearRotation(node);
    if (outwards < -1e-9L) return {0, boundary};
    if (outwards > 1e-9L) return {boundary, 0.5L};
    return {boundary, boundary};
  }

  /// The Farey rationals p/q of (lo, hi), p > 0, that are not yet among the island's chains.
  static std::vector<Rational> fareyRationals(int index, std::int64_t q, long double lo, long double hi,
                                              const std::vector<AtlasNode>& children) {
    std::vector<Rational> out;
    const auto first = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(lo * q)) + 1);  // p/q > lo
    for (std::int64_t p = first; p < hi * q; ++p) {
      const Rational pq{p, q};
      auto known = [&](const AtlasNode& c) { return c.parent == index && c.aboutParent && *c.aboutParent == pq; };
      if (std::gcd(p, q) == 1 && std::none_of(children.begin(), children.end(), known)) out.push_back(pq);
    }
    return out;
  }

  /// The windows of the lines the Farey step searches: at the centre both lines between half the radius of the
  /// island's equal-area disc and the fixed point's distance (the MMP code's annulus); about a chain's island each ray
  /// from its proven circle to the ray's end (the island's cell: half the distance to the chain's next island).
  std::vector<LineWindow> fareyWindows(const AtlasNode& node, int index, const std::vector<Ray>& rays) const {
    if (index == 0) {
      const long double inner = std::sqrt(node.areaLower / std::numbers::pi_v<long double>) / 2;
      return annulusWindows(K_, inner, rays.front().island.reach);
    }
    std::vector<LineWindow> windows;
    for (const Ray& ray : rays) {
      if (!ray.circleX) continue;
      const long double end = ray.island.centre.x + ray.direction * ray.island.range;
      windows.push_back({ray.island.line, std::min(*ray.circleX, end), std::max(*ray.circleX, end)});
    }
    return windows;
  }

  /// Adds a symmetric orbit of period n·q found by the Farey step as the chain p/q about the island when it is one
  /// (isFareyChainAbout), started at its member on a line nearest the point found (at the centre) or nearest the
  /// member c of a ray it is a chain about.  Whether it was added.
  bool addFareyChain(const Atlas& atlas, int index, const std::vector<Ray>& rays, const PeriodicOrbit& orbit,
                     const Rational& pq, std::vector<AtlasNode>& children) const {
    const AtlasNode& node = atlas.nodes[static_cast<std::size_t>(index)];
    if (node.period > 1 && chainRotation(orbit, rays, node.period) != pq) return false;
    for (const Ray& ray : rays) {
      const PhysicalPoint c = ray.island.centre;
      const auto member = memberOnLine(orbit, node.period == 1 ? orbit.points.front() : c);
      if (!member) return false;
      const PeriodicOrbit chain = orbit.rotatedToStart(member->first);
      if (!isFareyChainAbout(chain, ray, node.period, pq)) continue;
      AtlasNode child;
      child.parent = index;
      child.level = node.level + 1;
      child.period = chain.points.size();
      child.aboutParent = pq;
      child.orbit = chain;
      child.centre = chain.points.front();
      return addChain(atlas, std::move(child), member->second, children);
    }
    return false;
  }

  /// The finder's cheap test of a root z on a ray's line, before its quad polish (in a chaotic band most roots are
  /// not chains about the island): z and its Qⁿ-images in long double lie within twice the ray's reach of the ray's
  /// member c and their order about it is one of the `sought` p/q's (rotationAbout, as addFareyChain checks the
  /// polished orbit); the sought share their q.
  bool mayBeChainAbout(PhysicalPoint z, const std::vector<Ray>& rays, std::uint64_t n,
                       const std::vector<Rational>& sought) const {
    for (const Ray& ray : rays) {
      const PhysicalPoint c = ray.island.centre;
      if (distance(z, c) > 2 * ray.island.reach) continue;
      smooth::Point<long double> w{z.x, z.y};
      std::vector<PhysicalPoint> images{z};
      for (std::int64_t k = 1; k < sought.front().q; ++k) {
        for (std::uint64_t i = 0; i < n; ++i) w = smooth::step(K_, w);
        images.push_back({w.x, w.y});
      }
      const std::optional<Rational> about = rotationAbout(images, c, ray.island.sense, 2 * ray.island.reach);
      if (about && std::find(sought.begin(), sought.end(), *about) != sought.end()) return true;
    }
    return false;
  }

  /// Whether `chain` is the chain p/q about the island of period n at the ray's member c: at the centre (n = 1) it
  /// winds p times about c and is well ordered about it; else its Qⁿ-images z_0, z_n, … (z_0 its first point) lie
  /// within twice the ray's reach of c and their order about it is p/q's (rotationAbout).
  static bool isFareyChainAbout(const PeriodicOrbit& chain, const Ray& ray, std::uint64_t n, const Rational& pq) {
    const PhysicalPoint c = ray.island.centre;
    if (n == 1) return chain.windingTurns == pq.p && wellOrdered(chain.points, c);
    std::vector<PhysicalPoint> images;
    for (std::size_t k = 0; k < chain.points.size(); k += n) images.push_back(chain.points[k]);
    return rotationAbout(images, c, ray.island.sense, 2 * ray.island.reach) == pq;
  }

  const AtlasRequest& r_;
  const AtlasProgress& progress_;
  ZoneRegions zones_;  ///< each found flux's zones, by node (settleLayers)
  std::stop_token stop_;
  long double K_;
};

}  // namespace

std::pair<long double, int> atlasIslandsInside(const Atlas& atlas, const PolygonRegion& zone) {
  long double area = 0;
  int count = 0;
  for (const AtlasNode& other : atlas.nodes) {
    if (!other.boundaryFound) continue;
    int inside = 0;
    for (const PhysicalPoint& p : other.orbit.points) inside += zone.contains(p.x, p.y) ? 1 : 0;
    area += static_cast<long double>(inside) * other.area;
    count += inside;
  }
  return {area, count};
}

void refuseEmptyLayer(AtlasFlux& f) {
  if (!f.found || f.layerArea > 0) return;
  f.found = false;
  f.failure = "its zone, " + number(f.zoneArea) + ", is no larger than the " + std::to_string(f.enclosedCount) +
              " islands of the atlas inside it, " + number(f.enclosedIslands) +
              ": the separatrix's curves do not enclose this chain's layer";
}

void refuseEmptyLayer(SeparatrixFlux& f) {
  if (!f.found || f.layerArea > 0 || (f.enclosedCount == 0 && f.layerArea == 0)) return;
  f.found = false;
  f.failure = "its zone, " + number(f.zoneArea) + ", is no larger than the " + std::to_string(f.enclosedCount) +
              " islands of the atlas inside it, " + number(f.enclosedIslands) +
              ": the inner separatrix's curves do not enclose the band inside this chain";
}

std::optional<std::string> validationError(const AtlasRequest& r) {
  MeasureSettings measure;  // the map's and the rotation measurements' rules (0 < K < 1, iterations, threshold)
  measure.map = r.map;
  measure.iterations = r.iterations;
  measure.digitsThreshold = r.digitsThreshold;
  if (auto e = validationError(measure)) return e;
  if (auto e = rangeError("depth", r.depth, 0, kMaxAtlasDepth)) return e;
  if (auto e = rangeError("max period", r.maxPeriod, 1, PeriodicOrbitSearch::kMaxPeriod)) return e;
  if (!(r.minArea >= 0) || !std::isfinite(r.minArea))
    return "min area = " + shortestDecimal(r.minArea) + " must be a finite number ≥ 0";
  if (auto e = rangeError("scan points", r.scanPoints, 16, kMaxScanPoints)) return e;
  if (auto e = realRangeError("scan steps", r.scanSteps, 0, 1e13)) return e;
  if (auto e = rangeError("bisections", r.bisections, 0, 60)) return e;
  if (auto e = threadsError(r.threads)) return e;
  if (auto e = realRangeError("time budget", r.timeBudget, 0, 1e7, "seconds; 0: none")) return e;
  return std::nullopt;
}

std::optional<std::string> atlasRequestError(const AtlasRequest& r) {
  if (auto e = validationError(r)) return e;
  return atlasBoxError(r.map);
}

std::optional<std::string> resumeError(const AtlasRequest& r, const Atlas& a) {
  const AtlasRequest& q = a.request;
  auto differs = [](const char* field, const std::string& was, const std::string& is) {
    return std::optional<std::string>(std::string("the atlas to resume was computed with ") + field + " = " + was +
                                      ", this request has " + is);
  };
  if (q.map.K != r.map.K || q.map.xmin != r.map.xmin || q.map.xmax != r.map.xmax)
    return differs("the map (K, xmin, xmax)",
                   shortestDecimal(q.map.K) + ", " + shortestDecimal(q.map.xmin) + ", " + shortestDecimal(q.map.xmax),
                   shortestDecimal(r.map.K) + ", " + shortestDecimal(r.map.xmin) + ", " + shortestDecimal(r.map.xmax));
  if (q.depth != r.depth) return differs("depth", std::to_string(q.depth), std::to_string(r.depth));
  if (q.maxPeriod != r.maxPeriod) return differs("max period", std::to_string(q.maxPeriod), std::to_string(r.maxPeriod));
  if (q.minArea != r.minArea) return differs("min area", shortestDecimal(q.minArea), shortestDecimal(r.minArea));
  if (q.iterations != r.iterations) return differs("iterations", std::to_string(q.iterations), std::to_string(r.iterations));
  if (q.digitsThreshold != r.digitsThreshold)
    return differs("threshold", shortestDecimal(q.digitsThreshold), shortestDecimal(r.digitsThreshold));
  if (q.scanPoints != r.scanPoints) return differs("scan points", std::to_string(q.scanPoints), std::to_string(r.scanPoints));
  if (q.scanSteps != r.scanSteps) return differs("scan steps", shortestDecimal(q.scanSteps), shortestDecimal(r.scanSteps));
  if (q.bisections != r.bisections) return differs("bisections", std::to_string(q.bisections), std::to_string(r.bisections));
  if (a.nodes.empty() || a.nodes[0].parent != -1) return "the atlas to resume has no central island";
  for (std::size_t i = 1; i < a.nodes.size(); ++i) {
    const AtlasNode& n = a.nodes[i];
    if (n.parent < 0 || static_cast<std::size_t>(n.parent) >= i || !a.nodes[static_cast<std::size_t>(n.parent)].measured)
      return "the atlas to resume is not a tree of measured parents (node " + std::to_string(i) + ")";
  }
  return std::nullopt;
}

Atlas computeAtlas(const AtlasRequest& request, const AtlasProgress& progress, std::stop_token stop,
                   const Atlas* resume) {
  if (auto e = atlasRequestError(request)) throw std::invalid_argument(*e);
  if (resume)
    if (auto e = resumeError(request, *resume)) throw std::invalid_argument(*e);
  return AtlasBuilder(request, progress, std::move(stop)).build(resume);
}

std::optional<BoundaryCircle> centralBoundaryCircle(const AtlasRequest& request, long double range,
                                                    std::stop_token stop) {
  if (auto e = validationError(request)) throw std::invalid_argument(*e);
  const auto K = static_cast<long double>(request.map.K);
  Island island = centreIsland({-std::sqrt(K), 0}, K, smooth::SymmetryLine::S2);
  if (auto e = realIntervalError("range", static_cast<double>(range), 0, true, static_cast<double>(island.range)))
    throw std::invalid_argument(*e);
  island.range = range;
  const Classifier c(request, island);
  const ScanRay ray = lineScanRay(c, island, -1);
  SideScan s = scanSide(c, ray, request.scanPoints, stop, request.threads);
  std::optional<ProvenCircle> circle = provenCircle(c, island, ray, s, request.bisections, stop);
  if (!circle) return std::nullopt;
  return BoundaryCircle{circle->point.point, circle->point.rotation, std::move(circle->polygon.curve)};
}

std::string atlasPath(const Atlas& atlas, int node) {
  std::vector<std::uint64_t> periods;
  for (int i = node; i > 0; i = atlas.nodes.at(static_cast<std::size_t>(i)).parent)
    periods.push_back(atlas.nodes[static_cast<std::size_t>(i)].period);
  if (periods.empty()) return "centre";
  std::string s;
  for (auto it = periods.rbegin(); it != periods.rend(); ++it) s += (s.empty() ? "" : " > ") + std::to_string(*it);
  return s;
}

}  // namespace archipelago
