// Python binding of core/markovtree (issue 40): markov_tree() returns the dict of `archipelago-cli markov-tree --json`
// (parsed from the same JSON, so the two agree to the last digit), from an atlas dict (atlas()'s) or an atlas file.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "Conversions.hpp"
#include "Interruption.hpp"
#include "core/atlas/AtlasExport.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/markovtree/MarkovTreeExport.hpp"
#include "core/tail/TailFile.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {
// The defaults are the request's own (issue 35: a front end restates no default).
const MarkovTreeRequest kTree{};

py::dict markovTree(const py::object& atlas, double alpha, double b2, double tMax, int perDecade,
                    const std::vector<std::uint64_t>& at, double exponentFrom, const py::object& tail,
                    bool innerSeparatrices, bool cantori, int levels) {
  MarkovTreeRequest r;
  r.barriers = {.innerSeparatrices = innerSeparatrices, .cantori = cantori, .maxLevel = levels};
  r.alpha = alpha;
  r.b2 = b2;
  r.tMax = tMax;
  r.perDecade = perDecade;
  r.at = at;
  r.exponentFrom = exponentFrom;
  std::string text;
  if (py::isinstance<py::dict>(atlas)) {
    text = jsonArgument(atlas, "atlas");
    r.atlasSource = "(a dict)";
  } else if (py::isinstance<py::str>(atlas) || py::hasattr(atlas, "__fspath__")) {
    const std::string path = py::str(py::module_::import("os").attr("fspath")(atlas));
    r.atlasSource = path;
    try {
      text = io::readRegularFile(path, kMaxAtlasFileBytes);
    } catch (const std::exception& e) {
      throw std::invalid_argument(std::string("atlas: ") + e.what());
    }
  } else {
    throw std::invalid_argument("atlas must be an atlas dict (atlas()) or the path of an atlas JSON file");
  }
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  Atlas a;
  try {
    a = atlasFromJson(text);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("atlas: ") + e.what());
  }
  std::optional<TailState> sampled;
  if (!tail.is_none()) {
    if (!(py::isinstance<py::str>(tail) || py::hasattr(tail, "__fspath__")))
      throw std::invalid_argument("tail must be the path of a tail sampler's file (archipelago-cli tail --out)");
    r.tailSource = py::str(py::module_::import("os").attr("fspath")(tail));
    try {
      sampled = loadTailFile(r.tailSource);
    } catch (const std::exception& e) {
      throw std::invalid_argument("tail: " + std::string(e.what()));
    }
  }
  // Without the GIL on a worker thread, Ctrl-C polled: KeyboardInterrupt within a second (issue 54: it was ignored
  // for two minutes on a large atlas).
  const std::string json = bindings::interruptible([&](std::stop_token stop) {
    return markovTreeJson(computeMarkovTree(a, r, sampled ? &*sampled : nullptr, stop));
  });
  return py::module_::import("json").attr("loads")(json);
}
}  // namespace

void bindMarkovTree(py::module_& m) {
  m.def("markov_tree", &markovTree, py::arg("atlas"), py::kw_only(), py::arg("alpha") = kTree.alpha,
        py::arg("b2") = kTree.b2, py::arg("t_max") = kTree.tMax, py::arg("per_decade") = kTree.perDecade,
        py::arg("at") = std::vector<std::uint64_t>{}, py::arg("exponent_from") = kTree.exponentFrom,
        py::arg("tail") = py::none(), py::arg("inner_separatrices") = kTree.barriers.innerSeparatrices,
        py::arg("cantori") = kTree.barriers.cantori, py::arg("levels") = kTree.barriers.maxLevel,
        "The Meiss-Ott Markov tree of an atlas (core/markovtree/MarkovTree.hpp, docs/markov-tree.md): `atlas` is an\n"
        "atlas dict (atlas()) or the path of an atlas JSON file.  States between successive barriers, rates flux / area\n"
        "(each with its source), chains without a flux lumped; S(t) exactly on a grid of per_decade points a decade to\n"
        "t_max and at the steps `at`, each level's share, gamma over decade windows; with alpha (the run's mean segment\n"
        "length, steps) and b2 (the stochastic area) also P_t = alpha flux / b2 S(t).  The same dict as\n"
        "`archipelago-cli markov-tree --json`; with `tail` (the path of a tail sampler's file of the atlas's map, and\n"
        "alpha and b2) also \"comparison\": the model over each reliable level from 10^3 steps, and the reach (the last\n"
        "t within a factor 3) and \"ablation\" (each variant's reach).  inner_separatrices=False, cantori=False and\n"
        "levels=L leave those barriers out (issue 50; markov-tree --without, --levels).  ValueError for bad input or an\n"
        "atlas that cannot make a tree.");
}
