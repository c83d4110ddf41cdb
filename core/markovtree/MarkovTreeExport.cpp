#include "core/markovtree/MarkovTreeExport.hpp"

#include "core/limits/Limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/io/Json.hpp"
#include "core/io/NumberText.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {
using json = nlohmann::ordered_json;

/// A long double as a JSON number: its double, or null when it does not fit (below the smallest normal double: the
/// CSV keeps it).
json number(long double v) {
  const auto d = static_cast<double>(v);
  if (!std::isfinite(d) || (v != 0 && std::fabs(d) < std::numeric_limits<double>::min())) return nullptr;
  return d;
}

std::string text(long double v) { return io::formatC("%.12Lg", v); }

}  // namespace

Provenance markovTreeProvenance(const MarkovTreeResult& r) {
  Provenance p = mapProvenance(r.map);
  p.add("Model", "Meiss-Ott Markov tree of the atlas (docs/markov-tree.md)");
  p.add("Atlas", r.request.atlasSource.empty() ? std::string("(given)") : r.request.atlasSource);
  p.add("Atlas depth", std::to_string(r.atlasDepth));
  p.add("t max", r.request.tMax);
  p.add("Points per decade", std::to_string(r.request.perDecade));
  if (r.weight) {
    p.add("alpha", r.request.alpha);
    p.add("b2", r.request.b2);
    p.add("Entry weight", *r.weight);
  }
  if (r.comparison) p.add("Tail", r.request.tailSource.empty() ? std::string("(given)") : r.request.tailSource);
  return p;
}

std::optional<std::string> validationError(const MarkovTreeRequest& r) {
  if (auto e = realRangeError("t-max", r.tMax, 1, 1e18, "steps")) return e;
  if (auto e = rangeError("points per decade", r.perDecade, 1, 1000)) return e;
  for (std::uint64_t t : r.at)
    if (t > kMarkovTreeMaxT) return "t = " + std::to_string(t) + " must be at most 2^62";
  if (r.at.size() > 100000) return "at most 100000 extra t";
  const bool a = r.alpha != 0, b = r.b2 != 0;
  if (a != b && !r.needsP)
    return std::string(a ? "b2" : "alpha") + " is missing or 0, and must be > 0: alpha and b2 go together: both " +
           "(P_t = alpha flux / b2 S(t)) or neither (S(t) only)";
  if (a || b || r.needsP)
    if (auto e = markovTreeEntryError(r.alpha, r.b2)) return e;
  if (auto e = realIntervalError("exponent from", r.exponentFrom, 1, false, std::numeric_limits<double>::infinity(),
                                 "the first window's start, steps"))
    return e;
  if (auto e = rangeError("levels", r.barriers.maxLevel, 0, kMaxAtlasDepth)) return e;
  return std::nullopt;
}

MarkovTreeResult computeMarkovTree(const Atlas& atlas, const MarkovTreeRequest& request, const TailState* tail,
                                   std::stop_token stop) {
  if (auto e = validationError(request)) throw std::invalid_argument("markov tree: " + *e);
  MarkovTreeResult r;
  r.request = request;
  r.map = atlas.request.map;
  r.atlasDepth = atlas.request.depth;
  r.atlasIslands = atlas.nodes.size();
  r.tree = markovTreeFromAtlas(atlas, request.barriers);
  if (request.alpha != 0) r.weight = markovTreeEntryWeight(r.tree, request.alpha, request.b2);  // the entry's rules
  if (tail) {  // checked before any work
    const MapParameters& m = tail->request.run.map;
    if (!(m == r.map))
      throw std::invalid_argument("the tail is of K = " + shortestDecimal(m.K) + " in the box (" +
                                  shortestDecimal(m.xmin) + ", " + shortestDecimal(m.xmax) + "), the atlas of K = " +
                                  shortestDecimal(r.map.K) + " in (" + shortestDecimal(r.map.xmin) + ", " +
                                  shortestDecimal(r.map.xmax) + "): compare a tail of the atlas's map");
    if (!r.weight) throw std::invalid_argument("a comparison with the tail needs alpha and b2 (the model's P_t)");
  }
  std::vector<std::uint64_t> t = markovTreeGrid(request.tMax, request.perDecade);
  t.insert(t.end(), request.at.begin(), request.at.end());
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  r.survival = markovTreeSurvival(r.tree, t, stop);  // refuses a cost past the limits before it starts
  r.exponents = markovTreeExponents(r.survival, request.exponentFrom, request.tMax);
  if (tail)
    r.comparison = compareMarkovTreeWithTail(r.tree, request.alpha, request.b2, tailResult(*tail),
                                             kMarkovTreeCompareFrom, kMarkovTreeAgreementFactor, stop);
  if (tail) r.ablation = markovTreeAblation(atlas, request.alpha, request.b2, tailResult(*tail), stop);
  return r;
}

