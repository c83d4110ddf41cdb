// The K scan of section 5 (core/scan): the box rule, the K list, and the scan's summary of one run.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>

#include "core/scan/ScanBox.hpp"
#include "core/scan/ScanPoint.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "python/Conversions.hpp"
#include "python/Run.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

py::dict scanPoint(const Run& r, const py::object& fraction) {
  r.check();
  const TrappingStatistics st = statisticsOf(r.state);
  std::optional<StochasticAreaValue> b2;
  if (!fraction.is_none()) b2 = stochasticAreaOf(r.state.params.map, fractionArgument(fraction.cast<double>()));
  const ScanPoint p = scanPointOf(r.state, st, b2);
  py::dict d;
  d["K"] = p.K;
  d["xmin"] = p.box.xmin;
  d["xmax"] = p.box.xmax;
  d["blocks_done"] = p.blocksDone;
  d["blocks_total"] = p.blocksTotal;
  d["segments"] = p.segments;
  d["D"] = p.D;
  d["D_error"] = p.DError;
  d["D_error_subsets"] = st.DError;
  d["longest_steps"] = p.longestSteps;
  d["long_fraction"] = p.longFraction;
  if (p.boxInvariant) {
    d["b2"] = p.boxInvariant->b2.area;
    d["b2_D"] = p.boxInvariant->b2D;
    d["b2_D_error"] = p.boxInvariant->b2DError;
  }
  return d;
}

}  // namespace

void bindScan(py::module_& m) {
  m.def("scan_box", [](double K) { const MapParameters b = scanBox(K); return py::make_tuple(b.xmin, b.xmax); },
        py::arg("K"), "The box (xmin, xmax) the K scan of section 5 uses for K in [0, 4].");
  m.def("scan_values", &scanValues, py::arg("start"), py::arg("stop"), py::arg("step"),
        "The K values of a scan: start, start + step, ... up to stop (rounded to 12 significant digits).");
  m.def("scan_point", &scanPoint, py::arg("run"), py::arg("fraction") = py::none(),
        "The K scan's summary of one run (section 5): D, the longest segment, the fraction of time in segments of at\n"
        "least 10^4 steps, and b2 D when the visited fraction of stochastic_area() is given.  D_error (and b2_D_error):\n"
        "the supported error of statistics(), NaN when the longest segments dominate D; D_error_subsets: the subsets'.");
}
