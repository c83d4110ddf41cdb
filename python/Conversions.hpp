// The conversions that more than one bind_*.cpp needs, written once: arguments from Python (paths, whole and real
// numbers, the map's box, a visited fraction) checked before any work with the module's messages (issue #23: never
// cut, truncated or taken as "None"), results to Python (NumPy arrays, the map's coefficients), and OSError.
// Errors: std::invalid_argument -> ValueError, py::type_error -> TypeError; no maths here.

#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/atlas/BoxIslandCheck.hpp"
#include "core/limits/Limits.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"

namespace archipelago::bindings {

namespace py = pybind11;

/// Raises OSError(message): a file that cannot be read or written.
[[noreturn]] inline void raiseOSError(const std::string& message) {
  PyErr_SetString(PyExc_OSError, message.c_str());
  throw py::error_already_set();
}

/// The JSON text of a dict given as an argument (an atlas, a run spec) for core's reader: ValueError naming `name`
/// for what json.dumps cannot write — a dict nested too deeply (RecursionError: 100,000 levels, issue 54), a value
/// that is not JSON (TypeError, ValueError: nan is not refused by dumps, core's reader refuses it).
inline std::string jsonArgument(const py::object& value, const std::string& name) {
  try {
    return py::str(py::module_::import("json").attr("dumps")(value));
  } catch (py::error_already_set& e) {
    if (e.matches(PyExc_RecursionError))
      throw std::invalid_argument(name + ": nested too deeply to be written as JSON (a forged or circular dict)");
    if (e.matches(PyExc_TypeError) || e.matches(PyExc_ValueError))
      throw std::invalid_argument(name + ": not a JSON document (" + std::string(py::str(e.value())) + ")");
    throw;
  }
}

/// A one-dimensional NumPy array holding a copy of v.
template <class T>
py::array_t<T> toArray(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

/// A (rows, cols) NumPy array holding a copy of v, row by row (an image: row 0 at the top).
template <class T>
py::array_t<T> toArray(const std::vector<T>& v, py::ssize_t rows, py::ssize_t cols) {
  py::array_t<T> a({rows, cols});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

/// The points of an orbit (or a replayed segment) as arrays X, Y (unit coordinates, uint64) and x, y (physical):
/// allocated with the GIL, filled by set() without it (plain memory), returned by dict().
class OrbitArrays {
 public:
  OrbitArrays(const FixedPointMap& map, py::ssize_t points) : map_(map), X_(points), Y_(points), x_(points), y_(points) {
    pX_ = X_.mutable_data();
    pY_ = Y_.mutable_data();
    px_ = x_.mutable_data();
    py_ = y_.mutable_data();
  }
  void set(std::uint64_t i, const UnitState& z) {
    pX_[i] = z.X;
    pY_[i] = z.Y;
    const PhysicalPoint p = map_.toPhysical(z);
    px_[i] = static_cast<double>(p.x);
    py_[i] = static_cast<double>(p.y);
  }
  [[nodiscard]] py::dict dict() const {
    py::dict d;
    d["X"] = X_;
    d["Y"] = Y_;
    d["x"] = x_;
    d["y"] = y_;
    return d;
  }

 private:
  FixedPointMap map_;
  py::array_t<std::uint64_t> X_, Y_;
  py::array_t<double> x_, y_;
  std::uint64_t *pX_, *pY_;
  double *px_, *py_;
};

/// A file path from Python: str or os.PathLike (os.fspath), never None or another type (a run once got saved to a
/// file named "None"), never with a NUL character (the C library would cut the name there).  Issue #23.
inline std::string pathArgument(const py::object& path, const char* name) {
  if (path.is_none() || !(py::isinstance<py::str>(path) || py::hasattr(path, "__fspath__")))
    throw py::type_error(std::string(name) + " must be a path (str or os.PathLike), not " +
                         std::string(py::str(py::type::handle_of(path).attr("__name__"))));
  const py::object text = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(text)) throw py::type_error(std::string(name) + " must be a text path, not bytes");
  const std::string s = text.cast<std::string>();
  if (s.empty()) throw std::invalid_argument(std::string(name) + " must not be empty");
  if (s.find('\0') != std::string::npos) throw std::invalid_argument(std::string(name) + " must not contain a NUL character");
  return s;
}

/// A whole number from Python: int or anything with __index__ (NumPy integers), or a float that is exactly whole
/// (T=2e7: core's one rule, core/io/NumberText.hpp, as "2e7" is typed); never bool or text (TypeError), never a
/// fraction (ValueError).
inline py::int_ wholeArgument(py::handle v, const std::string& name) {
  if (PyBool_Check(v.ptr()) || py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v))
    throw py::type_error(name + " must be a whole number, not " + std::string(py::str(py::repr(v))));
  if (PyIndex_Check(v.ptr())) return py::reinterpret_steal<py::int_>(PyNumber_Index(v.ptr()));
  if (PyFloat_Check(v.ptr()) || py::hasattr(v, "__float__")) {
    const double d = PyFloat_AsDouble(v.ptr());
    if (d == -1.0 && PyErr_Occurred()) throw py::error_already_set();
    if (!std::isfinite(d) || std::floor(d) != d)
      throw std::invalid_argument(name + " = " + std::string(py::str(py::repr(v))) + " must be a whole number");
    return py::reinterpret_steal<py::int_>(PyLong_FromDouble(d));
  }
  throw py::type_error(name + " must be a whole number, not " + std::string(py::str(py::repr(v))));
}

/// wholeArgument(v, name) in [0, max]: ValueError with core's wording (wholeRangeError) outside.
inline std::uint64_t unsignedArgument(py::handle v, const std::string& name, std::uint64_t max,
                                      const std::string& range) {
  const py::int_ i = wholeArgument(v, name);
  if (i < py::int_(0) || i > py::int_(max))  // a conversion, not a range: a Python int has no bound (core's wording)
    throw std::invalid_argument(wholeRangeError(name, std::string(py::str(py::handle(i))), range));
  return i.cast<std::uint64_t>();
}

/// A real number from Python: int, float or a NumPy number, never bool or str.
inline double realArgument(py::handle v, const std::string& name) {
  if (PyBool_Check(v.ptr()) || py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v) ||
      !(PyFloat_Check(v.ptr()) || PyIndex_Check(v.ptr()) || py::hasattr(v, "__float__")))
    throw py::type_error(name + " must be a real number, not " + std::string(py::str(py::repr(v))));
  const double d = PyFloat_AsDouble(v.ptr());
  if (d == -1.0 && PyErr_Occurred()) throw py::error_already_set();
  return d;
}

