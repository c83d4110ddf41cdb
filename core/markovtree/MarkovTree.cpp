#include "core/markovtree/MarkovTree.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>

#include "core/stats/TrappingStatistics.hpp"

namespace archipelago {

namespace {

__extension__ typedef __float128 quad;

std::string sci(long double v, int digits = 4) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*Le", digits, v);
  return buffer;
}

bool positiveFinite(long double v) { return std::isfinite(v) && v > 0; }

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

MarkovTree markovTreeFromAtlas(const Atlas& a) {
  if (a.nodes.empty()) refuse("the atlas has no island");
  if (a.cancelled)
    refuse("the atlas was stopped before its end (" + a.stopReason +
           "): continue it (archipelago-cli atlas --resume) before building the tree");
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    if (!a.nodes[i].measured)
      refuse("island " + atlasPath(a, static_cast<int>(i)) +
             " is not measured (an atlas stopped early): continue it (archipelago-cli atlas --resume) first");
  const AtlasNode& centre = a.nodes[0];
  if (!centre.flux.found)
    refuse("the atlas has no flux through the centre's loop (" +
           (centre.flux.failure.empty() ? std::string("not computed") : centre.flux.failure) +
           "): the tree has no entry");
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const AtlasFlux& f = a.nodes[i].flux;
    if (!f.found) continue;
    const std::string who = atlasPath(a, static_cast<int>(i));
    if (!positiveFinite(f.flux)) refuse("the flux of " + who + " = " + sci(f.flux) + " must be finite and > 0");
    if (!positiveFinite(f.layerArea))
      refuse("the layer of " + who + " = " + sci(f.layerArea) + " must be finite and > 0");
    if (!positiveFinite(f.zoneArea)) refuse("the zone of " + who + " = " + sci(f.zoneArea) + " must be finite and > 0");
  }

  // The chains about island i that are barriers, outermost first (by zone area), checked against the twist.
  auto barrierChildren = [&](int i) {
    const AtlasNode& p = a.nodes[static_cast<std::size_t>(i)];
    std::vector<int> kids;
    for (int c : p.children)
      if (a.nodes[static_cast<std::size_t>(c)].flux.found) kids.push_back(c);
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
  };

  MarkovTree tree;
  tree.entryFlux = centre.flux.flux;
  tree.residence = centre.flux.layerArea / centre.flux.flux;
  std::vector<int> stateOf(a.nodes.size(), -1);

  // The state of barrier c, opening onto `container`, with its inner sibling (or −1).
  std::function<void(int, int, int)> addState = [&](int c, int container, int innerSibling) {
    const AtlasNode& n = a.nodes[static_cast<std::size_t>(c)];
    MarkovTreeState s;
    s.node = c;
    s.path = atlasPath(a, c);
    s.level = n.level;
    s.container = container;
    s.flux = n.flux.flux;
    s.layer = n.flux.layerArea;
    s.area = s.layer;
    s.source = "layer of " + s.path + " (" + sci(s.layer) + ")";
    const std::vector<int> kids = barrierChildren(c);
    if (innerSibling >= 0) s.subtracted.push_back(innerSibling);
    if (!kids.empty()) s.subtracted.push_back(kids.front());
    for (int d : s.subtracted) {
      const long double l = a.nodes[static_cast<std::size_t>(d)].flux.layerArea;
      s.area -= l;
      s.source += " - layer of " + atlasPath(a, d) + " (" + sci(l) + ")";
    }
    if (!(s.area > 0))
      refuse("the state of " + s.path + " has area " + sci(s.area) + " = " + s.source +
             ": the layers inside its barrier exceed its own");
    const int index = static_cast<int>(tree.states.size());
    stateOf[static_cast<std::size_t>(c)] = index;
    tree.states.push_back(s);
    for (std::size_t k = 0; k < kids.size(); ++k)
      addState(kids[k], k == 0 ? index : stateOf[static_cast<std::size_t>(kids[k - 1])],
               k + 1 < kids.size() ? kids[k + 1] : -1);
  };
  addState(0, -1, -1);

  // Nodes without a barrier: lumped, with their subtree, into the state whose region holds them.
  std::function<void(int, int, const std::string&)> lump = [&](int node, int state, const std::string& reason) {
    tree.lumped.push_back({node, atlasPath(a, node), reason, state});
    for (int c : a.nodes[static_cast<std::size_t>(node)].children)
      lump(c, state, "inside " + atlasPath(a, node) + ", which has no barrier in the tree");
  };
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    if (stateOf[i] < 0) continue;  // lumped nodes' children are handled by lump()
    const AtlasNode& p = a.nodes[i];
    const std::vector<int> kids = barrierChildren(static_cast<int>(i));
    for (int f : p.children) {
      const AtlasNode& n = a.nodes[static_cast<std::size_t>(f)];
      if (n.flux.found) continue;
      // The innermost barrier about p that lies farther out than f holds it; none: p's own state.
      int holder = stateOf[i];
      for (int c : kids)
        if (twistDistance(p, a.nodes[static_cast<std::size_t>(c)]) > twistDistance(p, n))
          holder = stateOf[static_cast<std::size_t>(c)];
      lump(f, holder, n.flux.failure.empty() ? std::string("no flux") : "no flux: " + n.flux.failure);
    }
  }

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
  for (std::size_t s = 0; s < tree.states.size(); ++s) {
    long double out = 0;
    for (const MarkovTreeRate& r : tree.rates)
      if (r.from == static_cast<int>(s)) out += r.perStep;
    if (!(out <= 1))
      refuse("the rates out of the state of " + tree.states[s].path + " sum to " + sci(out) +
             " per step: its barriers' fluxes exceed its area");
  }
  return tree;
}

