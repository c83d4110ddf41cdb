// Python binding of core/atlas (issue 38): atlas() returns the tree as the dict of `archipelago-cli atlas --json`
// (parsed from the same JSON, so the two agree to the last digit).  It releases the GIL and stops on Ctrl-C at core's
// next check of the stop token (python/Interruption.hpp): KeyboardInterrupt.

#include <pybind11/pybind11.h>

#include <optional>
#include <stdexcept>
#include <stop_token>
#include <string>

#include "Conversions.hpp"
#include "Interruption.hpp"
#include "core/atlas/AtlasExport.hpp"
#include "core/atlas/AtlasJob.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {
// The defaults are the request's own (issue 35: a front end restates no default).
const AtlasRequest kAtlas{};

py::dict atlas(double K, double xmin, double xmax, int depth, std::uint64_t maxPeriod, double minArea,
               std::uint64_t iterations, double threshold, int scanPoints, double scanSteps, int bisections,
               int threads, double timeBudget, bool cantori, const py::object& resume) {
  AtlasRequest r;
  r.map = mapOf(K, xmin, xmax);
  r.depth = depth;
  r.maxPeriod = maxPeriod;
  r.minArea = minArea;
  r.iterations = iterations;
  r.digitsThreshold = threshold;
  r.scanPoints = scanPoints;
  r.scanSteps = scanSteps;
  r.bisections = bisections;
  r.threads = threads;
  r.timeBudget = timeBudget;
  r.cantori = cantori;
  if (auto e = atlasRequestError(r)) throw std::invalid_argument(*e);
  // resume: an atlas dict stopped early (its 'cancelled' true), continued by core from its finished islands.
  std::optional<Atlas> previous;
  if (!resume.is_none()) previous = atlasToResume(r, jsonArgument(resume, "resume"), "resume");
  const std::string json = interruptible(
      [&](std::stop_token stop) { return atlasJson(computeAtlas(r, {}, stop, previous ? &*previous : nullptr)); });
  return py::module_::import("json").attr("loads")(json);
}
}  // namespace

void bindAtlas(py::module_& m) {
  m.def("atlas", &atlas, py::arg("K") = kDefaultMap.K, py::kw_only(), py::arg("xmin") = kDefaultMap.xmin,
        py::arg("xmax") = kDefaultMap.xmax, py::arg("depth") = kAtlas.depth, py::arg("max_period") = kAtlas.maxPeriod,
        py::arg("min_area") = kAtlas.minArea, py::arg("iterations") = kAtlas.iterations,
        py::arg("threshold") = kAtlas.digitsThreshold, py::arg("scan_points") = kAtlas.scanPoints,
        py::arg("scan_steps") = kAtlas.scanSteps,
        py::arg("bisections") = kAtlas.bisections, py::arg("threads") = kAtlas.threads,
        py::arg("time_budget") = kAtlas.timeBudget, py::arg("cantori") = kAtlas.cantori, py::arg("resume") = py::none(),
        "The atlas of the islands around islands from the centre (-sqrt K, 0) (core/atlas/Atlas.hpp, docs/atlas.md):\n"
        "each island's boundary circle and area, the chains just outside it with their period, p/q about the parent,\n"
        "turnstile flux, zone and layer areas and mean residence time, to `depth` levels.  The same dict as\n"
        "`archipelago-cli atlas --json`: 'nodes' is the tree (each with its 'parent' index).  time_budget (seconds, 0:\n"
        "none) stops it keeping the finished islands ('cancelled', 'stop_reason'); resume=<such a dict> continues it\n"
        "with the same arguments; cantori=True adds the cantori about each island, between its chains and its\n"
        "boundary cantorus ('cantori': 'island', 'boundary', MacKay-Meiss-Percival flux and layer).  ValueError for\n"
        "bad input.");
}
