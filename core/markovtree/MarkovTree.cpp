#include "core/markovtree/MarkovTree.hpp"

#include "core/atlas/AtlasCantori.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/limits/Limits.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

namespace {

__extension__ typedef __float128 quad;

std::string sci(long double v, int digits = 4) { return io::formatC("%.*Le", digits, v); }  // C locale: the GUI's too

bool positiveFinite(long double v) { return std::isfinite(v) && v > 0; }

/// A rate's flux / area in quad.
quad quadRate(const MarkovTreeRate& r) { return static_cast<quad>(r.flux) / static_cast<quad>(r.area); }

[[noreturn]] void refuse(const std::string& why) { throw std::invalid_argument("markov tree: " + why); }

/// Distance of a chain's rotation about its parent from the parent's boundary rotation: the twist puts the chains
/// farther out the farther their p/q is from it (docs/atlas.md, step 5).
double twistDistance(const AtlasNode& parent, const AtlasNode& child) {
  const Rational r = child.aboutParent.value_or(Rational{0, 1});
  return std::fabs(static_cast<double>(r.p) / static_cast<double>(r.q) - parent.boundaryRotation);
}

std::string nameOf(const Atlas& a, int i) {
  const AtlasNode& n = a.nodes[static_cast<std::size_t>(i)];
  std::string s = atlasPath(a, i);
  if (n.aboutParent) s += " (" + toString(*n.aboutParent) + ")";
  return s;
}

}  // namespace

const char* toString(MarkovTreeBarrier b) {
  switch (b) {
    case MarkovTreeBarrier::OuterSeparatrix: return "outer separatrix";
    case MarkovTreeBarrier::InnerSeparatrix: return "inner separatrix";
    case MarkovTreeBarrier::Cantorus: return "cantorus";
  }
  return "?";
}

std::optional<std::string> markovTreeAtlasError(const Atlas& a) {
  if (a.nodes.empty()) return "the atlas has no island";
  if (a.cancelled)
    return "the atlas was stopped before its end (" + a.stopReason +
           "): resume the atlas to its end before building the tree";
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    if (!a.nodes[i].measured)
      return "island " + atlasPath(a, static_cast<int>(i)) +
             " is not measured (an atlas stopped early): resume the atlas to its end first";
  const AtlasNode& centre = a.nodes[0];
  if (!centre.flux.found)
    return "the atlas has no flux through the centre's loop (" +
           (centre.flux.failure.empty() ? std::string("not computed") : centre.flux.failure) +
           "): the tree has no entry";
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const AtlasFlux& f = a.nodes[i].flux;
    if (!f.found) continue;
    const std::string who = atlasPath(a, static_cast<int>(i));
    if (!positiveFinite(f.flux)) return "the flux of " + who + " = " + sci(f.flux) + " must be finite and > 0";
    if (!positiveFinite(f.layerArea))
      return "the layer of " + who + " = " + sci(f.layerArea) + " must be finite and > 0";
    if (!positiveFinite(f.zoneArea))
      return "the zone of " + who + " = " + sci(f.zoneArea) + " must be finite and > 0";
  }
  return std::nullopt;
}

namespace {

/// The atlas's rules for a tree (markovTreeAtlasError's), thrown.
void checkAtlasForTree(const Atlas& a) {
  if (auto e = markovTreeAtlasError(a)) refuse(*e);
}

/// The chains about island i that are barriers (a flux, level ≤ maxLevel), outermost first (by zone area), checked
/// against the twist.
std::vector<int> barrierChildren(const Atlas& a, int i, int maxLevel) {
  const AtlasNode& p = a.nodes[static_cast<std::size_t>(i)];
  std::vector<int> kids;
  for (int c : p.children)
    if (a.nodes[static_cast<std::size_t>(c)].flux.found && a.nodes[static_cast<std::size_t>(c)].level <= maxLevel)
      kids.push_back(c);
  std::stable_sort(kids.begin(), kids.end(), [&](int x, int y) {
    return a.nodes[static_cast<std::size_t>(x)].flux.zoneArea > a.nodes[static_cast<std::size_t>(y)].flux.zoneArea;
  });
  for (std::size_t k = 1; k < kids.size(); ++k) {
    const AtlasNode& outer = a.nodes[static_cast<std::size_t>(kids[k - 1])];
    const AtlasNode& inner = a.nodes[static_cast<std::size_t>(kids[k])];
    if (!(outer.flux.zoneArea > inner.flux.zoneArea) || !(outer.flux.layerArea > inner.flux.layerArea) ||
        !(twistDistance(p, outer) > twistDistance(p, inner)))
      refuse("the chains about " + atlasPath(a, i) + " do not nest: " + nameOf(a, kids[k - 1]) + " (zone " +
             sci(outer.flux.zoneArea) + ", layer " + sci(outer.flux.layerArea) + ") and " + nameOf(a, kids[k]) +
             " (zone " + sci(inner.flux.zoneArea) + ", layer " + sci(inner.flux.layerArea) +
             ") against the boundary rotation " + sci(p.boundaryRotation, 5) +
             ": a larger zone must hold a larger layer and a rotation farther from the boundary's");
  }
  return kids;
}

/// One barrier of the tree: a chain's outer or inner separatrix, a cantorus (between two chains about an island, or
/// the island's boundary cantorus), or the centre's loop (issue 50).
struct Barrier {
  MarkovTreeBarrier kind = MarkovTreeBarrier::OuterSeparatrix;
  int node = -1;              ///< the chain's atlas node (−1: a cantorus)
  int level = 0;
  long double flux = 0, layer = 0;
  std::string path;           ///< the state's name
};

/// The tree's states, built from the atlas's barriers about each island, outermost first: each chain's outer
/// separatrix, its inner one, the cantorus to the next chain, the next chain's outer one, …, the boundary cantorus.  The
/// state inside a barrier is its layer less the layers of the barriers just inside it (its children): the next one
/// about the same island, and — inside a chain's outer separatrix — the outermost barrier about the chain's own
/// islands, which lie between its two separatrices.  stateOf[node]: the state inside the node's outer separatrix
/// (where its islands' subtrees open), bandOf[node]: the innermost of its states (where chains lumped below it lie).
struct TreeStates {
  const Atlas& a;
  MarkovTree& tree;
  const MarkovTreeOptions& options;
  std::vector<int> stateOf, bandOf;

