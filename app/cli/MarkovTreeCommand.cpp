#include "MarkovTreeCommand.hpp"

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/atlas/AtlasExport.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/tail/TailFile.hpp"

namespace archipelago::cli {

namespace {
struct MarkovTreeOptions {
  std::string atlas;
  std::string tail;
  std::string at;
  std::string csv;
  std::string json;
  std::string without;
  MarkovTreeRequest request;
  bool quiet = false;
};

/// "1008,2160,…": each item a whole number read by the CLI's one parser (its range is core's rule).
std::vector<std::uint64_t> parseTimes(const std::string& text) {
  std::vector<std::uint64_t> t;
  std::size_t begin = 0;
  while (!text.empty()) {
    const std::size_t comma = text.find(',', begin);
    const std::string item = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    const auto v = toNumber<std::uint64_t>(item);
    if (!v) throw std::invalid_argument("--at: '" + io::shortText(item) + "' is not a whole number of steps");
    t.push_back(*v);
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return t;
}

/// Each variant's reach and its ratio at each compared level (issue 50's ablation).
void printAblation(const MarkovTreeResult& r) {
  if (r.ablation.empty() || !r.comparison) return;
  std::printf("# ablation: the reach with and without each kind of barrier (model / measured at each level)\n");
  std::printf("# %-26s %6s %12s", "variant", "states", "reach");
  for (const MarkovTreeLevelComparison& m : r.comparison->levels) std::printf(" %9.3g", m.t);
  std::printf("\n");
  for (const MarkovTreeAblationRow& a : r.ablation) {
    std::printf("  %-26s %6zu %12s", a.variant.c_str(), a.states, a.reach > 0 ? shortestDecimal(a.reach).c_str() : "-");
    for (long double x : a.ratio) std::printf(" %9.3Lg", x);
    std::printf("\n");
  }
}

void printTree(const MarkovTreeResult& r) {
  const MarkovTree& t = r.tree;
  std::printf("# Markov tree of %s (K = %s, depth %d, %zu islands): %zu states, Meiss & Ott (1986)\n",
              r.request.atlasSource.c_str(), shortestDecimal(r.map.K).c_str(), r.atlasDepth, r.atlasIslands,
              t.states.size());
  std::printf("# %-3s %-18s %-16s %5s %9s %13s %13s %12s  %s\n", "st", "state", "barrier", "level", "container",
              "flux", "area", "area/flux", "area source");
  for (std::size_t i = 0; i < t.states.size(); ++i) {
    const MarkovTreeState& s = t.states[i];
    std::printf("  %-3zu %-18s %-16s %5d %9d %13.6Le %13.6Le %12.6Lg  %s\n", i, s.path.c_str(), toString(s.barrier),
                s.level, s.container, s.flux, s.area, s.area / s.flux, s.source.c_str());
  }
  for (const MarkovTreeLumped& l : t.lumped)
    std::printf("# lumped into state %d: %s (%s)\n", l.state, l.path.c_str(), l.reason.c_str());
  std::printf("# mean visit: %.12Lg steps (Kac: layer / flux of the loop = %.12Lg)\n", r.survival.meanVisit,
              t.residence);
  if (r.weight)
    std::printf("# entry: w = alpha * flux / b2 = %s * %.10Le / %s = %.10Lg visits per segment; P_t = w S(t)\n",
                shortestDecimal(r.request.alpha).c_str(), t.entryFlux, shortestDecimal(r.request.b2).c_str(), *r.weight);
  std::printf("# %12s %14s %14s", "t", "S(t)", "P_t");
  for (std::size_t l = 0; l < r.survival.level.size(); ++l) std::printf("   level %zu", l);
  std::printf("\n");
  const MarkovTreeSurvival& s = r.survival;
  for (std::size_t i = 0; i < s.t.size(); ++i) {
    bool decade = s.t[i] == 1;
    for (std::uint64_t p = 10; p <= s.t[i] && !decade; p *= 10) decade = s.t[i] == p;
    if (!decade && i + 1 != s.t.size()) continue;
    std::printf("  %12llu %14.6Le", static_cast<unsigned long long>(s.t[i]), s.S[i]);
    if (r.weight) std::printf(" %14.6Le", *r.weight * s.S[i]);
    else std::printf(" %14s", "-");
    for (const auto& level : s.level) std::printf(" %9.3Lf", s.S[i] > 0 ? level[i] / s.S[i] : 0.0L);
    std::printf("\n");
  }
  for (const MarkovTreeExponent& e : r.exponents)
    std::printf("# gamma over [%g, %g]: %.4f\n", e.from, e.to, e.gamma);
  if (!r.comparison) return;
  const MarkovTreeComparison& c = *r.comparison;
  std::printf("# against the tail %s: model / measured within a factor %g last at t = %s\n",
              r.request.tailSource.c_str(), c.factor, c.reach > 0 ? shortestDecimal(c.reach).c_str() : "(none)");
  std::printf("# %12s %12s %10s %14s %12s  %s\n", "t", "measured", "error", "model", "ratio", "level holding (share)");
  for (const MarkovTreeLevelComparison& m : c.levels) {
    std::printf("  %12.0f %12.4e %10.2e %14.4Le %12.3Lg", m.t, m.measured, m.measuredError, m.model, m.ratio);
    if (m.holdingLevel >= 0) std::printf("  %d (%.0f %%)", m.holdingLevel, 100 * m.holdingShare);
    std::printf("\n");
  }
  printAblation(r);
}

/// "inner,cantori": the barriers --without leaves out.
void parseWithout(const std::string& text, archipelago::MarkovTreeOptions& barriers) {
  std::size_t begin = 0;
  while (!text.empty()) {
    const std::size_t comma = text.find(',', begin);
    const std::string item = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    if (item == "inner") barriers.innerSeparatrices = false;
    else if (item == "cantori") barriers.cantori = false;
    else throw std::invalid_argument("--without: '" + io::shortText(item) + "' is not inner or cantori");
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
}

int runMarkovTree(MarkovTreeOptions o) {
  o.request.at = parseTimes(o.at);
  parseWithout(o.without, o.request.barriers);
  o.request.atlasSource = o.atlas;
  if (auto e = validationError(o.request)) throw std::invalid_argument(*e);
  o.request.tailSource = o.tail;
  io::checkCommandFiles({{"--atlas", o.atlas, io::FileUse::Input},
                         {"--tail", o.tail, io::FileUse::Input},
                         {"--csv", o.csv, io::FileUse::Output},
                         {"--json", o.json, io::FileUse::Output}});
  Atlas atlas;
  try {
    atlas = atlasFromJson(io::readRegularFile(o.atlas, kMaxAtlasFileBytes));
  } catch (const std::exception& e) {
    throw std::runtime_error("--atlas " + o.atlas + ": " + e.what());
  }
  std::optional<TailState> tail;
  if (!o.tail.empty()) {
    try {
      tail = loadTailFile(o.tail);
    } catch (const std::exception& e) {
      throw std::runtime_error("--tail " + o.tail + ": " + e.what());
    }
  }
  MarkovTreeResult r;
  try {
    r = computeMarkovTree(atlas, o.request, tail ? &*tail : nullptr, interruptToken());  // Ctrl-C: the one stop
  } catch (const OperationStopped&) {
    std::fprintf(stderr, "interrupted: no survival (nothing written)\n");
    return 130;
  }
  io::OutputBatch outputs;  // the JSON and the CSV: all or nothing (issue 54, item 4)
  if (!o.json.empty()) io::writeFileAtomically(o.json, markovTreeJson(r));
  if (!o.csv.empty()) io::writeFileAtomically(o.csv, markovTreeCsv(r));
  outputs.commit();
  if (!o.quiet) printTree(r);
  return 0;
}
}  // namespace

void addMarkovTreeCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<MarkovTreeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "markov-tree", "the Meiss-Ott Markov tree of an atlas (states between barriers, rates flux / area) and its exact "
                     "survival S(t) and P_t = w S(t), with each level's share (docs/markov-tree.md)");
  cmd->add_option("--atlas", o->atlas, "the atlas JSON (archipelago-cli atlas --json)")->required();
  addNumberOption(*cmd, "--t-max", o->request.tMax, "the grid's last t (steps)");
  addNumberOption(*cmd, "--per-decade", o->request.perDecade, "grid points per decade");
  cmd->add_option("--tail", o->tail,
                  "a tail sampler's file of the atlas's map (archipelago-cli tail --out): the model against its reliable "
                  "levels from 10^3 steps (needs --alpha and --b2 of that run process)");
  cmd->add_option("--at", o->at, "more t, comma-separated steps (e.g. the tail sampler's levels)");
  addNumberOption(*cmd, "--alpha", o->request.alpha,
                  "the run's mean segment length alpha (steps; archipelago-cli stats): with --b2, P_t = alpha flux / b2 S(t)");
  addNumberOption(*cmd, "--b2", o->request.b2, "the stochastic area b2 of the run's box (archipelago-cli stochastic-area)");
  addNumberOption(*cmd, "--exponent-from", o->request.exponentFrom, "gamma's windows start at or above this t (steps)");
  cmd->add_option("--without", o->without,
                  "leave out these barriers, comma-separated: inner (the chains' inner separatrices), cantori "
                  "(issue 50's ablation; --tail prints every variant's reach)");
  addNumberOption(*cmd, "--levels", o->request.barriers.maxLevel,
                  "take the chains of the atlas's levels up to this one as barriers, lump the deeper ones");
  cmd->add_option("--json", o->json, "write the tree, its rates' sources and the survival as JSON here");
  cmd->add_option("--csv", o->csv, "write t, S, P, each level's and each state's share as CSV here");
  cmd->add_flag("--quiet", o->quiet, "no table");
  cmd->callback([o, &status] { status = runMarkovTree(*o); });
}

}  // namespace archipelago::cli
