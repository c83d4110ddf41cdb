#pragma once
/// \file VectorKernels.hpp
/// \brief The kernels of every instruction-set path: trapping blocks and plain orbit iteration.
///
/// Karney (1983), appendix B: a trapping run iterates N⁻¹ on many independent orbits (steps 5–9), and a
/// phase portrait iterates N or N⁻¹ (fig. 1–3).  The map is defined on 52-bit integers (FixedPointMap.hpp), so
/// every path computes exactly the same numbers:
///   - scalar     : portable C++ with 128-bit products (the reference, advanceBlocksScalar in trapping/);
///   - avx2       : 4 orbits per 256-bit vector; 52×52-bit products from four 32×32-bit vpmuludq;
///   - avx512ifma : 8 orbits per 512-bit vector; ⌊a·b/2^52⌋ is one vpmadd52huq, exact for a, b < 2^52.
/// Each vector path advances several vectors of orbits in lockstep (the chain of two dependent products per
/// step has ~13 cycles of latency, so independent vectors fill the pipeline).
///
/// The avx2 and avx512ifma functions are compiled for those instruction sets only (function target
/// attributes; the rest of the program stays generic), so they may be called only when the CPU has them:
/// use KernelDispatch.hpp, which checks cpuid, rather than calling them directly.
///
/// Contract of every BlockKernel: identical to advanceBlocksScalar() — bit-identical orbit states (z, block,
/// draws, length, start) and the same SegmentSink records (possibly in another order, which the sink's
/// histograms and longest-segment list do not depend on).

#include <cstdint>
#include <span>

#include "map/FixedPointMap.hpp"
#include "trapping/BlockKernel.hpp"

namespace archipelago {

/// Which map a plain orbit iteration applies.
enum class MapDirection { forward, backward };  ///< N (Q*) or N⁻¹

/// Advances every orbit by `steps` steps of N or N⁻¹.  When `trace` is not null it receives, after step j
/// (0-based), the state of orbit i at trace[j·orbits.size() + i]; it must hold steps·orbits.size() states.
using OrbitKernel = void (*)(const MapCoefficients& coefficients, MapDirection direction,
                             std::span<UnitState> orbits, std::uint64_t steps, UnitState* trace);

void iterateOrbitsScalar(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                         std::uint64_t steps, UnitState* trace);

/// AVX2 path (requires AVX2).
void advanceBlocksAvx2(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                       std::uint64_t blocks, SegmentSink& sink);
void iterateOrbitsAvx2(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                       std::uint64_t steps, UnitState* trace);

/// AVX-512 IFMA path (requires AVX-512 F, VL, DQ and IFMA).
void advanceBlocksAvx512Ifma(const KernelSettings& settings, std::span<OrbitState> orbits,
                             std::uint64_t firstOrbit, std::uint64_t blocks, SegmentSink& sink);
void iterateOrbitsAvx512Ifma(const MapCoefficients& coefficients, MapDirection direction,
                             std::span<UnitState> orbits, std::uint64_t steps, UnitState* trace);

}  // namespace archipelago
