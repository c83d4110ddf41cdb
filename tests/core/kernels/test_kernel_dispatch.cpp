// Run-time choice of the instruction-set path (core/kernels/KernelDispatch.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"

namespace archipelago {
namespace {

std::string errorOf(const auto& call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Sets an environment variable for one scope and restores the previous value.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old, hadOld_ = true;
    value ? setenv(name, value, 1) : unsetenv(name);
  }
  ~ScopedEnv() { hadOld_ ? setenv(name_, old_.c_str(), 1) : unsetenv(name_); }

 private:
  const char* name_;
  std::string old_;
  bool hadOld_ = false;
};

TEST(KernelDispatch, ScalarIsAlwaysSupportedAndLast) {
  const auto supported = supportedKernels();
  ASSERT_FALSE(supported.empty());
  EXPECT_EQ(supported.back().kind, KernelKind::scalar);
  EXPECT_EQ(supported.front().kind, bestKernel().kind);
  EXPECT_TRUE(supports(CpuFeatures{}, KernelKind::scalar));
  EXPECT_EQ(kernelByName("scalar", CpuFeatures{}).blocks, &advanceBlocksScalar);
  EXPECT_NE(supportedKernelNames().find("scalar"), std::string::npos);
  RecordProperty("supported_kernels", supportedKernelNames());
}

TEST(KernelDispatch, PreferenceOrderFollowsTheCpuFeatures) {
  EXPECT_EQ(kernelByName("auto", CpuFeatures{false, false}).kind, KernelKind::scalar);
  EXPECT_EQ(kernelByName("auto", CpuFeatures{true, false}).kind, KernelKind::avx2);
  EXPECT_EQ(kernelByName("auto", CpuFeatures{true, true, true}).kind, KernelKind::avx512ifma);
  // Issue 41: AVX-512F without IFMA (Skylake-SP, Cascade Lake) takes the AVX-512F path, between IFMA and AVX2.
  EXPECT_EQ(kernelByName("auto", CpuFeatures{true, false, true}).kind, KernelKind::avx512f);
  std::vector<std::string_view> order;
  for (const auto& k : allKernels()) order.push_back(k.name);
  EXPECT_EQ(order, (std::vector<std::string_view>{"avx512ifma", "avx512f", "avx2", "scalar"}));
  EXPECT_EQ(kernelByName("auto").kind, bestKernel().kind);
  const CpuFeatures cpu = CpuFeatures::detect();
  for (const auto& k : allKernels())  // by name: found exactly when this CPU supports it
    EXPECT_EQ(supports(cpu, k.kind), errorOf([&] { (void)kernelByName(k.name, cpu); }).empty()) << k.name;
}

TEST(KernelDispatch, EveryKernelIsFoundByName) {
  for (const auto& k : allKernels()) {
    const auto& found = kernelByName(k.name, CpuFeatures{true, true, true});
    EXPECT_EQ(found.kind, k.kind);
    EXPECT_EQ(found.name, k.name);
  }
}

TEST(KernelDispatch, UnknownOrUnsupportedKernelIsAClearError) {
  const std::string unknown = errorOf([] { (void)kernelByName("avx1024"); });
  EXPECT_NE(unknown.find("unknown kernel 'avx1024'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("avx512ifma"), std::string::npos) << unknown;  // lists the known names

  const std::string noIfma = errorOf([] { (void)kernelByName("avx512ifma", CpuFeatures{true, false}); });
  EXPECT_NE(noIfma.find("kernel 'avx512ifma' is not supported by this CPU"), std::string::npos) << noIfma;
  // Issue 41: forcing the AVX-512F path on a CPU without it (this machine, CI) is an error, never a crash.
  const std::string noAvx512F = errorOf([] { (void)kernelByName("avx512f", CpuFeatures{true, false, false}); });
  EXPECT_NE(noAvx512F.find("kernel 'avx512f' is not supported by this CPU"), std::string::npos) << noAvx512F;
  const std::string noAvx2 = errorOf([] { (void)kernelByName("avx2", CpuFeatures{false, false}); });
  EXPECT_NE(noAvx2.find("kernel 'avx2' is not supported by this CPU"), std::string::npos) << noAvx2;
}

TEST(KernelDispatch, EnvironmentVariableOverridesTheDefault) {
  {
    const ScopedEnv env("ARCHIPELAGO_KERNEL", nullptr);
    EXPECT_EQ(selectKernel().kind, bestKernel().kind);
  }
  {
    const ScopedEnv env("ARCHIPELAGO_KERNEL", "");
    EXPECT_EQ(selectKernel().kind, bestKernel().kind);
  }
  for (const auto& k : supportedKernels()) {
    const ScopedEnv env("ARCHIPELAGO_KERNEL", std::string(k.name).c_str());
    EXPECT_EQ(selectKernel().kind, k.kind);
    EXPECT_EQ(selectKernel("scalar").kind, KernelKind::scalar);  // an explicit request wins
  }
  {
    const ScopedEnv env("ARCHIPELAGO_KERNEL", "fastest");
    const std::string error = errorOf([] { (void)selectKernel(); });
    EXPECT_NE(error.find("ARCHIPELAGO_KERNEL: unknown kernel 'fastest'"), std::string::npos) << error;
  }
}

// runTrapping sizes its groups by the kernel it is given (TrappingRun.cpp, KernelInfo::blockOrbits): every path
// names how many orbits it keeps in flight, whole vectors of its width.
TEST(KernelDispatch, EveryPathNamesTheOrbitsItKeepsInFlight) {
  for (const auto& k : allKernels()) {
    SCOPED_TRACE(k.name);
    const std::size_t width =
        k.kind == KernelKind::avx512ifma || k.kind == KernelKind::avx512f ? 8 : k.kind == KernelKind::avx2 ? 4 : 1;
    EXPECT_GE(k.blockOrbits, 2 * width);
    EXPECT_EQ(k.blockOrbits % width, 0u);
    // Tasks are whole groups of what the path keeps in flight when there are enough orbits …
    EXPECT_EQ(orbitsPerTask(k, 2 * k.blockOrbits * 4, 4), k.blockOrbits);
    // … and smaller ones (never below a vector's worth, multiples of 8) so that few orbits still feed every thread.
    for (const std::size_t orbits : {1u, 21u, 75u, 200u}) {
      const std::size_t task = orbitsPerTask(k, orbits, 2);
      EXPECT_GE(task, std::min<std::size_t>(8, k.blockOrbits)) << orbits;
      EXPECT_LE(task, k.blockOrbits) << orbits;
      if (task < k.blockOrbits) {
        EXPECT_EQ(task % 8, 0u) << orbits;
      }
    }
  }
  EXPECT_EQ(&kernelOrBest(nullptr), &bestKernel());
  EXPECT_EQ(&kernelOrBest(&allKernels().back()), &allKernels().back());
}

}  // namespace
}  // namespace archipelago
