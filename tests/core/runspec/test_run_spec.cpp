// The run specification: one codec for run files, presets, settings and the CLI; exact round trips; every
// bad value named; the paper's presets.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>

#include <unistd.h>

#include "core/io/BadFile.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/runspec/RunSpec.hpp"

namespace archipelago {
namespace {

std::string specWith(const std::string& parameters, const std::string& rest = "") {
  return R"({"format": "archipelago-spec", "version": 1, "parameters": {)" + parameters + "}" + rest + "}";
}

void expectRejected(const std::string& text, const std::string& mention) {
  try {
    (void)parseRunSpec(text);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const io::BadFile& e) {
    EXPECT_NE(std::string(e.what()).find(mention), std::string::npos) << e.what() << "\n  expected: " << mention;
  }
}

TEST(RunSpec, RoundTripIsExactForRandomValues) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 2000; ++i) {
    RunSpec s;
    s.parameters.map.K = std::ldexp(unit(rng), -static_cast<int>(rng() % 40));  // down to 1e-12: exact digits matter
    s.parameters.map.xmin = -std::sqrt(s.parameters.map.K) - unit(rng) - 1e-3;
    s.parameters.map.xmax = s.parameters.map.xmin + 0.5 + 3 * unit(rng);
    s.parameters.Xr = unit(rng) * 0.5;
    s.parameters.q = 1 + static_cast<std::uint32_t>(rng() % 1000);
    s.parameters.T = 1 + rng() % (kMaxStepsPerOrbit / s.parameters.q);
    s.parameters.M = 64 + rng() % 100000;
    s.parameters.seed = rng();  // the whole 64-bit range, beyond a double's 53 bits
    s.parameters.subsets = 1 + static_cast<std::uint32_t>(rng() % 64);
    s.parameters.longestKept = static_cast<std::uint32_t>(rng() % 1000);
    s.kernel = i % 2 ? "auto" : "scalar";
    s.threads = static_cast<int>(rng() % 9);
    s.name = i % 3 ? "" : "a name, with ünïcode ±";
    ASSERT_FALSE(validationError(s)) << *validationError(s);
    EXPECT_EQ(parseRunSpec(runSpecJson(s)), s) << runSpecJson(s);
  }
}

TEST(RunSpec, WritesShortestRealsAndEveryField) {
  const std::string text = runSpecJson(RunSpec{});
  EXPECT_NE(text.find("\"K\": 0.1,"), std::string::npos) << text;  // not 0.10000000000000001
  for (const ParameterRule& p : parameterRules())
    EXPECT_NE(text.find("\"" + std::string(p.key) + "\":"), std::string::npos) << p.key;
  EXPECT_NE(text.find("\"kernel\": \"auto\""), std::string::npos);
}

TEST(RunSpec, MissingParametersTakeTheDocumentedDefaults) {
  const RunSpec s = parseRunSpec(specWith(R"("K": 0.2, "xmin": -1)"));
  EXPECT_EQ(s.parameters.map.K, 0.2);
  EXPECT_EQ(s.parameters.map.xmin, -1.0);
  TrappingParameters defaults;
  EXPECT_EQ(s.parameters.map.xmax, defaults.map.xmax);
  EXPECT_EQ(s.parameters.M, defaults.M);
  EXPECT_EQ(s.kernel, "auto");
  EXPECT_EQ(s.threads, 0);
  EXPECT_EQ(parseRunSpec(specWith(R"("T": 2e7)")).parameters.T, 20'000'000u);  // a real that is a whole number
}

TEST(RunSpec, EveryBadValueIsNamed) {
  expectRejected("", "not valid JSON");
  expectRejected("{\"format\": \"archipelago-spec\", \"version\": 1", "not valid JSON");
  expectRejected("[]", "must be a JSON object");
  // Found by fuzz_runspec: a number too large for a double escaped as nlohmann's out_of_range, not a clean error.
  expectRejected(specWith(R"("K": 215e4434690031883725)"), "not valid JSON: number overflow");
  expectRejected(R"({"version": 1})", "not a run spec");
  expectRejected(R"({"format": "archipelago-run", "version": 1})", "not a run spec");
  expectRejected(R"({"format": "archipelago-spec", "version": 2})", "version 2 is not supported");
  expectRejected(R"({"format": "archipelago-spec"})", "version (missing)");
  expectRejected(specWith(R"("Kk": 0.2)"), "unknown parameter 'Kk'");      // a typo never falls back to a default
  expectRejected(specWith("", R"(, "thread": 2)"), "unknown key 'thread'");
  expectRejected(specWith(R"("K": 0.2, "K": 0.3)"), "'K' appears twice");  // nlohmann alone keeps the last
  expectRejected(specWith(R"("K": "0.1")"), "K must be a number");
  expectRejected(specWith(R"("q": 1.5)"), "q = 1.5 must be a whole number");
  expectRejected(specWith(R"("seed": -5)"), "seed = -5 must be a whole number");
  expectRejected(specWith(R"("seed": 18446744073709551616)"), "seed");      // 2^64: not silently 2^64 − 1
  expectRejected(specWith(R"("seed": 1e30)"), "seed");
  expectRejected(specWith(R"("q": 4294967296)"), "q = 4294967296 must lie in [1, 65536]");
  expectRejected(specWith(R"("longestKept": 4294967295)"), "longestKept = 4294967295 must lie in [0, 100000]");
  expectRejected(specWith(R"("q": 65536, "T": 4611686018427387904)"), "q·T");
  expectRejected(specWith(R"("M": 0)"), "M = 0 must lie in [1, 2³²]");
  expectRejected(specWith(R"("M": 4294967297)"), "M = 4294967297 must lie in [1, 2³²]");
  expectRejected(specWith(R"("xmin": -0.2)"), "must be < −√K");
  expectRejected(specWith(R"("Xr": 1)"), "Xr = 1 must lie in [0, 1)");
  expectRejected(specWith("", R"(, "kernel": "avx9")"), "kernel = 'avx9' is not a kernel");
  expectRejected(specWith("", R"(, "threads": 100000)"), "threads");
  expectRejected(specWith("", R"(, "name": 3)"), "name must be a string");
}

