#pragma once
/// \file KernelDispatch.hpp
/// \brief Chooses the instruction-set path (scalar, AVX2, AVX-512F, AVX-512 IFMA) at run time, by CPU features.
///
/// Every path computes bit-identical results (VectorKernels.hpp), so the choice changes only the speed.
/// The order of preference is avx512ifma, avx512f, avx2, scalar; scalar runs everywhere.  A path may be forced:
///   - by name, kernelByName("avx2") (the CLI/GUI option), or
///   - by the environment variable ARCHIPELAGO_KERNEL=<name>, which selectKernel() honours when no name is
///     given;
/// forcing a path the CPU lacks is an error (std::invalid_argument with a one-line message), never a crash.
/// The name "auto" means bestKernel().

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/kernels/VectorKernels.hpp"

namespace archipelago {

enum class KernelKind { scalar, avx2, avx512f, avx512ifma };

/// One path: its name (as the CLI, run files and the GUI show it) and its entry points.  The table of paths
/// (allKernels()) has static storage: a `const KernelInfo*` into it stays valid for the program's life.
struct KernelInfo {
  KernelKind kind;
  std::string_view name;         ///< "scalar", "avx2", "avx512f", "avx512ifma"
  std::string_view description;  ///< one line for --help and the About box
  BlockKernel blocks;            ///< the trapping block kernel (BlockKernel.hpp)
  OrbitKernel orbits;            ///< plain orbit iteration (portraits)
  DensityKernel density;         ///< orbit iteration with density binning (portraits, mode (a))
  std::size_t blockOrbits;       ///< orbits `blocks` advances at full speed together: give it multiples
};

/// The CPU features the vector paths need (cpuid, including the operating system's support of the
/// registers, as reported by __builtin_cpu_supports).
struct CpuFeatures {
  bool avx2 = false;        ///< AVX2 and FMA together
  bool avx512ifma = false;  ///< AVX-512 F, VL, DQ and IFMA together
  bool avx512f = false;     ///< AVX-512 F, with AVX2 and FMA (every such CPU has them; the measures use them)
  /// The features of the CPU this program runs on.
  [[nodiscard]] static CpuFeatures detect() noexcept;
};

/// Every path, in order of preference (fastest first), whether or not this CPU supports it.
[[nodiscard]] std::span<const KernelInfo> allKernels() noexcept;

/// Whether `cpu` can run `kind` (scalar: always).
[[nodiscard]] bool supports(const CpuFeatures& cpu, KernelKind kind) noexcept;

/// The paths this CPU supports, fastest first (scalar is always last).
[[nodiscard]] std::vector<KernelInfo> supportedKernels();

/// The fastest path this CPU supports (ignores ARCHIPELAGO_KERNEL).
[[nodiscard]] const KernelInfo& bestKernel();

/// The path called `name` ("auto" = bestKernel()).  Throws std::invalid_argument when the name is unknown
/// (the message lists the known names) or when `cpu` lacks the instructions it needs.
[[nodiscard]] const KernelInfo& kernelByName(std::string_view name, const CpuFeatures& cpu = CpuFeatures::detect());

/// The path to use: `requested` when non-empty, else $ARCHIPELAGO_KERNEL when set and non-empty, else
/// bestKernel().  Throws like kernelByName() (naming the environment variable when it was the source).
/// Called once, at the edge (CLI command, GUI worker); core takes the result as a value (TrappingRunOptions,
/// PortraitRequest, StochasticAreaRequest) and never reads the environment itself.
[[nodiscard]] const KernelInfo& selectKernel(std::string_view requested = {});

/// `chosen`, the path a caller passed in a request or options, or bestKernel() when it passed none (nullptr).
[[nodiscard]] const KernelInfo& kernelOrBest(const KernelInfo* chosen);

/// Orbits per parallel task when `orbits` orbits are shared by `threads` threads (runs, b₂): the path's
/// blockOrbits, what it keeps in flight (fewer leave its pipeline half empty), or with few orbits smaller
/// groups (multiples of 8, at least min(8, blockOrbits)) so that every thread gets several tasks.
[[nodiscard]] std::size_t orbitsPerTask(const KernelInfo& kernel, std::size_t orbits, int threads) noexcept;

/// "avx512ifma, avx512f, avx2, scalar": the supported names, for help texts and error messages.
[[nodiscard]] std::string supportedKernelNames();

}  // namespace archipelago