  const AtlasNode& node(int i) const { return a.nodes[static_cast<std::size_t>(i)]; }

  /// Whether node i's chain is a barrier of this tree (a flux, within the levels asked for).
  bool isBarrier(int i) const { return node(i).flux.found && node(i).level <= options.maxLevel; }

  int add(const Barrier& b, int container) {
    MarkovTreeState s;
    s.node = b.node;
    s.barrier = b.kind;
    s.path = b.path;
    s.level = b.level;
    s.container = container;
    s.flux = b.flux;
    s.layer = b.layer;
    s.area = b.layer;
    s.source = "layer of " + s.path + " (" + sci(s.layer) + ")";
    tree.states.push_back(s);
    return static_cast<int>(tree.states.size()) - 1;
  }

  /// The inner separatrix of chain c as a barrier, when the tree takes it and its layer is settled inside the outer's.
  std::optional<Barrier> innerOf(int c) const {
    const AtlasFlux& f = node(c).flux;
    if (!options.innerSeparatrices || !f.inner.found || !(f.inner.layerArea > 0)) return std::nullopt;
    if (!(f.inner.layerArea < f.layerArea))
      refuse("the inner separatrix of " + atlasPath(a, c) + " has a layer " + sci(f.inner.layerArea) +
             " not inside its outer one's " + sci(f.layerArea));
    return Barrier{MarkovTreeBarrier::InnerSeparatrix, c, node(c).level, f.inner.flux, f.inner.layerArea,
                   atlasPath(a, c) + " inner"};
  }

  /// The cantorus between the chains `outer` and `inner` about one island (or, `inner` = −1, the island's boundary
  /// cantorus inside `outer`), when the tree takes cantori and the atlas found it.
  std::optional<Barrier> cantorusBetween(int outer, int inner) const {
    if (!options.cantori) return std::nullopt;
    for (const AtlasCantorus& c : a.cantori)
      if (c.found && c.island == node(outer).parent && c.boundary == (inner < 0) && node(outer).aboutParent == c.outer &&
          (inner < 0 || node(inner).aboutParent == c.inner))
        return Barrier{MarkovTreeBarrier::Cantorus, -1, node(outer).level, c.flux, c.layerArea, atlasCantorusName(a, c)};
    return std::nullopt;
  }

  /// The barriers about island i (the centre, or a chain's islands) from outside in, opening onto `container`.
  void addIsland(int i, int container) {
    const std::vector<int> kids = barrierChildren(a, i, options.maxLevel);
    int outside = container;
    for (std::size_t k = 0; k < kids.size(); ++k) {
      const int c = kids[k];
      const int r = add({MarkovTreeBarrier::OuterSeparatrix, c, node(c).level, node(c).flux.flux,
                         node(c).flux.layerArea, atlasPath(a, c)},
                        outside);
      stateOf[static_cast<std::size_t>(c)] = r;
      addIsland(c, r);
      outside = r;
      if (auto in = innerOf(c)) outside = add(*in, outside);
      bandOf[static_cast<std::size_t>(c)] = outside;
      if (k + 1 < kids.size())
        if (auto cantorus = cantorusBetween(c, kids[k + 1])) outside = add(*cantorus, outside);
    }
    // The island's boundary cantorus, between its innermost chain and its boundary circle: a state inside that
    // chain's band (chains lumped there stay in the band).
    if (!kids.empty())
      if (auto cantorus = cantorusBetween(kids.back(), -1)) add(*cantorus, outside);
  }

