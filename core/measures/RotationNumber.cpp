#include "core/measures/RotationNumber.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

namespace archipelago {
namespace {
#include "core/measures/MeasureMath.inl"
#include "core/limits/Limits.hpp"

constexpr std::uint64_t kMaxPower = 100'000;
constexpr std::uint64_t kStopCheckSteps = std::uint64_t{1} << 16;

/// The centre split as the kernels split it (MeasureKernels.hpp): an integer (exact in double) and a fraction.
struct SplitCentre {
  double x, y, fx, fy;
  explicit SplitCentre(const PhysicalPoint& c) {
    const long double ix = std::floor(c.x), iy = std::floor(c.y);
    x = static_cast<double>(ix);
    y = static_cast<double>(iy);
    fx = static_cast<double>(c.x - ix);
    fy = static_cast<double>(c.y - iy);
  }
};
}  // namespace

RotationCentre centralFixedPoint(const MapParameters& map) noexcept { return {rotationCentreUnits(map), 1}; }

RotationMeasurement measureRotation(const RotationRequest& r, std::stop_token stop) {
  if (auto e = mapError(r.map)) throw std::invalid_argument(*e);
  if (auto e = rangeError("power", r.power, 1, kMaxPower)) throw std::invalid_argument(*e);
  if (r.centre.sense != 1 && r.centre.sense != -1) throw std::invalid_argument("sense must be +1 or -1");
  if (!std::isfinite(r.centre.units.x) || !std::isfinite(r.centre.units.y))
    throw std::invalid_argument("the rotation centre must be finite");
  if (auto e = realRangeError("digits threshold", r.digitsThreshold, 0, kMaxDigits)) throw std::invalid_argument(*e);
  if (r.frame) {
    const std::array<double, 4>& B = *r.frame;
    const double det = B[0] * B[3] - B[1] * B[2];
    if (!std::isfinite(det) || !std::isnormal(det)) throw std::invalid_argument("the frame must be finite and invertible");
  }
  const BirkhoffWeights w = birkhoffWeights(r.iterations, stop);  // validates the iterations
  if (stop.stop_requested()) return {};
  const MapCoefficients k = computeCoefficients(r.map);
  const SplitCentre c(r.centre.units);
  const std::uint64_t T = r.iterations;

  // The offset z − c (unit coordinates: the integer parts subtracted exactly), in the frame B where one is given.
  const auto offset = [&c, B = r.frame.value_or(std::array<double, 4>{1, 0, 0, 1}), framed = r.frame.has_value()](
                          const UnitState& z, double& ox, double& oy) {
    const double dx = (static_cast<double>(z.X) - c.x) - c.fx, dy = (static_cast<double>(z.Y) - c.y) - c.fy;
    ox = framed ? B[0] * dx + B[1] * dy : dx;
    oy = framed ? B[2] * dx + B[3] * dy : dy;
  };
  UnitState z{r.start.X & FixedPointMap::kMask, r.start.Y & FixedPointMap::kMask};
  bool wrapped = false;
  double px = 0, py = 0;
  offset(z, px, py);
  double hi = 0, lo = 0, firstBlock = 0;
  std::uint64_t sinceCheck = 0;
  for (std::uint64_t step = 0; step < 2 * T; ++step) {
    for (std::uint64_t j = 0; j < r.power; ++j) wrapped |= forwardStep(k, z);
    sinceCheck += r.power;
    if (sinceCheck >= kStopCheckSteps) {
      sinceCheck = 0;
      if (stop.stop_requested()) return {};
    }
    double dx = 0, dy = 0;
    offset(z, dx, dy);
    twoSumAdd(hi, lo, w.g[step < T ? step : step - T] * clockwiseAngle(px, py, dx, dy));
    px = dx;
    py = dy;
    if (step + 1 == T) {
      firstBlock = hi + lo;
      hi = 0;
      lo = 0;
    }
  }
  constexpr double turn = 2 * std::numbers::pi;
  const double a = firstBlock / w.sum / turn, b = (hi + lo) / w.sum / turn;
  RotationMeasurement m;
  m.digits = convergenceDigits(a, b);
  m.difference = std::fabs(a - b);
  if (wrapped) m.verdict = OrbitVerdict::Escaping;
  else if (!(m.digits >= r.digitsThreshold)) m.verdict = OrbitVerdict::Chaotic;
  else m.verdict = OrbitVerdict::Regular;
  if (m.verdict == OrbitVerdict::Regular) m.rotation = (a + b) / 2 * r.centre.sense;
  return m;
}

SubsequenceCloud subsequenceCloud(const MapParameters& map, UnitState start, std::uint64_t power,
                                  std::uint64_t count) {
  if (power < 1 || power > kMaxPower || count < 1 || count > kMaxIterations)
    throw std::invalid_argument("subsequenceCloud: power or count out of range");
  const MapCoefficients k = computeCoefficients(map);
  std::vector<UnitState> points(static_cast<std::size_t>(count));
  UnitState z{start.X & FixedPointMap::kMask, start.Y & FixedPointMap::kMask};
  SubsequenceCloud cloud;
  long double sx = 0, sy = 0;
  for (std::uint64_t i = 0; i < count; ++i) {
    points[i] = z;
    sx += static_cast<long double>(z.X);
    sy += static_cast<long double>(z.Y);
    if (i + 1 < count)
      for (std::uint64_t j = 0; j < power; ++j) cloud.wrapped |= forwardStep(k, z);
  }
  const auto n = static_cast<long double>(count);
  cloud.centroid = {sx / n, sy / n};
  for (const UnitState& p : points)
    cloud.radius = std::max(cloud.radius, std::hypot(static_cast<long double>(p.X) - cloud.centroid.x,
                                                     static_cast<long double>(p.Y) - cloud.centroid.y));
  return cloud;
}

}  // namespace archipelago
