#pragma once
/// \file SegmentAnalysis.hpp
/// \brief A recorded long segment, replayed into buffers: its points, where it spent its time, its chain.
///
/// Karney (1983), §7 and fig. 8: the longest trapped segments stick to chains of islands around islands; to
/// look at one, replay it exactly from its recorded start state (TrappingRun.hpp), draw it zoomed to where it
/// spent its time, and identify the chain it sticks to (IslandChain.hpp).  This file is the computational half
/// of the GUI's long-segment table; the GUI only calls it from worker threads and draws the results.
///
/// Exactness: traceSegment() runs the same block as every kernel and as replaySegment()
/// (advanceBlockVisiting, BlockKernel.hpp) from the recorded start state, so the states it keeps are bit for
/// bit those of the recorded run.  Segments can be ~10⁸ steps long, so the trace keeps every `stride`-th step
/// (stride ≥ 1 chosen so that at most maxPoints states are kept; stride 1 keeps every step).
///
/// Cancellation: the replays check their std::stop_token every 4096 blocks and return nothing when stopped.
///
/// Coordinates: the run iterates N⁻¹ (time reversed); states are unit coordinates (X, Y) of the torus,
/// points are physical (x, y) (FixedPointMap.hpp).  The chain a segment sticks to is the same for Q and Q⁻¹.

#include <cstdint>
#include <optional>
#include <span>
#include <stop_token>
#include <string>
#include <vector>

