#pragma once
/// \file PortraitRenderer.hpp
/// \brief Renders a phase portrait of Q* (Karney 1983, fig. 2 and its enlargements) into a PortraitRaster.
///
/// One entry point, renderPortrait(request, observer, stop): an immutable request in, a raster out, a
/// progress observer and a stop token (the Fraktaler/XaoS shape: GUI and CLI both call it).
///
/// The orbits are those of the exact map N (FixedPointMap.hpp), so every pixel is reproducible bit for bit:
///   - Density (a): `orbits` orbits of N start in the chaotic sea — on random points of the strip
///     0.98 ≤ X/2^52 < 1 next to xmax, outside the islands of Q — and each of their points inside the view
///     is counted.  The sea is connected on the torus, so the counts approach the invariant density of the
///     sea and the islands stay empty.  At deep zoom the sea rarely enters a view of width w (the chance per
///     step is about the view's area w² over the sea's area b₂L²), so density views below ~10⁻⁴ are nearly
///     empty: use Orbits there.
///   - Orbits (b): a seedColumns × seedRows grid of seeds at the centres of the cells of the view, each
///     iterated by N; a pixel's label is 1 + the smallest seed index reaching it, so every orbit (a KAM curve
///     or island chain) gets its own colour.  Seeding inside the view is what makes content appear at depth:
///     orbits near an elliptic periodic point stay near it.
///   - Stickiness (c): `orbits` trapping orbits exactly as trapping runs (§3, appendix B, BlockKernel.hpp):
///     from (0, 0), blocks of q steps of N⁻¹ with the randomizing zone X ≤ ⌊Xr·2^52⌋; a segment ends on a
///     wrap or in the zone.  When a segment ends, each of its points inside the view adds its length (in
///     steps, q·blocks) to its pixel; a pixel's value is the mean over its visits (log scale when drawn).
///     The first segment of each orbit (it starts at X = 0) and the open segment at the end are dropped,
///     as in the trapping statistics.
///
/// Progressive refinement: the work is split into `passes` passes ending at 2^−(passes−1), 2^−(passes−2),
/// …, 1 of the points per orbit; each pass continues the same orbits, so nothing is recomputed, and the
/// observer receives a snapshot of the raster after each pass.  With `passPoints` set, a doubling pass longer
/// than that is split into passes of at most passPoints points (all orbits), so that a large budget (the
/// explorer accumulates up to 10¹⁰ points into one raster while the view stays put) still shows a snapshot
/// every passPoints points: passSchedule() lists where the passes end.  Within a pass the work goes in rounds in
/// which every orbit advances by at most `chunkSteps` points; the stop token is checked before every chunk
/// of every orbit, so after a stop request each thread finishes at most the chunk it is in.
///
/// Parallel over orbits (parallel/ParallelFor.hpp), each thread into its own raster, merged with integer sums
/// (and the minimum for labels): the raster does not depend on the number of threads.  No exception leaves a
/// parallel region: one raised inside (e.g. std::bad_alloc) is rethrown after it.
///
/// The instruction-set path is part of the request (the caller chooses it, selectKernel() at the CLI or GUI
/// edge); Density mode iterates and bins with its DensityKernel.  Orbits and Stickiness modes visit every
/// point with the scalar definitions (the lane loop of kernels/ScalarLanes.hpp; the trapping block of
/// BlockKernel.hpp), since no vector path visits single steps.  Every path gives the same raster.

#include <cstdint>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/portrait/PortraitRaster.hpp"
#include "core/view/Viewport.hpp"

namespace archipelago {

/// Everything that defines a portrait, as plain values.
struct PortraitRequest {
  MapParameters map;                    ///< K, xmin, xmax (default: the paper's K = 0.1 box, §5)
  Viewport view;                        ///< default: the whole box
  int width = 512;                      ///< pixels, 1 … limits::kRasterSide
  int height = 512;                     ///< pixels, 1 … limits::kRasterSide
  PortraitMode mode = PortraitMode::Density;
  std::uint64_t points = 20'000'000;    ///< map steps in all; each orbit does ⌈points / orbits⌉ of them
  std::uint32_t orbits = 256;           ///< Density and Stickiness: number of orbits, 1 … limits::kRasterOrbits
  std::uint32_t seedColumns = 24;       ///< Orbits: seed grid, 1 … limits::kSeedGridSide each way
  std::uint32_t seedRows = 24;
  double Xr = 0.02;                     ///< Stickiness: randomizing zone in unit X, [0, 1) (appendix B)
  std::uint32_t q = 16;                 ///< Stickiness: steps of N⁻¹ per block, 1 … limits::kRasterQ
  std::uint64_t seed = 1;               ///< random numbers (CounterRng.hpp): start points and randomization
  std::uint32_t passes = 6;             ///< progressive refinement, 1 … 30
  std::uint32_t chunkSteps = 8192;      ///< points per orbit per chunk, 1 … 2^20: the cancellation latency
  std::uint64_t passPoints = 0;         ///< most points (all orbits) in one pass after splitting, 0: no limit;
                                        ///< at most 2^16 passes in all (see passSchedule)
  const KernelInfo* kernel = nullptr;   ///< the instruction-set path (allKernels()); nullptr: bestKernel()

