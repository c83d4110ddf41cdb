#pragma once
/// \file ParallelFor.hpp
/// \brief The one OpenMP parallel loop of core: a range of independent iterations, a stop token, and no
/// exception lost or escaping the parallel region.
///
/// STYLE.md: "no exceptions escape an OpenMP region".  An exception that leaves an OpenMP structured block
/// ends the program (std::terminate), so every parallel region of core is this loop: each iteration runs
/// inside a try block; the first exception thrown by any iteration is kept (std::exception_ptr), the other
/// threads take no new iteration, and it is rethrown on the calling thread after the region, when every
/// thread has left it.  Later exceptions (from iterations already running) are dropped: the caller sees
/// exactly one.  The stop token is checked before every iteration, so after a stop request each thread
/// finishes at most the iteration it is in.

#include <omp.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <stop_token>

namespace archipelago {

/// The number of threads parallelFor() uses for `requested` (0 or less: OpenMP's default), at least 1:
/// the size of per-thread buffers indexed by parallelFor's thread index.
[[nodiscard]] inline int parallelThreads(int requested = 0) noexcept {
  return requested > 0 ? requested : (omp_get_max_threads() > 0 ? omp_get_max_threads() : 1);
}

/// Runs body(i, thread) for every i in [0, count), in parallel on parallelThreads(threads) threads, one
/// iteration at a time per thread in any order (schedule(dynamic, 1)); `thread` (0 … threads − 1) is the
/// calling thread's index in the team, for per-thread buffers.  Returns true when every iteration ran, false
/// when `stop` was requested and some were skipped.  Rethrows the first exception an iteration threw, after
/// the region (see the file comment); iterations not yet started when it was thrown do not run.
template <class Body>
bool parallelFor(std::size_t count, Body&& body, std::stop_token stop = {}, int threads = 0) {
  std::exception_ptr error;  // written by the one thread that wins `failed`, read after the region's barrier
  std::atomic<bool> failed{false};
  std::atomic<bool> skipped{false};
  const auto n = static_cast<std::int64_t>(count);
#pragma omp parallel for num_threads(parallelThreads(threads)) schedule(dynamic, 1)
  for (std::int64_t i = 0; i < n; ++i) {
    if (failed.load(std::memory_order_relaxed)) continue;
    if (stop.stop_requested()) {
      skipped.store(true, std::memory_order_relaxed);
      continue;
    }
    try {
      body(static_cast<std::size_t>(i), omp_get_thread_num());
    } catch (...) {
      if (!failed.exchange(true)) error = std::current_exception();
    }
  }
  if (error) std::rethrow_exception(error);
  return !skipped.load();
}

}  // namespace archipelago
