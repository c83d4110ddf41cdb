#include "core/theory/BoxExtension.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "core/trapping/BlockKernel.hpp"

namespace archipelago {
namespace {

/// The small box as a rectangle of the large grid: X in [xlo, xhi), Y in [ylo, yhi).
struct SmallRegion {
  std::uint64_t xlo, xhi, ylo, yhi;
  [[nodiscard]] bool contains(const UnitState& z) const noexcept {
    return z.X >= xlo && z.X < xhi && z.Y >= ylo && z.Y < yhi;
  }
};

SmallRegion regionOf(const MapParameters& small, const MapParameters& large) {
  const long double L = large.width();
  const auto unit = [&](long double offset) {  // the first large-grid point at or after offset (from the edge)
    return static_cast<std::uint64_t>(std::ceil(std::ldexp(offset / L, fixedpoint::kBits)));
  };
  const long double l = small.width();
  return {unit(static_cast<long double>(small.xmin) - large.xmin),
          unit(static_cast<long double>(small.xmax) - large.xmin), unit((L - l) / 2), unit((L + l) / 2)};
}

/// Points outside the small box and inside the large one met by stepping `z` with `step` (N⁻¹ or N of the
/// large box) until it wraps (leaves the large box) or re-enters the small box; `merged` tells which.
template <class Step>
std::uint64_t gapLength(UnitState z, const SmallRegion& small, std::uint64_t maxTrace, Step&& step, bool& merged) {
  merged = false;
  for (std::uint64_t n = 0;; ++n) {
    if (step(z)) return n;
    if (small.contains(z)) {
      merged = true;
      return n;
    }
    if (n >= maxTrace) throw std::runtime_error("box extension: a gap outside the small box exceeds maxTrace steps");
  }
}

}  // namespace

BoxExtensionResult measureBoxExtension(const BoxExtensionRequest& r) {
  for (const MapParameters* p : {&r.small, &r.large})
    if (const auto e = mapError(*p)) throw std::invalid_argument(*e);
  if (r.small.K != r.large.K)
    throw std::invalid_argument("box extension: the two boxes must share K (" + shortestDecimal(r.small.K) +
                                " and " + shortestDecimal(r.large.K) + ")");
  if (!(r.large.xmin <= r.small.xmin && r.large.xmax >= r.small.xmax))
    throw std::invalid_argument("box extension: the large box (" + shortestDecimal(r.large.xmin) + ", " +
                                shortestDecimal(r.large.xmax) + ") must contain the small one (" +
                                shortestDecimal(r.small.xmin) + ", " + shortestDecimal(r.small.xmax) + ")");
  if (const auto e = randomizingZoneError(r.Xr)) throw std::invalid_argument(*e);

  const FixedPointMap smallMap(r.small), largeMap(r.large);
  const MapCoefficients& big = largeMap.coefficients();
  const SmallRegion region = regionOf(r.small, r.large);
  const auto forwardInTime = [&](UnitState& z) { return backwardStep(big, z); };  // N⁻¹, as trapping runs
  const auto backwardInTime = [&](UnitState& z) { return forwardStep(big, z); };  // N

  BoxExtensionResult result;
  const KernelSettings sampling = blockSettings(smallMap.coefficients(), r.Xr, 1, r.seed);
  OrbitState s;
  for (std::uint64_t i = 0; i < r.orbitSteps; ++i) {
    const bool randomized = s.z.X <= sampling.randomizingX;
    const bool ended = advanceBlockVisiting(sampling, 0, s, [](const UnitState&) {});
    if (!ended || randomized) continue;  // only a wrap makes s.z the first point of a small-box segment
    const PhysicalPoint p = smallMap.toPhysical(s.z);
    const UnitState first = largeMap.toUnit(p.x, p.y);
    UnitState previous = first;
    if (!region.contains(first) || (!backwardInTime(previous) && region.contains(previous))) {
      ++result.rejected;
      continue;
    }
    OriginalSegmentExtension e;
    UnitState z = first;
    e.first = e.last = first;
    e.length = 1;
    bool leftLarge = false;
    for (;;) {  // the original segment: points inside the small box
      e.last = z;
      leftLarge = forwardInTime(z);
      if (leftLarge || !region.contains(z)) break;
      if (++e.length > r.maxTrace)
        throw std::runtime_error("box extension: an original segment exceeds maxTrace steps");
    }
    if (!leftLarge) e.after = 1 + gapLength(z, region, r.maxTrace, forwardInTime, e.mergedAfter);
    if (!backwardInTime(z = first))  // z is now the point before the segment, outside the small box
      e.before = 1 + gapLength(z, region, r.maxTrace, backwardInTime, e.mergedBefore);
    result.segments.push_back(e);
  }
  return result;
}

}  // namespace archipelago
