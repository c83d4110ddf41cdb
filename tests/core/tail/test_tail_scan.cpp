// The tail sampler scanned over K (core/tail/TailScan.hpp, issue 55): the windows common to every K, γ per K and
// window with its error from the replicas' covariance, and the K-average with its spread, each against a hand
// computation on small synthetic runs.  The figure γ(t, K): the heat map of a hand-made summary, cell by cell; the
// folder of a tiny scan read back (loadTailScan) as the scan summarized it, and its refusals.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include "core/job/Ranks.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailScan.hpp"

namespace archipelago {
namespace {

/// One replica's counts at the levels t = 10, 100, 1000 (q = 1): {population, survivors, ancestors} each.
TailReplica replica(const std::vector<std::array<std::uint64_t, 3>>& counts) {
  TailReplica r;
  for (const auto& c : counts) r.levels.push_back({c[0], c[1], c[2], 0, 0});
  return r;
}

/// A finished synthetic run of two replicas at the levels 10, 100 and 1000 steps.
TailState synthetic(TailReplica a, TailReplica b) {
  TailState s;
  s.request.run.q = 1;
  s.request.replicas = 2;
  s.request.minAncestors = 20;
  s.levels = {10, 100, 1000};
  s.next = s.levels.size();
  s.replicas = {std::move(a), std::move(b)};
  return s;
}

// K1: every level reliable.  P_A = 0.1, 0.025, 0.003; P_B = 0.12, 0.012, 0.0012.
TailState firstK() {
  return synthetic(replica({{1000, 100, 100}, {100, 25, 20}, {100, 12, 12}}),
                   replica({{1000, 120, 120}, {100, 10, 10}, {100, 10, 10}}));
}

// K2: the last level unreliable (5 + 5 lineages < 20).  P_A = 0.09, 0.0225; P_B = 0.11, 0.022.
TailState secondK() {
  return synthetic(replica({{1000, 90, 90}, {100, 25, 25}, {100, 8, 5}}),
                   replica({{1000, 110, 110}, {100, 20, 20}, {100, 9, 5}}));
}

/// The hand computation of γ over a decade between two levels i < j (no level inside): γ = −ln(P_j/P_i)/ln 10, its
/// variance to first order (C_ii/P_i² − 2 C_ij/(P_i P_j) + C_jj/P_j²)/ln²10 with C the replicas' covariance of the
/// mean, at least the binomial floor b_j/ln²10 (the levels after i up to j: only j's term survives).
struct Hand {
  double gamma, error;
};
Hand hand(const std::vector<double>& A, const std::vector<double>& B, std::size_t i, std::size_t j, double bj) {
  const double Pi = (A[i] + B[i]) / 2, Pj = (A[j] + B[j]) / 2;
  const auto cov = [&](std::size_t m, std::size_t n) {
    const double Pm = (A[m] + B[m]) / 2, Pn = (A[n] + B[n]) / 2;
    return ((A[m] - Pm) * (A[n] - Pn) + (B[m] - Pm) * (B[n] - Pn)) / 2;  // Σ_r …/(R(R − 1)), R = 2
  };
  const double ln10 = std::log(10.0);
  const double var = (cov(i, i) / (Pi * Pi) - 2 * cov(i, j) / (Pi * Pj) + cov(j, j) / (Pj * Pj)) / (ln10 * ln10);
  return {-std::log(Pj / Pi) / ln10, std::sqrt(std::max(var, bj / (ln10 * ln10)))};
}

TEST(TailScan, WindowsAreDecadesSteppedByHalfADecadeFromLowestToLargest) {
  const std::vector<LogWindow> w = tailScanWindows(10, 1000);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].from, 10);
  EXPECT_EQ(w[0].to, 100);
  EXPECT_DOUBLE_EQ(w[1].from, std::sqrt(1000.0));
  EXPECT_DOUBLE_EQ(w[1].to, std::sqrt(100000.0));
  EXPECT_EQ(w[2].from, 100);
  EXPECT_EQ(w[2].to, 1000);
  const std::vector<LogWindow> v = tailScanWindows(1077, 1.2e5);  // a first level above 10^3, t_max 10^5
  ASSERT_EQ(v.size(), 2u);
  EXPECT_DOUBLE_EQ(v[0].from, std::sqrt(1e7));
  EXPECT_EQ(v[1].from, 1e4);
  EXPECT_EQ(v[1].to, 1e5);
  EXPECT_TRUE(tailScanWindows(100, 999).empty());
}

