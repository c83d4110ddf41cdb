#include "core/periodic/IslandChain.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

/// The q-quantile (0 ≤ q ≤ 1) of v, reordering v.
long double quantile(std::vector<long double>& v, long double q) {
  const auto k = static_cast<std::size_t>(std::lround(q * static_cast<long double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

/// Points z_{phase + k·lag}, at most `limit` of them, evenly spaced in k.
std::vector<PhysicalPoint> subsequence(std::span<const PhysicalPoint> segment, std::size_t lag, std::size_t phase,
                                       std::size_t limit) {
  const std::size_t count = (segment.size() - phase + lag - 1) / lag;
  const std::size_t take = std::min(count, limit);
  std::vector<PhysicalPoint> points;
  points.reserve(take);
  for (std::size_t i = 0; i < take; ++i) {
    const std::size_t k = take == count ? i : i * (count - 1) / (take - 1);
    points.push_back(segment[phase + k * lag]);
  }
  return points;
}

PhysicalPoint coordinateMedian(const std::vector<PhysicalPoint>& points) {
  std::vector<long double> xs, ys;
  xs.reserve(points.size());
  ys.reserve(points.size());
  for (const PhysicalPoint& p : points) {
    xs.push_back(p.x);
    ys.push_back(p.y);
  }
  return {quantile(xs, 0.5L), quantile(ys, 0.5L)};
}

long double spreadOf(const std::vector<PhysicalPoint>& points) {
  const PhysicalPoint m = coordinateMedian(points);
  std::vector<long double> distances;
  distances.reserve(points.size());
  for (const PhysicalPoint& p : points) distances.push_back(std::hypot(p.x - m.x, p.y - m.y));
  return quantile(distances, 0.9L);
}

/// |Turns| of the path p_0 → p_1 → … about the median point (each increment wrapped into (−π, π]).
/// Around an island the sub-sequence keeps turning (one turn per 1/ν samples); an arc of a quasi-periodic
/// near-return, or two clusters visited alternately, turn less than half a turn or erratically.  Counting turns
/// is invariant under linear maps of the plane, so thin elliptical islands are counted as well as round ones.
long double turnsAboutMedian(const std::vector<PhysicalPoint>& points) {
  const PhysicalPoint m = coordinateMedian(points);
  const long double pi = std::numbers::pi_v<long double>;
  long double total = 0;
  long double previous = points.empty() ? 0 : std::atan2(points[0].y - m.y, points[0].x - m.x);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const long double angle = std::atan2(points[i].y - m.y, points[i].x - m.x);  // each point's angle once
    long double d = angle - previous;
    previous = angle;
    if (d > pi) d -= 2 * pi;
    if (d <= -pi) d += 2 * pi;
    total += d;
  }
  return std::fabs(total) / (2 * pi);
}

/// The first `limit` points z_{phase + k·lag}, k = 0, 1, … (consecutive in k, for turns).
std::vector<PhysicalPoint> consecutiveSubsequence(std::span<const PhysicalPoint> segment, std::size_t lag,
                                                  std::size_t phase, std::size_t limit) {
  std::vector<PhysicalPoint> points;
  for (std::size_t t = phase; t < segment.size() && points.size() < limit; t += lag) points.push_back(segment[t]);
  return points;
}

/// The phases of lag n used for statistics: up to phasesSampled, evenly spaced in [0, n).
std::vector<std::size_t> sampledPhases(std::size_t n, const IslandChainOptions& o) {
  const std::size_t count = std::min<std::size_t>(n, static_cast<std::size_t>(o.phasesSampled));
  std::vector<std::size_t> phases;
  for (std::size_t i = 0; i < count; ++i) phases.push_back(i * n / count);
  return phases;
}

/// How lag `child` (a multiple of `parent`) splits the parent's sub-sequences: the median over sampled
/// phases φ of σ(child, φ)/σ(parent, φ mod parent), and the median turns of the child's sub-sequences about
/// their medians.
struct LevelTest {
  long double spreadRatio;
  long double turns;
  long double spread;  // σ(child), median over the phases
};

LevelTest testLevel(std::span<const PhysicalPoint> segment, std::size_t parent, std::size_t child,
                    const IslandChainOptions& o) {
  const auto limit = static_cast<std::size_t>(o.pointsPerPhase);
  std::vector<long double> ratios, turns, spreads;
  std::map<std::size_t, long double> parentSpreads;  // by the parent's phase, which several phases share
  for (std::size_t phase : sampledPhases(child, o)) {
    const std::vector<PhysicalPoint> points = subsequence(segment, child, phase, limit);
    const long double spread = spreadOf(points);
    auto known = parentSpreads.find(phase % parent);
    if (known == parentSpreads.end())
      known = parentSpreads.emplace(phase % parent, spreadOf(subsequence(segment, parent, phase % parent, limit))).first;
    const long double parentSpread = known->second;
    spreads.push_back(spread);
    ratios.push_back(parentSpread > 0 ? spread / parentSpread : 1);
    turns.push_back(turnsAboutMedian(consecutiveSubsequence(segment, child, phase, limit)));
  }
  return {quantile(ratios, 0.5L), quantile(turns, 0.5L), quantile(spreads, 0.5L)};
}

void validate(const IslandChainOptions& o) {
  if (auto e = lowerBoundError("maxPeriod", o.maxPeriod, 1)) throw std::invalid_argument(*e);
  if (auto e = realOpenIntervalError("confinementRatio", static_cast<double>(o.confinementRatio), 0, 1))
    throw std::invalid_argument(*e);
  if (!(o.minTurns > 0)) throw std::invalid_argument("minTurns must be > 0");
  if (o.minPointsPerPhase < 2 || o.phasesSampled < 1 || o.pointsPerPhase < o.minPointsPerPhase)
    throw std::invalid_argument(
        "need minPointsPerPhase >= 2, phasesSampled >= 1 and pointsPerPhase >= minPointsPerPhase");
}

}  // namespace

long double subsequenceSpread(std::span<const PhysicalPoint> segment, int lag, const IslandChainOptions& options) {
  if (auto e = rangeError("lag", lag, 1, static_cast<long long>(segment.size()), "at most the segment's length"))
    throw std::invalid_argument(*e);
  const auto n = static_cast<std::size_t>(lag);
  std::vector<long double> spreads;
  for (std::size_t phase : sampledPhases(n, options))
    spreads.push_back(spreadOf(subsequence(segment, n, phase, static_cast<std::size_t>(options.pointsPerPhase))));
  return quantile(spreads, 0.5L);
}

IslandChain identifyIslandChain(long double K, std::span<const PhysicalPoint> segment,
                                const IslandChainOptions& options) {
  validate(options);
  if (!std::isfinite(K)) throw std::invalid_argument("K must be a finite number");
  const auto minPoints = static_cast<std::size_t>(options.minPointsPerPhase);
  if (segment.size() < 2 * minPoints)
    throw std::invalid_argument("segment of " + std::to_string(segment.size()) + " points is too short (need " +
                                std::to_string(2 * minPoints) + ")");
  for (const PhysicalPoint& p : segment)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw std::invalid_argument("segment has a non-finite point");

  // A lag is usable when every phase keeps minPointsPerPhase points.
  const long longestLag = std::min<long>(options.maxPeriod, static_cast<long>(segment.size() / minPoints));

  IslandChain chain;
  chain.hierarchy.push_back(1);
  chain.spreads.push_back(subsequenceSpread(segment, 1, options));
  for (bool deeper = true; deeper;) {
    deeper = false;
    const long current = chain.hierarchy.back();
    for (long lag = 2 * current; lag <= longestLag; lag += current) {
      const LevelTest test =
          testLevel(segment, static_cast<std::size_t>(current), static_cast<std::size_t>(lag), options);
      if (test.spreadRatio <= options.confinementRatio && test.turns >= options.minTurns) {
        chain.hierarchy.push_back(static_cast<int>(lag));
        chain.spreads.push_back(test.spread);
        deeper = true;
        break;
      }
    }
  }
  chain.period = chain.hierarchy.back();
  chain.member = coordinateMedian(
      subsequence(segment, static_cast<std::size_t>(chain.period), 0, static_cast<std::size_t>(options.pointsPerPhase)));

  const long double rootK = std::sqrt(K);
  chain.windingTurns = 0;
  {
    long double total = 0;
    const long double pi = std::numbers::pi_v<long double>;
    for (std::size_t t = 1; t < segment.size(); ++t) {
      long double d = std::atan2(segment[t].y, segment[t].x + rootK) -
                      std::atan2(segment[t - 1].y, segment[t - 1].x + rootK);
      if (d > pi) d -= 2 * pi;
      if (d <= -pi) d += 2 * pi;
      total += d;
    }
    chain.windingTurns = std::lround(-total / (2 * pi));
    chain.rotationNumber = -total / (2 * pi) / static_cast<long double>(segment.size() - 1);
  }

  if (options.findCentreOrbit) {
    PeriodicOrbitSearch search;
    search.period = chain.period;
    search.near = chain.member;
    search.searchRadius = std::max(2 * chain.spreads.back(), 1e-4L);
    std::vector<PeriodicOrbit> orbits = findSymmetricPeriodicOrbits(K, search);
    // The centre of an island is elliptic: prefer a stable orbit close to the member over a nearer hyperbolic one.
    const auto stable = std::find_if(orbits.begin(), orbits.end(), [&](const PeriodicOrbit& o) {
      return o.stable() && o.distanceTo(chain.member) <= search.searchRadius;
    });
    if (stable != orbits.end())
      chain.centre = std::move(*stable);
    else if (!orbits.empty())
      chain.centre = std::move(orbits.front());
    else if (std::optional<PeriodicOrbit> general = refinePeriodicOrbit(K, chain.period, chain.member))
      chain.centre = general->rotatedToStart(general->nearestIndex(chain.member));
  }
  return chain;
}

}  // namespace archipelago
