#include "core/measures/ChainIdentification.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/measures/OrbitMeasures.hpp"  // MeasureSettings, boxPointError
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {
constexpr long double kMaxBound = 2147483648.0L;  // 2^31: numerators and denominators then fit in 64 bits

/// The Stern–Brocot descent for 0 < lo ≤ hi ≤ 2^31 (see the header).
std::optional<Rational> positiveSmallest(long double lo, long double hi, std::int64_t maxDen) {
  // Invariant: a/b < lo and c/d > hi (1/0 is +∞).
  std::int64_t a = 0, b = 1, c = 1, d = 0;
  for (;;) {
    const std::int64_t p = a + c, q = b + d;
    if (q > maxDen) return std::nullopt;
    const auto lp = static_cast<long double>(p), lq = static_cast<long double>(q);
    if (lp < lo * lq) {
      // The left bound moves k times towards c/d while (a + k c)/(b + k d) < lo.
      const long double room = (lo * static_cast<long double>(b) - static_cast<long double>(a)) /
                               (static_cast<long double>(c) - lo * static_cast<long double>(d));
      auto k = static_cast<std::int64_t>(std::max(1.0L, std::ceil(room) - 1));
      if (d > 0) k = std::min(k, (maxDen - b) / d + 1);
      a += k * c;
      b += k * d;
    } else if (lp > hi * lq) {
      const long double room = (static_cast<long double>(c) - hi * static_cast<long double>(d)) /
                               (hi * static_cast<long double>(b) - static_cast<long double>(a));
      auto k = static_cast<std::int64_t>(std::max(1.0L, std::ceil(room) - 1));
      k = std::min(k, (maxDen - d) / b + 1);
      c += k * a;
      d += k * b;
    } else {
      return Rational{p, q};
    }
  }
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

/// The sense in which DQⁿ turns points about an elliptic point z: clockwise (+1) when the image of (1, 0)
/// has a negative y component, as DQ at (−√K, 0) = [[1 − 4√K, 1], [−4√K, 1]] has.
int senseOf(long double K, PhysicalPoint z, std::uint64_t n) {
  smooth::Matrix2<long double> product;
  (void)smooth::iterate(K, smooth::Point<long double>{z.x, z.y}, static_cast<long>(n), &product);
  return product.yx < 0 ? 1 : -1;
}

PhysicalPoint toUnits(const MapParameters& map, PhysicalPoint p) {
  const long double L = static_cast<long double>(map.xmax) - static_cast<long double>(map.xmin);
  const long double one = static_cast<long double>(FixedPointMap::kOne);
  return {(p.x - static_cast<long double>(map.xmin)) / L * one, (p.y + L / 2) / L * one};
}

PhysicalPoint toPhysical(const MapParameters& map, PhysicalPoint units) {
  const long double L = static_cast<long double>(map.xmax) - static_cast<long double>(map.xmin);
  const long double one = static_cast<long double>(FixedPointMap::kOne);
  return {static_cast<long double>(map.xmin) + L * units.x / one, -L / 2 + L * units.y / one};
}

/// The elliptic orbit of minimal period n around `guess` (step 3 of the header), or nothing.
std::optional<PeriodicOrbit> ellipticOrbitNear(long double K, std::uint64_t n, PhysicalPoint guess,
                                               long double radius) {
  if (auto o = refinePeriodicOrbit(K, static_cast<int>(n), guess); o && o->stable()) return o;
  if (n > kMaxSymmetricSearchPeriod) return std::nullopt;
  PeriodicOrbitSearch search;
  search.period = static_cast<int>(n);
  search.near = guess;
  search.searchRadius = std::max(radius, 1e-6L);
  search.stableOnly = true;
  const std::vector<PeriodicOrbit> found = findSymmetricPeriodicOrbits(K, search);
  if (found.empty()) return std::nullopt;
  return found.front();
}

std::string describeEnd(const RotationMeasurement& m, std::uint64_t T) {
  switch (m.verdict) {
    case OrbitVerdict::Chaotic: return "chaotic (" + fixed(m.digits, 3) + " digits at T = " + std::to_string(T) + ")";
    case OrbitVerdict::Escaping: return "escaping (the orbit leaves the box, where Q* is not Q)";
    default: return "not computed";
  }
}
}  // namespace

std::optional<Rational> smallestDenominatorRational(double lo, double hi, std::int64_t maxDenominator) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
    throw std::invalid_argument("smallestDenominatorRational: need finite lo <= hi");
  if (auto e = rangeError("maxDenominator", maxDenominator, 1, std::int64_t{1} << 31))
    throw std::invalid_argument("smallestDenominatorRational: " + *e);
  if (std::fabs(lo) > kMaxBound || std::fabs(hi) > kMaxBound)
    throw std::invalid_argument("smallestDenominatorRational: bounds must lie within ±2^31");
  if (lo <= 0 && hi >= 0) return Rational{0, 1};
  if (hi < 0) {
    auto r = positiveSmallest(-static_cast<long double>(hi), -static_cast<long double>(lo), maxDenominator);
    if (r) r->p = -r->p;
    return r;
  }
  return positiveSmallest(lo, hi, maxDenominator);
}