/// The box (K, xmin, xmax) of the map, checked by core's mapError (appendix B).
/// The map's defaults of every function's K, xmin, xmax: core's MapParameters{} (the paper's K = 0.1 box), never
/// restated here (issue 35: the (0.1, −0.8, 0.5) box was written in nine signatures).
inline const MapParameters kDefaultMap{};

inline MapParameters mapOf(double K, double xmin, double xmax) {
  MapParameters p{K, xmin, xmax};
  if (auto e = mapError(p)) throw std::invalid_argument(*e);
  return p;
}

/// The visited fraction stochastic_area() returns (a number in [0, 1]), given back to compute b2 in a box.
/// warnings.warn(core's text) when the box or its randomizing zone cuts the central island (checkBoxAgainstIsland,
/// core/atlas/BoxIslandCheck.hpp: one message for every front end).  The run goes on; warnings.filterwarnings
/// ("error", …) makes it a refusal, "ignore" quiets it.
inline void warnIfBoxCutsIsland(const MapParameters& map, double Xr) {
  if (const BoxIslandCheck c = checkBoxAgainstIsland(map, Xr); c.cuts())
    py::module_::import("warnings").attr("warn")(c.warning, py::module_::import("builtins").attr("UserWarning"), 2);
}

inline double fractionArgument(double fraction) {
  if (auto e = visitedFractionError("fraction", fraction)) throw std::invalid_argument(*e);  // core's rule
  return fraction;
}

/// The integers (A, B, C, m) of the exact map N (appendix B) as a dict.
inline py::dict coefficientsDict(const MapCoefficients& c) {
  py::dict d;
  d["A"] = c.A;
  d["B"] = c.B;
  d["C"] = c.C;
  d["m"] = c.m;
  return d;
}

}  // namespace archipelago::bindings
