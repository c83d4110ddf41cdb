// The Meiss–Ott Markov tree built from the atlas (core/markovtree/MarkovTree.hpp, issue 40): a two-state chain against
// its closed form; the mean visit against Kac's lemma (the atlas's own residence of the loop); the tree recomputed
// from an atlas JSON file with every rate = the file's flux / the file's layer difference; one flux changed changes
// exactly the two rates through that barrier; bad or incomplete atlases refused with a clear message.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <stop_token>
#include <utility>
#include <vector>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "core/atlas/AtlasExport.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/BadFile.hpp"
#include "core/io/Json.hpp"
#include "core/markovtree/MarkovTree.hpp"
#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/limits/Limits.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {
namespace {

AtlasNode node(int parent, int level, std::uint64_t period, std::optional<Rational> about, long double flux,
               long double zone, long double layer, double boundaryRotation) {
  AtlasNode n;
  n.parent = parent;
  n.level = level;
  n.period = period;
  n.aboutParent = about;
  n.centre = {0.01 * static_cast<double>(period % 97), 0};
  n.orbit.K = 0.1L;
  n.orbit.period = static_cast<int>(period);
  n.orbit.points = {n.centre};
  n.orbit.residue = 0.25L;
  n.boundaryFound = true;
  n.boundaryPoint = {n.centre.x + 0.001, 0};
  n.boundaryRotation = boundaryRotation;
  n.boundaryDigits = 13;
  n.area = n.circleArea = n.areaLower = n.areaUpper = 1e-6L;  // an interval of no width (issue 50's fields)
  n.areaPoints = 8192;
  n.measured = true;
  if (flux > 0) {
    n.flux.found = true;
    if (parent >= 0) {
      PeriodicOrbit partner = n.orbit;
      partner.residue = -0.5L;
      n.flux.partner = partner;
    }
    n.flux.flux = flux;
    n.flux.zoneArea = zone;
    n.flux.enclosedIslands = zone - layer;
    n.flux.layerArea = layer;
    n.flux.fluxDigits = 12;
    n.flux.zoneDigits = 10;
    n.flux.residence = static_cast<double>(layer / flux);
  } else {
    n.flux.failure = "refused: the lobe is not small";
  }
  return n;
}

void link(Atlas& a) {
  for (std::size_t i = 1; i < a.nodes.size(); ++i)
    a.nodes[static_cast<std::size_t>(a.nodes[i].parent)].children.push_back(static_cast<int>(i));
}

/// The K = 0.1 atlas of docs/atlas.md (depth 2) in its numbers: fluxes and layers as the table gives them, zones
/// nested, the 4/29 chain refused (with a child of its own), the 2/19 chain about 13 without a flux.
Atlas k01() {
  Atlas a;
  a.request.depth = 2;
  a.nodes = {
      node(-1, 0, 1, std::nullopt, 3.843389e-3L, 0.5136L, 0.22957L, 0.1668),            // 0 centre
      node(0, 1, 6, Rational{1, 6}, 2.040311e-5L, 0.3112L, 0.029719L, 0.09327),           // 1 six
      node(0, 1, 13, Rational{2, 13}, 2.083998e-4L, 0.3900L, 0.093772L, 0.2),             // 2
      node(0, 1, 19, Rational{3, 19}, 4.204463e-5L, 0.3700L, 0.066583L, 0.2),             // 3
      node(0, 1, 29, Rational{4, 29}, 0, 0, 0, 0.2),                                      // 4 refused
      node(0, 1, 31, Rational{5, 31}, 1.135358e-5L, 0.3400L, 0.042958L, 0.2),             // 5
      node(1, 2, 72, Rational{1, 12}, 8.377229e-7L, 0.0190L, 7.853e-3L, 0.25),            // 6
      node(1, 2, 138, Rational{2, 23}, 4.440813e-7L, 0.0170L, 6.869e-3L, 0.25),           // 7
      node(1, 2, 204, Rational{3, 34}, 1.925387e-7L, 0.0150L, 4.994e-3L, 0.25),           // 8
      node(1, 2, 258, Rational{4, 43}, 3.137311e-10L, 0.0030L, 1.319e-4L, 0.25),          // 9
      node(1, 2, 324, Rational{5, 54}, 7.599679e-9L, 0.0040L, 4.785e-4L, 0.25),           // 10
      node(2, 2, 247, Rational{2, 19}, 0, 0, 0, 0.25),                                    // 11 no flux
      node(4, 2, 406, Rational{3, 14}, 1e-9L, 1e-5L, 1e-6L, 0.25),                        // 12 under 29
  };
  link(a);
  return a;
}

/// The states of k01(): the centre, 2/13, 3/19, 5/31, 1/6 and the five chains about the six.
constexpr std::size_t k01States = 10;

/// A legal atlas of `chains` chains about the centre whose zones nest (issue 54's hostile atlas: 1000 of them ran past
/// 360 s, 20,000 asked 6.4 GB): chain k has p/q = 1/(k + 6) (farther from the boundary rotation 0 the farther out),
/// layer ℓ₁ (chains + 1 − k)/chains, so that each state's area is ℓ₁/chains, and a flux of 10⁻³ of that area.
Atlas nestingChains(int chains) {
  Atlas a;
  a.request.depth = 1;
  const long double l1 = 0.1L, step = l1 / chains, flux = 1e-3L * step;
  a.nodes.push_back(node(-1, 0, 1, std::nullopt, 3.8e-3L, 0.5L, 0.23L, 0.0));
  for (int k = 1; k <= chains; ++k) {
    const long double layer = l1 * static_cast<long double>(chains + 1 - k) / chains;
    a.nodes.push_back(node(0, 1, static_cast<std::uint64_t>(k + 6), Rational{1, k + 6}, flux, layer + 0.01L, layer, 0.0));
  }
  link(a);
  return a;
}

/// e_top Mᵗ by t products of a vector with M, row by row in quad (no eigen-decomposition): the survival's independent
/// reference.
std::vector<long double> survivalByProducts(const MarkovTree& tree, std::uint64_t t) {
  __extension__ typedef __float128 quad;
  std::vector<quad> v(tree.states.size(), 0);
  v[0] = 1;
  for (std::uint64_t step = 0; step < t; ++step) {
    std::vector<quad> w = v;
    for (const MarkovTreeRate& r : tree.rates) {
      const quad moved = v[static_cast<std::size_t>(r.from)] * (static_cast<quad>(r.flux) / static_cast<quad>(r.area));
      w[static_cast<std::size_t>(r.from)] -= moved;
      if (r.to >= 0) w[static_cast<std::size_t>(r.to)] += moved;
    }
    v = w;
  }
  return {v.begin(), v.end()};
}

/// Atlas index → state index.
std::map<int, int> statesByNode(const MarkovTree& t) {
  std::map<int, int> m;
  for (std::size_t s = 0; s < t.states.size(); ++s) m[t.states[s].node] = static_cast<int>(s);
  return m;
}

std::string refusal(const Atlas& a) {
  try {
    (void)markovTreeFromAtlas(a);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return {};
}

/// The two-state tree of the closed-form tests: the centre's loop (Φ₀, ℓ₀) and one chain of six inside it (Φ₁, ℓ₁).
constexpr long double phi0 = 3.8e-3L, l0 = 0.23L, phi1 = 2.0e-5L, l1 = 0.03L;
Atlas twoStates() {
  Atlas a;
  a.nodes = {node(-1, 0, 1, std::nullopt, phi0, 0.5L, l0, 0.1668),
             node(0, 1, 6, Rational{1, 6}, phi1, 0.3L, l1, 0.09)};
  link(a);
  return a;
}

TEST(MarkovTree, TwoStatesFollowTheirClosedForm) {
  const Atlas a = twoStates();
  const MarkovTree tree = markovTreeFromAtlas(a);
  ASSERT_EQ(tree.states.size(), 2u);
  // G = I − M = [[a + b, −b], [−c, c]]: a = Φ₀/A₀ to the sea, b = Φ₁/A₀ in, c = Φ₁/A₁ out; A₀ = ℓ₀ − ℓ₁, A₁ = ℓ₁.
  const long double A0 = l0 - l1, ra = phi0 / A0, rb = phi1 / A0, rc = phi1 / l1;
  const long double tr = ra + rb + rc, disc = std::sqrt(tr * tr - 4 * ra * rc);
  const long double muSmall = 2 * ra * rc / (tr + disc), muLarge = (tr + disc) / 2;  // eigenvalues of G
  // S(t) = A (1 − μ₋)ᵗ + B (1 − μ₊)ᵗ with S(0) = 1 and S(1) = 1 − a.
  const long double A = (muLarge - ra) / (muLarge - muSmall), B = 1 - A;
  const std::vector<std::uint64_t> t{0, 1, 2, 3, 10, 100, 1000, 10000, 100000, 1000000, 10000000};
  const MarkovTreeSurvival s = markovTreeSurvival(tree, t);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto ti = static_cast<long double>(t[i]);
    const long double exact = A * std::exp(ti * std::log1p(-muSmall)) + B * std::exp(ti * std::log1p(-muLarge));
    EXPECT_NEAR(static_cast<double>(s.S[i] / exact), 1.0, 1e-14) << "t = " << t[i];
    EXPECT_NEAR(static_cast<double>((s.state[0][i] + s.state[1][i]) / s.S[i]), 1.0, 1e-15);
    EXPECT_EQ(s.level[0][i], s.state[0][i]);
    EXPECT_EQ(s.level[1][i], s.state[1][i]);
  }
  EXPECT_NEAR(static_cast<double>(s.S[1]), static_cast<double>(1 - ra), 1e-15);
  // Kac: the mean visit is ℓ₀/Φ₀, whatever happens inside.
  EXPECT_NEAR(static_cast<double>(s.meanVisit / (l0 / phi0)), 1.0, 1e-15);
}

TEST(MarkovTree, TheStatesOfTheK01AtlasNestAndTheMeanVisitIsTheLoopsResidence) {
  const MarkovTree tree = markovTreeFromAtlas(k01());
  const auto st = statesByNode(tree);
  // Every chain with a flux has a state; 4/29 (refused), 2/19 about 13 (no flux) and 406 under 29 are lumped.
  ASSERT_EQ(tree.states.size(), 10u);
  ASSERT_EQ(tree.lumped.size(), 3u);
  const std::map<int, int> nestedIn{{2, 0}, {3, 2}, {5, 3}, {1, 5}, {6, 1}, {7, 6}, {8, 7}, {10, 8}, {9, 10}};
  for (const auto& [n, container] : nestedIn)
    EXPECT_EQ(tree.states[static_cast<std::size_t>(st.at(n))].container, st.at(container)) << "node " << n;
  // A = ℓ − ℓ(inner sibling) − ℓ(outermost child), by hand from the table.
  const std::map<int, long double> area{{0, 0.22957L - 0.093772L},      {2, 0.093772L - 0.066583L},
                                        {3, 0.066583L - 0.042958L},     {5, 0.042958L - 0.029719L},
                                        {1, 0.029719L - 7.853e-3L},     {6, 7.853e-3L - 6.869e-3L},
                                        {7, 6.869e-3L - 4.994e-3L},     {8, 4.994e-3L - 4.785e-4L},
                                        {10, 4.785e-4L - 1.319e-4L},    {9, 1.319e-4L}};
  long double total = 0;
  for (const auto& [n, A] : area) {
    EXPECT_NEAR(static_cast<double>(tree.states[static_cast<std::size_t>(st.at(n))].area / A), 1.0, 1e-15) << n;
    total += tree.states[static_cast<std::size_t>(st.at(n))].area;
  }
  EXPECT_NEAR(static_cast<double>(total / 0.22957L), 1.0, 1e-15);
  EXPECT_EQ(tree.levels, 3);
  for (const MarkovTreeLumped& l : tree.lumped) {
    if (l.node == 4) {
      EXPECT_EQ(l.state, st.at(0));  // 4/29 lies outside 2/13: in the top state
      EXPECT_NE(l.reason.find("the lobe is not small"), std::string::npos) << l.reason;
    }
    if (l.node == 12) {
      EXPECT_NE(l.reason.find("inside 29"), std::string::npos) << l.reason;
    }
    if (l.node == 11) {
      EXPECT_EQ(l.state, st.at(2));
    }
  }
  const MarkovTreeSurvival s = markovTreeSurvival(tree, {0, 1, 1000, 1000000});
  EXPECT_NEAR(static_cast<double>(s.meanVisit / (0.22957L / 3.843389e-3L)), 1.0, 1e-14);
  EXPECT_EQ(s.S[0], 1);
  EXPECT_NEAR(static_cast<double>(s.S[1]), static_cast<double>(1 - 3.843389e-3L / (0.22957L - 0.093772L)), 1e-15);
  // After 10⁶ steps what survives sits at level 2 (the slowest states are about the island of six).
  EXPECT_GT(s.level[2][3], 0.9L * s.S[3]);
}

TEST(MarkovTree, IsRecomputedFromAnAtlasFileWithEveryRateFromItsNumbers) {
  const auto path = std::filesystem::temp_directory_path() / "archipelago-markov-tree-test.json";
  writeAtlasJson(path, k01());
  const std::string text = io::readRegularFile(path.string(), kMaxAtlasFileBytes);
  std::filesystem::remove(path);
  const MarkovTree tree = markovTreeFromAtlas(atlasFromJson(text));
  // The file's own numbers, read here without the atlas's reader.
  const nlohmann::json j = nlohmann::json::parse(text);
  auto flux = [&](int n) { return j["nodes"][static_cast<std::size_t>(n)]["flux"]["flux_per_step"].get<double>(); };
  auto layer = [&](int n) { return j["nodes"][static_cast<std::size_t>(n)]["flux"]["layer_area"].get<double>(); };
  const auto st = statesByNode(tree);
  auto areaOf = [&](int n) {
    long double A = layer(n);
    for (int d : tree.states[static_cast<std::size_t>(st.at(n))].subtracted)  // the states just inside it
      A -= layer(tree.states[static_cast<std::size_t>(d)].node);
    return A;
  };
  ASSERT_EQ(tree.rates.size(), 2 * tree.states.size() - 1);
  for (const MarkovTreeRate& r : tree.rates) {
    const int from = tree.states[static_cast<std::size_t>(r.from)].node;
    const long double expected = static_cast<long double>(flux(r.fluxNode)) / areaOf(from);
    EXPECT_NEAR(static_cast<double>(r.perStep / expected), 1.0, 1e-15) << r.source;
    EXPECT_FALSE(r.source.empty());
    // The barrier crossed is the inner state's: its own node's flux.
    const int inner = r.to >= 0 && tree.states[static_cast<std::size_t>(r.to)].container == r.from ? r.to : r.from;
    EXPECT_EQ(r.fluxNode, tree.states[static_cast<std::size_t>(inner)].node);
  }
  EXPECT_EQ(tree.rates[0].to, -1);
  EXPECT_NEAR(static_cast<double>(tree.rates[0].perStep), flux(0) / (layer(0) - layer(2)), 1e-15);
}

/// k01() with issue 50's barriers: the inner separatrices of 2/13 and 1/6 (the latter's band down to the central
/// island's boundary circle, 1/6's inner lobe 2.13e-8 as docs/atlas.md's K = 0.1 atlas gives it) and the cantorus
/// between 5/31 and 1/6 (MMP's 1.1632e-5, docs/markov-tree.md), its layer between theirs.
Atlas k01WithInnerSeparatricesAndACantorus() {
  Atlas a = k01();
  auto inner = [](AtlasNode& n, long double flux, long double layer) {
    n.flux.inner.found = true;
    n.flux.inner.flux = flux;
    n.flux.inner.zoneArea = layer + 0.2L;
    n.flux.inner.enclosedIslands = 0.2L;
    n.flux.inner.layerArea = layer;
    n.flux.outerByZone = true;
  };
  inner(a.nodes[2], 6.5e-5L, 0.0737L);      // 2/13
  inner(a.nodes[1], 2.13e-8L, 1.35e-4L);    // 1/6
  AtlasCantorus c;
  c.outer = {5, 31};
  c.inner = {1, 6};
  c.found = true;
  c.flux = 1.1632e-5L;
  c.zoneArea = 0.3189L;
  c.layerArea = 0.0395L;
  c.enclosedIslands = c.zoneArea - c.layerArea;
  a.cantori = {c};
  return a;
}

const MarkovTreeState& stateOf(const MarkovTree& t, int node, MarkovTreeBarrier kind) {
  for (const MarkovTreeState& s : t.states)
    if (s.node == node && s.barrier == kind) return s;
  throw std::logic_error("no such state");
}

// Issue 50: the tree is a tree — the state inside 1/6's outer separatrix opens both into the band inside its inner
// separatrix and into the subtree of its islands; inner separatrices and cantori are states; each area is its layer
// less its children's, the whole the loop's layer; the mean visit is still the loop's residence (Kac).
TEST(MarkovTree, InnerSeparatricesAndCantoriAreStatesAndTheTreeBranches) {
  const Atlas a = k01WithInnerSeparatricesAndACantorus();
  const MarkovTree tree = markovTreeFromAtlas(a);
  ASSERT_EQ(tree.states.size(), k01States + 3);
  const auto index = [&](const MarkovTreeState& s) { return static_cast<int>(&s - tree.states.data()); };
  const MarkovTreeState& six = stateOf(tree, 1, MarkovTreeBarrier::OuterSeparatrix);
  const MarkovTreeState& sixInner = stateOf(tree, 1, MarkovTreeBarrier::InnerSeparatrix);
  const MarkovTreeState& thirteenInner = stateOf(tree, 2, MarkovTreeBarrier::InnerSeparatrix);
  const MarkovTreeState& cantorus = stateOf(tree, -1, MarkovTreeBarrier::Cantorus);
  const MarkovTreeState& thirtyOne = stateOf(tree, 5, MarkovTreeBarrier::OuterSeparatrix);
  const MarkovTreeState& seventyTwo = stateOf(tree, 6, MarkovTreeBarrier::OuterSeparatrix);
  EXPECT_EQ(six.subtracted, (std::vector<int>{index(seventyTwo), index(sixInner)}));  // branching: two children
  EXPECT_EQ(sixInner.container, index(six));
  EXPECT_EQ(seventyTwo.container, index(six));
  EXPECT_EQ(six.container, index(cantorus));
  EXPECT_EQ(cantorus.container, index(thirtyOne));
  EXPECT_EQ(thirteenInner.container, index(stateOf(tree, 2, MarkovTreeBarrier::OuterSeparatrix)));
  EXPECT_NEAR(static_cast<double>(six.area), 0.029719 - 7.853e-3 - 1.35e-4, 1e-15);
  EXPECT_NEAR(static_cast<double>(sixInner.area), 1.35e-4, 1e-18);
  EXPECT_NEAR(static_cast<double>(cantorus.area), 0.0395 - 0.029719, 1e-15);
  EXPECT_NEAR(static_cast<double>(thirtyOne.area), 0.042958 - 0.0395, 1e-15);
  EXPECT_NEAR(static_cast<double>(thirteenInner.area), 0.0737 - 0.066583, 1e-15);
  long double total = 0;
  for (const MarkovTreeState& s : tree.states) total += s.area;
  EXPECT_NEAR(static_cast<double>(total / 0.22957L), 1.0, 1e-15);
  // The rates through the cantorus and 1/6's inner separatrix are their fluxes over the area they leave.
  bool throughCantorus = false, throughInner = false;
  for (const MarkovTreeRate& r : tree.rates) {
    if (r.from == index(cantorus) && r.to == index(thirtyOne)) {
      EXPECT_NEAR(static_cast<double>(r.perStep / (1.1632e-5L / cantorus.area)), 1.0, 1e-15);
      throughCantorus = true;
    }
    if (r.from == index(sixInner) && r.to == index(six)) {
      EXPECT_NEAR(static_cast<double>(r.perStep / (2.13e-8L / 1.35e-4L)), 1.0, 1e-15);
      throughInner = true;
    }
  }
  EXPECT_TRUE(throughCantorus && throughInner);
  EXPECT_NEAR(static_cast<double>(markovTreeSurvival(tree, {1}).meanVisit / (0.22957L / 3.843389e-3L)), 1.0, 1e-14);

  // Left out, each ingredient merges the states it divides; a level left out is lumped.
  EXPECT_EQ(markovTreeFromAtlas(a, {.innerSeparatrices = false}).states.size(), k01States + 1);
  EXPECT_EQ(markovTreeFromAtlas(a, {.cantori = false}).states.size(), k01States + 2);
  const MarkovTree outerOnly = markovTreeFromAtlas(a, {.innerSeparatrices = false, .cantori = false});
  ASSERT_EQ(outerOnly.states.size(), k01States);
  const MarkovTree old = markovTreeFromAtlas(k01());
  for (std::size_t s = 0; s < old.states.size(); ++s)
    EXPECT_EQ(outerOnly.states[s].area, old.states[s].area) << s;
  const MarkovTree level1 = markovTreeFromAtlas(a, {.maxLevel = 1});
  for (const MarkovTreeState& s : level1.states) EXPECT_LE(s.level, 1);
  EXPECT_EQ(level1.states.size(), k01States + 3 - 5);  // the five chains about the six are lumped into its state

  // A cantorus whose layer is not inside the barrier outside it leaves a state of no area: refused.
  Atlas bad = a;
  bad.cantori[0].layerArea = 0.05L;
  EXPECT_THROW((void)markovTreeFromAtlas(bad), std::invalid_argument);
}

// Issue 50, item 4 (2026-12-07): the cantori about a chain's island and the boundary cantori are states too.  About
// the six, between 1/12 and 2/23 (the atlas's 4.81e−7 at K = 0.1, depth 2), its layer between theirs; the centre's
// boundary cantorus (1/6 and 15/89, 1.449e−9, layer 8.6e−5) inside 1/6's inner separatrix; the six's (4/43 and
// 11/118; a flux for the test: the atlas does not reach its terms) inside its innermost chain, 4/43.
TEST(MarkovTree, IslandAndBoundaryCantoriAreStatesInsideTheBarriersTheyFollow) {
  Atlas a = k01WithInnerSeparatricesAndACantorus();
  auto cantorus = [](int island, bool boundary, Rational outer, Rational inner, long double flux, long double layer) {
    AtlasCantorus c;
    c.island = island;
    c.boundary = boundary;
    c.outer = outer;
    c.inner = inner;
    c.found = true;
    c.flux = flux;
    c.layerArea = layer;
    c.zoneArea = layer + 0.01L;
    c.enclosedIslands = 0.01L;
    return c;
  };
  a.cantori.push_back(cantorus(0, true, {1, 6}, {15, 89}, 1.449e-9L, 8.6e-5L));
  a.cantori.push_back(cantorus(1, false, {1, 12}, {2, 23}, 4.81e-7L, 7.3e-3L));
  a.cantori.push_back(cantorus(1, true, {4, 43}, {11, 118}, 1e-10L, 5e-5L));
  const MarkovTree tree = markovTreeFromAtlas(a);
  ASSERT_EQ(tree.states.size(), k01States + 6);
  const auto index = [&](const MarkovTreeState& s) { return static_cast<int>(&s - tree.states.data()); };
  const auto named = [&](const std::string& path) -> const MarkovTreeState& {
    for (const MarkovTreeState& s : tree.states)
      if (s.path == path) return s;
    throw std::logic_error("no state " + path);
  };
  const MarkovTreeState& centreBoundary = named("boundary cantorus 1/6-15/89");
  const MarkovTreeState& aboutSix = named("cantorus 1/12-2/23 about 6");
  const MarkovTreeState& sixBoundary = named("boundary cantorus 4/43-11/118 of 6");
  const MarkovTreeState& sixInner = stateOf(tree, 1, MarkovTreeBarrier::InnerSeparatrix);
  const MarkovTreeState& seventyTwo = stateOf(tree, 6, MarkovTreeBarrier::OuterSeparatrix);
  const MarkovTreeState& oneThirtyEight = stateOf(tree, 7, MarkovTreeBarrier::OuterSeparatrix);
  const MarkovTreeState& fortyThree = stateOf(tree, 9, MarkovTreeBarrier::OuterSeparatrix);
  EXPECT_EQ(centreBoundary.barrier, MarkovTreeBarrier::Cantorus);
  EXPECT_EQ(centreBoundary.container, index(sixInner));
  EXPECT_EQ(aboutSix.container, index(seventyTwo));
  EXPECT_EQ(oneThirtyEight.container, index(aboutSix));
  EXPECT_EQ(sixBoundary.container, index(fortyThree));
  EXPECT_EQ(aboutSix.level, 2);
  EXPECT_NEAR(static_cast<double>(sixInner.area), 1.35e-4 - 8.6e-5, 1e-18);
  EXPECT_NEAR(static_cast<double>(centreBoundary.area), 8.6e-5, 1e-18);
  EXPECT_NEAR(static_cast<double>(seventyTwo.area), 7.853e-3 - 7.3e-3, 1e-15);
  EXPECT_NEAR(static_cast<double>(aboutSix.area), 7.3e-3 - 6.869e-3, 1e-15);
  EXPECT_NEAR(static_cast<double>(fortyThree.area), 1.319e-4 - 5e-5, 1e-17);
  long double total = 0;
  for (const MarkovTreeState& s : tree.states) total += s.area;
  EXPECT_NEAR(static_cast<double>(total / 0.22957L), 1.0, 1e-15);
  for (const MarkovTreeRate& r : tree.rates)
    if (r.from == index(centreBoundary)) {
      EXPECT_EQ(r.to, index(sixInner));
      EXPECT_NEAR(static_cast<double>(r.perStep / (1.449e-9L / 8.6e-5L)), 1.0, 1e-15);
    }
  // Without cantori all of them go; a boundary record does not stand in for a cantorus between chains, nor the
  // reverse (an island cantorus with the centre's index is not about the six).
  EXPECT_EQ(markovTreeFromAtlas(a, {.cantori = false}).states.size(), k01States + 2);
  Atlas wrongIsland = a;
  wrongIsland.cantori[2].island = 0;
  EXPECT_EQ(markovTreeFromAtlas(wrongIsland).states.size(), k01States + 5);
  // A boundary cantorus whose layer is not inside its chain's band leaves that band no area: refused.
  Atlas bad = a;
  bad.cantori[1].layerArea = 2e-4L;
  EXPECT_THROW((void)markovTreeFromAtlas(bad), std::invalid_argument);
}

TEST(MarkovTree, ChangingOneFluxChangesTheRatesThroughThatBarrierOnly) {
  const Atlas a = k01();
  Atlas b = a;
  b.nodes[7].flux.flux *= 2;  // the 2/23 chain about the six: the paper's 138
  const MarkovTree x = markovTreeFromAtlas(a), y = markovTreeFromAtlas(b);
  ASSERT_EQ(x.rates.size(), y.rates.size());
  int changed = 0;
  for (std::size_t i = 0; i < x.rates.size(); ++i) {
    if (x.rates[i].fluxNode == 7) {
      ++changed;
      EXPECT_NEAR(static_cast<double>(y.rates[i].perStep / x.rates[i].perStep), 2.0, 1e-15);
    } else {
      EXPECT_EQ(y.rates[i].perStep, x.rates[i].perStep) << x.rates[i].source;
    }
  }
  EXPECT_EQ(changed, 2);
  const MarkovTreeSurvival sx = markovTreeSurvival(x, {1, 100000, 1000000}), sy = markovTreeSurvival(y, {1, 100000, 1000000});
  EXPECT_EQ(sx.S[0], sy.S[0]);                           // one step: only the loop's rate acts
  EXPECT_GT(std::fabs(sx.S[2] / sy.S[2] - 1), 1e-3L);    // 10⁶ steps: the deeper states' share moved
  EXPECT_NEAR(static_cast<double>(sx.meanVisit / sy.meanVisit), 1.0, 1e-15);  // Kac: the mean does not move
}

TEST(MarkovTree, RefusesAnAtlasThatCannotMakeATree) {
  EXPECT_NE(refusal(Atlas{}).find("no island"), std::string::npos);
  {
    Atlas a = k01();
    a.cancelled = true;
    a.stopReason = "time budget of 60 s reached";
    EXPECT_NE(refusal(a).find("stopped before its end"), std::string::npos);
  }
  {
    Atlas a = k01();
    a.nodes[8].measured = false;
    EXPECT_NE(refusal(a).find("6 > 204 is not measured"), std::string::npos);
  }
  {
    Atlas a = k01();
    a.nodes[0].flux = AtlasFlux{};
    a.nodes[0].flux.failure = "no primary pair";
    EXPECT_NE(refusal(a).find("no flux through the centre's loop (no primary pair)"), std::string::npos);
  }
  {
    Atlas a = k01();  // 3/19's zone said larger than 2/13's: against the twist
    std::swap(a.nodes[2].flux.zoneArea, a.nodes[3].flux.zoneArea);
    const std::string e = refusal(a);
    EXPECT_NE(e.find("the chains about centre do not nest"), std::string::npos) << e;
  }
  {
    Atlas a = k01();  // the 1/12 chain's layer larger than the six's own: a negative state
    a.nodes[6].flux.layerArea = 0.0297195L;
    a.nodes[6].flux.zoneArea = 0.3L;
    const std::string e = refusal(a);
    EXPECT_NE(e.find("the state of 6 has area -"), std::string::npos) << e;
  }
  {
    Atlas a = k01();
    a.nodes[5].flux.flux = -1e-5L;
    EXPECT_NE(refusal(a).find("the flux of 31"), std::string::npos);
  }
  {
    Atlas a = k01();
    a.nodes[5].flux.layerArea = std::nanl("");
    EXPECT_NE(refusal(a).find("the layer of 31"), std::string::npos);
  }
  // Not an atlas at all: the reader's message.
  EXPECT_THROW((void)atlasFromJson("{\"format\": \"archipelago tail\"}"), std::runtime_error);
  EXPECT_THROW((void)markovTreeSurvival(markovTreeFromAtlas(k01()), {std::uint64_t{1} << 63}), std::invalid_argument);
  EXPECT_THROW((void)markovTreeEntryWeight(markovTreeFromAtlas(k01()), 0, 1.36), std::invalid_argument);
  EXPECT_THROW((void)markovTreeGrid(0.5), std::invalid_argument);
}

// Issue 53 finding 9: a front end says why an atlas makes no tree before it is asked (the GUI's "Model P_t…" was
// greyed out with no reason): markovTreeAtlasError gives the words markovTreeFromAtlas throws, nothing for a good one.
TEST(MarkovTree, TheAtlasErrorIsTheRefusalsWordsBeforeTheTree) {
  EXPECT_EQ(markovTreeAtlasError(k01()), std::nullopt);
  Atlas a = k01();
  a.cancelled = true;
  a.stopReason = "stopped";
  const std::optional<std::string> e = markovTreeAtlasError(a);
  ASSERT_TRUE(e);
  EXPECT_EQ(*e, "the atlas was stopped before its end (stopped): resume the atlas to its end before building the tree");
  EXPECT_EQ(refusal(a), "markov tree: " + *e);
  EXPECT_EQ(markovTreeAtlasError(Atlas{}), std::optional<std::string>("the atlas has no island"));
}

TEST(MarkovTree, GridAndEntryWeight) {
  const std::vector<std::uint64_t> g = markovTreeGrid(1e9, 10);
  EXPECT_EQ(g.front(), 1u);
  EXPECT_EQ(g.back(), 1000000000u);
  for (std::size_t i = 1; i < g.size(); ++i) EXPECT_LT(g[i - 1], g[i]);
  for (std::uint64_t decade = 1; decade <= 1000000000u; decade *= 10)  // 10^k exactly on the grid
    EXPECT_NE(std::find(g.begin(), g.end(), decade), g.end()) << decade;
  EXPECT_NE(std::find(g.begin(), g.end(), 1585u), g.end());  // ⌈10^3.2⌉
  const MarkovTree tree = markovTreeFromAtlas(k01());
  EXPECT_NEAR(static_cast<double>(markovTreeEntryWeight(tree, 40.0, 1.36)), 40.0 * 3.843389e-3 / 1.36, 1e-16);
}

// What the GUI draws and shows (issue 40, GUI): the curve is w S(t) of the two-state closed form at every t > 0 of the
// grid where it is a double, and nothing else; the shares at t are each level's part / S and sum to 1.
TEST(MarkovTree, CurveIsWTimesSAndSharesSumToOne) {
  const Atlas a = twoStates();
  MarkovTreeRequest r;
  r.tMax = 1e7;
  r.perDecade = 10;
  r.alpha = 20;
  r.b2 = 1.5;
  r.at = {12345};
  const MarkovTreeResult m = computeMarkovTree(a, r);
  const long double A0 = l0 - l1, ra = phi0 / A0, rb = phi1 / A0, rc = phi1 / l1;  // as TwoStatesFollowTheirClosedForm
  const long double tr = ra + rb + rc, disc = std::sqrt(tr * tr - 4 * ra * rc);
  const long double muSmall = 2 * ra * rc / (tr + disc), muLarge = (tr + disc) / 2;
  const long double A = (muLarge - ra) / (muLarge - muSmall), B = 1 - A;
  const long double w = 20 * phi0 / 1.5L;
  const Series curve = markovTreeCurve(m);
  std::size_t expected = 0;
  for (std::uint64_t t : m.survival.t) {
    const auto ti = static_cast<long double>(t);
    const long double P = w * (A * std::exp(ti * std::log1p(-muSmall)) + B * std::exp(ti * std::log1p(-muLarge)));
    if (t == 0 || static_cast<double>(P) < std::numeric_limits<double>::min()) continue;  // S(10⁷) ≈ e⁻⁶⁴⁰⁰
    ASSERT_LT(expected, curve.x.size()) << "t = " << t;
    EXPECT_EQ(curve.x[expected], static_cast<double>(t));
    EXPECT_NEAR(curve.value[expected] / static_cast<double>(P), 1.0, 1e-13) << "t = " << t;
    ++expected;
  }
  EXPECT_EQ(curve.x.size(), expected);
  EXPECT_LT(curve.x.back(), 1e7);  // the exponential tail is left out
  EXPECT_GT(curve.x.size(), 40u);
  for (std::uint64_t t : {std::uint64_t{1}, std::uint64_t{100}, std::uint64_t{12345}}) {
    const auto shares = markovTreeLevelShares(m.survival, t);
    ASSERT_TRUE(shares) << t;
    ASSERT_EQ(shares->size(), 2u);
    const auto i = static_cast<std::size_t>(std::find(m.survival.t.begin(), m.survival.t.end(), t) - m.survival.t.begin());
    EXPECT_NEAR((*shares)[1], static_cast<double>(m.survival.state[1][i] / m.survival.S[i]), 1e-15);
    EXPECT_NEAR((*shares)[0] + (*shares)[1], 1.0, 1e-15) << t;
  }
  EXPECT_FALSE(markovTreeLevelShares(m.survival, 12346));  // not on the grid
  r.alpha = r.b2 = 0;  // no entry: no P_t to draw
  EXPECT_TRUE(markovTreeCurve(computeMarkovTree(a, r)).x.empty());
}

/// The refusal of markovTreeFromJson for `j` signed again after an edit (as the writer signs), or "" when it reads.
std::string treeFileRefusal(nlohmann::ordered_json j) {
  j.erase("checksum");
  if (j.contains("format_version")) j["checksum"] = io::jsonChecksum(nlohmann::json::parse(j.dump()));
  try {
    (void)markovTreeFromJson(j.dump(2));
  } catch (const io::BadFile& e) {
    return e.what();
  }
  return {};
}

// Markov-tree files are signed and checked as atlases are (issue 54): read back whole; an edit refused by its
// checksum; a forger who signs again refused by the invariants, naming the field and its value; a file from before
// the version (unsigned) read.
TEST(MarkovTree, AFileIsReadBackAndAnEditedOneIsRefused) {
  MarkovTreeRequest r;
  r.tMax = 1e5;
  r.perDecade = 10;
  r.alpha = 20;
  r.b2 = 1.5;
  const MarkovTreeResult m = computeMarkovTree(twoStates(), r);
  const std::string text = markovTreeJson(m);
  const MarkovTreeResult back = markovTreeFromJson(text);
  EXPECT_EQ(back.survival.t, m.survival.t);
  EXPECT_EQ(back.survival.S[5], static_cast<double>(m.survival.S[5]));
  EXPECT_EQ(back.tree.rates[1].perStep, static_cast<double>(m.tree.rates[1].perStep));
  ASSERT_TRUE(back.weight);
  EXPECT_EQ(back.tree.states.size(), 2u);
  auto j = nlohmann::ordered_json::parse(text);
  EXPECT_EQ(j["format_version"], kMarkovTreeFormatVersion);
  auto edited = j;
  edited["survival"]["S"][3] = 0.5;
  try {
    (void)markovTreeFromJson(edited.dump(2));
    ADD_FAILURE() << "an edited file was read";
  } catch (const io::BadFile& e) {
    EXPECT_NE(std::string(e.what()).find("checksum does not match"), std::string::npos) << e.what();
  }
  auto unsignedOld = j;  // a file from before the version
  unsignedOld.erase("format_version");
  EXPECT_EQ(treeFileRefusal(unsignedOld), "");
  edited = j;
  edited["survival"]["S"][4] = edited["survival"]["S"][2];
  EXPECT_NE(treeFileRefusal(edited).find("survival.S[4] = "), std::string::npos) << treeFileRefusal(edited);
  EXPECT_NE(treeFileRefusal(edited).find("S(t) does not increase"), std::string::npos);
  edited = j;
  edited["survival"]["levels"][1][4] = 1.5;
  EXPECT_EQ(treeFileRefusal(edited), "markov tree file: survival.levels[1][4] = 1.5 must lie in [0, 1] (a probability)");
  edited = j;
  edited["states"][1]["container"] = 1;
  EXPECT_NE(treeFileRefusal(edited).find("states[1].container = 1 must be"), std::string::npos) << treeFileRefusal(edited);
  edited = j;
  edited["rates"][0]["per_step"] = 1e308;
  EXPECT_NE(treeFileRefusal(edited).find("rates[0].per_step = 1e+308 must lie in (0, 1]"), std::string::npos)
      << treeFileRefusal(edited);
  edited = j;
  edited["entry"]["weight"] = 2 * edited["entry"]["weight"].get<double>();
  EXPECT_NE(treeFileRefusal(edited).find("entry.weight = "), std::string::npos) << treeFileRefusal(edited);
  edited = j;
  edited["states"][0]["area"] = -1;
  EXPECT_EQ(treeFileRefusal(edited), "markov tree file: states[0].area = -1 must be > 0");
  edited = j;
  edited["format"] = "archipelago atlas";
  EXPECT_NE(treeFileRefusal(edited).find("format = "), std::string::npos);
}

// What a front end prefills for α and b₂ (issue 40, found by a session: the GUI offered K = 0.1's b₂ and the run's α
// whatever the atlas's map): a number only of the atlas's own map, else nothing, saying why.
// The comparison with a measured tail (issue 40: the report's item, markov-tree --tail): each ratio is w S(t) of the
// two-state closed form over the level's P; the reach is the last level before the first ratio outside [1/3, 3];
// unreliable levels, levels below 10³ and P = 0 are left out; a bad factor is refused.
TEST(MarkovTree, TheComparisonWithATailIsTheModelOverEachReliableLevel) {
  const Atlas a = twoStates();
  const MarkovTree tree = markovTreeFromAtlas(a);
  const double alpha = 20, b2 = 1.3;
  const long double w = alpha * phi0 / b2;
  const std::vector<std::uint64_t> ts{500, 1000, 3000, 10000, 30000, 100000};
  const MarkovTreeSurvival s = markovTreeSurvival(tree, ts);
  // The "measured" levels: the model times 1.5, 0.5, 2.9, 0.2 (outside), 1.0 at 10³ … 10⁵; 500 steps (below 10³)
  // and an unreliable level at 3·10³ are not compared.
  const double factors[] = {1.0, 1.5, 0.5, 2.9, 0.2, 1.0};
  TailResult tail;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    TailLevelResult L;
    L.t = static_cast<double>(ts[i]);
    L.P = static_cast<double>(w * s.S[i]) / factors[i];
    L.PError = 0.1 * L.P;
    L.reliable = true;
    tail.levels.push_back(L);
  }
  TailLevelResult unreliable = tail.levels[2];
  unreliable.reliable = false;
  unreliable.t = 5000;
  tail.levels.insert(tail.levels.begin() + 3, unreliable);
  TailLevelResult zero = tail.levels[1];
  zero.t = 7000;
  zero.P = 0;
  tail.levels.insert(tail.levels.begin() + 4, zero);

