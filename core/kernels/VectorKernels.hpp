#pragma once
/// \file VectorKernels.hpp
/// \brief The kernels of every instruction-set path: trapping blocks and plain orbit iteration.
///
/// Karney (1983), appendix B: a trapping run iterates N⁻¹ on many independent orbits (steps 5–9), and a
/// phase portrait iterates N or N⁻¹ (figs. 1 and 2).  The map is defined on 52-bit integers (FixedPointMap.hpp), so
/// every path computes exactly the same numbers:
///   - scalar     : portable C++ with 128-bit products (the reference, advanceBlocksScalar in trapping/);
///   - avx2       : 4 orbits per 256-bit vector; X and Y as integer-valued doubles, every floor division one
///                  FMA rounded toward −∞ (KernelAvx2.cpp);
///   - avx512f    : 8 orbits per 512-bit vector, the avx2 method with AVX-512 Foundation only (KernelAvx512F.inl);
///   - avx512ifma : 8 orbits per 512-bit vector; ⌊a·b/2^52⌋ is one vpmadd52huq, exact for a, b < 2^52.
/// Each vector path advances several vectors of orbits in lockstep (a step's chain of dependent operations is
/// long, so independent vectors fill the pipeline): a block kernel keeps k…BlockOrbits orbits in flight, and
/// a call with fewer runs at a fraction of the speed, so callers hand it multiples of that (TrappingRun).
///
/// The avx2, avx512f and avx512ifma functions are compiled for those instruction sets only (function target
/// attributes; the rest of the program stays generic), so they may be called only when the CPU has them:
/// use KernelDispatch.hpp, which checks cpuid, rather than calling them directly.
///
/// Contract of every BlockKernel: identical to advanceBlocksScalar() — bit-identical orbit states (z, block,
/// draws, length, start) and the same SegmentSink records (possibly in another order, which the sink's
/// histograms and longest-segment list do not depend on).

#include <cstdint>
#include <span>
#include <vector>

#include "core/map/FixedPointMap.hpp"
#include "core/trapping/BlockKernel.hpp"

namespace archipelago {

/// Which map a plain orbit iteration applies.
enum class MapDirection { forward, backward };  ///< N (Q*) or N⁻¹

/// Advances every orbit by `steps` steps of N or N⁻¹.  When `trace` is not null it receives, after step j
/// (0-based), the state of orbit i at trace[j·orbits.size() + i]; it must hold steps·orbits.size() states.
using OrbitKernel = void (*)(const MapCoefficients& coefficients, MapDirection direction,
                             std::span<UnitState> orbits, std::uint64_t steps, UnitState* trace);

/// Where a point falls in a raster of iw × ih pixels over a view (portrait/PortraitRenderer.hpp's PixelMapping
/// holds one): the offsets from the view's exact centre (cx, cy), exact integers below 2^53 and so exact in
/// double, are scaled by sx, sy pixels per unit, each product and sum rounded on its own (never fused):
///   fx = double(int64(X − cx))·sx + hw,   fy = hh − double(int64(Y − cy))·sy;
/// the point is inside when 0 ≤ fx < w and 0 ≤ fy < h, in pixel (min(⌊fx⌋, iw − 1), min(⌊fy⌋, ih − 1)).
/// Every kernel bins with exactly this arithmetic, so rasters do not depend on the path.
struct RasterGrid {
  std::uint64_t cx = 0, cy = 0;
  double sx = 0, sy = 0, hw = 0, hh = 0, w = 0, h = 0;
  std::int64_t iw = 0, ih = 0;

  /// The pixel index row·iw + col of z, or −1 when z lies outside.
  [[nodiscard]] std::int64_t pixelOf(const UnitState& z) const noexcept {
    const double fx = static_cast<double>(static_cast<std::int64_t>(z.X - cx)) * sx + hw;
    const double fy = hh - static_cast<double>(static_cast<std::int64_t>(z.Y - cy)) * sy;
    if (!(fx >= 0 && fx < w && fy >= 0 && fy < h)) return -1;
    auto col = static_cast<std::int64_t>(fx), row = static_cast<std::int64_t>(fy);
    col = col < iw ? col : iw - 1;  // guard against fx rounding up to exactly w in the product
    row = row < ih ? row : ih - 1;
    return row * iw + col;
  }
};

/// Density binning (portraits, mode (a)): advances every orbit by `steps` steps of N and, after each step,
/// counts the point in `counts[grid.pixelOf(z)]` when it is inside.  The counts are 8-bit, so that a
/// megapixel raster stays in cache; whenever a count wraps to 0 the pixel index is appended to `carries`
/// (each entry is worth 256).  Returns the number of points counted.  The same orbit states as an
/// OrbitKernel with MapDirection::forward.
using DensityKernel = std::uint64_t (*)(const MapCoefficients& coefficients, std::span<UnitState> orbits,
                                        std::uint64_t steps, const RasterGrid& grid, std::uint8_t* counts,
                                        std::vector<std::uint32_t>& carries);

std::uint64_t binDensityScalar(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                               const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries);
std::uint64_t binDensityAvx2(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                             const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries);
std::uint64_t binDensityAvx512F(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                                const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries);
std::uint64_t binDensityAvx512Ifma(const MapCoefficients& coefficients, std::span<UnitState> orbits,
                                   std::uint64_t steps, const RasterGrid& grid, std::uint8_t* counts,
                                   std::vector<std::uint32_t>& carries);

void iterateOrbitsScalar(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                         std::uint64_t steps, UnitState* trace);

/// Orbits the block kernels of the vector paths keep in flight (KernelInfo::blockOrbits).
inline constexpr std::size_t kAvx2BlockOrbits = 24;        ///< 6 vectors of 4
inline constexpr std::size_t kAvx512FBlockOrbits = 32;     ///< 4 vectors of 8
inline constexpr std::size_t kAvx512IfmaBlockOrbits = 32;  ///< 4 vectors of 8

/// AVX2 path (requires AVX2 and FMA).
void advanceBlocksAvx2(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                       std::uint64_t blocks, SegmentSink& sink);
void iterateOrbitsAvx2(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                       std::uint64_t steps, UnitState* trace);

/// AVX-512F path (requires AVX-512 F; CpuFeatures::avx512f also asks for AVX2 and FMA, which the measure
/// kernels' accumulation uses).
void advanceBlocksAvx512F(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                          std::uint64_t blocks, SegmentSink& sink);
void iterateOrbitsAvx512F(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                          std::uint64_t steps, UnitState* trace);

/// AVX-512 IFMA path (requires AVX-512 F, VL, DQ and IFMA).
void advanceBlocksAvx512Ifma(const KernelSettings& settings, std::span<OrbitState> orbits,
                             std::uint64_t firstOrbit, std::uint64_t blocks, SegmentSink& sink);
void iterateOrbitsAvx512Ifma(const MapCoefficients& coefficients, MapDirection direction,
                             std::span<UnitState> orbits, std::uint64_t steps, UnitState* trace);

}  // namespace archipelago