#include "core/map/FixedPointMap.hpp"
#include "core/periodic/IslandChain.hpp"
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago {

/// A replayed segment: exact states at steps 0, stride, 2·stride, …, and always the last step.
struct SegmentTrace {
  SegmentRecord record;
  std::uint64_t steps = 0;           ///< steps replayed: q · (blocks replayed); the last step index
  std::uint64_t blocks = 0;          ///< blocks replayed (== record.length for a record of these parameters)
  std::uint64_t stride = 1;          ///< states[i] is the state after step stepAt(i)
  std::vector<UnitState> states;    ///< exact unit coordinates
  std::vector<PhysicalPoint> points; ///< the same, physical (x, y)

  /// The step index of states[i]: i · stride, except the last one, which is `steps`.
  [[nodiscard]] std::uint64_t stepAt(std::size_t i) const noexcept {
    return i + 1 == states.size() ? steps : static_cast<std::uint64_t>(i) * stride;
  }
  /// The index of the kept state nearest to `step` (clamped to the segment).
  [[nodiscard]] std::size_t indexNear(std::uint64_t step) const noexcept;
};

/// Replays `record` of the run with parameters `params` exactly, keeping at most maxPoints ≥ 3 states:
/// stride 1 when the segment has at most maxPoints states (q·record.length + 1), else
/// ⌈q·record.length / (maxPoints − 2)⌉.  Returns nothing when stopped.
/// Throws std::invalid_argument for invalid parameters or maxPoints < 3.
[[nodiscard]] std::optional<SegmentTrace> traceSegment(const TrappingParameters& params, const SegmentRecord& record,
                                                       std::uint64_t maxPoints = 1'000'000,
                                                       std::stop_token stop = {});

/// The first `count` consecutive physical points z_0 … z_{count−1} of the replayed segment (fewer when the
/// segment is shorter): the input identifyIslandChain() needs.  Returns nothing when stopped.
[[nodiscard]] std::optional<std::vector<PhysicalPoint>> segmentPrefix(const TrappingParameters& params,
                                                                      const SegmentRecord& record,
                                                                      std::uint64_t count, std::stop_token stop = {});

/// A rectangle in physical coordinates.
struct SegmentRegion {
  long double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  double fraction = 0;  ///< fraction of the points inside
  [[nodiscard]] long double width() const noexcept { return x1 - x0; }
  [[nodiscard]] long double height() const noexcept { return y1 - y0; }
};

/// Where a segment spent its time: the points are binned on a grid × grid histogram over their bounding box;
/// the fullest cells are taken until they hold at least `fraction` of the points; the region is the bounding
/// box of those cells, widened by `margin` times its size on every side.  Robust to the short excursions at
/// the ends of a segment (which the plain bounding box would include).  `fraction` in (0, 1], grid ≥ 1,
/// margin ≥ 0; throws std::invalid_argument otherwise or when `points` is empty.  Equal points give a box of
/// zero size; callers that need a minimum size widen it themselves.
[[nodiscard]] SegmentRegion dwellRegion(std::span<const PhysicalPoint> points, double fraction = 0.9, int grid = 64,
                                        double margin = 0.05);

/// `r` widened (never shrunk) about its centre to the aspect ratio width/height = aspect and to at least
/// minSize in both directions, then shifted, and cut where it is larger than the box, to lie inside the box
/// [xmin, xmax] × [−L/2, L/2] of `map` (a view of the portrait must).  aspect > 0 and minSize ≥ 0, finite;
/// throws std::invalid_argument otherwise.
[[nodiscard]] SegmentRegion framedInBox(const SegmentRegion& r, const MapParameters& map, double aspect,
                                        long double minSize);

/// How many consecutive points of a segment identifySegmentChain() holds by default, whatever the segment's
/// length (segments reach 10⁸ steps; 2·10⁶ points are 64 MB and enough to resolve a chain of period ≤ 1000 with
/// 2000 points per phase).  The GUI's long-segment table and `archipelago-cli replay --identify` both use it.
inline constexpr std::uint64_t kChainIdentificationPoints = 2'000'000;

/// The chain of a recorded segment, and where it spent its time near one island of the chain.
struct SegmentChain {
  IslandChain chain;
  std::uint64_t points = 0;  ///< consecutive points z_0 … it was identified from: min(maxPoints, the segment's)
  /// dwellRegion() of the points z_{k·n₁} (k = 0, 1, …), n₁ = chain.hierarchy[1] the first level above the
  /// central island: they stay near the island of that level that z_0 is near, so this region frames one
  /// island with the satellites the segment winds around (e.g. one of the six islands and its 11 satellites
  /// for a chain of period 66 = 6 × 11).  For a segment on the central island itself (period 1) it frames the
  /// whole segment.
  SegmentRegion island;
};

/// identifyIslandChain() over the first `maxPoints` consecutive points of a recorded segment, and the
/// island region above.  Holds at most maxPoints points (physical, 2 long doubles each) however long the
/// segment is.  Returns nothing when stopped.  Throws std::invalid_argument when the segment is too
/// short to identify (fewer than 2·options.minPointsPerPhase points) and whatever identifyIslandChain() throws.
[[nodiscard]] std::optional<SegmentChain> identifySegmentChain(const TrappingParameters& params,
                                                               const SegmentRecord& record,
                                                               std::uint64_t maxPoints = kChainIdentificationPoints,
                                                               const IslandChainOptions& options = {},
                                                               std::stop_token stop = {});

/// The island region of SegmentChain for consecutive points z_0, z_1, … and the level n₁ ≥ 1 (every n₁-th
/// point from z_0).  Throws std::invalid_argument when n₁ < 1 or there are no points.
[[nodiscard]] SegmentRegion islandRegion(std::span<const PhysicalPoint> consecutive, int level, double fraction = 0.9,
                                         double margin = 0.05);

/// Writes the trace as CSV: a header line "step,x,y,X,Y", then one line per kept state (x, y with 17
/// significant digits, X, Y the exact integers), atomically (io::AtomicOutputFile).  Throws std::runtime_error
/// naming the file on failure.
void writeSegmentCsv(const std::string& path, const SegmentTrace& trace);

/// The rule of a replay's stride (every stride-th step kept): "stride = 0 must be >= 1", or nothing.
[[nodiscard]] std::optional<std::string> strideError(std::uint64_t stride);

/// Replays `record` exactly and streams the same CSV as above for steps 0, stride, 2·stride, … and the last
/// step, holding one state at a time (memory independent of the segment's length), into a temporary file that
/// is published only when the replay ended where the record says (io::AtomicOutputFile).  stride ≥ 1.
/// Returns record.length.  Throws std::invalid_argument for invalid parameters or stride 0,
/// std::runtime_error naming the file on failure and "replay mismatch: …" (replaySegment()) when the segment
/// does not end after record.length blocks; `path` is untouched then.
std::uint64_t writeSegmentCsv(const std::string& path, const TrappingParameters& params, const SegmentRecord& record,
                              std::uint64_t stride);

/// Writes the trace as a NumPy .npy array of shape (n, 3), little-endian float64, columns step, x, y (steps
/// are exact below 2^53).  Throws std::runtime_error naming the file on failure.
void writeSegmentNpy(const std::string& path, const SegmentTrace& trace);

}  // namespace archipelago