  const MarkovTreeComparison c = compareMarkovTreeWithTail(tree, alpha, b2, tail);
  ASSERT_EQ(c.levels.size(), 5u);
  EXPECT_NEAR(static_cast<double>(c.weight / w), 1.0, 1e-15);
  for (std::size_t k = 0; k < c.levels.size(); ++k) {
    EXPECT_EQ(c.levels[k].t, static_cast<double>(ts[k + 1]));
    EXPECT_NEAR(static_cast<double>(c.levels[k].ratio), factors[k + 1], 1e-12) << c.levels[k].t;
    EXPECT_GE(c.levels[k].holdingLevel, 0);
  }
  EXPECT_EQ(c.reach, 100000);  // the last level within 3: 3·10⁴ (off by 5) lies before it
  tail.levels.back().P *= 20;    // 10⁵ off by 20 (the exponential tail of a finite tree): the reach is 10⁴
  EXPECT_EQ(compareMarkovTreeWithTail(tree, alpha, b2, tail).reach, 10000);
  EXPECT_EQ(compareMarkovTreeWithTail(tree, alpha, b2, tail, 1e3, 25).reach, 100000);
  EXPECT_EQ(compareMarkovTreeWithTail(tree, alpha, b2, tail, 1e3, 1.4).reach, 0);  // 1.5, 0.5, 2.9, 0.2, 0.05
  EXPECT_TRUE(compareMarkovTreeWithTail(tree, alpha, b2, tail, 1e6).levels.empty());
  EXPECT_THROW((void)compareMarkovTreeWithTail(tree, alpha, b2, tail, 1e3, 0.5), std::invalid_argument);
  EXPECT_THROW((void)compareMarkovTreeWithTail(tree, alpha, b2, tail, std::nan(""), 3), std::invalid_argument);
  EXPECT_THROW((void)compareMarkovTreeWithTail(tree, 0, b2, tail), std::invalid_argument);
}