double rotationAccuracy(double difference) noexcept { return std::max(kAccuracyFactor * difference, 0x1p-50); }

std::optional<Rational> rationalOfRotation(double rotation, double difference, std::int64_t maxDenominator) {
  const double delta = rotationAccuracy(difference);
  return smallestDenominatorRational(rotation - delta, rotation + delta, maxDenominator);
}

std::string toString(const Rational& r) { return std::to_string(r.p) + "/" + std::to_string(r.q); }

namespace {

/// The request's map and bounds, checked before any measurement (the rotation measurement validates the rest).
void checkChainRequest(const ChainRequest& r) {
  if (auto e = mapError(r.map)) throw std::invalid_argument(*e);
  if (auto e = realOpenIntervalError("K", r.map.K, 0, 1,
                                     "for island chains: only there is the centre (−√K, 0) elliptic"))
    throw std::invalid_argument(*e);
  if (auto e = rangeError("maxPeriod", r.maxPeriod, 1, PeriodicOrbitSearch::kMaxPeriod)) throw std::invalid_argument(*e);
  if (auto e = rangeError("maxLevels", r.maxLevels, 0, 16)) throw std::invalid_argument(*e);
}

/// One step of the descent (the header): names the last level's rotation as a rational, confirms the island it
/// turns about, and measures the rotation about the next level's elliptic orbit (`measure` set to it); or says how
/// the chain ends.
std::optional<std::string> descendOneLevel(ChainIdentification& out, const ChainRequest& r, RotationRequest& measure,
                                           std::stop_token stop) {
  ChainLevel& current = out.levels.back();
  const RotationMeasurement& m = current.rotation;
  const std::string around = out.levels.size() == 1 ? "the centre" : "the period-" + std::to_string(current.power) + " orbit";
  if (m.verdict == OrbitVerdict::NotComputed) {
    out.cancelled = true;
    return "stopped";
  }
  if (m.verdict != OrbitVerdict::Regular)
    return describeEnd(m, r.iterations) + (out.levels.size() > 1 ? " about " + around : "");
  const auto maxQ = std::max<std::int64_t>(static_cast<std::int64_t>(r.maxPeriod / current.power), 1);
  current.rational = rationalOfRotation(m.rotation, m.difference, maxQ);
  if (out.levels.size() > 1 && (!current.rational || current.rational->p != 0)) {
    // The orbit turns about this level's orbit: its island is confirmed.
    out.factors.push_back(out.levels[out.levels.size() - 2].rational->q);
    out.period = current.power;
  }
  if (!current.rational) return "an invariant curve of rotation " + fixed(m.rotation, 10) + " about " + around;
  if (current.rational->p == 0)
    return out.levels.size() > 1 ? "the orbit does not turn about " + around + ", so it is not in its island"
                                 : "the orbit does not turn about the centre";
  if (static_cast<int>(out.levels.size()) > r.maxLevels)
    return "rotation " + toString(*current.rational) + " about " + around + ", not followed deeper (maxLevels)";
  const std::uint64_t n = out.period * static_cast<std::uint64_t>(current.rational->q);
  const EllipticOrbitGuess guess = ellipticOrbitAround(r.map, r.start, n, r.iterations);
  const std::optional<PeriodicOrbit>& orbit = guess.orbit;
  if (stop.stop_requested()) {
    out.cancelled = true;
    return "stopped";
  }
  if (!orbit)
    return "rotation " + toString(*current.rational) + " about " + around + ", but no elliptic orbit of period " +
           std::to_string(n) + " was found around the orbit's points";
  ChainLevel next;
  next.power = n;
  next.orbit = orbit->rotatedToStart(orbit->nearestIndex(guess.centroid));
  next.centre = next.orbit->points.front();
  next.sense = rotationSense(static_cast<long double>(r.map.K), next.centre, n);
  measure.centre = rotationCentreAt(r.map, next.centre, next.sense);
  measure.power = n;
  next.rotation = measureRotation(measure, stop);
  out.levels.push_back(next);
  return std::nullopt;
}

/// The summary: the chain's factors and rotations, then how it ends.
std::string chainSummary(const ChainIdentification& out) {
  std::ostringstream s;
  if (!out.factors.empty()) {
    for (std::size_t i = 0; i < out.factors.size(); ++i) s << (i ? " × " : "") << out.factors[i];
    if (out.factors.size() > 1) s << " = " << out.period;
    s << ", rotation ";
    for (std::size_t i = 0; i < out.factors.size(); ++i) {
      s << (i ? ", " : "") << toString(*out.levels[i].rational) << " about ";
      if (i == 0) s << "the centre";
      else if (i == 1) s << "its island";
      else s << "the period-" << out.levels[i].power << " island";
    }
    s << "; ";
  }
  s << out.ending;
  return s.str();
}

}  // namespace

