/// \file MarkovTreeRead.cpp
/// \brief markovTreeFromJson: a Markov-tree file read back with every invariant of a computed tree checked (issue 54).

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "core/io/Json.hpp"
#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

using rjson = nlohmann::json;
using io::JsonField;

constexpr std::string_view kPrefix = "markov tree file: ";
constexpr std::uint64_t kIntMax = std::numeric_limits<int>::max();

/// The format, its version and, from version 2, the checksum over the rest (taken out of `j`), as the atlas's reader.
void checkSignature(rjson& j, const JsonField& root) {
  const JsonField format = root["format"];
  if (!format.value().is_string() || format.value().get<std::string>() != "archipelago markov tree")
    format.refuseValue("is not a Markov tree (\"archipelago markov tree\")");
  io::checkSignature(j, root, kMarkovTreeFormatVersion, "Markov tree", "the file",
                     [&root](const std::string& why) { root.refuseDocument(why); });
}

/// A real > 0.
double positive(const JsonField& f) {
  const double v = f.real();
  if (!(v > 0)) f.refuseValue("must be > 0");
  return v;
}

/// A probability: a real in [0, 1], or null (written for a value below the smallest double) as 0.
double probability(const JsonField& f) {
  const double v = f.realOr(0);
  if (auto e = realRangeError(f.name(), v, 0, 1, "a probability")) f.refuseDocument(*e);
  return v;
}

void readRequest(const JsonField& root, MarkovTreeResult& r) {
  const JsonField map = root["map"];
  map.keys({"K", "xmin", "xmax"});
  r.map = {map["K"].real(), map["xmin"].real(), map["xmax"].real()};
  const JsonField q = root["request"];
  q.keys({"t_max", "per_decade", "alpha", "b2", "exponent_from"}, {"inner_separatrices", "cantori", "levels"});
  r.request.tMax = q["t_max"].real();
  r.request.perDecade = static_cast<int>(q["per_decade"].whole(kIntMax));
  r.request.alpha = q["alpha"].real();
  r.request.b2 = q["b2"].real();
  r.request.exponentFrom = q["exponent_from"].real();
  // Which barriers the tree took (issue 50; absent before: outer separatrices only were the tree then).
  if (const auto in = q.find("inner_separatrices")) r.request.barriers.innerSeparatrices = in->boolean();
  if (const auto c = q.find("cantori")) r.request.barriers.cantori = c->boolean();
  if (const auto l = q.find("levels")) r.request.barriers.maxLevel = static_cast<int>(l->whole(kIntMax));
  if (auto e = validationError(r.request)) q.refuseDocument("request: " + *e);
  const JsonField atlas = root["atlas"];
  atlas.keys({"source", "depth", "islands"});
  r.request.atlasSource = atlas["source"].string();
  r.atlasDepth = static_cast<int>(atlas["depth"].whole(kIntMax));
  r.atlasIslands = atlas["islands"].whole(kIntMax, 1);
  if (const auto c = root.find("comparison")) r.request.tailSource = c->keys({"tail", "factor", "reach", "levels"})["tail"].string();
}

/// The state's barrier (issue 50): "outer separatrix", "inner separatrix" or "cantorus"; absent in a file from
/// before, whose states were all inside outer separatrices.
MarkovTreeBarrier barrierOf(const JsonField& state) {
  const auto b = state.find("barrier");
  if (!b) return MarkovTreeBarrier::OuterSeparatrix;
  const std::string text = b->string();
  for (MarkovTreeBarrier k : {MarkovTreeBarrier::OuterSeparatrix, MarkovTreeBarrier::InnerSeparatrix,
                              MarkovTreeBarrier::Cantorus})
    if (text == toString(k)) return k;
  b->refuseValue("must be \"outer separatrix\", \"inner separatrix\" or \"cantorus\"");
}