TEST(MarkovTree, TheEntryOfferedIsNeverAnotherMapsNumber) {
  const MapParameters docs;                                  // K = 0.1 in (−0.8, 0.5): the docs' map
  const MapParameters k015{0.15, -0.8, 0.5}, wider{0.1, -0.8, 0.6};
  MarkovTreeEntryOffer o = markovTreeEntryOffer(docs, std::nullopt, 0);
  EXPECT_EQ(o.alpha, 18.9043);  // docs/markov-tree.md's numbers, typed from the page
  EXPECT_EQ(o.b2, 1.362484);
  EXPECT_NE(o.alphaSource.find("no run"), std::string::npos) << o.alphaSource;
  o = markovTreeEntryOffer(docs, docs, 12.5);  // a run of the atlas's map: its α
  EXPECT_EQ(o.alpha, 12.5);
  EXPECT_EQ(o.b2, 1.362484);
  EXPECT_NE(o.alphaSource.find("run's mean segment length"), std::string::npos) << o.alphaSource;
  o = markovTreeEntryOffer(docs, k015, 12.5);  // a run of another K: not its α
  EXPECT_EQ(o.alpha, 18.9043);
  EXPECT_NE(o.alphaSource.find("another map: K = 0.15"), std::string::npos) << o.alphaSource;
  o = markovTreeEntryOffer(docs, docs, std::numeric_limits<double>::quiet_NaN());  // no α yet
  EXPECT_EQ(o.alpha, 18.9043);
  for (const MapParameters& other : {k015, wider}) {  // an atlas of another K or box: no docs number
    o = markovTreeEntryOffer(other, docs, 12.5);
    EXPECT_EQ(o.alpha, 0.0);
    EXPECT_EQ(o.b2, 0.0);
    EXPECT_EQ(o.alphaSource.rfind("none for the atlas's K = " + shortestDecimal(other.K), 0), 0u) << o.alphaSource;
    EXPECT_NE(o.b2Source.find("stochastic-area"), std::string::npos) << o.b2Source;
    o = markovTreeEntryOffer(other, other, 20);  // its own run: its α, still no b₂
    EXPECT_EQ(o.alpha, 20.0);
    EXPECT_EQ(o.b2, 0.0);
  }
}

}  // namespace
}  // namespace archipelago

