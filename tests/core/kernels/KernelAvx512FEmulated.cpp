// The AVX-512F path's source (core/kernels/KernelAvx512F.inl) compiled a second time, against SIMDe 0.7.4's
// _mm512_* intrinsics (Debian's libsimde-dev), so that the tests run it on CPUs without AVX-512
// (KernelsUnderTest.hpp).  SIMDe implements each 512-bit operation as two native 256-bit ones here: the
// functions below are compiled for AVX2 + FMA (as KernelAvx2.cpp, through a target region that begins after
// every shared header), and SIMDe is told that AVX, AVX2 and FMA are native, so that its _mm512_fmadd_pd is two
// vfmadd…pd (a true fused multiply-add, rounded once in MXCSR's mode, which the exact-double method needs) and
// not a multiply and an add.

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/kernels/FloatModes.hpp"
#include "core/kernels/VectorKernels.hpp"
#include "core/random/CounterRng.hpp"
#include "core/trapping/TrappingHistogram.hpp"
#include "tests/core/kernels/KernelsUnderTest.hpp"

#if defined(__clang__)
#pragma clang attribute push(__attribute__((target("avx2,fma"))), apply_to = function)
#pragma clang diagnostic push
#pragma clang diagnostic ignored "-Wpsabi"  // 512-bit vector arguments of SIMDe's inline functions, inlined
#elif defined(__GNUC__)
#pragma GCC push_options
#pragma GCC target("avx2,fma")
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#define SIMDE_X86_AVX_NATIVE
#define SIMDE_X86_AVX2_NATIVE
#define SIMDE_X86_FMA_NATIVE
#define SIMDE_ENABLE_NATIVE_ALIASES
#include <simde/x86/avx512.h>
static_assert(SIMDE_NATURAL_VECTOR_SIZE == 256, "SIMDe must build each 512-bit operation from native 256-bit ones");
#if !defined(SIMDE_X86_FMA_NATIVE) || defined(SIMDE_X86_AVX512F_NATIVE)
#error "the emulated AVX-512F path needs SIMDe's FMA on native vfmadd and AVX-512F emulated"
#endif

namespace archipelago {
namespace {

#include "core/kernels/KernelAvx512F.inl"

void advanceBlocksEmulated(const KernelSettings& settings, std::span<OrbitState> orbits, std::uint64_t firstOrbit,
                           std::uint64_t blocks, SegmentSink& sink) {
  advanceBlocksAvx512FBody(settings, orbits, firstOrbit, blocks, sink);
}
void iterateOrbitsEmulated(const MapCoefficients& coefficients, MapDirection direction, std::span<UnitState> orbits,
                           std::uint64_t steps, UnitState* trace) {
  iterateOrbitsAvx512FBody(coefficients, direction, orbits, steps, trace);
}
std::uint64_t binDensityEmulated(const MapCoefficients& coefficients, std::span<UnitState> orbits,
                                 std::uint64_t steps, const RasterGrid& grid, std::uint8_t* counts,
                                 std::vector<std::uint32_t>& carries) {
  return binDensityAvx512FBody(coefficients, orbits, steps, grid, counts, carries);
}

}  // namespace
}  // namespace archipelago

#if defined(__clang__)
#pragma clang diagnostic pop
#pragma clang attribute pop
#elif defined(__GNUC__)
#pragma GCC diagnostic pop
#pragma GCC pop_options
#endif

namespace archipelago::kerneltests {

const KernelInfo& emulatedAvx512FKernel() noexcept {
  static const KernelInfo kernel{KernelKind::avx512f,
                                 "avx512f-emulated",
                                 "KernelAvx512F.inl on SIMDe's portable AVX-512F (tests only)",
                                 &advanceBlocksEmulated,
                                 &iterateOrbitsEmulated,
                                 &binDensityEmulated,
                                 kAvx512FBlockOrbits};
  return kernel;
}

std::vector<KernelInfo> kernelsUnderTest() {
  std::vector<KernelInfo> kernels = supportedKernels();
  const CpuFeatures cpu = CpuFeatures::detect();
  if (cpu.avx2 && !cpu.avx512f) kernels.push_back(emulatedAvx512FKernel());
  return kernels;
}

}  // namespace archipelago::kerneltests