TEST(RunSpec, FilesAreReadWithTheirPathInErrors) {
  const auto dir = std::filesystem::temp_directory_path() / ("archipelago-spec-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto good = dir / "good.json";
  std::ofstream(good) << runSpecJson(RunSpec{});
  EXPECT_EQ(loadRunSpec(good), RunSpec{});
  const auto broken = dir / "broken.json";
  std::ofstream(broken) << "{\"format\": \"archipelago-spec\", \"version\": 1, \"parameters\": {\"M\": -1}}";
  EXPECT_THROW((void)loadRunSpec(broken), io::BadFile);
  try {
    (void)loadRunSpec(dir);  // a folder is no spec, and says so (not "unexpected end of input")
    ADD_FAILURE();
  } catch (const io::BadFile& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)loadRunSpec(dir / "missing.json"), io::BadFile);
  std::filesystem::remove_all(dir);
}

TEST(Presets, ReproduceThePapersCases) {
  const auto all = presets();
  ASSERT_GE(all.size(), 5u);
  std::set<std::string> ids, names;
  for (const Preset& p : all) {
    EXPECT_TRUE(ids.insert(p.id).second) << p.id;
    EXPECT_TRUE(names.insert(p.spec.name).second) << p.spec.name;
    EXPECT_FALSE(p.spec.description.empty()) << p.id;
    EXPECT_FALSE(validationError(p.spec)) << p.id;
    EXPECT_EQ(findPreset(p.id), &p);
    EXPECT_EQ(findPreset(p.spec.name), &p);
  }
  EXPECT_EQ(findPreset("no such preset"), nullptr);
  // The start-up default is the paper's K = 0.1 box of §5.
  EXPECT_EQ(all.front().id, "k0.1-minute");
  EXPECT_EQ(all.front().spec.parameters.map.K, 0.1);
  // §5: M = 1600 orbits of qT = 2×10⁹ steps with q = 100 at K = 0.1.
  const Preset* paper = findPreset("k0.1-paper-fig6");
  ASSERT_NE(paper, nullptr);
  EXPECT_EQ(paper->spec.parameters.M, 1600u);
  EXPECT_EQ(paper->spec.parameters.q, 100u);
  EXPECT_EQ(paper->spec.parameters.q * paper->spec.parameters.T, 2'000'000'000u);
  // Fig. 3: K = −10⁻⁴, 0, 10⁻⁴ with q = 1 (§4).
  for (const auto& [id, K] : {std::pair{"small-k-negative", -1e-4}, {"small-k-zero", 0.0}, {"small-k-positive", 1e-4}}) {
    const Preset* p = findPreset(id);
    ASSERT_NE(p, nullptr) << id;
    EXPECT_EQ(p->spec.parameters.map.K, K) << id;
    EXPECT_EQ(p->spec.parameters.q, 1u) << id;
  }
}

// The run file's "parameters" object is the spec's: a run file edited by hand is read by the same rules.
TEST(RunSpec, RunFilesUseTheSameParameterCodec) {
  TrappingParameters p;
  p.T = 10;
  p.M = 4;
  p.subsets = 2;
  p.seed = 0xFFFF'FFFF'FFFF'FFFFu;
  const TrappingState state = startTrapping(p);
  const std::string text = runFileText(state);
  EXPECT_EQ(parseRunFile(text).params, p);
  RunSpec s;
  s.parameters = p;
  const std::string spec = runSpecJson(s);
  const auto params = [](const std::string& t) {
    const auto at = t.find("\"parameters\"");
    return t.substr(at, t.find('}', at) - at);
  };
  // Same keys, same order, same numbers (indentation differs).
  std::string a = params(text), b = params(spec);
  std::erase_if(a, [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
  std::erase_if(b, [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
  EXPECT_EQ(a, b);
  std::string typo = text;
  typo.replace(typo.find("\"seed\""), 6, "\"sead\"");
  EXPECT_THROW((void)parseRunFile(typo), std::runtime_error);
  std::string repeated = text;
  repeated.insert(repeated.find("\"seed\""), "\"M\": 5, ");
  EXPECT_THROW((void)parseRunFile(repeated), std::runtime_error);  // issue 12: duplicate keys, last one won
}

}  // namespace
}  // namespace archipelago