  /// Each state's area: its layer less its children's layers (the barriers just inside it), checked positive.
  void settleAreas() {
    for (const MarkovTreeState& s : tree.states) {
      if (s.container < 0) continue;
      MarkovTreeState& out = tree.states[static_cast<std::size_t>(s.container)];
      out.area -= s.layer;
      out.source += " - layer of " + s.path + " (" + sci(s.layer) + ")";
    }
    for (std::size_t k = 0; k < tree.states.size(); ++k) {
      if (tree.states[k].container >= 0)
        tree.states[static_cast<std::size_t>(tree.states[k].container)].subtracted.push_back(static_cast<int>(k));
    }
    for (const MarkovTreeState& s : tree.states)
      if (!(s.area > 0))
        refuse("the state of " + s.path + " has area " + sci(s.area) + " = " + s.source +
               ": the layers inside its barrier exceed its own");
  }

  /// A node without a barrier: lumped, with its subtree, into the state whose region holds it.
  void lump(int n, int state, const std::string& reason) {
    tree.lumped.push_back({n, atlasPath(a, n), reason, state});
    for (int c : node(n).children)
      lump(c, state, "inside " + atlasPath(a, n) + ", which has no barrier in the tree");
  }

  /// Every node without a barrier whose parent has a state: into the band inside the innermost barrier chain about
  /// the parent that lies farther out than it; none: the parent's own state.
  void lumpNodesWithoutBarrier() {
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
      if (stateOf[i] < 0) continue;  // lumped nodes' children are handled by lump()
      const AtlasNode& p = a.nodes[i];
      const std::vector<int> kids = barrierChildren(a, static_cast<int>(i), options.maxLevel);
      for (int f : p.children) {
        if (isBarrier(f)) continue;
        int holder = stateOf[i];
        for (int c : kids)
          if (twistDistance(p, node(c)) > twistDistance(p, node(f))) holder = bandOf[static_cast<std::size_t>(c)];
        const AtlasNode& n = node(f);
        const std::string why = !n.flux.found
                                    ? (n.flux.failure.empty() ? std::string("no flux") : "no flux: " + n.flux.failure)
                                    : "level " + std::to_string(n.level) + " is below the tree's levels (at most " +
                                          std::to_string(options.maxLevel) + ")";
        lump(f, holder, why);
      }
    }
  }
};

/// The rates between the states: out of the centre to the sea, and both ways through every other state's barrier;
/// and the tree's number of levels.
void addRates(MarkovTree& tree) {
  for (std::size_t s = 0; s < tree.states.size(); ++s) {
    const MarkovTreeState& st = tree.states[s];
    tree.levels = std::max(tree.levels, st.level + 1);
    const int i = static_cast<int>(s);
    if (st.container < 0) {
      tree.rates.push_back({i, -1, st.flux / st.area, st.flux, st.area, st.node,
                            "flux of the centre's loop (" + sci(st.flux) + ") / area of centre (" + sci(st.area) + ")"});
      continue;
    }
    const MarkovTreeState& out = tree.states[static_cast<std::size_t>(st.container)];
    tree.rates.push_back({i, st.container, st.flux / st.area, st.flux, st.area, st.node,
                          "flux of " + st.path + " (" + sci(st.flux) + ") / area of " + st.path + " (" + sci(st.area) +
                              ")"});
    tree.rates.push_back({st.container, i, st.flux / out.area, st.flux, out.area, st.node,
                          "flux of " + st.path + " (" + sci(st.flux) + ") / area of " + out.path + " (" +
                              sci(out.area) + ")"});
  }
}

/// The rates out of each state sum to at most 1 per step.
void checkRatesOut(const MarkovTree& tree) {
  std::vector<long double> outOf(tree.states.size(), 0);  // one pass: an atlas of 20,000 chains has 40,000 rates
  for (const MarkovTreeRate& r : tree.rates) outOf[static_cast<std::size_t>(r.from)] += r.perStep;
  for (std::size_t s = 0; s < tree.states.size(); ++s) {
    const long double out = outOf[s];
    if (!(out <= 1))
      refuse("the rates out of the state of " + tree.states[s].path + " sum to " + sci(out) +
             " per step: its barriers' fluxes exceed its area");
  }
}

}  // namespace

MarkovTree markovTreeFromAtlas(const Atlas& a, const MarkovTreeOptions& options) {
  checkAtlasForTree(a);
  if (auto e = rangeError("levels", options.maxLevel, 0, kMaxAtlasDepth)) refuse(*e);
  const AtlasNode& centre = a.nodes[0];
  MarkovTree tree;
  tree.entryFlux = centre.flux.flux;
  tree.residence = centre.flux.layerArea / centre.flux.flux;
  // L² to 12 digits (1.69, not 1.6900000000000002 of 1.3 · 1.3 in binary): the bound b₂'s rule states.
  tree.boxArea =
      io::parseLongDoubleC(sci(static_cast<long double>(a.request.map.width()) * a.request.map.width(), 11)).value_or(0);
  TreeStates states{a, tree, options, std::vector<int>(a.nodes.size(), -1), std::vector<int>(a.nodes.size(), -1)};
  const int top = states.add({MarkovTreeBarrier::OuterSeparatrix, 0, 0, centre.flux.flux, centre.flux.layerArea,
                              atlasPath(a, 0)},
                             -1);
  states.stateOf[0] = states.bandOf[0] = top;
  states.addIsland(0, top);
  states.settleAreas();
  states.lumpNodesWithoutBarrier();
  addRates(tree);
  checkRatesOut(tree);
  return tree;
}