TEST(TailScan, GammaPerKAndWindowIsTheHandComputationWithTheReplicasCovariance) {
  const TailScanSummary s = tailScanSummary({0.1, 0.15}, {firstK(), secondK()});
  ASSERT_EQ(s.windows.size(), 3u);
  ASSERT_EQ(s.gamma.size(), 2u);
  // K1 over [10, 100]: the replicas' covariance of the two ends (negative here: it adds to the variance).
  const std::vector<double> A1{0.1, 0.025, 0.003}, B1{0.12, 0.012, 0.0012};
  const Hand g1 = hand(A1, B1, 0, 1, (1 - 35.0 / 200) / 35);
  EXPECT_NEAR(s.gamma[0][0].gamma, g1.gamma, 1e-12);
  EXPECT_NEAR(s.gamma[0][0].gammaError, g1.error, 1e-12);
  EXPECT_GT(g1.error * g1.error * std::log(10.0) * std::log(10.0), (1 - 35.0 / 200) / 35)
      << "the replicas' term, not the floor, is tested";
  // K1 over [100, 1000].
  const Hand h1 = hand(A1, B1, 1, 2, (1 - 22.0 / 200) / 22);
  EXPECT_NEAR(s.gamma[0][2].gamma, h1.gamma, 1e-12);
  EXPECT_NEAR(s.gamma[0][2].gammaError, h1.error, 1e-12);
  // K2 over [10, 100]; its last level is unreliable, so it reaches neither [√10³, √10⁵] nor [100, 1000].
  const std::vector<double> A2{0.09, 0.0225, 0.0018}, B2{0.11, 0.022, 0.00198};
  const Hand g2 = hand(A2, B2, 0, 1, (1 - 45.0 / 200) / 45);
  EXPECT_NEAR(s.gamma[1][0].gamma, g2.gamma, 1e-12);
  EXPECT_NEAR(s.gamma[1][0].gammaError, g2.error, 1e-12);
  EXPECT_TRUE(std::isnan(s.gamma[1][1].gamma));
  EXPECT_TRUE(std::isnan(s.gamma[1][2].gamma));
  EXPECT_TRUE(std::isfinite(s.gamma[0][1].gamma)) << "K1 reaches the middle window: levels 10 and 1000 are reliable";
}

TEST(TailScan, TheKAverageIsOverTheKThatReachTheWindowWithItsSpreadAndError) {
  const TailScanSummary s = tailScanSummary({0.1, 0.15}, {firstK(), secondK()});
  ASSERT_EQ(s.average.size(), 3u);
  const double g1 = s.gamma[0][0].gamma, g2 = s.gamma[1][0].gamma;
  const double e1 = s.gamma[0][0].gammaError, e2 = s.gamma[1][0].gammaError;
  EXPECT_EQ(s.average[0].count, 2u);
  EXPECT_NEAR(s.average[0].mean, (g1 + g2) / 2, 1e-14);
  EXPECT_NEAR(s.average[0].spread, std::abs(g1 - g2) / std::sqrt(2.0), 1e-14);  // the sample deviation, n − 1 = 1
  EXPECT_NEAR(s.average[0].error, std::sqrt(e1 * e1 + e2 * e2) / 2, 1e-14);
  EXPECT_EQ(s.average[2].count, 1u);
  EXPECT_EQ(s.average[2].mean, s.gamma[0][2].gamma);
  EXPECT_EQ(s.average[2].error, s.gamma[0][2].gammaError);
  EXPECT_TRUE(std::isnan(s.average[2].spread)) << "no spread over one K";
}

