#include "core/kernels/KernelDispatch.hpp"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <stdexcept>

#include "core/io/NumberText.hpp"

namespace archipelago {

namespace {
// The one table of paths, fastest first: names, --help texts, dispatch and validation all read it.
const std::array<KernelInfo, 4> kKernels = {{
    {KernelKind::avx512ifma, "avx512ifma", "AVX-512 IFMA, 8 orbits per vector (vpmadd52huq)",
     &advanceBlocksAvx512Ifma, &iterateOrbitsAvx512Ifma, &binDensityAvx512Ifma, kAvx512IfmaBlockOrbits},
    {KernelKind::avx512f, "avx512f", "AVX-512F, 8 orbits per vector (the avx2 method: exact integer-valued doubles)",
     &advanceBlocksAvx512F, &iterateOrbitsAvx512F, &binDensityAvx512F, kAvx512FBlockOrbits},
    {KernelKind::avx2, "avx2", "AVX2 + FMA, 4 orbits per vector (exact integer-valued doubles, rounding down)", &advanceBlocksAvx2,
     &iterateOrbitsAvx2, &binDensityAvx2, kAvx2BlockOrbits},
    {KernelKind::scalar, "scalar", "portable C++ with 128-bit products (the reference)", &advanceBlocksScalar,
     &iterateOrbitsScalar, &binDensityScalar, kScalarBlockOrbits},
}};

std::string knownNames() {
  std::string s = "auto";
  for (const auto& k : kKernels) s += ", " + std::string(k.name);
  return s;
}
}  // namespace

CpuFeatures CpuFeatures::detect() noexcept {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __builtin_cpu_init();
  CpuFeatures f;
  f.avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");  // the AVX2 path needs both
  f.avx512ifma = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                 __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512ifma");
  f.avx512f = __builtin_cpu_supports("avx512f") && f.avx2;
  return f;
#else
  return {};
#endif
}

std::span<const KernelInfo> allKernels() noexcept { return kKernels; }

bool supports(const CpuFeatures& cpu, KernelKind kind) noexcept {
  switch (kind) {
    case KernelKind::scalar: return true;
    case KernelKind::avx2: return cpu.avx2;
    case KernelKind::avx512f: return cpu.avx512f;
    case KernelKind::avx512ifma: return cpu.avx512ifma;
  }
  return false;
}

std::vector<KernelInfo> supportedKernels() {
  const CpuFeatures cpu = CpuFeatures::detect();
  std::vector<KernelInfo> result;
  for (const auto& k : kKernels)
    if (supports(cpu, k.kind)) result.push_back(k);
  return result;
}

const KernelInfo& bestKernel() {
  const CpuFeatures cpu = CpuFeatures::detect();
  for (const auto& k : kKernels)
    if (supports(cpu, k.kind)) return k;
  return kKernels.back();
}

const KernelInfo& kernelByName(std::string_view name, const CpuFeatures& cpu) {
  if (name == "auto") {
    for (const auto& k : kKernels)
      if (supports(cpu, k.kind)) return k;
  }
  for (const auto& k : kKernels) {
    if (k.name != name) continue;
    if (!supports(cpu, k.kind))
      throw std::invalid_argument("kernel '" + io::shortText(name) + "' is not supported by this CPU (supported: " +
                                  supportedKernelNames() + ")");
    return k;
  }
  throw std::invalid_argument("unknown kernel '" + io::shortText(name) + "' (known: " + knownNames() + ")");
}

const KernelInfo& selectKernel(std::string_view requested) {
  if (!requested.empty()) return kernelByName(requested);
  const char* env = std::getenv("ARCHIPELAGO_KERNEL");
  if (env && *env) {
    try {
      return kernelByName(env);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("ARCHIPELAGO_KERNEL: ") + e.what());
    }
  }
  return bestKernel();
}

const KernelInfo& kernelOrBest(const KernelInfo* chosen) { return chosen ? *chosen : bestKernel(); }

std::size_t orbitsPerTask(const KernelInfo& kernel, std::size_t orbits, int threads) noexcept {
  const std::size_t full = kernel.blockOrbits;
  const auto perThread = static_cast<std::size_t>(threads > 0 ? threads : 1);
  if (orbits >= 2 * full * perThread) return full;
  return std::clamp<std::size_t>(orbits / (4 * perThread) / 8 * 8, std::min<std::size_t>(8, full), full);
}

std::string supportedKernelNames() {
  std::string s;
  for (const auto& k : supportedKernels()) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

}  // namespace archipelago