namespace {
using QMatrix = std::vector<std::vector<quad>>;

/// G = I − M in quad: off the diagonal −rate, on it the sum of the rates out (no cancellation against 1).
QMatrix generator(const MarkovTree& tree) {
  const std::size_t n = tree.states.size();
  QMatrix G(n, std::vector<quad>(n, 0));
  for (const MarkovTreeRate& r : tree.rates) {
    const quad rate = quadRate(r);
    G[static_cast<std::size_t>(r.from)][static_cast<std::size_t>(r.from)] += rate;
    if (r.to >= 0) G[static_cast<std::size_t>(r.from)][static_cast<std::size_t>(r.to)] -= rate;
  }
  return G;
}

}  // namespace

std::vector<std::vector<long double>> markovTreeMatrix(const MarkovTree& tree) {
  const QMatrix G = generator(tree);
  const std::size_t n = G.size();
  std::vector<std::vector<long double>> M(n, std::vector<long double>(n, 0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) M[i][j] = static_cast<long double>((i == j ? quad(1) : quad(0)) - G[i][j]);
  return M;
}

std::optional<std::string> markovTreeEntryError(double alpha, double b2, const MarkovTree* tree) {
  if (auto e = realIntervalError("alpha", alpha, 1, false, std::numeric_limits<double>::infinity(),
                                 "the run's mean segment length in steps: a segment lasts at least one"))
    return e;
  const double box = tree ? static_cast<double>(tree->boxArea) : std::numeric_limits<double>::infinity();
  if (auto e = realIntervalError("b2", b2, 0, true, box,
                                 tree ? "the stochastic area: a part of the box, whose area is L^2"
                                      : "the stochastic area"))
    return e;
  if (!tree || tree->states.empty()) return std::nullopt;
  const long double w = static_cast<long double>(alpha) * tree->entryFlux / static_cast<long double>(b2);
  const long double S1 = 1 - tree->entryFlux / tree->states[0].area;
  const long double P1 = w * S1;
  if (!(std::isfinite(P1) && P1 <= 1))  // realRangeError's words, the numbers in long double (w may pass 10^308)
    return "P_1 = w S(1) = " + sci(P1) + " must lie in [0, 1] (w = alpha flux / b2 = " + shortestDecimal(alpha) + " * " +
           sci(tree->entryFlux) + " / " + shortestDecimal(b2) + " = " + sci(w) +
           " visits per segment: a probability cannot exceed 1; alpha is too large or b2 too small for this atlas)";
  return std::nullopt;
}

long double markovTreeEntryWeight(const MarkovTree& tree, double alpha, double b2) {
  if (auto e = markovTreeEntryError(alpha, b2, &tree)) throw std::invalid_argument("markov tree: " + *e);
  return static_cast<long double>(alpha) * tree.entryFlux / static_cast<long double>(b2);
}

MarkovTreeCost markovTreeCost(std::size_t states, std::size_t times) {
  MarkovTreeCost c;
  c.states = states;
  c.times = times;
  const auto n = static_cast<double>(states), m = static_cast<double>(times);
  c.bytes = static_cast<double>(sizeof(long double)) * (n * n + n * m);
  c.operations = 10 * n * n * n + 2 * n * n * m;
  return c;
}

std::optional<std::string> markovTreeCostError(const MarkovTreeCost& c) {
  const std::string cost = "its survival holds " + sci(c.bytes / 1e9L, 2) + " GB (" + std::to_string(sizeof(long double)) +
                           " bytes x (n^2 + n m)) and takes about " + sci(c.operations, 1) +
                           " operations (10 n^3 + 2 n^2 m) for n = " + std::to_string(c.states) + " states and m = " +
                           std::to_string(c.times) + " times";
  if (auto e = rangeError("markov tree states", c.states, 1, limits::kMarkovTreeStates, cost)) return e;
  if (auto e = rangeError("markov tree survival values", c.states * c.times, 1,
                          static_cast<long long>(limits::kMarkovTreeValues), cost))
    return e;
  return std::nullopt;
}

namespace {

[[noreturn]] void stopped() { throw OperationStopped(); }

/// Householder reduction of the symmetric n×n matrix `v` to tridiagonal form, the transformations accumulated in `v`
/// (column k of the result stored as its k-th row): d the diagonal, e the subdiagonal (e[0] unused).  EISPACK's tred2
/// (Wilkinson & Reinsch, Handbook for Automatic Computation II, 1971), as JAMA writes it.  About 8/3 n³ operations;
/// the stop is checked once per row.
void tred2(std::size_t n, std::vector<long double>& v, std::vector<long double>& d, std::vector<long double>& e,
           const std::stop_token& stop) {
  // Column-major (Fortran's order, EISPACK's): the inner loops run down columns, contiguous here; the eigenvectors
  // end as columns, i.e. as rows of `v` read row-major, which is what tql2 wants.
  auto V = [&](std::size_t i, std::size_t j) -> long double& { return v[j * n + i]; };
  for (std::size_t j = 0; j < n; ++j) d[j] = V(n - 1, j);
  for (std::size_t i = n - 1; i > 0; --i) {
    if (stop.stop_requested()) stopped();
    long double scale = 0, h = 0;
    for (std::size_t k = 0; k < i; ++k) scale += std::fabs(d[k]);
    if (scale == 0) {
      e[i] = d[i - 1];
      for (std::size_t j = 0; j < i; ++j) {
        d[j] = V(i - 1, j);
        V(i, j) = 0;
        V(j, i) = 0;
      }
    } else {
      for (std::size_t k = 0; k < i; ++k) {
        d[k] /= scale;
        h += d[k] * d[k];
      }
      long double f = d[i - 1];
      long double g = std::sqrt(h);
      if (f > 0) g = -g;
      e[i] = scale * g;
      h -= f * g;
      d[i - 1] = f - g;
      for (std::size_t j = 0; j < i; ++j) e[j] = 0;
      for (std::size_t j = 0; j < i; ++j) {
        f = d[j];
        V(j, i) = f;
        g = e[j] + V(j, j) * f;
        for (std::size_t k = j + 1; k < i; ++k) {
          g += V(k, j) * d[k];
          e[k] += V(k, j) * f;
        }
        e[j] = g;
      }
      f = 0;
      for (std::size_t j = 0; j < i; ++j) {
        e[j] /= h;
        f += e[j] * d[j];
      }
      const long double hh = f / (h + h);
      for (std::size_t j = 0; j < i; ++j) e[j] -= hh * d[j];
      for (std::size_t j = 0; j < i; ++j) {
        f = d[j];
        g = e[j];
        for (std::size_t k = j; k < i; ++k) V(k, j) -= (f * e[k] + g * d[k]);
        d[j] = V(i - 1, j);
        V(i, j) = 0;
      }
    }
    d[i] = h;
  }
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (stop.stop_requested()) stopped();
    V(n - 1, i) = V(i, i);
    V(i, i) = 1;
    const long double h = d[i + 1];
    if (h != 0) {
      for (std::size_t k = 0; k <= i; ++k) d[k] = V(k, i + 1) / h;
      for (std::size_t j = 0; j <= i; ++j) {
        long double g = 0;
        for (std::size_t k = 0; k <= i; ++k) g += V(k, i + 1) * V(k, j);
        for (std::size_t k = 0; k <= i; ++k) V(k, j) -= g * d[k];
      }
    }
    for (std::size_t k = 0; k <= i; ++k) V(k, i + 1) = 0;
  }
  for (std::size_t j = 0; j < n; ++j) {
    d[j] = V(n - 1, j);
    V(n - 1, j) = 0;
  }
  V(n - 1, n - 1) = 1;
  e[0] = 0;
}

/// The eigenvalues d and eigenvectors of the tridiagonal matrix (d, e) by the QL method with implicit shifts, the
/// vectors accumulated into `w`, which holds tred2's transformations transposed (row k: the k-th column), so that row
/// k ends as the eigenvector of d[k].  EISPACK's tql2, as JAMA writes it.  Eigenvalues to about ε ‖G‖ (ε = 2⁻⁶³).
void tql2(std::size_t n, std::vector<long double>& w, std::vector<long double>& d, std::vector<long double>& e,
          const std::stop_token& stop) {
  for (std::size_t i = 1; i < n; ++i) e[i - 1] = e[i];
  e[n - 1] = 0;
  long double f = 0, tst1 = 0;
  const long double eps = std::numeric_limits<long double>::epsilon();
  for (std::size_t l = 0; l < n; ++l) {
    tst1 = std::max(tst1, std::fabs(d[l]) + std::fabs(e[l]));
    std::size_t m = l;
    while (m < n && !(std::fabs(e[m]) <= eps * tst1)) ++m;
    if (m == n) throw std::runtime_error("markov tree: the rate matrix's eigenvalues did not converge");
    if (m > l) {
      int iterations = 0;
      do {
        if (stop.stop_requested()) stopped();
        if (++iterations > 100) throw std::runtime_error("markov tree: the rate matrix's eigenvalues did not converge");
        long double g = d[l];
        long double p = (d[l + 1] - g) / (2 * e[l]);
        long double r = std::hypot(p, 1.0L);
        if (p < 0) r = -r;
        d[l] = e[l] / (p + r);
        d[l + 1] = e[l] * (p + r);
        const long double dl1 = d[l + 1];
        long double h = g - d[l];
        for (std::size_t i = l + 2; i < n; ++i) d[i] -= h;
        f += h;
        p = d[m];
        long double c = 1, c2 = 1, c3 = 1, s = 0, s2 = 0;
        const long double el1 = e[l + 1];
        for (std::size_t i = m; i-- > l;) {
          c3 = c2;
          c2 = c;
          s2 = s;
          g = c * e[i];
          h = c * p;
          r = std::hypot(p, e[i]);
          e[i + 1] = s * r;
          s = e[i] / r;
          c = p / r;
          p = c * d[i] - s * g;
          d[i + 1] = h + s * (c * g + s * d[i]);
          long double* a = &w[i * n];
          long double* b = &w[(i + 1) * n];
          for (std::size_t k = 0; k < n; ++k) {
            const long double bk = b[k];
            b[k] = s * a[k] + c * bk;
            a[k] = c * a[k] - s * bk;
          }
        }
        p = -s * s2 * c3 * el1 * e[l] / dl1;
        e[l] = s * p;
        d[l] = c * p;
      } while (std::fabs(e[l]) > eps * tst1);
    }
    d[l] += f;
    e[l] = 0;
  }
}

/// λᵗ for λ = 1 − μ, computed from μ (no cancellation against 1 for the slow modes, μ ~ 10⁻¹⁰).
long double powerOfOneMinus(long double mu, std::uint64_t t) {
  if (t == 0) return 1;
  if (mu == 1) return 0;
  const auto tt = static_cast<long double>(t);
  if (mu < 1) return std::exp(tt * std::log1p(-mu));
  const long double magnitude = std::exp(tt * std::log(mu - 1));  // λ < 0: its sign alternates
  return (t & 1U) != 0 ? -magnitude : magnitude;
}

/// G = I − M is similar to the symmetric B = D^½ G D^−½ (D = the states' areas: the chain is reversible with the
/// areas as its measure, A_i G_ij = A_j G_ji = −Φ), off the diagonal −Φ/√(A_i A_j), on it the rates out; n×n,
/// root[s] = √A_s.
std::vector<long double> symmetrizedGenerator(const MarkovTree& tree, const std::vector<long double>& root) {
  const std::size_t n = tree.states.size();
  std::vector<long double> v(n * n, 0);
  for (const MarkovTreeRate& r : tree.rates) {
    const auto from = static_cast<std::size_t>(r.from);
    v[from * n + from] += r.flux / r.area;
    if (r.to >= 0) {
      const auto to = static_cast<std::size_t>(r.to);
      v[from * n + to] = -r.flux / (root[from] * root[to]);
    }
  }
  return v;
}

/// Each eigenvalue again as its eigenvector's (row k of v) Rayleigh quotient written as the chain's Dirichlet form,
/// uᵀ B u = Σ_barriers Φ (x_i − x_j)² + Φ_centre x_top² with x = D^−½ u: a sum of positive terms, so a slow mode's μ
/// (10⁻⁹) is good to its own rounding, not to 2⁻⁶³ ‖G‖ (10⁻²¹: at t = 10⁷ a relative 2·10⁻¹⁴ in S), and the quotient
/// is stationary: the eigenvector's error enters squared.
void eigenvaluesFromDirichletForm(const MarkovTree& tree, const std::vector<long double>& v,
                                  const std::vector<long double>& root, std::vector<long double>& mu,
                                  std::stop_token stop) {
  const std::size_t n = tree.states.size();
  std::vector<long double> x(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (stop.stop_requested()) stopped();
    const long double* u = &v[k * n];
    long double norm = 0;
    for (std::size_t s = 0; s < n; ++s) {
      x[s] = u[s] / root[s];
      norm += u[s] * u[s];
    }
    long double form = 0;
    for (const MarkovTreeRate& r : tree.rates) {
      const auto from = static_cast<std::size_t>(r.from);
      if (r.to < 0) form += r.flux * x[from] * x[from];  // to the sea
      else if (r.to == tree.states[from].container) {       // each barrier once
        const long double d = x[from] - x[static_cast<std::size_t>(r.to)];
        form += r.flux * d * d;
      }
    }
    if (norm > 0) mu[k] = form / norm;
  }
}

/// Up to kMarkovTreeDirectSteps, e_top Mᵗ by t products with the sparse M in quad (its rates cross the states' tree
/// edges only): exact, O(t n), and where the modes' sum cancels most (S ≈ 1, Σ_k |c_k| ≫ its terms' differences).
/// Fills out's S, state and level at those t; returns which t it computed.
std::vector<bool> directSurvival(const MarkovTree& tree, const std::vector<std::uint64_t>& t, MarkovTreeSurvival& out,
                                 std::stop_token stop) {
  const std::size_t n = tree.states.size();
  std::vector<std::size_t> order(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return t[a] < t[b]; });
  std::vector<bool> direct(t.size(), false);
  std::vector<quad> state(n, 0), next(n, 0);
  if (n > 0) state[0] = 1;
  std::uint64_t done = 0;
  for (std::size_t i : order) {
    if (t[i] > kMarkovTreeDirectSteps) break;
    for (; done < t[i]; ++done) {
      if ((done & 63U) == 0 && stop.stop_requested()) stopped();
      next = state;
      for (const MarkovTreeRate& r : tree.rates) {
        const quad moved = state[static_cast<std::size_t>(r.from)] * quadRate(r);
        next[static_cast<std::size_t>(r.from)] -= moved;
        if (r.to >= 0) next[static_cast<std::size_t>(r.to)] += moved;
      }
      state.swap(next);
    }
    quad total = 0;
    for (std::size_t s = 0; s < n; ++s) {
      total += state[s];
      out.state[s][i] = static_cast<long double>(state[s]);
      out.level[static_cast<std::size_t>(tree.states[s].level)][i] += static_cast<long double>(state[s]);
    }
    out.S[i] = static_cast<long double>(total);
    direct[i] = true;
  }
  return direct;
}

