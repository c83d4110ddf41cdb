// parallelFor (parallel/ParallelFor.hpp), the one OpenMP loop of core: every iteration once, stop requests,
// and an exception rethrown once on the calling thread after every thread left the region (issue #11, item 5:
// an exception leaving an OpenMP region ends the program).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel/ParallelFor.hpp"

namespace archipelago {
namespace {

// Counts the iterations in progress; the destructor runs while an exception unwinds, too.
struct InFlight {
  explicit InFlight(std::atomic<int>& n) : n_(n) { n_.fetch_add(1); }
  ~InFlight() { n_.fetch_sub(1); }
  std::atomic<int>& n_;
};

TEST(ParallelFor, RunsEveryIterationOnceWithAThreadIndexInRange) {
  constexpr std::size_t kCount = 1000;
  constexpr int kThreads = 3;
  std::vector<std::atomic<int>> hits(kCount);
  std::atomic<int> badThread{0};
  const bool complete = parallelFor(
      kCount,
      [&](std::size_t i, int thread) {
        hits[i].fetch_add(1);
        if (thread < 0 || thread >= kThreads) badThread.fetch_add(1);
      },
      {}, kThreads);
  EXPECT_TRUE(complete);
  EXPECT_EQ(badThread.load(), 0);
  for (std::size_t i = 0; i < kCount; ++i) ASSERT_EQ(hits[i].load(), 1) << i;
  EXPECT_TRUE(parallelFor(0, [](std::size_t, int) { FAIL() << "no iteration in an empty range"; }));
}

TEST(ParallelFor, AnExceptionIsRethrownOnceAfterEveryThreadLeftAndTheRestIsSkipped) {
  constexpr std::size_t kCount = 4000;  // 0.2 ms each: about 0.4 s on 2 threads if nothing were skipped
  std::atomic<int> inFlight{0}, started{0};
  int caught = 0;
  std::string message;
  try {
    (void)parallelFor(
        kCount,
        [&](std::size_t i, int) {
          const InFlight guard(inFlight);
          started.fetch_add(1);
          std::this_thread::sleep_for(std::chrono::microseconds(200));
          if (i == 5) throw std::runtime_error("iteration 5");
          if (i == 6) throw std::logic_error("iteration 6");
        },
        {}, 4);
  } catch (const std::exception& e) {
    ++caught;
    message = e.what();
    EXPECT_EQ(inFlight.load(), 0) << "rethrown while an iteration was still running";
  }
  EXPECT_EQ(caught, 1);
  EXPECT_TRUE(message == "iteration 5" || message == "iteration 6") << message;
  EXPECT_LT(started.load(), static_cast<int>(kCount) / 2) << "the other threads did not stop early";
}

TEST(ParallelFor, KeepsTheExceptionsType) {
  EXPECT_THROW((void)parallelFor(8, [](std::size_t i, int) { if (i == 3) throw std::bad_alloc(); }, {}, 2),
               std::bad_alloc);
}

TEST(ParallelFor, StopRequestedBeforeRunsNothing) {
  std::stop_source source;
  source.request_stop();
  std::atomic<int> ran{0};
  EXPECT_FALSE(parallelFor(100, [&](std::size_t, int) { ran.fetch_add(1); }, source.get_token(), 2));
  EXPECT_EQ(ran.load(), 0);
}

TEST(ParallelFor, StopRequestedDuringTheLoopReturnsEarlyAfterFinishingTheIterationsInProgress) {
  constexpr std::size_t kCount = 4000;
  std::stop_source source;
  std::atomic<int> started{0}, finished{0};
  const bool complete = parallelFor(
      kCount,
      [&](std::size_t i, int) {
        started.fetch_add(1);
        if (i == 10) source.request_stop();
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        finished.fetch_add(1);
      },
      source.get_token(), 2);
  EXPECT_FALSE(complete);
  EXPECT_EQ(started.load(), finished.load());  // nothing abandoned halfway
  EXPECT_LT(started.load(), static_cast<int>(kCount) / 2);
}

}  // namespace
}  // namespace archipelago