ChainIdentification identifyChain(const ChainRequest& r, std::stop_token stop) {
  checkChainRequest(r);
  const auto K = static_cast<long double>(r.map.K);

  ChainIdentification out;
  RotationRequest measure;
  measure.map = r.map;
  measure.start = r.start;
  measure.centre = centralFixedPoint(r.map);
  measure.iterations = r.iterations;
  measure.digitsThreshold = r.digitsThreshold;

  ChainLevel level;
  level.power = 1;
  level.centre = {-std::sqrt(K), 0};
  level.sense = 1;
  level.rotation = measureRotation(measure, stop);  // validates the rest
  out.levels.push_back(level);
  std::optional<std::string> ending;
  do ending = descendOneLevel(out, r, measure, stop);
  while (!ending);
  out.ending = *ending;
  out.summary = chainSummary(out);
  return out;
}

int rotationSense(long double K, PhysicalPoint z, std::uint64_t n) { return senseOf(K, z, n); }

RotationCentre rotationCentreAt(const MapParameters& map, PhysicalPoint centre, int sense) {
  return {toUnits(map, centre), sense};
}

EllipticOrbitGuess ellipticOrbitAround(const MapParameters& map, UnitState start, std::uint64_t n,
                                       std::uint64_t iterations) {
  const auto K = static_cast<long double>(map.K);
  const long double unitLength = (static_cast<long double>(map.xmax) - map.xmin) / FixedPointMap::kOne;
  const SubsequenceCloud cloud = subsequenceCloud(map, start, n, std::min<std::uint64_t>(iterations, 4096));
  EllipticOrbitGuess out;
  out.centroid = toPhysical(map, cloud.centroid);
  out.radius = cloud.radius * unitLength;
  if (cloud.wrapped) return out;
  out.orbit = ellipticOrbitNear(K, n, out.centroid, 2 * out.radius);
  return out;
}

ChainRequest chainRequestAt(ChainRequest request, PhysicalPoint start) {
  MeasureSettings check;  // the measure's rules first, as the rotation measurement reads them
  check.map = request.map;
  check.iterations = request.iterations;
  check.digitsThreshold = request.digitsThreshold;
  if (auto e = validationError(check)) throw std::invalid_argument(*e);
  if (auto e = boxPointError("the start (x, y)", request.map, start)) throw std::invalid_argument(*e);
  request.start = FixedPointMap(request.map).toUnit(start.x, start.y);
  return request;
}

}  // namespace archipelago