void readStates(const JsonField& root, MarkovTree& tree) {
  const JsonField states = root["states"];
  const std::size_t n = states.array(kIntMax);
  if (n == 0) states.refuse("must hold the top state at least");
  for (std::size_t i = 0; i < n; ++i) {
    const JsonField o = states[i];
    o.keys({"node", "path", "level", "container", "flux", "layer", "subtracted", "area", "source"}, {"barrier"});
    MarkovTreeState s;
    s.barrier = barrierOf(o);
    s.node = static_cast<int>(o["node"].integer(s.barrier == MarkovTreeBarrier::Cantorus ? -1 : 0, kIntMax));
    if ((s.node < 0) != (s.barrier == MarkovTreeBarrier::Cantorus))
      o["node"].refuseValue("must be -1 exactly for a cantorus (it is no atlas node's)");
    s.path = o["path"].string();
    s.level = static_cast<int>(o["level"].whole(kIntMax));
    s.container = static_cast<int>(o["container"].integer(i == 0 ? -1 : 0, static_cast<std::int64_t>(i) - 1));
    if (i == 0 && s.container != -1) o["container"].refuseValue("must be -1 (the top opens onto the sea)");
    s.flux = positive(o["flux"]);
    s.layer = positive(o["layer"]);
    s.area = positive(o["area"]);
    if (s.area > s.layer) o["area"].refuseValue("must be at most its layer, " + shortestDecimal(static_cast<double>(s.layer)));
    const JsonField sub = o["subtracted"];
    for (std::size_t k = 0, size = sub.array(kIntMax); k < size; ++k) s.subtracted.push_back(static_cast<int>(sub[k].whole(kIntMax)));
    s.source = o["source"].string();
    tree.levels = std::max(tree.levels, s.level + 1);
    tree.states.push_back(std::move(s));
  }
  tree.entryFlux = positive(root["entry_flux"]);
  tree.residence = positive(root["residence"]);
}

/// Each rate between a state and its container, a probability per step.
void readRates(const JsonField& root, MarkovTree& tree) {
  const JsonField rates = root["rates"];
  const auto n = static_cast<std::int64_t>(tree.states.size());
  for (std::size_t k = 0, size = rates.array(2 * tree.states.size()); k < size; ++k) {
    const JsonField o = rates[k];
    o.keys({"from", "to", "per_step", "flux_node", "source"});
    MarkovTreeRate x;
    x.from = static_cast<int>(o["from"].integer(0, n - 1));
    x.to = static_cast<int>(o["to"].integer(-1, n - 1));
    const auto container = [&](int s) { return tree.states[static_cast<std::size_t>(s)].container; };
    if (container(x.from) != x.to && (x.to < 0 || container(x.to) != x.from))
      o["to"].refuseValue("must be the container of state " + std::to_string(x.from) + " or one of its children");
    x.perStep = o["per_step"].real();
    if (auto e = realIntervalError(o["per_step"].name(), static_cast<double>(x.perStep), 0, true, 1, "a probability per step"))
      o.refuseDocument(*e);
    x.fluxNode = static_cast<int>(o["flux_node"].whole(kIntMax));
    x.source = o["source"].string();
    tree.rates.push_back(std::move(x));
  }
  const JsonField lumped = root["lumped"];
  for (std::size_t k = 0, size = lumped.array(); k < size; ++k) {
    const JsonField o = lumped[k];
    o.keys({"node", "path", "reason", "state"});
    tree.lumped.push_back({static_cast<int>(o["node"].whole(kIntMax)), o["path"].string(), o["reason"].string(),
                           static_cast<int>(o["state"].integer(0, n - 1))});
  }
}

/// w = α Φ_centre / b₂ when α and b₂ are given (to the double written), null otherwise.
void readEntry(const JsonField& root, MarkovTreeResult& r) {
  const JsonField e = root["entry"];
  e.keys({"state", "weight", "rule"});
  (void)e["state"].whole(0, 0);
  (void)e["rule"].string();
  if (r.request.alpha == 0) {
    if (!e["weight"].isNull()) e["weight"].refuseValue("must be null without alpha and b2");
    return;
  }
  const long double w = positive(e["weight"]);
  const long double expected = static_cast<long double>(r.request.alpha) * r.tree.entryFlux / r.request.b2;
  if (std::fabs(w - expected) > 1e-12L * expected)
    e["weight"].refuseValue("must be alpha * entry_flux / b2 = " + shortestDecimal(static_cast<double>(expected)));
  r.weight = w;
}

/// One row per t of a part of S: as many as t, each a probability.
std::vector<long double> column(const JsonField& f, std::size_t rows) {
  f.tuple(rows, "one value per t");
  std::vector<long double> v;
  for (std::size_t i = 0; i < rows; ++i) v.push_back(probability(f[i]));
  return v;
}