/// The other t by the modes of B = U diag(μ) Uᵀ (U's columns the rows of v): e_top Mᵗ = A_top^−½ Σ_k U_top,k
/// (1 − μ_k)ᵗ U_s,k A_s^½, state by state, O(n²) per t.
void modalSurvival(const MarkovTree& tree, const std::vector<std::uint64_t>& t, const std::vector<long double>& v,
                   const std::vector<long double>& mu, const std::vector<long double>& root,
                   const std::vector<bool>& direct, MarkovTreeSurvival& out, std::stop_token stop) {
  const std::size_t n = tree.states.size();
  std::vector<long double> part(n);
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (direct[i]) continue;
    if (stop.stop_requested()) stopped();
    std::fill(part.begin(), part.end(), 0.0L);
    for (std::size_t k = 0; k < n; ++k) {
      const long double pk = v[k * n] * powerOfOneMinus(mu[k], t[i]);
      if (pk == 0) continue;
      const long double* row = &v[k * n];
      for (std::size_t s = 0; s < n; ++s) part[s] += row[s] * pk;
    }
    long double total = 0;
    for (std::size_t s = 0; s < n; ++s) {
      const long double x = part[s] * root[s] / root[0];
      total += x;
      out.state[s][i] = x;
      out.level[static_cast<std::size_t>(tree.states[s].level)][i] += x;
    }
    out.S[i] = total;
  }
}