// A window of the caller's (the report's tail-gamma-K: 10⁴–10⁶), by the summary's rule: γ where the K reaches it,
// NaN where its end is past the last reliable level; the average over the K that reach it.
TEST(TailScan, AnyWindowByTheSummarysRuleAndItsAverage) {
  const LogWindow whole{10, 1000};
  const TailExponent k1 = tailScanExponentOver(tailResult(firstK()), whole);
  const TailExponent expected = tailExponentOver(tailResult(firstK()), 10, 1000);
  EXPECT_EQ(k1.gamma, expected.gamma);
  EXPECT_EQ(k1.gammaError, expected.gammaError);
  EXPECT_TRUE(std::isnan(tailScanExponentOver(tailResult(secondK()), whole).gamma));
  const TailScanWindow a = tailScanAverage({k1, tailScanExponentOver(tailResult(secondK()), whole)}, whole);
  EXPECT_EQ(a.count, 1u);
  EXPECT_EQ(a.mean, k1.gamma);
}

TEST(TailScan, TheRunningExponentIsTheOneDefinitionOverAnyWindow) {
  const TailState k1 = firstK();
  const TailResult r = tailResult(k1);
  ASSERT_FALSE(r.exponents.empty());
  for (const TailExponent& e : r.exponents) {
    const TailExponent again = tailExponentOver(r, e.tFrom, e.tTo);
    EXPECT_EQ(again.gamma, e.gamma);
    EXPECT_EQ(again.gammaError, e.gammaError);
    EXPECT_EQ(again.points, e.points);
  }
}

TEST(TailScan, ASummaryRefusesUnfinishedRunsAndRunsOfOtherLevels) {
  TailState unfinished = secondK();
  unfinished.next = 2;
  EXPECT_THROW((void)tailScanSummary({0.1, 0.15}, {firstK(), unfinished}), std::invalid_argument);
  TailState other = secondK();
  other.levels = {10, 100, 2000};
  EXPECT_THROW((void)tailScanSummary({0.1, 0.15}, {firstK(), other}), std::invalid_argument);
  // A K whose pilot found its first level out of reach is listed apart, and left out of every average.
  TailState refused = secondK();
  refused.next = 0;
  refused.pilotTrials = kPilotTrials;
  refused.pilotOrbits = 64;
  const TailScanSummary s = tailScanSummary({0.1, 0.15}, {firstK(), refused});
  EXPECT_EQ(s.K, (std::vector<double>{0.1}));
  ASSERT_EQ(s.outOfReach.size(), 1u);
  EXPECT_EQ(s.outOfReach[0].K, 0.15);
  EXPECT_EQ(tailScanAverageCsv(s), tailScanAverageCsv(tailScanSummary({0.1}, {firstK()})));
  EXPECT_THROW((void)tailScanSummary({0.15}, {refused}), std::invalid_argument);
}

