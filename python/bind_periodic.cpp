// Periodic orbits and island chains (core/periodic): the orbit of minimal period n near a point with Greene's
// residue and rotation number, and the island chain a segment sticks to.  The orbit search releases the GIL and
// stops on Ctrl-C.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "core/periodic/IslandChain.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "python/Interruption.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

py::dict periodicOrbitDict(const PeriodicOrbit& o) {
  const auto n = static_cast<py::ssize_t>(o.points.size());
  py::array_t<double> x(n), y(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    x.mutable_at(i) = static_cast<double>(o.points[static_cast<std::size_t>(i)].x);
    y.mutable_at(i) = static_cast<double>(o.points[static_cast<std::size_t>(i)].y);
  }
  py::dict d;
  d["K"] = static_cast<double>(o.K);
  d["period"] = o.period;
  d["x"] = x;
  d["y"] = y;
  d["trace"] = static_cast<double>(o.trace);
  d["residue"] = static_cast<double>(o.residue);
  d["stable"] = o.stable();
  d["winding_turns"] = o.windingTurns;
  d["rotation_number"] = static_cast<double>(o.rotationNumber);
  d["rotation_number_text"] = rotationNumberText(o);
  d["linear_rotation"] = o.linearRotation;
  d["closure"] = static_cast<double>(o.closure);
  d["symmetry"] = std::string(toString(o.symmetry));
  return d;
}

py::dict periodicOrbit(double K, int period, double x, double y, double radius, bool stableOnly) {
  if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("near must be finite");
  PeriodicOrbitSearch s;
  s.period = period;
  s.near = {x, y};
  s.searchRadius = radius;
  s.stableOnly = stableOnly;
  validate(K, s);
  try {
    // A stop throws OperationStopped, which interruptible() answers with the KeyboardInterrupt that asked for it.
    return periodicOrbitDict(interruptible([&](std::stop_token stop) { return findPeriodicOrbit(K, s, stop); }));
  } catch (const std::runtime_error& e) {  // no orbit found
    throw std::invalid_argument(e.what());
  }
}

py::dict islandChain(double K, const py::array_t<double>& x, const py::array_t<double>& y) {
  if (x.size() != y.size()) throw std::invalid_argument("x and y must have the same size");
  std::vector<PhysicalPoint> pts(static_cast<std::size_t>(x.size()));
  for (py::ssize_t i = 0; i < x.size(); ++i) pts[static_cast<std::size_t>(i)] = {x.at(i), y.at(i)};
  IslandChain c;
  {
    py::gil_scoped_release release;
    c = identifyIslandChain(K, pts);
  }
  py::dict d;
  d["period"] = c.period;
  d["hierarchy"] = c.hierarchy;
  d["spreads"] = std::vector<double>(c.spreads.begin(), c.spreads.end());
  d["member"] = py::make_tuple(static_cast<double>(c.member.x), static_cast<double>(c.member.y));
  d["winding_turns"] = c.windingTurns;
  d["rotation_number"] = static_cast<double>(c.rotationNumber);
  d["centre"] = c.centre ? py::object(periodicOrbitDict(*c.centre)) : py::none();
  return d;
}

}  // namespace

void bindPeriodic(py::module_& m) {
  m.def("periodic_orbit", &periodicOrbit, py::arg("K"), py::arg("period"), py::arg("x"), py::arg("y"),
        py::arg("radius") = 0.01, py::arg("stable_only") = false,
        "The periodic orbit of Q of minimal period n nearest to (x, y): points, Greene's residue R = (2 - trace)/4,\n"
        "stability, rotation number W/n (clockwise turns about (-sqrt K, 0)).  ValueError when none is found.");
  m.def("island_chain", &islandChain, py::arg("K"), py::arg("x"), py::arg("y"),
        "The island chain a segment (consecutive iterates of Q, physical x, y) sticks to (core/periodic/IslandChain.hpp).\n"
        "Note: a replayed segment is of N^-1; reverse it (x[::-1], y[::-1]) for iterates of Q.");
}