/// Σ_{t≥0} S(t) = e_top (I − M)⁻¹ 1 = x_top of G x = 1, by elimination in quad from the leaves up: each state's
/// container comes before it (markovTreeFromAtlas), so eliminating the last state first creates no fill-in.  O(n).
long double meanVisit(const MarkovTree& tree) {
  const std::size_t n = tree.states.size();
  std::vector<quad> diagonal(n, 0), rhs(n, 1), toContainer(n, 0), fromContainer(n, 0);
  for (const MarkovTreeRate& r : tree.rates) {
    const quad rate = quadRate(r);
    const auto from = static_cast<std::size_t>(r.from);
    diagonal[from] += rate;
    if (r.to < 0) continue;
    const auto to = static_cast<std::size_t>(r.to);
    if (tree.states[from].container == r.to) toContainer[from] = -rate;  // G[from][container]
    else fromContainer[to] = -rate;                                       // G[container][to], to's container = from
  }
  for (std::size_t s = n; s-- > 1;) {
    const auto c = static_cast<std::size_t>(tree.states[s].container);
    const quad factor = fromContainer[s] / diagonal[s];
    diagonal[c] -= factor * toContainer[s];
    rhs[c] -= factor * rhs[s];
  }
  return n > 0 ? static_cast<long double>(rhs[0] / diagonal[0]) : 0.0L;
}
}  // namespace