TEST(TailScan, TheGammaHeatMapHoldsEachKsGammaPerWindowAndNaNWhereNotReached) {
  // Two K, three windows: the values put in, a column per K, a row per window at its centre t.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  TailScanSummary s;
  s.K = {0.1, 0.2};
  const std::array<double, 3> from = {10, std::sqrt(1000.0), 100}, to = {100, std::sqrt(1e5), 1000};
  const std::array<std::array<double, 3>, 2> gamma = {{{1.25, 1.5, nan}, {0.75, nan, nan}}};
  for (std::size_t w = 0; w < 3; ++w) {
    s.windows.push_back({from[w], to[w]});
    s.average.push_back(TailScanWindow{from[w], to[w], std::sqrt(from[w] * to[w]), 0, nan, nan, nan});
  }
  for (std::size_t k = 0; k < 2; ++k) {
    s.gamma.emplace_back();
    for (std::size_t w = 0; w < 3; ++w)
      s.gamma[k].push_back(TailExponent{from[w], to[w], std::sqrt(from[w] * to[w]), 3, gamma[k][w], 0.1});
  }
  const ScanHeatMap map = tailGammaHeatMap(s);
  EXPECT_EQ(map.K, (std::vector<double>{0.1, 0.2}));
  ASSERT_EQ(map.tau.size(), 3u);
  EXPECT_DOUBLE_EQ(map.tau[0], std::sqrt(1000.0));
  EXPECT_DOUBLE_EQ(map.tau[1], 100);
  EXPECT_DOUBLE_EQ(map.tau[2], std::sqrt(1e5));
  ASSERT_EQ(map.value.size(), 6u);
  EXPECT_EQ(map.value[0], 1.25);  // row 0 (t = 31.6): K = 0.1, then K = 0.2
  EXPECT_EQ(map.value[1], 0.75);
  EXPECT_EQ(map.value[2], 1.5);   // row 1 (t = 100)
  EXPECT_TRUE(std::isnan(map.value[3])) << "K = 0.2 does not reach the second window";
  EXPECT_TRUE(std::isnan(map.value[4]));
  EXPECT_TRUE(std::isnan(map.value[5]));
  // Its colour scale: the K scan's one scale, up to 3 (the middle stop, orange, at 1.5).
  EXPECT_EQ(map.top, 3);
  const auto stops = heatMapStops();
  EXPECT_EQ(heatMapColour(1.5, map.top), stops[1].colour);
  EXPECT_EQ(heatMapColour(3, map.top), stops[2].colour);
  EXPECT_EQ(heatMapColour(1, kHeatMapTop), stops[1].colour) << "the K scan's top stays 2";
}

TEST(TailScan, TheReferenceExponentsAreTheLiteratures) {
  const std::vector<ReferenceExponent>& r = tailScanReferenceExponents();
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].gamma, 1.57);  // Cristadoro & Ketzmerick; Alus, Fishman & Meiss
  EXPECT_EQ(r[1].gamma, 1.44);  // ln 2/ln(1 + r_g)
  EXPECT_NEAR(r[1].gamma, std::log(2.0) / std::log(1 + (std::sqrt(5.0) - 1) / 2), 0.005);
}

/// A tiny scan of K = 0.1 and 0.15 into `dir` (N = 50, R = 4, 10 to 10^4 steps: a second each).
TailScanOutcome tinyScan(const std::filesystem::path& dir, std::uint32_t population = 50, std::stop_token stop = {}) {
  TailScanRequest r;
  r.K = "0.1,0.15";
  r.base.threads = 2;
  r.request.population = population;
  r.request.replicas = 4;
  r.request.minAncestors = 4;
  r.request.firstSteps = 10;
  r.request.maxSteps = 10000;
  r.dir = dir.string();
  OneProcess one;
  return runTailScan(r, {}, one, std::move(stop));
}