  /// Number of orbits in the chosen mode (seedColumns·seedRows in Orbits mode).
  [[nodiscard]] std::uint64_t orbitCount() const noexcept;
  /// Steps per orbit: ⌈points / orbitCount⌉, rounded up to a multiple of q in Stickiness mode.
  [[nodiscard]] std::uint64_t stepsPerOrbit() const noexcept;
};

/// The first violated rule, naming the field, or nothing when the request is valid.
[[nodiscard]] std::optional<std::string> validationError(const PortraitRequest& r);

/// Steps per orbit done at the end of each pass, increasing, the last one stepsPerOrbit(): the doubling
/// levels of `passes` (whole blocks of q in Stickiness mode), each split into equal parts of at most
/// passPoints points when passPoints is set.  (Valid requests only.)
[[nodiscard]] std::vector<std::uint64_t> passSchedule(const PortraitRequest& r);

/// Sets `passes` and `passPoints` of r for a budget of r.points accumulated progressively: the first pass
/// does about `firstPassPoints` points (the doubling levels from there up to the budget, at most 30), and
/// no pass does more than `passPoints` (0: no limit).  Raises passPoints if needed so that the schedule
/// stays within 2^16 passes.
void setProgressiveSchedule(PortraitRequest& r, std::uint64_t firstPassPoints, std::uint64_t passPoints);

/// The number of sea points expected in the view of `r` after `points` steps of the Density mode's orbits,
/// if the whole view were chaotic sea: the orbits of the sea are equidistributed over its area b₂L² (an
/// area-preserving map, ergodic on the sea; §5), so a view of area A gets the fraction A / (b₂L²) ≥ A / L²
/// of them; this returns the lower bound points · A / L².
[[nodiscard]] double seaPointsExpectedIfAllSea(const PortraitRequest& r, std::uint64_t points) noexcept;

/// How many sea points seaPointsExpectedIfAllSea() must promise before an empty Density view is declared
/// free of chaotic points: an all-sea view then stays empty with probability e^−64, a view whose sea
/// covers a fraction f with probability e^−64f.
inline constexpr double kNoSeaExpectedPoints = 64;

/// True when the Density portrait `raster` of request `r` has no point in its view although
/// seaPointsExpectedIfAllSea(r, raster.pointsIterated) ≥ kNoSeaExpectedPoints: the view lies inside
/// islands (or has a chaotic part smaller than about 1/64 of its area).  False in the other modes.
[[nodiscard]] bool viewHoldsNoSea(const PortraitRequest& r, const PortraitRaster& raster) noexcept;

/// Progress, reported on the calling thread after every round (never inside a parallel region).
struct PortraitProgress {
  std::uint64_t pointsDone = 0;       ///< steps done so far, all orbits
  std::uint64_t pointsTotal = 0;      ///< orbitCount · stepsPerOrbit
  std::uint32_t pass = 0;             ///< the pass in progress (0-based), or the one just finished
  std::uint32_t passes = 0;
  const PortraitRaster* snapshot = nullptr;  ///< non-null after a pass ended: the raster so far
  bool final = false;                 ///< the last snapshot
};

using PortraitObserver = std::function<void(const PortraitProgress&)>;

struct PortraitResult {
  PortraitRaster raster;
  bool cancelled = false;          ///< stopped before the last pass ended
  std::uint32_t passesDone = 0;
};

/// Renders the portrait; throws std::invalid_argument when validationError(request) is set.  On a stop
/// request, returns at once (within one chunk per thread) the raster accumulated so far, with cancelled set.
[[nodiscard]] PortraitResult renderPortrait(const PortraitRequest& request, const PortraitObserver& observer = {},
                                            std::stop_token stop = {});

/// Where the points of a view fall: the pixel (col, row) of a unit state, exactly as renderPortrait bins.
class PixelMapping {
 public:
  PixelMapping(const Viewport& view, int width, int height) noexcept;
  /// The pixel index row·width + col of z, or −1 when z lies outside the view (RasterGrid::pixelOf: offsets
  /// from the exact centre are exact integers below 2^53, hence exact in double).
  [[nodiscard]] std::int64_t pixelOf(const UnitState& z) const noexcept { return grid_.pixelOf(z); }
  /// The same mapping as plain numbers, for the vector kernels (kernels/VectorKernels.hpp).
  [[nodiscard]] const RasterGrid& grid() const noexcept { return grid_; }

 private:
  RasterGrid grid_;
};

}  // namespace archipelago