MarkovTreeEntryOffer markovTreeEntryOffer(const MapParameters& atlasMap, const std::optional<MapParameters>& runMap,
                                          double runAlpha) {
  MarkovTreeEntryOffer o;
  const bool docs = atlasMap == MapParameters{};
  const std::string atlasK = "K = " + shortestDecimal(atlasMap.K);
  const std::string box = " in the box (" + shortestDecimal(atlasMap.xmin) + ", " + shortestDecimal(atlasMap.xmax) + ")";
  if (runMap && *runMap == atlasMap && std::isfinite(runAlpha) && runAlpha > 0) {
    o.alpha = runAlpha;
    o.alphaSource = "the run's mean segment length (" + atlasK + ", the atlas's map)";
  } else if (docs) {
    o.alpha = kMarkovTreeDocsAlpha;
    o.alphaSource = runMap ? "docs/markov-tree.md's, K = 0.1 (the run shown is of another map: K = " +
                                 shortestDecimal(runMap->K) + ")"
                           : "docs/markov-tree.md's, K = 0.1 (no run is shown)";
  } else {
    o.alphaSource = "none for the atlas's " + atlasK + box +
                    ": give the mean segment length alpha of a run of that map (archipelago-cli stats)";
  }
  if (docs) {
    o.b2 = kMarkovTreeDocsB2;
    o.b2Source = "docs/markov-tree.md's, K = 0.1 (stochastic-area on a 4096² grid)";
  } else {
    o.b2Source = "none for the atlas's " + atlasK + box +
                 ": give the stochastic area b2 of that box (archipelago-cli stochastic-area)";
  }
  return o;
}

Series markovTreeCurve(const MarkovTreeResult& r) {
  Series out;
  if (!r.weight) return out;
  const MarkovTreeSurvival& s = r.survival;
  for (std::size_t i = 0; i < s.t.size() && i < s.S.size(); ++i) {
    if (s.t[i] == 0) continue;
    const long double P = *r.weight * s.S[i];
    const auto d = static_cast<double>(P);
    if (!(std::isfinite(d) && d >= std::numeric_limits<double>::min())) continue;  // 0, or the exponential tail
    out.x.push_back(static_cast<double>(s.t[i]));
    out.value.push_back(d);
    out.error.push_back(0);
  }
  return out;
}

std::optional<std::vector<double>> markovTreeLevelShares(const MarkovTreeSurvival& s, std::uint64_t t) {
  const auto at = std::find(s.t.begin(), s.t.end(), t);
  if (at == s.t.end()) return std::nullopt;
  const auto i = static_cast<std::size_t>(at - s.t.begin());
  if (i >= s.S.size() || !(s.S[i] > 0)) return std::nullopt;
  std::vector<double> shares;
  for (const auto& level : s.level) shares.push_back(i < level.size() ? static_cast<double>(level[i] / s.S[i]) : 0.0);
  return shares;
}

namespace {

/// The tree's states, each with its barrier, layer, children and area's source.
json statesJson(const MarkovTree& tree) {
  json states = json::array();
  for (const MarkovTreeState& s : tree.states) {
    json sub = json::array();
    for (int d : s.subtracted) sub.push_back(d);
    states.push_back({{"node", s.node},
                      {"barrier", toString(s.barrier)},
                      {"path", s.path},
                      {"level", s.level},
                      {"container", s.container},
                      {"flux", static_cast<double>(s.flux)},
                      {"layer", static_cast<double>(s.layer)},
                      {"subtracted", sub},
                      {"area", static_cast<double>(s.area)},
                      {"source", s.source}});
  }
  return states;
}

/// Each row of `rows` (a level's or a state's part of S) as numbers.
json rowsJson(const std::vector<std::vector<long double>>& rows) {
  json out = json::array();
  for (const auto& row : rows) {
    json l = json::array();
    for (long double v : row) l.push_back(number(v));
    out.push_back(l);
  }
  return out;
}

/// The survival on its grid: t, S, P (null without w) and the parts of S per level and per state.
json survivalJson(const MarkovTreeResult& r) {
  const MarkovTreeSurvival& s = r.survival;
  json tj = json::array(), Sj = json::array(), Pj = json::array();
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    tj.push_back(s.t[i]);
    Sj.push_back(number(s.S[i]));
    Pj.push_back(r.weight ? number(*r.weight * s.S[i]) : json(nullptr));
  }
  return {{"t", tj}, {"S", Sj}, {"P", Pj}, {"levels", rowsJson(s.level)}, {"states", rowsJson(s.state)}};
}