/// The message of loadTailScan(dir)'s error; empty when it reads the folder.
std::string loadError(const std::filesystem::path& dir) {
  try {
    (void)loadTailScan(dir);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return {};
}

TEST(TailScan, AFolderIsReadBackAsTheScanSummarizedItAndRefusedWhenNotOneScans) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / "archipelago_test_tail_scan_folder";
  fs::remove_all(root);
  fs::create_directories(root);
  const TailScanOutcome scan = tinyScan(root / "scan");
  ASSERT_EQ(scan.end, TailScanOutcome::End::finished);
  const TailScanFolder read = loadTailScan(root / "scan");
  EXPECT_TRUE(read.unfinished.empty());
  EXPECT_EQ(tailScanGammaCsv(read.summary), tailScanGammaCsv(scan.summary));
  EXPECT_EQ(tailScanAverageCsv(read.summary), tailScanAverageCsv(scan.summary));
  EXPECT_EQ(read.summary.K, (std::vector<double>{0.1, 0.15}));

  // A folder holding one unfinished K (the scan stopped at once: K = 0.1's checkpoint only), then a finished K
  // beside it: the finished K summarized, the other named.
  std::stop_source stop;
  stop.request_stop();
  (void)tinyScan(root / "running", 50, stop.get_token());
  ASSERT_FALSE(loadTailFile(tailScanFile(root / "running", 0.1)).finished());
  EXPECT_NE(loadError(root / "running").find("holds no finished tail file yet (1 unfinished)"), std::string::npos)
      << loadError(root / "running");
  fs::copy_file(tailScanFile(root / "scan", 0.15), tailScanFile(root / "running", 0.15));
  const TailScanFolder partial = loadTailScan(root / "running");
  EXPECT_EQ(partial.summary.K, (std::vector<double>{0.15}));
  EXPECT_EQ(partial.unfinished, (std::vector<double>{0.1}));

  // Refusals: one line naming the folder or the file and the reason.
  const auto expectError = [&](const fs::path& dir, const std::string& part) {
    const std::string e = loadError(dir);
    EXPECT_NE(e.find(part), std::string::npos) << dir << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  };
  expectError(root / "none", "is not a folder");
  fs::create_directories(root / "empty");
  std::ofstream(root / "empty" / "notes.txt") << "not a tail file";
  expectError(root / "empty", "holds no tail file");
  fs::create_directories(root / "truncated");
  std::ostringstream whole;
  whole << std::ifstream(tailScanFile(root / "scan", 0.1)).rdbuf();
  std::ofstream(tailScanFile(root / "truncated", 0.1)) << whole.str().substr(0, 5000);
  expectError(root / "truncated", "tail-K0.1.json");
  fs::create_directories(root / "swapped");
  fs::copy_file(tailScanFile(root / "scan", 0.1), tailScanFile(root / "swapped", 0.15));
  expectError(root / "swapped", "holds the run of K = 0.1, not that of its name");
  (void)tinyScan(root / "other", 60);
  fs::copy_file(tailScanFile(root / "scan", 0.1), tailScanFile(root / "other", 0.1), fs::copy_options::overwrite_existing);
  expectError(root / "other", "tail-K0.15.json holds a tail run of other settings than tail-K0.1.json (population differs)");
  fs::remove_all(root);
}

// The pilot's rule as a state (tailFirstLevelRefusal): out of reach once kPilotTrials segments gave fewer than
// kPilotSuccesses/8 successes, or kMaxPilotOrbits orbits fewer than kPilotSuccesses; not before, and never once the
// entry orbits are set.
TEST(TailScan, TheFirstLevelIsOutOfReachExactlyByThePilotsRule) {
  TailState s = startTail(TailRequest{});
  EXPECT_FALSE(tailFirstLevelRefusal(s));
  s.pilotTrials = kPilotTrials;
  s.pilotSuccesses = kPilotSuccesses / 8 - 1;
  s.pilotOrbits = 64;
  ASSERT_TRUE(tailFirstLevelRefusal(s));
  EXPECT_NE(tailFirstLevelRefusal(s)->find("segments lasted longer than the first level t = 1008"), std::string::npos)
      << *tailFirstLevelRefusal(s);
  s.pilotSuccesses = kPilotSuccesses / 8;
  EXPECT_FALSE(tailFirstLevelRefusal(s));
  s.pilotTrials = kPilotTrials - 1;
  s.pilotSuccesses = 0;
  EXPECT_FALSE(tailFirstLevelRefusal(s));
  s.pilotOrbits = kMaxPilotOrbits;
  s.pilotSuccesses = kPilotSuccesses - 1;
  EXPECT_TRUE(tailFirstLevelRefusal(s));
  s.pilotSuccesses = kPilotSuccesses;
  s.entryOrbits = 100;
  EXPECT_FALSE(tailFirstLevelRefusal(s));
}

