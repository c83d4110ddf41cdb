// The exact map and its kernels (core/map/FixedPointMap.hpp, core/kernels; appendix B) as NumPy arrays: the box's
// rules, the integer coefficients of N, orbits of N and N^-1, the involution J, the instruction-set paths.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/io/Memory.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/map/OrbitIterator.hpp"
#include "python/Conversions.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

// A unit coordinate from Python: an integer in [0, 2^52).
std::uint64_t unitCoordinate(const py::object& v, const char* name) {
  if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
    throw std::invalid_argument(std::string(name) + " must be an integer in [0, 2^52) (unit coordinates)");
  const py::int_ i = py::reinterpret_borrow<py::int_>(v);
  const bool whole64 = i >= py::int_(0) && i <= py::int_(std::numeric_limits<std::uint64_t>::max());
  const std::optional<std::uint64_t> value = whole64 ? std::optional(i.cast<std::uint64_t>()) : std::nullopt;
  if (auto e = unitCoordinateError(name, value, std::string(py::str(py::handle(i))))) throw std::invalid_argument(*e);
  return *value;
}

// A one-dimensional array of unit coordinates from Python: integers only (a float array was once truncated to
// zeros silently), each in [0, 2^52).
py::array_t<std::uint64_t> unitArray(const py::object& values, const char* name) {
  const py::array a = py::module_::import("numpy").attr("asarray")(values);
  const char kind = a.dtype().kind();
  if (kind != 'u' && kind != 'i')
    throw py::type_error(std::string(name) + " must hold integers (unit coordinates in [0, 2^52)), not dtype " +
                         std::string(py::str(a.dtype())));
  if (a.ndim() != 1) throw std::invalid_argument(std::string(name) + " must be one-dimensional");
  const py::object numpy = py::module_::import("numpy");
  if (kind == 'i' && a.size() > 0 && numpy.attr("any")(a.attr("__lt__")(0)).cast<bool>()) {
    const py::object first = a.attr("__getitem__")(numpy.attr("argmin")(a));  // the most negative: not 64-bit whole
    if (auto e = unitCoordinateError(name, std::nullopt, std::string(py::str(first)))) throw std::invalid_argument(*e);
  }
  return py::array_t<std::uint64_t>::ensure(a.attr("astype")("uint64"));
}

py::dict orbit(double K, double xmin, double xmax, const py::object& x0, const py::object& y0, const py::object& X0,
               const py::object& Y0, std::uint64_t steps, bool backward) {
  const FixedPointMap map(mapOf(K, xmin, xmax));
  OrbitRequest r;
  r.map = mapOf(K, xmin, xmax);
  r.steps = steps;
  r.backward = backward;
  if (!X0.is_none() || !Y0.is_none()) {
    r.start.X = unitCoordinate(X0, "X0");
    r.start.Y = unitCoordinate(Y0, "Y0");
  } else {
    if (x0.is_none() || y0.is_none()) throw std::invalid_argument("give x0 and y0 (physical) or X0 and Y0 (unit)");
    const double x = x0.cast<double>(), y = y0.cast<double>();
    if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("x0 and y0 must be finite");
    r.start = map.toUnit(x, y);
  }
  // core's one orbit loop and its rules (the length limit of core/limits, the CLI's message), before any memory.
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  // X, Y (8 bytes each), x, y (8 each) and wrapped (1) per point (issue #23).
  io::checkMemory((steps + 1) * 33, "orbit(steps=" + std::to_string(steps) + ")");
  const auto n = static_cast<py::ssize_t>(steps + 1);
  OrbitArrays points(map, n);
  py::array_t<bool> wrapped(n);
  auto pw = wrapped.mutable_data();
  {
    py::gil_scoped_release release;
    iterateOrbit(r, [&](std::uint64_t i, const UnitState& z, bool w) {
      pw[i] = w;
      points.set(i, z);
    });
  }
  py::dict d = points.dict();
  d["wrapped"] = wrapped;
  return d;
}

py::tuple involution(const py::object& Xin, const py::object& Yin) {
  const py::array_t<std::uint64_t> X = unitArray(Xin, "X"), Y = unitArray(Yin, "Y");
  if (X.size() != Y.size()) throw std::invalid_argument("X and Y must have the same size");
  py::array_t<std::uint64_t> oX(X.size()), oY(Y.size());
  for (py::ssize_t i = 0; i < X.size(); ++i) {
    UnitState z{X.at(i), Y.at(i)};
    if (auto e = unitCoordinateError("X", z.X, std::to_string(z.X))) throw std::invalid_argument(*e);
    if (auto e = unitCoordinateError("Y", z.Y, std::to_string(z.Y))) throw std::invalid_argument(*e);
    FixedPointMap::involution(z);
    oX.mutable_at(i) = z.X;
    oY.mutable_at(i) = z.Y;
  }
  return py::make_tuple(oX, oY);
}

}  // namespace

void bindMap(py::module_& m) {
  m.def("map_error", [](double K, double xmin, double xmax) { return mapError({K, xmin, xmax}); },
        py::arg("K"), py::arg("xmin"), py::arg("xmax"),
        "The first violated rule of the box (appendix B: xmin < -sqrt(K), xmax > xmin), or None.");
  m.def("coefficients", [](double K, double xmin, double xmax) {
          return coefficientsDict(computeCoefficients(mapOf(K, xmin, xmax))); },
        py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin, py::arg("xmax") = kDefaultMap.xmax,
        "The integers (A, B, C, m) that define the fixed-point map N exactly (appendix B):\n"
        "G(X) = 2^m (floor(A floor(X^2/2^52)/2^52) - floor(B X/2^52) + C), in units of 2^-52.");
  m.def("orbit", &orbit,
        py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin, py::arg("xmax") = kDefaultMap.xmax, py::arg("x0") = py::none(),
        py::arg("y0") = py::none(), py::kw_only(), py::arg("X0") = py::none(), py::arg("Y0") = py::none(),
        py::arg("steps") = 1000, py::arg("backward") = false,
        "An orbit of the exact map N (forward) or N^-1 (backward=True), appendix B, from (x0, y0) in physical\n"
        "coordinates (rounded to the 2^-52 grid) or (X0, Y0) in unit coordinates (integers in [0, 2^52)).\n"
        "Returns a dict of arrays of steps+1 points: X, Y (uint64, units of 2^-52), x, y (physical, x = xmin + L X/2^52,\n"
        "y = -L/2 + L Y/2^52) and wrapped (the step left the box: the trapped segment ends, section 3).");
  m.def("involution", &involution, py::arg("X"), py::arg("Y"),
        "The involution J of appendix B (X <- X - Y + 2^51, Y <- -Y, mod 2^52; J^2 = 1, N^-1 = J N J) on unit arrays.");

  m.def("kernels", [] {
          std::vector<std::string> names;
          for (const KernelInfo& k : supportedKernels()) names.emplace_back(k.name);
          return names; },
        "The instruction-set paths this CPU supports (every one gives bit-identical results).");
}