/// The model against the tail: each level's model, ratio and holding level, and the reach.
json comparisonJson(const MarkovTreeComparison& c, const std::string& tail) {
  json lv = json::array();
  for (const MarkovTreeLevelComparison& m : c.levels)
    lv.push_back({{"t", m.t},
                  {"measured", m.measured},
                  {"measured_error", number(m.measuredError)},
                  {"model", number(m.model)},
                  {"log10_model", m.model > 0 ? json(static_cast<double>(std::log10(m.model))) : json(nullptr)},
                  {"ratio", number(m.ratio)},
                  {"log10_ratio", m.ratio > 0 ? json(static_cast<double>(std::log10(m.ratio))) : json(nullptr)},
                  {"holding_level", m.holdingLevel},
                  {"holding_share", m.holdingShare}});
  return {{"tail", tail}, {"factor", c.factor}, {"reach", c.reach}, {"levels", lv}};
}

/// The ablation (issue 50): each variant's states, reach and ratios.
json ablationJson(const std::vector<MarkovTreeAblationRow>& rows) {
  json ab = json::array();
  for (const MarkovTreeAblationRow& a : rows) {
    json ratio = json::array();
    for (long double x : a.ratio) ratio.push_back(number(x));
    ab.push_back({{"variant", a.variant}, {"states", a.states}, {"reach", a.reach}, {"ratio", ratio}});
  }
  return ab;
}

}  // namespace

std::string markovTreeJson(const MarkovTreeResult& r) {
  json j;
  j["format"] = "archipelago markov tree";
  j["format_version"] = kMarkovTreeFormatVersion;
  j["program"] = programDescription();
  json prov = json::object();
  for (const auto& [k, v] : markovTreeProvenance(r).fields) prov[k] = v;
  j["provenance"] = prov;
  j["map"] = {{"K", r.map.K}, {"xmin", r.map.xmin}, {"xmax", r.map.xmax}};
  j["request"] = {{"t_max", r.request.tMax},
                  {"per_decade", r.request.perDecade},
                  {"alpha", r.request.alpha},
                  {"b2", r.request.b2},
                  {"exponent_from", r.request.exponentFrom},
                  {"inner_separatrices", r.request.barriers.innerSeparatrices},
                  {"cantori", r.request.barriers.cantori},
                  {"levels", r.request.barriers.maxLevel}};
  j["atlas"] = {{"source", r.request.atlasSource}, {"depth", r.atlasDepth}, {"islands", r.atlasIslands}};
  if (r.weight)
    j["entry"] = {{"state", 0},
                  {"weight", static_cast<double>(*r.weight)},
                  {"rule", "w = alpha * flux of the centre's loop / b2: visits to the loop's zone per segment"}};
  else
    j["entry"] = {{"state", 0}, {"weight", nullptr}, {"rule", "no alpha and b2: S(t) per visit only"}};
  j["entry_flux"] = static_cast<double>(r.tree.entryFlux);
  j["residence"] = static_cast<double>(r.tree.residence);
  j["mean_visit"] = static_cast<double>(r.survival.meanVisit);
  j["states"] = statesJson(r.tree);
  json rates = json::array();
  for (const MarkovTreeRate& x : r.tree.rates)
    rates.push_back({{"from", x.from},
                     {"to", x.to},
                     {"per_step", static_cast<double>(x.perStep)},
                     {"flux_node", x.fluxNode},
                     {"source", x.source}});
  j["rates"] = rates;
  json lumped = json::array();
  for (const MarkovTreeLumped& l : r.tree.lumped)
    lumped.push_back({{"node", l.node}, {"path", l.path}, {"reason", l.reason}, {"state", l.state}});
  j["lumped"] = lumped;
  j["survival"] = survivalJson(r);
  json ex = json::array();
  for (const MarkovTreeExponent& e : r.exponents) ex.push_back({{"from", e.from}, {"to", e.to}, {"gamma", e.gamma}});
  j["exponents"] = ex;
  if (r.comparison) j["comparison"] = comparisonJson(*r.comparison, r.request.tailSource);
  if (!r.ablation.empty()) j["ablation"] = ablationJson(r.ablation);
  // Signed as run, tail and atlas files are (issue 54): any edit of the file is refused on load.
  j["checksum"] = io::jsonChecksum(nlohmann::json::parse(j.dump()));
  return j.dump(2) + "\n";
}

std::string markovTreeCsv(const MarkovTreeResult& r) {
  std::ostringstream out;
  for (const auto& [k, v] : markovTreeProvenance(r).fields) out << "# " << k << ": " << v << "\n";
  out << "t,S,P";
  for (std::size_t l = 0; l < r.survival.level.size(); ++l) out << ",level_" << l;
  for (const MarkovTreeState& s : r.tree.states) out << ",state " << s.path;
  out << "\n";
  const MarkovTreeSurvival& s = r.survival;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    out << s.t[i] << "," << text(s.S[i]) << "," << (r.weight ? text(*r.weight * s.S[i]) : std::string());
    for (const auto& level : s.level) out << "," << text(level[i]);
    for (const auto& st : s.state) out << "," << text(st[i]);
    out << "\n";
  }
  return out.str();
}

}  // namespace archipelago
