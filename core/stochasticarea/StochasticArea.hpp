#pragma once
/// \file StochasticArea.hpp
/// \brief The stochastic area b₂ of Q* (Karney 1983, §5) and its convergence with the number of iterations.
///
/// §5: "the area b₂ occupied by the stochastic trajectories … was calculated by dividing the phase space into
/// 1024 × 1024 little boxes, iterating the mapping many times, and counting the number of occupied boxes";
/// the paper's b₂ = 0.693 at K = 0.1 is an area in the (x, y) plane (appendix A: b₀ = L² is the whole box, b₂
/// its stochastic part), in the box of its fig. 6 caption, which our copy lacks.  What the box counting
/// measures is the visited fraction of the box; stats/StochasticAreaQuantities.hpp turns it into the area
/// (fraction · L²) and the box-invariant products of eq. (A3).  (With xmin = −0.8, xmax = 0.5 the fraction is
/// 0.811, an area of 1.371.)  Here the orbits are exactly those of the trapping runs (appendix B, BlockKernel.hpp): orbit i
/// starts at (0, 0) and iterates blocks of q steps of N⁻¹, its Y randomized (its own counter-based draws)
/// whenever a block starts in the zone X ≤ ⌊Xr·2^52⌋.  Every point after every step marks its box
/// (X >> 42, Y >> 42) — exact integer boxing of the unit square.  The steps are computed by the request's
/// instruction-set path (kernels/TracedBlocks.hpp); every path visits the same boxes.
///
/// Convergence: the visited fraction is recorded each time the total number of steps doubles, from
/// firstCheckpoint up to `iterations`; each checkpoint has every orbit at the same number of steps, so the
/// curve does not depend on the number of threads.  b₂ can only grow with the iterations (it counts a union),
/// and it approaches the area of the sea slowly because the orbits must reach "all the nooks and crannies".

#include <cstdint>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/map/MapParameters.hpp"

namespace archipelago {

struct StochasticAreaRequest {
  MapParameters map;                       ///< default: the paper's K = 0.1 box
  double Xr = 0.02;                        ///< randomizing zone in unit X, [0, 1)
  std::uint32_t q = 16;                    ///< steps of N⁻¹ per block, 1 … limits::kRasterQ
  std::uint32_t orbits = 64;               ///< orbits in parallel, 1 … limits::kRasterOrbits
  std::uint64_t seed = 1;                  ///< CounterRng seed of the randomization
  std::uint64_t iterations = 1ULL << 28;   ///< total steps, all orbits (rounded up to whole blocks per orbit)
  std::uint64_t firstCheckpoint = 1ULL << 20;  ///< total steps at the first point of the convergence curve
  int gridBits = 10;                       ///< boxes per side = 2^gridBits, 1 … 12 (paper: 1024)
  const KernelInfo* kernel = nullptr;      ///< the instruction-set path (allKernels()); nullptr: bestKernel()
};

[[nodiscard]] std::optional<std::string> validationError(const StochasticAreaRequest& r);

/// One point of the convergence curve.
struct StochasticAreaPoint {
  std::uint64_t iterations = 0;     ///< total steps of N⁻¹ so far, all orbits
  std::uint64_t boxesVisited = 0;
  double b2 = 0;                    ///< boxesVisited / boxes: the fraction of the box (the area: stochasticAreaOf)
};

struct StochasticAreaResult {
  std::vector<StochasticAreaPoint> convergence;  ///< at doubling iterations; the last is the final value
  std::uint64_t boxes = 0;                       ///< 4^gridBits
  std::vector<std::uint8_t> visited;             ///< row-major (row = Y box, col = X box): 1 visited, 0 not
  bool cancelled = false;
  /// The visited fraction of the box (not the area b₂: stochasticAreaOf(map, fraction()) gives that).
  [[nodiscard]] double fraction() const noexcept { return convergence.empty() ? 0.0 : convergence.back().b2; }
};

/// Called on the calling thread at every checkpoint of the convergence curve.
using StochasticAreaObserver = std::function<void(const StochasticAreaPoint&)>;

/// Computes b₂ (as the visited fraction) and its convergence curve; throws std::invalid_argument on an invalid request.  On a stop
/// request (checked between chunks of at most 2^16 steps per orbit) returns the curve so far, cancelled set.
[[nodiscard]] StochasticAreaResult computeStochasticArea(const StochasticAreaRequest& request,
                                                         const StochasticAreaObserver& observer = {},
                                                         std::stop_token stop = {});

}  // namespace archipelago
