// The phase portrait and the area of the stochastic region (core/portrait; fig. 1, appendix A) as NumPy arrays:
// portraits of the whole box, b2 with its convergence curve, and the box-independent values scaled by b2
// (core/stats/StochasticAreaQuantities.hpp).  Both computations release the GIL and stop on Ctrl-C.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "core/kernels/KernelDispatch.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/stochasticarea/StochasticArea.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "python/Conversions.hpp"
#include "python/Interruption.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

py::dict stochasticArea(double K, double xmin, double xmax, double Xr, std::uint32_t q, std::uint32_t orbits,
                        std::uint64_t seed, std::uint64_t iterations, int gridBits, const std::string& kernel) {
  StochasticAreaRequest r;
  r.map = mapOf(K, xmin, xmax);
  r.Xr = Xr;
  r.q = q;
  r.orbits = orbits;
  r.seed = seed;
  r.iterations = iterations;
  r.gridBits = gridBits;
  r.kernel = &selectKernel(kernel);
  r.firstCheckpoint = std::min<std::uint64_t>(r.firstCheckpoint, iterations);
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const StochasticAreaResult res =
      interruptible([&](std::stop_token stop) { return computeStochasticArea(r, {}, stop); });
  std::vector<std::uint64_t> it, boxes;
  std::vector<double> frac;
  for (const auto& p : res.convergence) {
    it.push_back(p.iterations);
    boxes.push_back(p.boxesVisited);
    frac.push_back(p.b2);
  }
  const StochasticAreaValue v = stochasticAreaOf(r.map, res.fraction());
  const auto side = py::ssize_t{1} << gridBits;
  py::dict d;
  d["fraction"] = v.fraction;
  d["box_area"] = v.boxArea;
  d["b2"] = v.area;
  d["iterations"] = toArray(it);
  d["boxes_visited"] = toArray(boxes);
  d["fractions"] = toArray(frac);
  d["visited"] = toArray(res.visited, side, side);
  return d;
}

py::dict boxInvariant(double K, double xmin, double xmax, double fraction, double D, double DError) {
  const double f = fractionArgument(fraction);
  if (auto e = diffusionInputError(D, DError)) throw std::invalid_argument(*e);
  const BoxInvariantQuantities b = boxInvariantQuantities(stochasticAreaOf(mapOf(K, xmin, xmax), f), D, DError);
  py::dict d;
  d["b2"] = b.b2.area;
  d["b2_D"] = b.b2D;
  d["b2_D_error"] = b.b2DError;
  d["accelerator_factor"] = b.acceleratorFactor;
  d["enhancement_n1"] = b.enhancementN1;
  return d;
}

py::dict portrait(double K, double xmin, double xmax, const std::string& mode, int width, int height,
                  std::uint64_t points, std::uint32_t orbits, std::uint64_t seed, double Xr, std::uint32_t q,
                  const std::string& kernel) {
  PortraitRequest r;
  r.map = mapOf(K, xmin, xmax);
  const auto pm = parsePortraitMode(mode);
  if (!pm) throw std::invalid_argument("mode must be density, orbits or stickiness, not " + mode);
  r.mode = *pm;
  r.width = width;
  r.height = height;
  r.points = points;
  r.orbits = orbits;
  r.seed = seed;
  r.Xr = Xr;
  r.q = q;
  r.passes = 1;
  r.kernel = &selectKernel(kernel);
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const PortraitResult res = interruptible([&](std::stop_token stop) { return renderPortrait(r, {}, stop); });
  const PortraitRaster& ras = res.raster;
  const py::ssize_t rows = ras.height, cols = ras.width;
  py::dict d;
  if (!ras.counts.empty()) d["counts"] = toArray(ras.counts, rows, cols);
  if (!ras.labels.empty()) d["labels"] = toArray(ras.labels, rows, cols);
  if (!ras.lengthSums.empty()) d["mean_length"] = toArray(ras.meanSegmentLengths(), rows, cols);
  d["points_iterated"] = ras.pointsIterated;
  d["points_binned"] = ras.pointsBinned;
  return d;
}

}  // namespace

// The defaults are the requests' own (issue 35: a front end restates no default).
const StochasticAreaRequest kArea{};
const PortraitRequest kPortrait{};

void bindPortrait(py::module_& m) {
  m.def("stochastic_area", &stochasticArea,
        py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin, py::arg("xmax") = kDefaultMap.xmax, py::kw_only(), py::arg("Xr") = kArea.Xr,
        py::arg("q") = kArea.q, py::arg("orbits") = kArea.orbits, py::arg("seed") = kArea.seed,
        py::arg("iterations") = kArea.iterations, py::arg("grid_bits") = kArea.gridBits, py::arg("kernel") = "auto",
        "b2, the area of the stochastic region (appendix A): the fraction of 2^grid_bits x 2^grid_bits boxes visited by\n"
        "randomized orbits, times the box area L^2; with its convergence curve and the visited map (rows = Y boxes).");
  m.def("box_invariant", &boxInvariant,
        py::arg("K"), py::arg("xmin"), py::arg("xmax"), py::arg("fraction"), py::arg("D"), py::arg("D_error") = 0.0,
        "The b2-scaled, box-independent values (core/stats/StochasticAreaQuantities.hpp): b2 D with its error, the\n"
        "accelerator-mode factor (8/pi^2) b2 and the n = 1 enhancement, from the visited fraction and D of statistics().");
  m.def("portrait", &portrait,
        py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin, py::arg("xmax") = kDefaultMap.xmax, py::kw_only(), py::arg("mode") = "density",
        py::arg("width") = kPortrait.width, py::arg("height") = kPortrait.height, py::arg("points") = kPortrait.points,
        py::arg("orbits") = kPortrait.orbits, py::arg("seed") = kPortrait.seed, py::arg("Xr") = kPortrait.Xr,
        py::arg("q") = kPortrait.q, py::arg("kernel") = "auto",
        "A portrait of the whole box (fig. 1): mode density (visits, counts), orbits (labels of seed orbits) or\n"
        "stickiness (mean trapped-segment length in steps per pixel); arrays of shape (height, width), row 0 at the top.");
}