namespace archipelago {
namespace {

// Issue 54, item 2 (and the GUI's finding 6 of issue 53): α = 10⁶ with b₂ = 10⁻³ gave w = 3843 visits per segment
// and P₁ = 3.7·10³; α = 10³⁰⁰ with b₂ = 10⁻³⁰⁰ and b₂ = 10⁻³²⁰ overflowed w (null in the JSON); b₂ = 100 is above the
// box's area (L² = 1.69); α = 10⁻³⁰⁰ is below one step.  One rule, one wording, in core.
TEST(MarkovTree, RefusesAnImpossibleEntryWithOneWording) {
  const MarkovTree tree = markovTreeFromAtlas(k01());
  EXPECT_EQ(markovTreeEntryError(18.9043, 1.362484, &tree), std::nullopt);  // docs/markov-tree.md's entry
  const auto error = [&](double alpha, double b2) { return markovTreeEntryError(alpha, b2, &tree).value_or("(none)"); };
  EXPECT_EQ(error(1e-300, 1.36).rfind("alpha = 1e-300 must be finite and at least 1", 0), 0u) << error(1e-300, 1.36);
  EXPECT_EQ(error(0, 1.36).rfind("alpha = 0 must be finite and at least 1", 0), 0u);
  EXPECT_EQ(error(INFINITY, 1.36).rfind("alpha = inf must be", 0), 0u);
  EXPECT_EQ(error(18.9, 100).rfind("b2 = 100 must lie in (0, 1.69", 0), 0u) << error(18.9, 100);
  EXPECT_EQ(error(18.9, 0).rfind("b2 = 0 must lie in (0, ", 0), 0u);
  EXPECT_EQ(error(18.9, NAN).rfind("b2 = nan must lie in (0, ", 0), 0u);
  for (const auto& [alpha, b2] : std::vector<std::pair<double, double>>{{1e6, 1e-3}, {1e300, 1e-300}, {18.9, 1e-320}}) {
    const std::string e = error(alpha, b2);
    EXPECT_EQ(e.rfind("P_1 = w S(1) = ", 0), 0u) << e;
    EXPECT_NE(e.find("cannot exceed 1"), std::string::npos) << e;
  }
  // The boundary: w S(1) = 1 exactly is a probability; just above it is not.
  const long double S1 = 1 - tree.entryFlux / tree.states[0].area;
  const double alphaMax = static_cast<double>(1.36L / (tree.entryFlux * S1));
  EXPECT_EQ(markovTreeEntryError(std::nextafter(alphaMax, 0.0), 1.36, &tree), std::nullopt);
  EXPECT_NE(markovTreeEntryError(alphaMax * (1 + 1e-12), 1.36, &tree), std::nullopt);
  // Without the atlas (the request's own check) only α and b₂ > 0: the box is not known yet.
  EXPECT_EQ(markovTreeEntryError(18.9, 100), std::nullopt);
  EXPECT_NE(markovTreeEntryError(0.5, 1.36), std::nullopt);
  // Every front end's path: the request and computeMarkovTree say the same words.
  MarkovTreeRequest r;
  r.alpha = 1e6;
  r.b2 = 1e-3;
  EXPECT_EQ(validationError(r), std::nullopt);
  try {
    (void)computeMarkovTree(k01(), r);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "markov tree: " + error(1e6, 1e-3));
  }
  r.alpha = 1e-300;
  EXPECT_EQ(validationError(r), error(1e-300, 1e-3));
  // The GUI draws P_t: α = b₂ = 0 is no entry at all there (it drew an empty curve), and refused.
  r = MarkovTreeRequest{};
  EXPECT_EQ(validationError(r), std::nullopt);
  r.needsP = true;
  EXPECT_EQ(validationError(r).value_or("").rfind("alpha = 0 must be finite and at least 1", 0), 0u);
}

// Issue 54, item 3: the survival by an eigen-decomposition (the binary powering before cost n³ log t in quad) against
// t products of a vector with M in quad, on the K = 0.1 atlas's 10 states and 40 nesting chains.
TEST(MarkovTree, TheSurvivalIsThatOfTProductsWithM) {
  for (const Atlas& a : {k01(), nestingChains(40)}) {
    const MarkovTree tree = markovTreeFromAtlas(a);
    const std::vector<std::uint64_t> t{0, 1, 2, 7, 100, 3000, 20000};
    const MarkovTreeSurvival s = markovTreeSurvival(tree, t);
    for (std::size_t i = 0; i < t.size(); ++i) {
      const std::vector<long double> v = survivalByProducts(tree, t[i]);
      long double S = 0;
      for (std::size_t st = 0; st < v.size(); ++st) {
        S += v[st];
        EXPECT_NEAR(static_cast<double>(s.state[st][i]), static_cast<double>(v[st]), 1e-15) << t[i] << " " << st;
      }
      EXPECT_NEAR(static_cast<double>(s.S[i] / S), 1.0, 1e-13) << "t = " << t[i] << ", " << tree.states.size();
    }
  }
}

// Issue 54, item 3: a legal atlas of nesting chains finishes (1000 of them ran past 360 s; cli.hostile_models runs the
// 1000, 500 here keep the sanitizer presets' time), its mean visit Kac's; one of 20,000 is refused before any work with
// its cost (it asked 6.4 GB per matrix power and was killed at 4 GiB); a stop requested is honoured (Ctrl-C,
// KeyboardInterrupt, the GUI's Cancel all request it).
TEST(MarkovTree, ALargeTreeFinishesOrIsRefusedWithItsCostAndStops) {
  const Atlas nesting = nestingChains(500);
  MarkovTreeRequest r;
  r.tMax = 1e6;
  r.perDecade = 5;
  const MarkovTreeResult m = computeMarkovTree(nesting, r);
  ASSERT_EQ(m.tree.states.size(), 501u);
  EXPECT_NEAR(static_cast<double>(m.survival.meanVisit / m.tree.residence), 1.0, 1e-15);  // Kac
  for (std::size_t i = 1; i < m.survival.S.size(); ++i) {
    EXPECT_LE(m.survival.S[i], m.survival.S[i - 1]) << m.survival.t[i];
    EXPECT_GT(m.survival.S[i], 0) << m.survival.t[i];
  }

  const auto states = static_cast<std::size_t>(limits::kMarkovTreeStates);  // the limit itself fits
  EXPECT_EQ(markovTreeCostError(markovTreeCost(states, 31)), std::nullopt);
  const Atlas large = nestingChains(20000);
  try {
    (void)computeMarkovTree(large, r);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("markov tree states = 20001 must lie in [1, " + std::to_string(states) + "]"), std::string::npos)
        << what;
    EXPECT_NE(what.find(" GB "), std::string::npos) << what;  // its cost
  }
  const MarkovTreeCost c = markovTreeCost(20001, 31);
  EXPECT_GT(c.bytes, 6.4e9L);
  // Past the values (states × times) too: the states fit, the times do not.
  EXPECT_NE(markovTreeCostError(markovTreeCost(1000, limits::kMarkovTreeValues / 1000 + 1)), std::nullopt);

  std::stop_source stop;
  stop.request_stop();
  EXPECT_THROW((void)computeMarkovTree(nesting, r, nullptr, stop.get_token()), OperationStopped);
}

}  // namespace
}  // namespace archipelago