MarkovTreeSurvival markovTreeSurvival(const MarkovTree& tree, const std::vector<std::uint64_t>& t, std::stop_token stop) {
  for (std::uint64_t v : t)
    if (v > kMarkovTreeMaxT) throw std::invalid_argument("markov tree: t = " + std::to_string(v) + " must be at most 2^62");
  const std::size_t n = tree.states.size();
  if (auto e = markovTreeCostError(markovTreeCost(n, t.size()))) throw std::invalid_argument("markov tree: " + *e);

  // With B = U diag(μ) Uᵀ (symmetrizedGenerator()): O(n³) once, O(n²) per t (the matrix is a tree's, but its powers
  // are dense: issue 54 measured the binary powering of M in quad at n³ log t).
  std::vector<long double> mu(n, 0), e(n, 0), root(n, 0);
  for (std::size_t s = 0; s < n; ++s) root[s] = std::sqrt(tree.states[s].area);
  std::vector<long double> v = symmetrizedGenerator(tree, root);
  tred2(n, v, mu, e, stop);  // B is symmetric: its row-major and column-major layouts are one
  tql2(n, v, mu, e, stop);
  eigenvaluesFromDirichletForm(tree, v, root, mu, stop);

  MarkovTreeSurvival out;
  out.t = t;
  out.S.assign(t.size(), 0);
  out.state.assign(n, std::vector<long double>(t.size(), 0));
  out.level.assign(static_cast<std::size_t>(tree.levels), std::vector<long double>(t.size(), 0));
  const std::vector<bool> direct = directSurvival(tree, t, out, stop);
  modalSurvival(tree, t, v, mu, root, direct, out, stop);
  out.meanVisit = meanVisit(tree);
  return out;
}