// A scan over K whose first level is out of reach at one K (K = 1.3: no segment of brute force lasts 10³ steps
// there) keeps that K's file with the pilot's counts, says so, and goes on: the summary is the other K's, with the
// refused K listed.  A rerun reuses the file (the pilot is not run again: the file's bytes stay); the folder reads
// back the same; a folder of refused K alone is refused, naming the pilot's reason.
TEST(TailScan, AKWhoseFirstLevelIsOutOfReachIsListedAndTheScanGoesOn) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / "archipelago_test_tail_scan_out_of_reach";
  fs::remove_all(root);
  fs::create_directories(root);
  TailScanRequest r;
  r.K = "0.1,1.3";
  r.base.threads = 2;
  r.request.population = 50;
  r.request.replicas = 4;
  r.request.minAncestors = 4;
  r.request.maxSteps = 10000;
  r.dir = (root / "scan").string();
  std::vector<std::string> hows;
  std::vector<double> refused;
  TailScanView view;
  view.begins = [&](std::size_t, std::size_t, double, const std::string& how) { hows.push_back(how); };
  view.outOfReach = [&](std::size_t, double K, const std::string& reason) {
    refused.push_back(K);
    EXPECT_NE(reason.find("give a lower first level"), std::string::npos) << reason;
  };
  OneProcess one;
  const TailScanOutcome first = runTailScan(r, view, one);
  ASSERT_EQ(first.end, TailScanOutcome::End::finished);
  EXPECT_EQ(hows, (std::vector<std::string>{"started", "started"}));
  EXPECT_EQ(refused, (std::vector<double>{1.3}));
  EXPECT_EQ(first.summary.K, (std::vector<double>{0.1}));
  ASSERT_EQ(first.summary.outOfReach.size(), 1u);
  EXPECT_EQ(first.summary.outOfReach[0].K, 1.3);
  const std::string text = tailScanText(first.summary);
  EXPECT_NE(text.find("#   K = 1.3: only "), std::string::npos) << text;
  // The figure holds a column for it, with no γ: K = 0.1's cells do not stretch over it.
  const ScanHeatMap map = tailGammaHeatMap(first.summary);
  ASSERT_EQ(map.K, (std::vector<double>{0.1, 1.3}));
  for (std::size_t w = 0; w < map.tau.size(); ++w) {
    EXPECT_EQ(map.value[w * 2], first.summary.gamma[0][w].gamma);
    EXPECT_TRUE(std::isnan(map.value[w * 2 + 1]));
  }
  const TailState kept = loadTailFile(tailScanFile(r.dir, 1.3));
  EXPECT_FALSE(kept.finished());
  EXPECT_TRUE(tailFirstLevelRefusal(kept));
  EXPECT_GE(kept.pilotTrials, kPilotTrials);

  std::ostringstream before;
  before << std::ifstream(tailScanFile(r.dir, 1.3)).rdbuf();
  hows.clear();
  refused.clear();
  const TailScanOutcome again = runTailScan(r, view, one);
  ASSERT_EQ(again.end, TailScanOutcome::End::finished);
  EXPECT_EQ(hows, (std::vector<std::string>{"reused", "out of reach"}));
  EXPECT_EQ(refused, (std::vector<double>{1.3}));
  std::ostringstream after;
  after << std::ifstream(tailScanFile(r.dir, 1.3)).rdbuf();
  EXPECT_EQ(after.str(), before.str());
  EXPECT_EQ(tailScanText(again.summary), text);

  const TailScanFolder read = loadTailScan(r.dir);
  EXPECT_TRUE(read.unfinished.empty());
  EXPECT_EQ(read.summary.K, (std::vector<double>{0.1}));
  ASSERT_EQ(read.summary.outOfReach.size(), 1u);
  EXPECT_EQ(read.summary.outOfReach[0].reason, first.summary.outOfReach[0].reason);

  fs::create_directories(root / "refused");
  fs::copy_file(tailScanFile(r.dir, 1.3), tailScanFile(root / "refused", 1.3));
  EXPECT_NE(loadError(root / "refused").find("no K of the scan reached its first level: K = 1.3: only "),
            std::string::npos)
      << loadError(root / "refused");
  // The tail command's way: the same run without returnRefused is an error naming the first level.
  EXPECT_THROW((void)runTail(kept, {}), TailSettingOutOfReach);
  fs::remove_all(root);
}

}  // namespace
}  // namespace archipelago
