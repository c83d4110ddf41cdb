// Regression test for issue #11, item 5: runTrapping() computed in an OpenMP region with no exception guard, and
// the threads' longest-segment lists (LongestSegments::insert) allocate there: a std::bad_alloc ended the program
// through std::terminate.  It must reach the caller as std::bad_alloc, for every kernel, and leave the program
// able to run again.
//
// The failure is real: this executable replaces the global operator new, which throws std::bad_alloc once,
// at the first allocation made inside an active OpenMP region after the test arms it.  (Its own executable, so
// that no other test runs with the replacement.)
#include <gtest/gtest.h>

#include <omp.h>

#include <atomic>
#include <cstdlib>
#include <new>

#include "core/kernels/KernelDispatch.hpp"
#include "core/run/TrappingRun.hpp"

namespace {
std::atomic<bool> gFailNextAllocationInParallel{false};
}  // namespace

// The replacement pair allocates with malloc and frees with free, which GCC cannot tell apart from a mismatch.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  if (gFailNextAllocationInParallel.load(std::memory_order_relaxed) && omp_in_parallel() &&
      gFailNextAllocationInParallel.exchange(false))
    throw std::bad_alloc();
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace archipelago {
namespace {

TrappingParameters smallRun() {
  TrappingParameters p;  // the paper's K = 0.1 box
  p.q = 4;
  p.T = 400;
  p.M = 96;
  p.longestKept = 50;  // each thread's list starts empty every chunk: its first insert allocates
  return p;
}

TEST(AllocationFailure, InsideARunArrivesAsBadAllocForEveryKernel) {
  // The OpenMP runtime initialised before the replacement is armed: libomp (clang's, the asan preset's) initialises
  // at its first call and may load an OMPT tool (Debian's loads libarcher) that allocates; an armed operator new
  // calling omp_in_parallel() from inside that initialisation re-entered it and spun on its lock for ever.
  ASSERT_FALSE(omp_in_parallel());
  for (const auto& kernel : supportedKernels()) {
    SCOPED_TRACE(kernel.name);
    TrappingRunOptions options;
    options.kernel = &kernel;
    options.threads = 2;
    gFailNextAllocationInParallel = true;
    EXPECT_THROW((void)runTrapping(startTrapping(smallRun()), options), std::bad_alloc);
    EXPECT_FALSE(gFailNextAllocationInParallel.exchange(false)) << "no allocation failed inside the region";
    // Nothing is left broken: the same run now completes.
    const TrappingState done = runTrapping(startTrapping(smallRun()), options);
    EXPECT_TRUE(done.finished());
    EXPECT_GT(done.total().segments(), 0u);
  }
}

}  // namespace
}  // namespace archipelago
