// Session files (.archipelago, issue #13): an exact round trip of everything the window shows, the run referenced
// or embedded (with its checksum), and every bad or foreign document refused with the key named, before anything
// is applied.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <limits>
#include <random>

#include <nlohmann/json.hpp>
#include <unistd.h>

#include "core/atlas/AtlasExport.hpp"
#include "core/io/Json.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/session/SessionFile.hpp"
#include "tests/core/DecimalCommaLocale.hpp"

namespace archipelago {
namespace {

namespace fs = std::filesystem;

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("archipelago-session-" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() { fs::remove_all(path); }
};

TrappingParameters smallRun() {
  TrappingParameters p;
  p.q = 4;
  p.T = 2000;
  p.M = 8;
  p.subsets = 4;
  p.seed = 5;
  return p;
}

Session fullSession(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  Session s;
  s.spec.parameters = smallRun();
  s.spec.parameters.map.K = 0.05 + unit(rng) / 10;  // digits that a short decimal would lose
  s.spec.name = "Custom";
  s.spec.threads = 2;
  s.tab = "Phase portrait";
  // Views down to the resolution limit, with sizes whose long double digits a double would lose.
  Viewport v = Viewport::wholeBox();
  s.portrait.history.push_back(v);
  for (int i = 0; i < 5; ++i) {
    v = v.zoomedAboutFraction(unit(rng), unit(rng), 1.0L + 1000.0L * static_cast<long double>(unit(rng)));
    s.portrait.history.push_back(v);
  }
  s.portrait.current = 4;
  s.portrait.mode = PortraitMode::Orbits;
  s.portrait.colours = ColourMapName::Viridis;
  s.portrait.budget = 123'456'789'012;
  s.portrait.orbits = {{{unit(rng), -unit(rng)}, 1 + rng() % 100'000'000, rng() % 2 == 0, 7},
                       {{1e-300, -0.0}, 20000, false, 0}};
  s.portrait.periodic = {{"7/20", {{0.1 * unit(rng), 0.2}, {0.3, 0.4}}}, {"", {{0, 0}}}};
  // The manifolds layer (issue 37, finding 4): off, of the fixed point, or of an orbit.
  const auto manifolds = rng() % 3;
  s.portrait.manifolds = manifolds > 0;
  if (manifolds == 2) s.portrait.manifoldOrbit = {{0.05 * unit(rng), 0.1}, {-0.2, 0.3 * unit(rng)}};
  s.segmentRank = 3;
  s.segmentPosition = 987654321;
  s.plots = {{"f_t", {1, 1e6, 1e-12, 1}}, {"C_tau", {1, 1e4, 1e-5, 0.5 * unit(rng) + 0.6}}};
  return s;
}

void expectSame(const Session& a, const Session& b) {
  EXPECT_TRUE(a.spec == b.spec);
  EXPECT_EQ(a.runFile, b.runFile);
  EXPECT_EQ(a.embeddedRun.has_value(), b.embeddedRun.has_value());
  EXPECT_EQ(a.tab, b.tab);
  EXPECT_TRUE(a.portrait == b.portrait);
  EXPECT_EQ(a.segmentRank, b.segmentRank);
  EXPECT_EQ(a.segmentPosition, b.segmentPosition);
  EXPECT_TRUE(a.plots == b.plots);
}

void expectRejected(const std::string& text, const std::string& mention) {
  try {
    (void)parseSession(text);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const io::BadFile& e) {
    EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what() << "\n  expected: " << mention;
  }
}

/// A valid document with `key` replaced by `value` (value "" removes the key), edited as JSON text.
std::string edited(const std::string& path, const std::string& value) {
  std::mt19937_64 rng(1);
  nlohmann::json j = nlohmann::json::parse(sessionText(fullSession(rng)));
  nlohmann::json* at = &j;
  std::string rest = path;
  for (std::size_t dot; (dot = rest.find('.')) != std::string::npos; rest = rest.substr(dot + 1))
    at = &(*at)[rest.substr(0, dot)];
  if (value.empty()) at->erase(rest);
  else (*at)[rest] = nlohmann::json::parse(value);
  return j.dump();
}

TEST(SessionFile, RoundTripIsExact) {
  std::mt19937_64 rng(2026);
  for (int i = 0; i < 200; ++i) {
    const Session s = fullSession(rng);
    const Session back = parseSession(sessionText(s));
    expectSame(s, back);
    EXPECT_EQ(sessionText(back), sessionText(s));
  }
}

TEST(SessionFile, EmbeddedRunKeepsItsStateAndChecksum) {
  std::mt19937_64 rng(7);
  Session s = fullSession(rng);
  s.spec.parameters = smallRun();
  s.embeddedRun = runTrapping(startTrapping(s.spec.parameters), TrappingRunOptions{});
  const std::string text = sessionText(s);
  const Session back = parseSession(text);
  ASSERT_TRUE(back.embeddedRun);
  EXPECT_EQ(back.embeddedRun->blocksDone, s.embeddedRun->blocksDone);
  EXPECT_TRUE(back.embeddedRun->subsets == s.embeddedRun->subsets);
  EXPECT_TRUE(back.embeddedRun->orbits == s.embeddedRun->orbits);
  EXPECT_TRUE(back.embeddedRun->longest == s.embeddedRun->longest);

  // An edit inside the embedded run is caught by the run file's own checksum.
  nlohmann::json j = nlohmann::json::parse(text);
  j["run"]["embedded"]["blocksDone"] = s.embeddedRun->blocksDone - 1;
  expectRejected(j.dump(), "run.embedded");
  // The panel's parameters may differ from the run's (edited after the run ended): both are kept.
  Session other = s;
  other.spec.parameters.seed += 1;
  const Session otherBack = parseSession(sessionText(other));
  EXPECT_EQ(otherBack.spec.parameters.seed, s.spec.parameters.seed + 1);
  EXPECT_EQ(otherBack.embeddedRun->params.seed, s.spec.parameters.seed);
}

// Issue 25, finding 13: a stopped run is final; its session says so, so that it does not come back resumable.
TEST(SessionFile, StoppedRunStaysStopped_Issue25Finding13) {
  std::mt19937_64 rng(9);
  Session s = fullSession(rng);
  s.runFile = "run.json";
  EXPECT_FALSE(parseSession(sessionText(s)).runStopped);
  s.runStopped = true;
  const std::string text = sessionText(s);
  EXPECT_TRUE(parseSession(text).runStopped);
  nlohmann::json j = nlohmann::json::parse(text);
  j["run"]["stopped"] = 1;
  expectRejected(j.dump(), "run.stopped");
  j["run"] = {{"stopped", true}};
  expectRejected(j.dump(), "exactly one");
}

TEST(SessionFile, ReferencedRunResolvesBesideTheSession) {
  TempDir dir;
  std::mt19937_64 rng(3);
  Session s = fullSession(rng);
  s.spec.parameters = smallRun();
  saveRunFile(dir.path / "run.json", runTrapping(startTrapping(s.spec.parameters), TrappingRunOptions{}));
  s.runFile = "run.json";
  saveSession(dir.path / "a.archipelago", s);
  const Session back = loadSession(dir.path / "a.archipelago");
  ASSERT_TRUE(back.runFile);
  EXPECT_EQ(fs::weakly_canonical(*back.runFile), fs::weakly_canonical(dir.path / "run.json"));

  fs::remove(dir.path / "run.json");
  try {
    (void)loadSession(dir.path / "a.archipelago");
    ADD_FAILURE() << "a missing run file was accepted";
  } catch (const io::BadFile& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
}

TEST(SessionFile, BadAndForeignDocumentsAreRefusedWithTheKeyNamed) {
  expectRejected("", "");
  expectRejected("[]", "JSON object");
  expectRejected(R"({"format": "archipelago-spec", "version": 1})", "not an Archipelago session");
  expectRejected(R"({"format": "archipelago-session", "version": 2, "spec": {}})", "version 2");
  expectRejected(R"({"format": "archipelago-session", "version": 1, "version": 1})", "");  // repeated key
  expectRejected(edited("spec", ""), "no 'spec'");
  expectRejected(edited("extra", "1"), "unknown key 'extra'");
  expectRejected(edited("spec.parameters", R"({"K": -1e300})"), "spec:");
  expectRejected(edited("portrait.history", R"([{"centre": [0, 0]}])"), "portrait.history[0] has no 'size'");
  expectRejected(edited("portrait.history", R"([{"centre": [1, 2, 3], "size": ["1e6", "1e6"]}])"), ".centre must be");
  expectRejected(edited("portrait.history", R"([{"centre": [4503599627370496, 0], "size": ["1e6", "1e6"]}])"),
                 "portrait.history[0].centre[0]");                                  // X = 2^52 is off the grid
  expectRejected(edited("portrait.history", R"([{"centre": [1000, 1000], "size": ["1e6", "1e6"]}])"),
                 "not inside the box");
  expectRejected(edited("portrait.history", R"([{"centre": [2251799813685248, 2251799813685248], "size": ["10", "1e6"]}])"),
                 "grid units must lie in");                                        // below the resolution
  expectRejected(edited("portrait.history", R"([{"centre": [2251799813685248, 2251799813685248], "size": ["nan", "1e6"]}])"),
                 "grid units must lie in");
  expectRejected(edited("portrait.history", R"([{"centre": [2251799813685248, 2251799813685248], "size": ["1e6x", "1e6"]}])"),
                 "is not a number");
  expectRejected(edited("portrait.current", "6"), "not an entry of portrait.history");
  std::string huge = edited("plots", R"([{"name": "f_t", "zoom": [0, 12345.5, 0, 1]}])");
  huge.replace(huge.find("12345.5"), 7, "1e999");  // past the largest double
  expectRejected(huge, "");
  expectRejected(edited("plots", R"([{"name": "f_t", "zoom": [1, 0, 0, 1]}])"), "xmin < xmax");
  expectRejected(edited("portrait.mode", R"("sketch")"), "not a portrait mode");
  expectRejected(edited("portrait.colours", R"("jet")"), "not a colour map");
  expectRejected(edited("portrait.budget", "-1"), "portrait.budget");
  expectRejected(edited("portrait.budget", "1e300"), "portrait.budget");
  expectRejected(edited("portrait.orbits", "[[0]]"), "portrait.orbits[0]");
  expectRejected(edited("portrait.orbits", R"([{"steps": 5}])"), "portrait.orbits[0] has no 'start'");
  expectRejected(edited("portrait.orbits", R"([{"start": [0.1, 0.2], "steps": 0}])"), "portrait.orbits[0].steps = 0");
  expectRejected(edited("portrait.orbits", R"([{"start": [0.1, 0.2], "steps": 100000001}])"), "portrait.orbits[0].steps");
  expectRejected(edited("portrait.orbits", R"([{"start": [0.1, 0.2], "backward": 1}])"), "backward must be true or false");
  expectRejected(edited("portrait.orbits", R"([{"start": [0.1, 0.2], "colour": 1}])"), "unknown key 'colour'");
  expectRejected(edited("portrait.orbits", R"([{"start": [0.1, 0.2], "number": 3}, {"start": [0.1, 0.3], "number": 3}])"),
                 "portrait.orbits[1].number = 3 is another orbit's number too");
  expectRejected(edited("portrait.periodic", R"([{"label": "x"}])"), "no 'points'");
  expectRejected(edited("portrait.manifolds", R"({"orbit": [], "x": 1})"), "unknown key 'x' in portrait.manifolds");
  expectRejected(edited("portrait.manifolds", R"({"orbit": []})"), "portrait.manifolds.orbit must hold");
  expectRejected(edited("portrait.manifolds", R"({"orbit": [[0.1]]})"), "portrait.manifolds.orbit[0]");
  expectRejected(edited("portrait.manifolds", "3"), "portrait.manifolds must be");
  expectRejected(edited("segment.rank", "-1"), "segment.rank");
  expectRejected(edited("segment.rank", "100000"), "segment.rank");
  expectRejected(edited("plots", R"([{"name": "f_t", "zoom": [1, 2, 1, 2]}, {"name": "f_t", "zoom": [1, 2, 1, 2]}])"),
                 "zoomed twice");
  expectRejected(edited("run", R"({"file": "a.json", "embedded": {}})"), "exactly one");
  expectRejected(edited("run", R"({"file": ""})"), "must not be empty");
  expectRejected(edited("tab", "3"), "tab must be a string");

  // Oversized lists are refused before they are held.
  nlohmann::json orbits = nlohmann::json::array();
  for (std::size_t i = 0; i <= kMaxSessionOrbits; ++i) orbits.push_back({0.1, 0.2});
  expectRejected(edited("portrait.orbits", orbits.dump()), "at most");
}

// Issue 53, finding 2: a session kept only each launched orbit's start ("orbits": [[x, y], …]), so 100 000 steps
// backward came back as 20 000 forward, renumbered and recoloured.  Each keeps its steps, direction and number now;
// an old session's entries still read, as what they meant: 20 000 steps forward, numbered in order.
TEST(SessionFile, LaunchedOrbitsKeepStepsDirectionAndNumber_Issue53) {
  std::mt19937_64 rng(53);
  Session s = fullSession(rng);
  s.portrait.orbits = {{{0.06, 0.0974}, 100000, true, 4}, {{-0.2, 0.01}, 1, false, 9}};
  const Session back = parseSession(sessionText(s));
  ASSERT_EQ(back.portrait.orbits.size(), 2u);
  EXPECT_EQ(back.portrait.orbits[0].start, (std::array<double, 2>{0.06, 0.0974}));
  EXPECT_EQ(back.portrait.orbits[0].steps, 100000u);
  EXPECT_TRUE(back.portrait.orbits[0].backward);
  EXPECT_EQ(back.portrait.orbits[0].number, 4u);
  EXPECT_EQ(back.portrait.orbits[1].steps, 1u);
  EXPECT_FALSE(back.portrait.orbits[1].backward);
  EXPECT_EQ(back.portrait.orbits[1].number, 9u);

  const Session old = parseSession(edited("portrait.orbits", "[[0.06, 0.0974], [-0.2, 0.01]]"));
  ASSERT_EQ(old.portrait.orbits.size(), 2u);
  EXPECT_EQ(old.portrait.orbits[1].start, (std::array<double, 2>{-0.2, 0.01}));
  EXPECT_EQ(old.portrait.orbits[1].steps, kSessionOrbitSteps);
  EXPECT_FALSE(old.portrait.orbits[1].backward);
  EXPECT_EQ(old.portrait.orbits[1].number, 0u);
}

// Issue #23, finding 1: a deep value anywhere in a session (its version, spec, embedded run, a plot zoom, the
// budget) crashed the reader; each is now one clean error naming the depth.
TEST(SessionFile, DeepJson_Issue23_IsACleanErrorAnywhere) {
  const std::string deep = std::string(60000, '[') + std::string(60000, ']');
  for (const char* key : {"version", "spec", "run", "portrait.budget", "plots", "tab"}) {
    std::string text = edited(key, R"("@DEEP@")");
    text.replace(text.find(R"("@DEEP@")"), 8, deep);
    expectRejected(text, "nested deeper than");
  }
  // A version-1 embedded run (no checksum) is refused like a version-1 run file.
  std::mt19937_64 rng(7);
  Session s = fullSession(rng);
  s.spec.parameters = smallRun();
  s.embeddedRun = runTrapping(startTrapping(s.spec.parameters), TrappingRunOptions{});
  nlohmann::json j = nlohmann::json::parse(sessionText(s));
  j["run"]["embedded"].erase("checksum");
  j["run"]["embedded"]["version"] = 1;
  expectRejected(j.dump(), "version 1 has no checksum");
  // A NUL in the run's path would be cut by the C library: refused.
  expectRejected(edited("run", R"({"file": "run.json\u0000x"})"), "NUL");
}

class SessionLocale : public testing::DecimalCommaLocale {};

// Issue #23, finding 2: under a decimal-comma locale view sizes were written "4503599627370,5", which another
// locale's reader refused.  The text is the same bytes in any locale, and reads back in any locale.
TEST_F(SessionLocale, SessionsAreTheSameBytesInEveryLocale_Issue23) {
  std::mt19937_64 rng(11);
  const Session s = fullSession(rng);
  const std::string here = sessionText(s);
  EXPECT_EQ(here.find(",5\""), std::string::npos);
  expectSame(s, parseSession(here));
  std::setlocale(LC_ALL, "C");
  EXPECT_EQ(sessionText(s), here);
  expectSame(s, parseSession(here));
}

TEST(SessionFile, FilesAreBoundedAndRegular) {
  TempDir dir;
  EXPECT_THROW((void)loadSession(dir.path), io::BadFile);             // a folder
  EXPECT_THROW((void)loadSession(dir.path / "none.archipelago"), io::BadFile);
  EXPECT_THROW((void)loadSession("/dev/zero"), io::BadFile);          // not a regular file
  std::ofstream(dir.path / "truncated.archipelago") << R"({"format": "archipelago-session", "vers)";
  EXPECT_THROW((void)loadSession(dir.path / "truncated.archipelago"), io::BadFile);
}

// Issue 38, deliverable 3: the Atlas page's atlas is kept in the session as core/atlas's document (read back, not
// recomputed); a session without one opens as before, a corrupted one or one of another map is refused by name.
Atlas smallAtlas(const MapParameters& map) {
  Atlas a;
  a.request.map = map;
  a.request.depth = 1;
  a.seconds = 3.25;
  AtlasNode centre;
  centre.centre = {-std::sqrt(map.K), 0};
  centre.orbit.period = 1;
  centre.orbit.points = {centre.centre};
  centre.orbit.residue = std::sqrt(map.K);
  centre.boundaryFound = true;
  centre.boundaryPoint = {-0.08, 0};
  centre.boundaryRotation = 0.17;
  centre.boundaryDigits = 14;
  centre.area = centre.circleArea = 0.2391965;
  centre.polygonError = 2e-7;
  centre.areaLower = 0.2391963;
  centre.areaUpper = 0.2406;  // issue 50: the interval that holds the true area
  centre.areaError = centre.areaUpper - centre.area;
  centre.areaPoints = 8192;
  centre.children = {1};
  centre.measured = true;
  AtlasNode six;
  six.parent = 0;
  six.level = 1;
  six.period = 6;
  six.aboutParent = Rational{1, 6};
  six.centre = {0.0157, 0};
  six.orbit.period = 6;
  six.orbit.points = {six.centre};
  six.boundaryFailure = "below the scan's resolution";
  six.flux.failure = "no hyperbolic partner found between the islands";
  six.measured = true;
  a.nodes = {centre, six};
  return a;
}

TEST(SessionFile, KeepsTheAtlasOfItsMap_Issue38) {
  std::mt19937_64 rng(38);
  Session s = fullSession(rng);
  EXPECT_EQ(sessionText(s).find("\"atlas\""), std::string::npos);  // written only when there is one
  EXPECT_FALSE(parseSession(sessionText(s)).atlas.has_value());    // and a session without it opens as before
  s.atlas = smallAtlas(s.spec.parameters.map);
  const std::string text = sessionText(s);
  const Session back = parseSession(text);
  expectSame(s, back);
  ASSERT_TRUE(back.atlas.has_value());
  EXPECT_EQ(atlasJson(*back.atlas), atlasJson(*s.atlas));
  EXPECT_EQ(sessionText(back), text);

  const auto withAtlas = [&](const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = nlohmann::json::parse(text);
    nlohmann::json& a = j["atlas"];
    edit(a);
    if (a.is_object() && a.contains("format_version")) {  // signed again: the edit meets the rule it tests
      a.erase("checksum");
      a["checksum"] = io::jsonChecksum(a);
    }
    return j.dump();
  };
  expectRejected(withAtlas([](nlohmann::json& a) { a["nodes"][1]["period"] = -1; }), "atlas: nodes[1].period");
  expectRejected(withAtlas([](nlohmann::json& a) { a["nodes"][1]["area"] = nullptr; }), "atlas: nodes[1].area");
  expectRejected(withAtlas([](nlohmann::json& a) { a.erase("nodes"); }), "atlas: the atlas has no 'nodes'");
  expectRejected(withAtlas([](nlohmann::json& a) { a = 3; }), "atlas: the atlas must be a JSON object");
  expectRejected(withAtlas([](nlohmann::json& a) { a["map"]["K"] = 0.2; }), "not the session's map");
  std::string truncated = text;
  truncated.resize(text.find("\"nodes\"") + 20);
  expectRejected(truncated, "");
}

}  // namespace
}  // namespace archipelago