void readSurvival(const JsonField& root, MarkovTreeResult& r) {
  const JsonField s = root["survival"];
  s.keys({"t", "S", "P", "levels", "states"});
  const JsonField t = s["t"];
  const std::size_t rows = t.array(kIntMax);
  for (std::size_t i = 0; i < rows; ++i) {
    r.survival.t.push_back(t[i].whole(kMarkovTreeMaxT));
    if (i > 0 && r.survival.t[i] <= r.survival.t[i - 1]) t[i].refuseValue("must be above the t before it");
  }
  r.survival.S = column(s["S"], rows);
  for (std::size_t i = 1; i < rows; ++i)
    if (r.survival.S[i] > r.survival.S[i - 1])
      s["S"][i].refuseValue("must be at most S before it, " + shortestDecimal(static_cast<double>(r.survival.S[i - 1])) +
                            " (S(t) does not increase)");
  const JsonField P = s["P"];
  P.tuple(rows, "one value per t");
  for (std::size_t i = 0; i < rows; ++i)
    if (r.weight) (void)probability(P[i]);
    else if (!P[i].isNull()) P[i].refuseValue("must be null without alpha and b2");
  const JsonField levels = s["levels"], states = s["states"];
  levels.tuple(static_cast<std::size_t>(r.tree.levels), "one row per level");
  for (std::size_t l = 0; l < static_cast<std::size_t>(r.tree.levels); ++l) r.survival.level.push_back(column(levels[l], rows));
  states.tuple(r.tree.states.size(), "one row per state");
  for (std::size_t k = 0; k < r.tree.states.size(); ++k) r.survival.state.push_back(column(states[k], rows));
  r.survival.meanVisit = positive(root["mean_visit"]);
}

void readExponents(const JsonField& root, MarkovTreeResult& r) {
  const JsonField ex = root["exponents"];
  for (std::size_t k = 0, size = ex.array(); k < size; ++k) {
    const JsonField o = ex[k];
    o.keys({"from", "to", "gamma"});
    r.exponents.push_back({o["from"].real(), o["to"].real(), o["gamma"].real()});
  }
}

/// The ablation's rows (issue 50): each variant's name, states, reach (≥ 0) and ratios (≥ 0, null below a double).
void readAblation(const JsonField& list, MarkovTreeResult& r) {
  for (std::size_t k = 0, size = list.array(); k < size; ++k) {
    const JsonField o = list[k];
    o.keys({"variant", "states", "reach", "ratio"});
    MarkovTreeAblationRow row;
    row.variant = o["variant"].string();
    row.states = o["states"].whole(kIntMax, 1);
    row.reach = o["reach"].nonNegative();
    const JsonField ratio = o["ratio"];
    for (std::size_t i = 0, n = ratio.array(); i < n; ++i) {  // null: below the smallest double (written so)
      const double x = ratio[i].realOr(0);
      if (!(x >= 0)) ratio[i].refuseValue("is negative: a ratio of two probabilities is not");
      row.ratio.push_back(x);
    }
    r.ablation.push_back(std::move(row));
  }
}

MarkovTreeResult markovTreeFrom(rjson j) {
  const JsonField root(j, "the Markov tree", kPrefix);
  root.keys({"format", "program", "provenance", "map", "request", "atlas", "entry", "entry_flux", "residence",
             "mean_visit", "states", "rates", "lumped", "survival", "exponents"},
            {"format_version", "checksum", "comparison", "ablation"});
  checkSignature(j, root);
  (void)root["program"].string();
  (void)root["provenance"].object();
  MarkovTreeResult r;
  readRequest(root, r);
  readStates(root, r.tree);
  readRates(root, r.tree);
  readEntry(root, r);
  readSurvival(root, r);
  readExponents(root, r);
  if (const auto a = root.find("ablation")) readAblation(*a, r);
  return r;
}

}  // namespace

MarkovTreeResult markovTreeFromJson(const std::string& text) {
  try {
    return markovTreeFrom(io::parseJson(text));  // a copy: its checksum is taken out to verify the rest
  } catch (const io::BadFile&) {
    throw;
  } catch (const std::exception& e) {  // nlohmann's own, should one escape
    throw io::BadFile(std::string(kPrefix) + e.what());
  }
}

}  // namespace archipelago
