#pragma once
/// \file BoxExtension.hpp
/// \brief How much a larger box extends the trapped segments of a smaller one (Karney 1983, appendix A).
///
/// Appendix A: increasing the box (xmin down, xmax up) makes new short segments appear, and "all the original
/// segments may be extended both forwards and backwards"; "we can, for instance, double the edge of the box and
/// only increase the average length of the orbit segments by less than one".  This measures that extension.
///
/// Definitions (docs/design.md, "Trapping statistics"; the paper, appendix B).  A box [xmin, xmax) × [−L/2, L/2) is the torus of its map N; a step of N
/// wraps exactly when the plane map Q (no periodic continuation) leaves the box, so a segment of a box is a
/// maximal run of consecutive points of a plane orbit inside the box, and its length is the number of those
/// points (the kernel's length with q = 1).  The two boxes share K; the larger contains the smaller.  The plane
/// map is realised by the LARGE box's N: as long as it does not wrap it is Q on the large grid, so one map
/// traces both the original segment (its points inside the small box) and its extension.  Time runs as in
/// trapping runs (N⁻¹ forwards).
///
/// Sampling the original segments: one orbit of the small box's own trapping block (BlockKernel.hpp, q = 1,
/// randomizing zone Xr, its seed) is followed; every state right after a wrap of it is the first point of a
/// small-box segment (its predecessor lies outside the box), sampled with the run's own weights.  That state
/// is carried to the large grid (toPhysical/toUnit: the nearest large-grid point, within one grid unit), where
/// the segment is traced again forwards until it leaves the small box, and its extension is counted:
///   - after:  points after the segment's last point still inside the large box and outside the small one,
///             until the orbit leaves the large box (a wrap of the large N) or re-enters the small box;
///   - before: the same backwards (N) from the segment's first point.
/// When the orbit re-enters the small box without leaving the large one, the large box's segment merges
/// this original segment with another one; that side is marked merged and its gap (the points between the
/// two) is what `after` or `before` counts.  States of the small orbit whose predecessor on the large grid is
/// inside the small box (rounding at the edge) are not segment starts there and are counted as rejected.

#include <cstdint>
#include <vector>

#include "core/map/FixedPointMap.hpp"

namespace archipelago {

struct BoxExtensionRequest {
  MapParameters small;              ///< the original box
  MapParameters large;              ///< the larger box: the same K, containing the small one
  double Xr = 0.02;                 ///< the small box's randomizing zone (only the sampling orbit uses it)
  std::uint64_t seed = 1;           ///< the sampling orbit's random numbers (orbit index 0)
  std::uint64_t orbitSteps = 1'000'000;  ///< steps of the small box's sampling orbit
  std::uint64_t maxTrace = std::uint64_t{1} << 32;  ///< longest trace (segment or gap) before giving up
};

/// One original segment traced on the large grid.
struct OriginalSegmentExtension {
  std::uint64_t length = 0;         ///< points inside the small box
  std::uint64_t before = 0;         ///< points before it inside the large box and outside the small one
  std::uint64_t after = 0;          ///< points after it, likewise
  bool mergedBefore = false;        ///< the orbit came from the small box without leaving the large one
  bool mergedAfter = false;         ///< the orbit re-enters the small box without leaving the large one
  UnitState first;                  ///< the segment's first point, on the large grid
  UnitState last;                   ///< its last point inside the small box, on the large grid
  [[nodiscard]] bool merged() const noexcept { return mergedBefore || mergedAfter; }
  [[nodiscard]] std::uint64_t extension() const noexcept { return before + after; }
};

struct BoxExtensionResult {
  std::vector<OriginalSegmentExtension> segments;  ///< in the order the sampling orbit met them
  std::uint64_t rejected = 0;       ///< segment starts of the small grid that are not starts on the large one
};

/// Traces the original segments met by the sampling orbit (see the file comment).  Throws
/// std::invalid_argument with a one-line message when either box is invalid (mapError), the K differ, the
/// large box does not contain the small one, or Xr is outside [0, 1); std::runtime_error when a trace (an
/// original segment or a gap) exceeds maxTrace steps, rather than looping on.
[[nodiscard]] BoxExtensionResult measureBoxExtension(const BoxExtensionRequest& request);

}  // namespace archipelago
