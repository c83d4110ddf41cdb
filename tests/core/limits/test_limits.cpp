// The one table of limits (issue 35, item 2).  The bug it guards: the thread limit was 256 for runs, 1024 for
// indicator maps and rotation profiles, 4096 for the Kac check (and `flux`), with three wordings; rasters were
// bounded by four bare literals.  Every request now reads the table and words the error one way.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/limits/Limits.hpp"
#include "core/manifolds/KacCheck.hpp"
#include "core/measures/IndicatorMap.hpp"
#include "core/measures/RotationProfile.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/runspec/InputRules.hpp"
#include "core/runspec/RunSpec.hpp"

namespace archipelago {
namespace {

TEST(Limits, OneWordingOfARangeError) {
  EXPECT_EQ(rangeError("q", 0, 1, 65536), "q = 0 must lie in [1, 65536]");
  EXPECT_EQ(rangeError("q", 65536, 1, 65536), std::nullopt);
  EXPECT_EQ(rangeError("q", 1, 1, 65536), std::nullopt);
  EXPECT_EQ(rangeError("threads", -1, 0, 256, "0: one per core"), "threads = -1 must lie in [0, 256] (0: one per core)");
  EXPECT_EQ(threadsError(limits::kThreads), std::nullopt);
  EXPECT_EQ(threadsError(0), std::nullopt);
  EXPECT_EQ(threadsError(limits::kThreads + 1), "threads = 257 must lie in [0, 256] (0: one per core)");
}

// Issue 54: the Markov tree's entry (alpha >= 1 step, 0 < b2 <= the box's area) had no bound of its own wording.
TEST(Limits, OneWordingOfAHalfOpenOrUnboundedRealRange) {
  EXPECT_EQ(realIntervalError("b2", 0, 0, true, 1.69), "b2 = 0 must lie in (0, 1.69]");
  EXPECT_EQ(realIntervalError("b2", 1.69, 0, true, 1.69), std::nullopt);
  EXPECT_EQ(realIntervalError("b2", 2, 0, true, 1.69, "the area"), "b2 = 2 must lie in (0, 1.69] (the area)");
  EXPECT_EQ(realIntervalError("alpha", 0.5, 1, false, INFINITY), "alpha = 0.5 must be finite and at least 1");
  EXPECT_EQ(realIntervalError("alpha", 1, 1, false, INFINITY), std::nullopt);
  EXPECT_EQ(realIntervalError("alpha", INFINITY, 1, false, INFINITY), "alpha = inf must be finite and at least 1");
  EXPECT_EQ(realIntervalError("b2", -1, 0, true, INFINITY), "b2 = -1 must be finite and above 0");
  EXPECT_NE(realIntervalError("b2", NAN, 0, true, 1.69), std::nullopt);
}

TEST(Limits, TheTableHoldsEveryLimitOnce) {
  std::vector<std::string_view> keys;
  for (const LimitInfo& l : limitsTable()) {
    EXPECT_LE(l.min, l.max) << l.key;
    EXPECT_FALSE(l.what.empty()) << l.key;
    for (std::string_view k : keys) EXPECT_NE(k, l.key);
    keys.push_back(l.key);
  }
  EXPECT_EQ(keys.size(), 14u);
  EXPECT_EQ(kMaxThreads, limits::kThreads);  // the run spec's settings read the table
  EXPECT_EQ(kMaxQ, limits::kRunQ);           // the run's parameter table too
}

// Issue 51: the seed ensemble's limit moved from the CLI into the table; the seed list reader is core's.
TEST(Limits, ASeedListHoldsAtMostTheTablesSeeds) {
  EXPECT_EQ(parseSeedList("--seeds", "1..1000").size(), limits::kSeeds);
  try {
    (void)parseSeedList("--seeds", "1..1001");
    ADD_FAILURE() << "1001 seeds were read";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "--seeds = 1..1001 asks for more than 1000 seeds");
  }
  EXPECT_THROW((void)parseSeedList("seeds", "5..3"), std::invalid_argument);
  EXPECT_EQ(parseSeedList("seeds", "3,1..2"), (std::vector<std::uint64_t>{3, 1, 2}));
}

TEST(Limits, EveryComputationTakesTheSameThreads) {
  // One request of each kind, valid as made, then one thread too many: the same message from each.
  const std::string expected = *threadsError(limits::kThreads + 1);
  RunSpec spec;
  ASSERT_EQ(validationError(spec), std::nullopt);
  spec.threads = limits::kThreads + 1;
  EXPECT_EQ(validationError(spec), expected);

  IndicatorRequest indicator;
  ASSERT_EQ(validationError(indicator), std::nullopt);
  indicator.threads = limits::kThreads;
  EXPECT_EQ(validationError(indicator), std::nullopt);
  indicator.threads = limits::kThreads + 1;
  EXPECT_EQ(validationError(indicator), expected);

  KacRequest kac;
  ASSERT_EQ(validationError(kac), std::nullopt);
  kac.threads = limits::kThreads + 1;  // was accepted up to 4096
  EXPECT_EQ(validationError(kac), expected);

  RotationProfileRequest profile;
  profile.from = {-0.4L, 0};
  profile.to = {-0.2L, 0};
  ASSERT_EQ(validationError(profile), std::nullopt);
  profile.threads = limits::kThreads + 1;  // was accepted up to 1024
  EXPECT_EQ(validationError(profile), expected);
}

TEST(Limits, RastersOneRule) {
  PortraitRequest portrait;
  ASSERT_EQ(validationError(portrait), std::nullopt);
  portrait.width = limits::kRasterSide;
  portrait.height = limits::kRasterSide;
  EXPECT_EQ(validationError(portrait), std::nullopt);
  portrait.width = limits::kRasterSide + 1;
  EXPECT_EQ(validationError(portrait), "raster size = 16385x16384 must lie in [1, 16384] pixels each way");

  IndicatorRequest indicator;
  indicator.width = 4096;
  indicator.height = 4096;  // 2^24: the indicator's own bound in all
  EXPECT_EQ(validationError(indicator), std::nullopt);
  indicator.height = 4097;
  EXPECT_EQ(validationError(indicator),
            "raster size = 4096x4097 must lie in [1, 16384] pixels each way and at most 2^24 in all");
  indicator.height = 0;
  EXPECT_EQ(validationError(indicator), "raster size = 4096x0 must lie in [1, 16384] pixels each way and at most 2^24 in all");
}

}  // namespace
}  // namespace archipelago
