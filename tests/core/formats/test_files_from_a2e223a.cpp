// Files written by commit a2e223a, before issue 51's job layer and issue 54's signed atlases and trees, still load
// with today's readers, with their values (issue 51, "Done when"): a run file, a tail file, an atlas (depth 1), a
// Markov tree and a GUI session.  tests/data/a2e223a/README.md says the command that made each.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/atlas/AtlasExport.hpp"
#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/session/SessionFile.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailResult.hpp"

namespace archipelago {
namespace {

const std::filesystem::path kData = std::filesystem::path(ARCHIPELAGO_TEST_DATA) / "a2e223a";

std::string text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(FilesFromA2e223a, ARunFileLoads) {
  const TrappingState s = loadRunFile(kData / "run.json");
  EXPECT_EQ(s.params.map.K, 0.1);
  EXPECT_EQ(s.params.q, 4u);
  EXPECT_EQ(s.params.T, 1000u);
  EXPECT_EQ(s.params.M, 16u);
  EXPECT_EQ(s.params.seed, 7u);
  EXPECT_TRUE(s.finished());
  EXPECT_EQ(s.orbits.size(), 16u);
  EXPECT_EQ(s.total().segments(), 10974u);  // "done: 10974 segments" when it was made
}

TEST(FilesFromA2e223a, ATailFileLoads) {
  const TailState s = loadTailFile(kData / "tail.json");
  EXPECT_EQ(s.request.run.q, 4u);
  EXPECT_EQ(s.request.population, 20u);
  EXPECT_EQ(s.request.replicas, 2u);
  EXPECT_EQ(s.steps, 683076u);
  EXPECT_TRUE(s.finished());
  const TailResult r = tailResult(s);
  ASSERT_FALSE(r.levels.empty());
  EXPECT_EQ(r.levels[0].t, 100.0);
  EXPECT_NEAR(r.levels[0].P, 0.0020780787529931146, 1e-15);  // the file's own estimate, recomputed from its state
}

TEST(FilesFromA2e223a, AnAtlasLoadsUnsigned) {
  const Atlas a = atlasFromJson(text(kData / "atlas.json"));
  EXPECT_EQ(a.request.map.K, 0.1);
  EXPECT_EQ(a.request.depth, 1);
  ASSERT_EQ(a.nodes.size(), 2u);
  EXPECT_EQ(a.nodes[1].period, 6u);
  EXPECT_EQ(toString(*a.nodes[1].aboutParent), "1/6");
  EXPECT_EQ(static_cast<double>(a.nodes[1].area), 0.006520957439150787);
  EXPECT_EQ(static_cast<double>(a.nodes[0].flux.flux), 0.00384338930254766);
}

TEST(FilesFromA2e223a, AMarkovTreeLoadsUnsigned) {
  const MarkovTreeResult m = markovTreeFromJson(text(kData / "tree.json"));
  EXPECT_EQ(m.map.K, 0.1);
  EXPECT_EQ(m.request.alpha, 18.9043);
  ASSERT_TRUE(m.weight);
  EXPECT_EQ(static_cast<double>(*m.weight), 0.05332655971897778);
  ASSERT_GE(m.survival.S.size(), 4u);
  EXPECT_EQ(m.survival.t[3], 4u);
  EXPECT_EQ(static_cast<double>(m.survival.S[0]), 0.981003205590889);
}

TEST(FilesFromA2e223a, ASessionLoadsWithItsRunAndAtlas) {
  const Session s = loadSession(kData / "session.archipelago");
  ASSERT_TRUE(s.runFile);
  EXPECT_EQ(*s.runFile, kData / "run.json");  // written relative, resolved against the session's folder
  EXPECT_EQ(loadRunFile(*s.runFile).params, s.spec.parameters);
  EXPECT_EQ(s.spec.parameters.seed, 7u);
  EXPECT_EQ(s.tab, "Phase portrait");
  EXPECT_EQ(s.portrait.mode, PortraitMode::Orbits);
  EXPECT_EQ(s.portrait.colours, ColourMapName::Viridis);
  EXPECT_EQ(s.portrait.history.size(), 2u);
  EXPECT_EQ(s.portrait.current, 1u);
  EXPECT_EQ(s.portrait.orbits.size(), 2u);
  EXPECT_EQ(s.segmentRank, 0);
  EXPECT_EQ(s.segmentPosition, 12u);
  ASSERT_EQ(s.plots.size(), 1u);
  EXPECT_EQ(s.plots[0].name, "f_t");
  ASSERT_TRUE(s.atlas);
  EXPECT_EQ(s.atlas->nodes.size(), 2u);
}

}  // namespace
}  // namespace archipelago
