// The AVX-512F path: 8 orbits per 512-bit vector with the AVX2 path's exact-double method, for CPUs with
// AVX-512 Foundation and no IFMA (VectorKernels.hpp).  The policy and the loops are KernelAvx512F.inl, which the
// test suite also compiles against SIMDe to run it on CPUs without AVX-512 (tests/core/kernels).

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "core/kernels/FloatModes.hpp"
#include "core/kernels/VectorKernels.hpp"
#include "core/random/CounterRng.hpp"
#include "core/trapping/TrappingHistogram.hpp"

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx512f"))), apply_to = function)
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC target("avx512f")
// GCC 12's avx512fintrin.h: false -Wmaybe-uninitialized once inlined (GCC bug 105593), as in KernelAvx512Ifma.cpp.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

namespace archipelago {
namespace {

#include "core/kernels/KernelAvx512F.inl"

}  // namespace

void advanceBlocksAvx512F(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                          std::uint64_t blocks, SegmentSink& sink) {
  advanceBlocksAvx512FBody(settings, orbits, firstOrbit, blocks, sink);
}

void iterateOrbitsAvx512F(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                          std::uint64_t steps, UnitState* trace) {
  iterateOrbitsAvx512FBody(coefficients, direction, orbits, steps, trace);
}

std::uint64_t binDensityAvx512F(const MapCoefficients& coefficients, std::span<UnitState> orbits, std::uint64_t steps,
                                const RasterGrid& grid, std::uint8_t* counts, std::vector<std::uint32_t>& carries) {
  return binDensityAvx512FBody(coefficients, orbits, steps, grid, counts, carries);
}

}  // namespace archipelago

#if defined(__clang__)
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif
