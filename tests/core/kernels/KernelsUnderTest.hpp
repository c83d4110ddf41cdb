#pragma once
// The paths the bit-identity tests compare: every path this CPU supports (supportedKernels()), and, on a CPU with
// AVX2 and FMA but without AVX-512F, the AVX-512F path's very source (core/kernels/KernelAvx512F.inl) compiled
// against SIMDe's portable _mm512_* intrinsics (KernelAvx512FEmulated.cpp), named "avx512f-emulated".  So the
// AVX-512F kernel is checked bit for bit against the others on machines (this one, CI) that cannot run it
// natively.  Test-only: the emulated path is in no table of core and no program can choose it.

#include <vector>

#include "core/kernels/KernelDispatch.hpp"

namespace archipelago::kerneltests {

/// The emulated AVX-512F path (kind KernelKind::avx512f, so that the measures take the avx2 accumulation on its
/// trace); callable on any CPU with AVX2 and FMA.
[[nodiscard]] const KernelInfo& emulatedAvx512FKernel() noexcept;

/// supportedKernels(), fastest first, with emulatedAvx512FKernel() after them when the CPU has AVX2 and FMA
/// and no native AVX-512F path.
[[nodiscard]] std::vector<KernelInfo> kernelsUnderTest();

}  // namespace archipelago::kerneltests