std::vector<std::uint64_t> markovTreeGrid(double tMax, int perDecade) {
  if (auto e = realRangeError("t-max", tMax, 1, 1e18, "steps")) throw std::invalid_argument("markov tree: " + *e);
  if (auto e = rangeError("points per decade", perDecade, 1, 1000)) throw std::invalid_argument("markov tree: " + *e);
  std::vector<std::uint64_t> t;
  for (int k = 0;; ++k) {
    const auto v = static_cast<std::uint64_t>(std::ceil(std::pow(10.0L, static_cast<long double>(k) / perDecade)));
    if (t.empty() || v > t.back()) t.push_back(v);
    if (static_cast<double>(v) >= tMax) break;
  }
  return t;
}

std::vector<MarkovTreeExponent> markovTreeExponents(const MarkovTreeSurvival& s, double lowest, double tEnd) {
  Series series;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    const auto v = static_cast<double>(s.S[i]);
    if (s.t[i] == 0 || !(v >= std::numeric_limits<double>::min())) continue;
    series.x.push_back(static_cast<double>(s.t[i]));
    series.value.push_back(v);
    series.error.push_back(0);
  }
  std::vector<MarkovTreeExponent> out;
  if (series.x.size() < 3) return out;
  const LogSeries logs(series);
  for (const LogWindow& w : runningExponentWindows(tEnd, lowest)) {
    const double g = fitLogSlope(logs, w.from, w.to);
    if (g == g) out.push_back({w.from, w.to, g});
  }
  return out;
}

MarkovTreeComparison compareMarkovTreeWithTail(const MarkovTree& tree, double alpha, double b2, const TailResult& tail,
                                               double from, double factor, std::stop_token stop) {
  if (!std::isfinite(from) || !std::isfinite(factor) || !(factor >= 1))
    throw std::invalid_argument("the comparison needs a finite first t and a finite factor >= 1");
  MarkovTreeComparison c;
  c.weight = markovTreeEntryWeight(tree, alpha, b2);
  c.factor = factor;
  std::vector<std::uint64_t> ts;
  for (const TailLevelResult& L : tail.levels) {
    if (!L.reliable || !(L.P > 0) || !(L.t >= from) || !(L.t <= static_cast<double>(kMarkovTreeMaxT))) continue;
    MarkovTreeLevelComparison m;
    m.t = L.t;
    m.measured = L.P;
    m.measuredError = L.PError;
    c.levels.push_back(m);
    ts.push_back(static_cast<std::uint64_t>(std::llround(L.t)));
  }
  if (ts.empty()) return c;
  const MarkovTreeSurvival s = markovTreeSurvival(tree, ts, stop);
  for (std::size_t i = 0; i < c.levels.size(); ++i) {
    MarkovTreeLevelComparison& m = c.levels[i];
    m.model = c.weight * s.S[i];
    m.ratio = m.model / static_cast<long double>(m.measured);
    for (std::size_t k = 0; k < s.level.size(); ++k)
      if (s.S[i] > 0 && (m.holdingLevel < 0 || s.level[k][i] > s.level[static_cast<std::size_t>(m.holdingLevel)][i]))
        m.holdingLevel = static_cast<int>(k);
    if (m.holdingLevel >= 0)
      m.holdingShare = static_cast<double>(s.level[static_cast<std::size_t>(m.holdingLevel)][i] / s.S[i]);
    if (m.ratio >= 1 / static_cast<long double>(factor) && m.ratio <= factor) c.reach = m.t;
  }
  return c;
}

std::vector<MarkovTreeAblationRow> markovTreeAblation(const Atlas& atlas, double alpha, double b2,
                                                     const TailResult& tail, std::stop_token stop) {
  std::vector<MarkovTreeAblationRow> rows;
  auto add = [&](std::string variant, MarkovTreeOptions options) {
    MarkovTreeAblationRow row;
    row.variant = std::move(variant);
    row.options = options;
    const MarkovTree tree = markovTreeFromAtlas(atlas, options);
    row.states = tree.states.size();
    const MarkovTreeComparison c = compareMarkovTreeWithTail(tree, alpha, b2, tail, kMarkovTreeCompareFrom,
                                                             kMarkovTreeAgreementFactor, stop);
    row.reach = c.reach;
    for (const MarkovTreeLevelComparison& m : c.levels) row.ratio.push_back(m.ratio);
    rows.push_back(std::move(row));
  };
  add("every barrier", {});
  add("no inner separatrices", {.innerSeparatrices = false});
  add("no cantori", {.cantori = false});
  add("outer separatrices only", {.innerSeparatrices = false, .cantori = false});
  int deepest = 0;
  for (const AtlasNode& n : atlas.nodes) deepest = std::max(deepest, n.level);
  for (int L = deepest - 1; L >= 0; --L) add("levels <= " + std::to_string(L), {.maxLevel = L});
  return rows;
}

}  // namespace archipelago
