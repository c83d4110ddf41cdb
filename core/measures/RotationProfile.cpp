#include "core/measures/RotationProfile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/limits/Limits.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
#include "core/provenance/Provenance.hpp"

namespace archipelago {

namespace {
constexpr std::uint32_t kMaxPoints = 1'000'000;
constexpr std::size_t kRoundPoints = 4096;
constexpr std::uint64_t kMaxPower = 100'000;  // measureRotation's power

/// The rational a regular rotation names (RotationProfile.hpp).
std::optional<Rational> rationalOf(const OrbitMeasure& m, std::int64_t maxDenominator) {
  if (m.verdict != OrbitVerdict::Regular) return std::nullopt;
  return rationalOfRotation(m.value, std::pow(10.0, -m.digits), maxDenominator);
}
}  // namespace

std::optional<std::string> validationError(const RotationProfileRequest& r) {
  MeasureSettings s = r.measure;
  s.kind = IndicatorKind::Rotation;
  if (auto e = validationError(s)) return e;
  if (auto e = rangeError("points", r.points, 1, kMaxPoints)) return e;
  if (auto e = rangeError("maxDenominator", r.maxDenominator, 1, 1'000'000)) return e;
  if (auto e = boxPointError("from", r.measure.map, r.from)) return e;
  if (auto e = boxPointError("to", r.measure.map, r.to)) return e;
  if (auto e = threadsError(r.threads)) return e;
  if (r.about) {
    if (auto e = boxPointError("about", r.measure.map, *r.about)) return e;
    if (auto e = rangeError("period", r.power, 1, kMaxPower)) return e;
  }
  return std::nullopt;
}

RotationProfile computeRotationProfile(const RotationProfileRequest& r, const RotationProfileObserver& observer,
                                       std::stop_token stop) {
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  MeasureSettings settings = r.measure;
  settings.kind = IndicatorKind::Rotation;
  const OrbitMeasurer measurer(settings);
  const FixedPointMap map(settings.map);

  RotationProfile profile;
  profile.points.resize(r.points);
  std::vector<UnitState> starts(r.points);
  for (std::uint32_t i = 0; i < r.points; ++i) {
    const long double t = r.points == 1 ? 0.0L : static_cast<long double>(i) / (r.points - 1);
    starts[i] = map.toUnit(r.from.x + t * (r.to.x - r.from.x), r.from.y + t * (r.to.y - r.from.y));
    profile.points[i].start = starts[i];
    profile.points[i].point = map.toPhysical(starts[i]);
  }
  std::optional<RotationCentre> centre;  // about an island's centre: Q^power about it, scalar per orbit
  if (r.about) centre = rotationCentreAt(settings.map, *r.about,
                                         rotationSense(static_cast<long double>(settings.map.K), *r.about, r.power));
  std::vector<OrbitMeasure> measured;
  for (std::size_t first = 0; first < starts.size(); first += kRoundPoints) {
    const std::size_t n = std::min(kRoundPoints, starts.size() - first);
    measured.assign(n, OrbitMeasure{});
    bool complete = true;
    if (!centre) {
      complete = measurer.measure(std::span<const UnitState>(starts.data() + first, n), measured, stop, r.threads);
    } else {
      complete = parallelFor(n, [&](std::size_t i, int) {
        RotationRequest q;
        q.map = settings.map;
        q.start = starts[first + i];
        q.centre = *centre;
        q.power = r.power;
        q.iterations = settings.iterations;
        q.digitsThreshold = settings.digitsThreshold;
        const RotationMeasurement m = measureRotation(q, stop);
        measured[i] = {m.rotation, m.digits, m.verdict};
      }, stop, r.threads);
      complete = complete && !stop.stop_requested();
    }
    for (std::size_t i = 0; i < n; ++i) {
      RotationProfilePoint& p = profile.points[first + i];
      p.measure = measured[i];
      p.rational = rationalOf(measured[i], r.maxDenominator);
    }
    if (!complete) {
      profile.cancelled = true;
      break;
    }
    if (observer) observer(first + n, starts.size());
  }
  return profile;
}

Provenance rotationProfileProvenance(const RotationProfileRequest& r) {
  Provenance p = mapProvenance(r.measure.map);
  p.add("From", shortestDecimal(static_cast<double>(r.from.x)) + "," + shortestDecimal(static_cast<double>(r.from.y)));
  p.add("To", shortestDecimal(static_cast<double>(r.to.x)) + "," + shortestDecimal(static_cast<double>(r.to.y)));
  p.add("Points", std::to_string(r.points));
  p.add("Iterations", std::to_string(r.measure.iterations));
  p.add("Digits threshold", r.measure.digitsThreshold);
  p.add("Max denominator", std::to_string(r.maxDenominator));
  if (r.about) {
    p.add("About", shortestDecimal(static_cast<double>(r.about->x)) + "," + shortestDecimal(static_cast<double>(r.about->y)));
    p.add("Period", std::to_string(r.power));
  }
  return p;
}

void writeRotationProfileCsv(const std::string& path, const RotationProfileRequest& r, const RotationProfile& profile) {
  io::AtomicOutputFile file(path);
  std::ostream& out = file.stream();
  char line[512];
  std::snprintf(line, sizeof line,
                "# rotation profile: rotation number about (-sqrt K, 0), turns per step, positive clockwise "
                "(the sense Q turns), weighted Birkhoff average over two blocks of T steps\n"
                "# K: %s\n# xmin: %s\n# xmax: %s\n# iterations: %llu\n# digits_threshold: %s\n"
                "# from: %.19Lg,%.19Lg\n# to: %.19Lg,%.19Lg\n# points: %u\n# max_denominator: %lld\n",
                shortestDecimal(r.measure.map.K).c_str(), shortestDecimal(r.measure.map.xmin).c_str(),
                shortestDecimal(r.measure.map.xmax).c_str(), static_cast<unsigned long long>(r.measure.iterations),
                shortestDecimal(r.measure.digitsThreshold).c_str(), r.from.x, r.from.y, r.to.x, r.to.y, r.points,
                static_cast<long long>(r.maxDenominator));
  out << line;
  if (r.about) {  // issue 37, finding 17: the rotation of Q^n about an island's centre
    std::snprintf(line, sizeof line, "# about: %.21Lg,%.21Lg (instead of (-sqrt K, 0): the rotation of Q^period about this "
                  "point, turns per period)\n# period: %llu\n", r.about->x, r.about->y,
                  static_cast<unsigned long long>(r.power));
    out << line;
  }
  out << "# program: " << programDescription() << "\n" << "index,x,y,rotation,digits,verdict,rational\n";
  for (std::size_t i = 0; i < profile.points.size(); ++i) {
    const RotationProfilePoint& p = profile.points[i];
    std::snprintf(line, sizeof line, "%zu,%.19Lg,%.19Lg,", i, p.point.x, p.point.y);
    out << line;
    if (std::isfinite(p.measure.value)) {
      std::snprintf(line, sizeof line, "%.17g", p.measure.value);
      out << line;
    }
    out << ',';
    if (std::isfinite(p.measure.digits)) {
      std::snprintf(line, sizeof line, "%.3f", p.measure.digits);
      out << line;
    }
    out << ',' << toString(p.measure.verdict) << ',' << (p.rational ? toString(*p.rational) : "") << '\n';
  }
  file.commit();
}

}  // namespace archipelago