namespace {
using QMatrix = std::vector<std::vector<quad>>;

/// G = I − M in quad: off the diagonal −rate, on it the sum of the rates out (no cancellation against 1).
QMatrix generator(const MarkovTree& tree) {
  const std::size_t n = tree.states.size();
  QMatrix G(n, std::vector<quad>(n, 0));
  for (const MarkovTreeRate& r : tree.rates) {
    const quad rate = static_cast<quad>(r.flux) / static_cast<quad>(r.area);
    G[static_cast<std::size_t>(r.from)][static_cast<std::size_t>(r.from)] += rate;
    if (r.to >= 0) G[static_cast<std::size_t>(r.from)][static_cast<std::size_t>(r.to)] -= rate;
  }
  return G;
}

QMatrix multiply(const QMatrix& x, const QMatrix& y) {
  const std::size_t n = x.size();
  QMatrix z(n, std::vector<quad>(n, 0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < n; ++k) {
      if (x[i][k] == 0) continue;
      for (std::size_t j = 0; j < n; ++j) z[i][j] += x[i][k] * y[k][j];
    }
  return z;
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

long double markovTreeEntryWeight(const MarkovTree& tree, double alpha, double b2) {
  if (!(std::isfinite(alpha) && alpha > 0))
    throw std::invalid_argument("markov tree: alpha (the run's mean segment length, steps) must be finite and > 0");
  if (!(std::isfinite(b2) && b2 > 0))
    throw std::invalid_argument("markov tree: b2 (the stochastic area) must be finite and > 0");
  return static_cast<long double>(alpha) * tree.entryFlux / static_cast<long double>(b2);
}

MarkovTreeSurvival markovTreeSurvival(const MarkovTree& tree, const std::vector<std::uint64_t>& t) {
  for (std::uint64_t v : t)
    if (v > kMarkovTreeMaxT) throw std::invalid_argument("markov tree: t = " + std::to_string(v) + " must be at most 2^62");
  const std::size_t n = tree.states.size();
  const QMatrix G = generator(tree);
  QMatrix M(n, std::vector<quad>(n, 0));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) M[i][j] = (i == j ? quad(1) : quad(0)) - G[i][j];
  std::uint64_t largest = 0;
  for (std::uint64_t v : t) largest = std::max(largest, v);
  std::vector<QMatrix> powers{M};  // M^(2^k)
  while ((largest >> powers.size()) != 0) powers.push_back(multiply(powers.back(), powers.back()));

  MarkovTreeSurvival out;
  out.t = t;
  out.S.assign(t.size(), 0);
  out.state.assign(n, std::vector<long double>(t.size(), 0));
  out.level.assign(static_cast<std::size_t>(tree.levels), std::vector<long double>(t.size(), 0));
  for (std::size_t i = 0; i < t.size(); ++i) {
    std::vector<quad> v(n, 0);
    v[0] = 1;
    for (std::size_t k = 0; k < powers.size(); ++k) {
      if (((t[i] >> k) & 1U) == 0) continue;
      std::vector<quad> w(n, 0);
      for (std::size_t a = 0; a < n; ++a)
        if (v[a] != 0)
          for (std::size_t b = 0; b < n; ++b) w[b] += v[a] * powers[k][a][b];
      v = w;
    }
    quad total = 0;
    for (std::size_t s = 0; s < n; ++s) {
      total += v[s];
      out.state[s][i] = static_cast<long double>(v[s]);
      out.level[static_cast<std::size_t>(tree.states[s].level)][i] += static_cast<long double>(v[s]);
    }
    out.S[i] = static_cast<long double>(total);
  }

  // Σ_{t≥0} S(t) = e_top (I − M)⁻¹ 1 = x₀ of G x = 1 (G = I − M), by elimination with partial pivoting in quad.
  QMatrix A = G;
  std::vector<quad> b(n, 1);
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t pivot = c;
    auto magnitude = [](quad x) { return x < 0 ? -x : x; };
    for (std::size_t r = c + 1; r < n; ++r)
      if (magnitude(A[r][c]) > magnitude(A[pivot][c])) pivot = r;
    std::swap(A[c], A[pivot]);
    std::swap(b[c], b[pivot]);
    for (std::size_t r = c + 1; r < n; ++r) {
      const quad f = A[r][c] / A[c][c];
      if (f == 0) continue;
      for (std::size_t k = c; k < n; ++k) A[r][k] -= f * A[c][k];
      b[r] -= f * b[c];
    }
  }
  std::vector<quad> x(n, 0);
  for (std::size_t c = n; c-- > 0;) {
    quad s = b[c];
    for (std::size_t k = c + 1; k < n; ++k) s -= A[c][k] * x[k];
    x[c] = s / A[c][c];
  }
  out.meanVisit = static_cast<long double>(x[0]);
  return out;
}

std::vector<std::uint64_t> markovTreeGrid(double tMax, int perDecade) {
  if (!(std::isfinite(tMax) && tMax >= 1 && tMax <= 1e18))
    throw std::invalid_argument("markov tree: t-max must be a number of steps 1 ... 1e18");
  if (perDecade < 1 || perDecade > 1000)
    throw std::invalid_argument("markov tree: points per decade must be 1 ... 1000");
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
                                               double from, double factor) {
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
  const MarkovTreeSurvival s = markovTreeSurvival(tree, ts);
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

}  // namespace archipelago
