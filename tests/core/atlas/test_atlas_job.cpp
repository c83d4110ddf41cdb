// The atlas as a job (core/atlas/AtlasJob.hpp, issue 51): the atlas to continue read and checked in one call, and the
// report's reuse-or-resume of a file (once written three times: the CLI, the report, Python).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/atlas/AtlasExport.hpp"
#include "core/atlas/AtlasJob.hpp"
#include "core/io/AtomicFile.hpp"

namespace archipelago {
namespace {

/// The centre alone (depth 0) at K = 0.1, scanned coarsely: one island to compute.
AtlasRequest centreOnly() {
  AtlasRequest r;
  r.depth = 0;
  r.maxPeriod = 50;
  r.scanSteps = 0;
  return r;
}

std::stop_token stopped() {
  static std::stop_source source;
  source.request_stop();
  return source.get_token();
}

TEST(AtlasJob, TheAtlasToResumeIsReadAndCheckedWithTheFrontEndsName) {
  try {
    (void)atlasToResume(centreOnly(), "{not json", "resume");
    ADD_FAILURE() << "garbage was read as an atlas";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("resume: ", 0), 0u) << e.what();
  }
}

TEST(AtlasJob, AFileIsDiscardedResumedThenReused) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "archipelago_test_atlas_job.json";
  std::filesystem::remove(file);
  { std::ofstream(file) << "{not an atlas"; }
  // Unreadable: said why, computed anew (here stopped at once) and written.
  AtlasFileOutcome a = atlasOrResumeFile(file, centreOnly(), {}, stopped());
  EXPECT_NE(a.discarded.find(file.string()), std::string::npos) << a.discarded;
  EXPECT_FALSE(a.reused || a.resumed);
  EXPECT_TRUE(a.atlas.cancelled);
  // The stopped atlas of this request: continued to its end, written again.
  AtlasFileOutcome b = atlasOrResumeFile(file, centreOnly());
  EXPECT_TRUE(b.discarded.empty()) << b.discarded;
  EXPECT_TRUE(b.resumed);
  EXPECT_FALSE(b.atlas.cancelled);
  ASSERT_FALSE(b.atlas.nodes.empty());
  EXPECT_TRUE(b.atlas.nodes[0].measured);
  // The finished atlas of this request: reused, nothing computed.
  int calls = 0;
  AtlasFileOutcome c = atlasOrResumeFile(file, centreOnly(), [&](const Atlas&, int, const std::string&) { ++calls; });
  EXPECT_TRUE(c.reused);
  EXPECT_EQ(calls, 0);
  EXPECT_EQ(atlasJson(c.atlas), atlasJson(b.atlas));
  // An atlas of another request: not reused, said why.
  AtlasRequest other = centreOnly();
  other.maxPeriod = 60;
  AtlasFileOutcome d = atlasOrResumeFile(file, other, {}, stopped());
  EXPECT_FALSE(d.reused || d.resumed);
  EXPECT_FALSE(d.discarded.empty());
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace archipelago
