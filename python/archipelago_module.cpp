// The Python module `archipelago` (issue 18): core's public API as NumPy arrays, for notebooks and scripts.
// No maths here: every number comes from core (Karney 1983, Physica D 8; see the C++ headers cited in each
// docstring).  Errors: std::invalid_argument -> ValueError (core's messages, the CLI's), file errors -> OSError.

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <mutex>
#include <optional>
#include <thread>
#include <fstream>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "core/io/Memory.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/periodic/IslandChain.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/portrait/PortraitRenderer.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/spec/RunSpec.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/stats/StatisticsTable.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/stats/RunEnsemble.hpp"
#include "core/stats/TailAnalysis.hpp"
#include "core/portrait/StochasticArea.hpp"
#include "core/theory/SmallKTheory.hpp"
#include "core/scan/ScanPoint.hpp"
#include "core/markov/MarkovModel.hpp"

namespace py = pybind11;
using namespace archipelago;

void bindManifolds(py::module_& m);  // bind_manifolds.cpp

namespace {

[[noreturn]] void raiseOSError(const std::string& message) {
  PyErr_SetString(PyExc_OSError, message.c_str());
  throw py::error_already_set();
}

template <class T>
py::array_t<T> toArray(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// A unit coordinate from Python: an integer in [0, 2^52).
std::uint64_t unitCoordinate(const py::object& v, const char* name) {
  if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
    throw std::invalid_argument(std::string(name) + " must be an integer in [0, 2^52) (unit coordinates)");
  const py::int_ i = py::reinterpret_borrow<py::int_>(v);
  if (i < py::int_(0) || i >= py::int_(FixedPointMap::kOne))
    throw std::invalid_argument(std::string(name) + " = " + std::string(py::str(py::handle(i))) +
                                " must lie in [0, 2^52) (unit coordinates)");
  return i.cast<std::uint64_t>();
}

// A file path from Python: str or os.PathLike (os.fspath), never None or another type (a run once got saved to a
// file named "None"), never with a NUL character (the C library would cut the name there).  Issue #23.
std::string pathArgument(const py::object& path, const char* name) {
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

// A whole number from Python: int or anything with __index__ (NumPy integers), or a float that is exactly whole
// (T=2e7: core's one rule, core/io/NumberText.hpp, as "2e7" is typed); never bool or text (TypeError), never a
// fraction (ValueError).
py::int_ wholeArgument(py::handle v, const std::string& name) {
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

// A real number from Python: int, float or a NumPy number, never bool or str.
double realArgument(py::handle v, const std::string& name) {
  if (PyBool_Check(v.ptr()) || py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v) ||
      !(PyFloat_Check(v.ptr()) || PyIndex_Check(v.ptr()) || py::hasattr(v, "__float__")))
    throw py::type_error(name + " must be a real number, not " + std::string(py::str(py::repr(v))));
  const double d = PyFloat_AsDouble(v.ptr());
  if (d == -1.0 && PyErr_Occurred()) throw py::error_already_set();
  return d;
}

// Runs work(stop) on a worker thread with the GIL released, and checks for Ctrl-C every 50 ms: a pending signal
// stops the work at its next check of `stop` and raises KeyboardInterrupt (issue #23: stochastic_area and
// portrait once ran on for minutes after Ctrl-C).  Exceptions of the work are rethrown here.
template <class Work>
auto interruptible(Work work) -> decltype(work(std::stop_token{})) {
  using Result = decltype(work(std::stop_token{}));
  std::stop_source stop;
  std::optional<Result> result;
  std::exception_ptr failure;
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  PyObject *type = nullptr, *value = nullptr, *trace = nullptr;  // a KeyboardInterrupt, held until rethrown
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        result.emplace(work(stop.get_token()));
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard lock(mutex);
      done = true;
      finished.notify_all();
    });
    for (bool interrupted = false; !interrupted;) {
      {
        std::unique_lock lock(mutex);
        if (finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) break;
      }
      const py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {  // the signal's exception is now pending: keep it for after the join
        PyErr_Fetch(&type, &value, &trace);
        stop.request_stop();
        interrupted = true;
      }
    }
    worker.join();
  }
  if (type != nullptr) {
    PyErr_Restore(type, value, trace);
    throw py::error_already_set();
  }
  if (failure) std::rethrow_exception(failure);
  return std::move(*result);
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
  if (kind == 'i' && a.size() > 0 && py::module_::import("numpy").attr("any")(a.attr("__lt__")(0)).cast<bool>())
    throw std::invalid_argument(std::string(name) + " must lie in [0, 2^52) (unit coordinates)");
  return py::array_t<std::uint64_t>::ensure(a.attr("astype")("uint64"));
}

MapParameters mapOf(double K, double xmin, double xmax) {
  MapParameters p{K, xmin, xmax};
  if (auto e = mapError(p)) throw std::invalid_argument(*e);
  return p;
}

// Keyword arguments -> TrappingParameters, through core's one table of keys and ranges (parameterRules()).
void applyParameters(TrappingParameters& p, const py::dict& kwargs) {
  for (auto item : kwargs) {
    const std::string key = py::str(item.first);
    const ParameterRule* rule = findParameterRule(key);
    if (rule == nullptr) throw std::invalid_argument("unknown parameter " + key);
    py::handle v = item.second;
    if (rule->integer) {
      const py::int_ i = wholeArgument(v, key);
      if (i < py::int_(0) || i > py::int_(UINT64_MAX))
        throw std::invalid_argument(key + " = " + std::string(py::str(py::handle(i))) + " must lie in " + std::string(rule->range));
      setParameterValue(p, key, ParameterValue{i.cast<std::uint64_t>()});
    } else {
      setParameterValue(p, key, ParameterValue{realArgument(v, key)});
    }
  }
  if (auto e = validationError(p)) throw std::invalid_argument(*e);
}

// The theory curves are functions of a time t >= 0 (steps) and a finite K: anything else is an error, not NaN.
void checkShapeArguments(double t, double K) {
  if (!(std::isfinite(t) && t >= 0)) throw std::invalid_argument("t = " + shortestDecimal(t) + " must be a finite time >= 0 (steps)");
  if (!std::isfinite(K)) throw std::invalid_argument("K = " + shortestDecimal(K) + " must be a finite number");
}

py::dict seriesDict(const Series& s) {
  py::dict d;
  d["x"] = toArray(s.x);
  d["value"] = toArray(s.value);
  d["error"] = toArray(s.error);
  return d;
}

py::dict parametersDict(const TrappingParameters& p) {
  py::dict d;
  for (const ParameterRule& r : parameterRules()) {
    const ParameterValue v = parameterValue(p, r.key);
    if (std::holds_alternative<double>(v)) d[py::str(std::string(r.key))] = std::get<double>(v);
    else d[py::str(std::string(r.key))] = std::get<std::uint64_t>(v);
  }
  return d;
}

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

/// A trapping run held by Python: a TrappingState (core/run/TrappingRun.hpp).
/// Every access holds the GIL except advance()'s computation, which marks the run busy meanwhile.
struct Run {
  TrappingState state;
  bool valid = true;
  bool busy = false;

  void check() const {
    if (busy) throw std::invalid_argument("this run is being advanced (advance() is running)");
    if (!valid) throw std::runtime_error("this run was lost by an error while computing");
  }
};

Run startRun(const py::object& spec, const py::kwargs& kwargs) {
  TrappingParameters params;
  if (!spec.is_none()) {
    std::string text;
    if (py::isinstance<py::dict>(spec)) text = py::module_::import("json").attr("dumps")(spec).cast<std::string>();
    else text = spec.cast<std::string>();
    params = parseRunSpec(text).parameters;
  }
  applyParameters(params, kwargs);
  if (auto e = memoryError(params, 0)) throw std::invalid_argument(*e);
  Run r;
  r.state = startTrapping(params);
  return r;
}

// Advances the run with the GIL released; at each chunk boundary the observer takes the GIL back briefly to
// call the progress callback and PyErr_CheckSignals (Ctrl-C -> KeyboardInterrupt after the chunk).
void advanceRun(Run& run, int threads, const std::string& kernelName, const py::object& progress,
                std::uint64_t maxChunk, double chunkSeconds, const py::object& checkpoint) {
  run.check();
  // The checkpoint's path is checked before the work, not found wrong after it.
  const std::optional<std::string> checkpointPath =
      checkpoint.is_none() ? std::nullopt : std::optional<std::string>(pathArgument(checkpoint, "checkpoint"));
  if (auto e = threadsError(threads)) throw std::invalid_argument(*e);
  if (!(std::isfinite(chunkSeconds) && chunkSeconds > 0 && chunkSeconds <= 3600))
    throw std::invalid_argument("chunk_seconds must lie in (0, 3600]");
  if (auto e = memoryError(run.state.params, threads)) throw std::invalid_argument(*e);
  const KernelInfo& kernel = selectKernel(kernelName);
  TrappingRunOptions options;
  options.threads = threads;
  options.kernel = &kernel;
  options.maxChunkBlocks = maxChunk;
  options.chunkSeconds = chunkSeconds;
  std::stop_source stopper;
  py::object pending;  // the Python exception that stopped the run (held with the GIL)
  py::object pendingType, pendingValue, pendingTrace;
  bool failed = false;
  auto observer = [&](const TrappingState& s, const TrappingProgress& p) {
    py::gil_scoped_acquire gil;
    if (failed) return;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress.is_none()) {
        py::dict d;
        d["blocks_done"] = p.blocksDone;
        d["blocks_total"] = p.blocksTotal;
        d["fraction"] = p.fraction;
        d["steps_per_second"] = p.stepsPerSecond;
        d["eta_seconds"] = p.etaSeconds;
        d["session_seconds"] = p.sessionSeconds;
        d["segments"] = s.total().segments();
        progress(d);
      }
    } catch (py::error_already_set& e) {
      failed = true;
      e.restore();  // keep the exception pending in the interpreter until the run returns
      PyObject *t, *v, *tb;
      PyErr_Fetch(&t, &v, &tb);
      pendingType = py::reinterpret_steal<py::object>(t);
      pendingValue = py::reinterpret_steal<py::object>(v);
      pendingTrace = py::reinterpret_steal<py::object>(tb);
      stopper.request_stop();
    }
  };
  run.valid = false;
  run.busy = true;
  try {
    py::gil_scoped_release release;
    run.state = runTrapping(std::move(run.state), options, observer, stopper.get_token());
  } catch (...) {
    run.busy = false;
    throw;
  }
  run.busy = false;
  run.valid = true;
  if (checkpointPath && !run.state.finished()) {
    const std::string& path = *checkpointPath;
    try { saveRunFile(path, run.state); } catch (const std::exception& e) { raiseOSError(e.what()); }
  }
  if (failed) {
    PyErr_Restore(pendingType.release().ptr(), pendingValue.release().ptr(), pendingTrace.release().ptr());
    throw py::error_already_set();
  }
}

py::dict replayRecord(const TrappingParameters& params, const SegmentRecord& rec) {
  const FixedPointMap map(params.map);
  const std::uint64_t n = rec.length * params.q + 1;
  if (n > (std::uint64_t{1} << 31)) throw std::invalid_argument("segment too long to replay into arrays");
  py::array_t<std::uint64_t> X(static_cast<py::ssize_t>(n)), Y(static_cast<py::ssize_t>(n));
  py::array_t<double> x(static_cast<py::ssize_t>(n)), y(static_cast<py::ssize_t>(n));
  auto pX = X.mutable_data(); auto pY = Y.mutable_data(); auto px = x.mutable_data(); auto py_ = y.mutable_data();
  {
    py::gil_scoped_release release;
    replaySegment(params, rec, [&](std::uint64_t step, const UnitState& z) {
      pX[step] = z.X; pY[step] = z.Y;
      const PhysicalPoint q = map.toPhysical(z);
      px[step] = static_cast<double>(q.x); py_[step] = static_cast<double>(q.y);
    });
  }
  py::dict d;
  d["X"] = X; d["Y"] = Y; d["x"] = x; d["y"] = y;
  return d;
}

}  // namespace

void bindMeasures(py::module_& m);  // bind_measures.cpp
void bindTail(py::module_& m);      // bind_tail.cpp

PYBIND11_MODULE(_archipelago, m) {
  m.doc() = "Archipelago: stickiness of islands around islands in area-preserving maps "
            "(C. F. F. Karney, Long-time correlations in the stochastic regime, Physica D 8, 1983).";
  m.attr("__version__") = ARCHIPELAGO_VERSION;
  // A value of the wrong type met by an explicit cast is a TypeError, not pybind11's RuntimeError ("Unable to
  // cast Python instance…", issue #23).
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::cast_error& e) {
      PyErr_SetString(PyExc_TypeError, e.what());
    } catch (const io::NotEnoughMemory& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    }
  });
  bindManifolds(m);

  // ---- the map (core/map/FixedPointMap.hpp, appendix B) ----
  m.def("map_error", [](double K, double xmin, double xmax) { return mapError({K, xmin, xmax}); },
        py::arg("K"), py::arg("xmin"), py::arg("xmax"),
        "The first violated rule of the box (appendix B: xmin < -sqrt(K), xmax > xmin), or None.");
  m.def("coefficients", [](double K, double xmin, double xmax) {
          const MapCoefficients c = computeCoefficients(mapOf(K, xmin, xmax));
          py::dict d; d["A"] = c.A; d["B"] = c.B; d["C"] = c.C; d["m"] = c.m; return d; },
        py::arg("K") = 0.1, py::arg("xmin") = -0.8, py::arg("xmax") = 0.5,
        "The integers (A, B, C, m) that define the fixed-point map N exactly (appendix B):\n"
        "G(X) = 2^m (floor(A floor(X^2/2^52)/2^52) - floor(B X/2^52) + C), in units of 2^-52.");
  m.def("orbit", [](double K, double xmin, double xmax, py::object x0, py::object y0, py::object X0, py::object Y0,
                    std::uint64_t steps, bool backward) {
          const FixedPointMap map(mapOf(K, xmin, xmax));
          if (steps > (std::uint64_t{1} << 28)) throw std::invalid_argument("steps must be <= 2^28 (arrays in memory)");
          // X, Y (8 bytes each), x, y (8 each) and wrapped (1) per point: 2^28 steps need 8.9 GB (issue #23).
          io::checkMemory((steps + 1) * 33, "orbit(steps=" + std::to_string(steps) + ")");
          UnitState z;
          if (!X0.is_none() || !Y0.is_none()) {
            z.X = unitCoordinate(X0, "X0"); z.Y = unitCoordinate(Y0, "Y0");
          } else {
            if (x0.is_none() || y0.is_none()) throw std::invalid_argument("give x0 and y0 (physical) or X0 and Y0 (unit)");
            const double x = x0.cast<double>(), y = y0.cast<double>();
            if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("x0 and y0 must be finite");
            z = map.toUnit(x, y);
          }
          const auto n = static_cast<py::ssize_t>(steps + 1);
          py::array_t<std::uint64_t> X(n), Y(n);
          py::array_t<double> x(n), y(n);
          py::array_t<bool> wrapped(n);
          auto pX = X.mutable_data(); auto pY = Y.mutable_data(); auto px = x.mutable_data(); auto py_ = y.mutable_data();
          auto pw = wrapped.mutable_data();
          {
            py::gil_scoped_release release;
            for (std::uint64_t i = 0; i <= steps; ++i) {
              if (i > 0) pw[i] = backward ? map.backward(z) : map.forward(z);
              else pw[i] = false;
              pX[i] = z.X; pY[i] = z.Y;
              const PhysicalPoint p = map.toPhysical(z);
              px[i] = static_cast<double>(p.x); py_[i] = static_cast<double>(p.y);
            }
          }
          py::dict d; d["X"] = X; d["Y"] = Y; d["x"] = x; d["y"] = y; d["wrapped"] = wrapped; return d; },
        py::arg("K") = 0.1, py::arg("xmin") = -0.8, py::arg("xmax") = 0.5, py::arg("x0") = py::none(),
        py::arg("y0") = py::none(), py::kw_only(), py::arg("X0") = py::none(), py::arg("Y0") = py::none(),
        py::arg("steps") = 1000, py::arg("backward") = false,
        "An orbit of the exact map N (forward) or N^-1 (backward=True), appendix B, from (x0, y0) in physical\n"
        "coordinates (rounded to the 2^-52 grid) or (X0, Y0) in unit coordinates (integers in [0, 2^52)).\n"
        "Returns a dict of arrays of steps+1 points: X, Y (uint64, units of 2^-52), x, y (physical, x = xmin + L X/2^52,\n"
        "y = -L/2 + L Y/2^52) and wrapped (the step left the box: the trapped segment ends, section 3).");
  m.def("involution", [](const py::object& Xin, const py::object& Yin) {
          const py::array_t<std::uint64_t> X = unitArray(Xin, "X"), Y = unitArray(Yin, "Y");
          if (X.size() != Y.size()) throw std::invalid_argument("X and Y must have the same size");
          py::array_t<std::uint64_t> oX(X.size()), oY(Y.size());
          for (py::ssize_t i = 0; i < X.size(); ++i) {
            UnitState z{X.at(i), Y.at(i)};
            if (z.X >= FixedPointMap::kOne || z.Y >= FixedPointMap::kOne)
              throw std::invalid_argument("X and Y must lie in [0, 2^52) (unit coordinates)");
            FixedPointMap::involution(z);
            oX.mutable_at(i) = z.X; oY.mutable_at(i) = z.Y;
          }
          return py::make_tuple(oX, oY); },
        py::arg("X"), py::arg("Y"),
        "The involution J of appendix B (X <- X - Y + 2^51, Y <- -Y, mod 2^52; J^2 = 1, N^-1 = J N J) on unit arrays.");

  // ---- kernels ----
  m.def("kernels", [] {
          std::vector<std::string> names;
          for (const KernelInfo& k : supportedKernels()) names.emplace_back(k.name);
          return names; },
        "The instruction-set paths this CPU supports (every one gives bit-identical results).");

  // ---- runs (core/run/TrappingRun.hpp, section 3 and appendix B) ----
  py::class_<Run>(m, "Run",
                  "A trapping-statistics run (Karney 1983, section 3, appendix B): M orbits of N^-1 in blocks of q steps,\n"
                  "segments between visits of the randomizing zone 0 <= X <= Xr, lengths in steps.")
      .def_property_readonly("parameters", [](const Run& r) { r.check(); return parametersDict(r.state.params); })
      .def_property_readonly("blocks_done", [](const Run& r) { r.check(); return r.state.blocksDone; })
      .def_property_readonly("finished", [](const Run& r) { r.check(); return r.state.finished(); })
      .def_property_readonly("kernel", [](const Run& r) { r.check(); return r.state.kernel; })
      .def_property_readonly("elapsed_seconds", [](const Run& r) { r.check(); return r.state.elapsedSeconds; })
      .def_property_readonly("orbit_range", [](const Run& r) { r.check(); return py::make_tuple(r.state.orbitBegin, r.state.orbitEnd); })
      .def_property_readonly("coefficients", [](const Run& r) {
          r.check(); const MapCoefficients& c = r.state.coefficients;
          py::dict d; d["A"] = c.A; d["B"] = c.B; d["C"] = c.C; d["m"] = c.m; return d; })
      .def("advance", &advanceRun, py::arg("threads") = 0, py::arg("kernel") = "auto",
           py::arg("progress") = py::none(), py::arg("max_chunk") = 0, py::arg("chunk_seconds") = 0.25,
           py::arg("checkpoint") = py::none(),
           "Computes until finished.  The GIL is released while computing; at each chunk boundary progress(dict) is\n"
           "called and Ctrl-C is checked: KeyboardInterrupt (or an exception of the callback) stops the run after\n"
           "the chunk, the run stays valid and resumable (and is saved to `checkpoint` if given).  Bit-identical\n"
           "results for every kernel and thread count.")
      .def("save", [](const Run& r, const py::object& path) {
          r.check();
          const std::string file = pathArgument(path, "path");
          try { saveRunFile(file, r.state); } catch (const std::exception& e) { raiseOSError(e.what()); } },
           py::arg("path"), "Writes the run file atomically (core/runfile/RunFile.hpp).  OSError on failure.")
      .def("histogram", [](const Run& r, py::object subset) {
          r.check();
          const TrappingHistogram h = subset.is_none() ? r.state.total() : [&] {
            const auto i = subset.cast<std::size_t>();
            if (i >= r.state.subsets.size()) throw std::invalid_argument("subset out of range");
            return r.state.subsets[i]; }();
          const int n = TrappingHistogram::kBins;
          py::array_t<std::uint64_t> counts(n), sums(n), lower(n), upper(n);
          for (int i = 0; i < n; ++i) {
            counts.mutable_at(i) = h.count(i); sums.mutable_at(i) = h.lengthSum(i);
            lower.mutable_at(i) = TrappingHistogram::binLower(i); upper.mutable_at(i) = TrappingHistogram::binUpper(i);
          }
          py::dict d; d["counts"] = counts; d["length_sums"] = sums; d["lower"] = lower; d["upper"] = upper; return d; },
           py::arg("subset") = py::none(),
           "The histogram of segment lengths (blocks of q steps): counts and length sums per bin, bin edges in blocks\n"
           "[lower, upper).  subset=None: the total of the subsets.")
      .def("orbit_states", [](const Run& r) {
          r.check();
          const auto n = static_cast<py::ssize_t>(r.state.orbits.size());
          py::array_t<std::uint64_t> a({n, py::ssize_t{9}});
          for (py::ssize_t i = 0; i < n; ++i) {
            const OrbitState& o = r.state.orbits[static_cast<std::size_t>(i)];
            const std::uint64_t row[9] = {o.z.X, o.z.Y, o.block, o.draws, o.length, o.start.z.X, o.start.z.Y,
                                          o.start.block, o.start.draws};
            for (py::ssize_t j = 0; j < 9; ++j) a.mutable_at(i, j) = row[j];
          }
          return a; },
           "Every orbit's exact state, one row each: X, Y, block, draws, length, start X, start Y, start block, start draws.")
      .def("longest", [](const Run& r) {
          r.check();
          std::vector<std::uint64_t> orbit, length, X, Y, block, draws;
          for (const SegmentRecord& s : r.state.longest.items()) {
            orbit.push_back(s.orbit); length.push_back(s.length * r.state.params.q);
            X.push_back(s.start.z.X); Y.push_back(s.start.z.Y); block.push_back(s.start.block); draws.push_back(s.start.draws);
          }
          py::dict d; d["orbit"] = toArray(orbit); d["length_steps"] = toArray(length); d["X"] = toArray(X);
          d["Y"] = toArray(Y); d["block"] = toArray(block); d["draws"] = toArray(draws); return d; },
           "The longest segments, longest first: orbit, length in steps, exact start state (X, Y, block, draws).")
      .def("replay", [](const Run& r, std::size_t rank) {
          r.check();
          if (rank >= r.state.longest.items().size()) throw std::invalid_argument("rank out of range (longest segments kept: " +
                                                                                   std::to_string(r.state.longest.items().size()) + ")");
          const TrappingParameters params = r.state.params;  // copies: the replay runs without the GIL
          const SegmentRecord record = r.state.longest.items()[rank];
          return replayRecord(params, record); },
           py::arg("rank") = 0,
           "Replays the rank-th longest segment bit for bit: dict of arrays X, Y (unit) and x, y (physical), one point per\n"
           "step of N^-1 (q*length + 1 points).")
      .def("statistics", [](const Run& r, const py::object& shortRun) {
          r.check();
          // With its q = 1 companion (a Run, or the path of its run file): the spliced statistics (issue #26), as
          // `archipelago-cli stats RUN --short SHORT` computes them.  With the GIL: no advance() can run meanwhile.
          std::optional<TrappingState> companion;
          if (!shortRun.is_none()) {
            if (py::isinstance<Run>(shortRun)) {
              const Run& c = shortRun.cast<const Run&>();
              c.check();
              companion = c.state;
            } else {
              companion = loadRunFile(py::str(py::module_::import("os").attr("fspath")(shortRun)).cast<std::string>());
            }
          }
          const TrappingStatistics s = companion ? splicedStatisticsOf(r.state, *companion) : statisticsOf(r.state);
          // D's honest error, as `stats` prints it: the bootstrap over segments (default options), none (NaN)
          // when the longest segments dominate D or there are too few segments to resample.
          double DError = kTailUndefined;
          bool dominated = false;
          std::string verdict;
          if (s.segments > 0) {
            try {
              const TailAnalysis tail = analyseTail(ensembleOf({r.state}));
              DError = supportedDError(tail);
              dominated = tail.dominated();
              verdict = dominanceMessage(tail);
            } catch (const std::invalid_argument& e) {
              verdict = std::string("no error of D: ") + e.what();
            }
          }
          py::dict d;
          // The series under the statistics table's keys (core/stats/StatisticsTable: f_t, p_t, P_t, C_tau, …), the
          // same names as the CSV files' value columns and the sessions'.
          for (const StatisticInfo& info : statisticsTable())
            d[py::str(std::string(info.key))] = seriesDict(seriesOf(s, info.statistic));
          d["alpha"] = s.alpha; d["alpha_error"] = s.alphaError; d["D"] = s.D; d["D_error"] = DError;
          d["D_error_subsets"] = s.DError; d["D_dominated"] = dominated; d["D_verdict"] = verdict;
          d["sum_t_f"] = s.sumTf; d["segments"] = s.segments; d["longest_blocks"] = s.longestBlocks;
          d["blocks_affected_below"] = s.blockAffectedBelow; d["spliced_at"] = s.splicedAt;
          return d; },
           py::arg("short") = py::none(),
           "The statistics of section 3 (core/stats/TrappingStatistics.hpp) under the keys of the statistics table\n"
           "(core/stats/StatisticsTable, the CSV files' names), each series a dict of arrays x, value, error (one-sigma,\n"
           "from the spread over subsets): f_t (per step), p_t = alpha f_t, P_t (eq. pdef), C_tau (eq. cdef),\n"
           "local_exponent (-dlog C/dlog tau, fig. 6d), S_t (eq. spreaddef), S_t_compensated (S_t/t^1.5, fig. 7b), D_t\n"
           "(S_t/2t); scalars alpha (mean segment length, steps) and alpha_error, D (eq. ddef).  D_error is D's one-sigma\n"
           "error where the run supports one, as `archipelago-cli stats` gives it (core supportedDError: the bootstrap\n"
           "over segments), NaN when the longest segments dominate D (D_dominated True; D_verdict says why in words,\n"
           "empty otherwise); D_error_subsets is the paper's error over the subsets, far too small for this heavy tail.\n"
           "short: the run's q = 1 companion (a Run or a run file, e.g. k01.short.json): the spliced statistics, f_t\n"
           "below spliced_at (steps) the companion's (issue #26).  blocks_affected_below: times below it (10 q for a run\n"
           "of q > 1 without its companion, else 0) carry the q-block artefact.  Lengths and times in steps of N.");

  m.def("start", &startRun, py::arg("spec") = py::none(),
        "A fresh run from a run spec (JSON text or dict, format archipelago-spec: core/spec/RunSpec.hpp) and/or keyword\n"
        "parameters K, xmin, xmax, Xr, q, T, M, seed, subsets, longestKept (defaults: the paper's K = 0.1 case, section 5).\n"
        "ValueError with the CLI's message for a bad parameter.");
  m.def("load", [](const py::object& path, bool allowModified) {
          Run r;
          const std::string file = pathArgument(path, "path");
          try { r.state = loadRunFile(file, {allowModified}); }
          catch (const std::exception& e) { raiseOSError(e.what()); }
          return r; },
        py::arg("path"), py::arg("allow_modified") = false,
        "Reads and validates a run file (checksum, consistency).  OSError naming the path for a missing, corrupt or\n"
        "edited file.  A loaded unfinished run resumes with .advance().");
  m.def("merge", [](const Run& a, const Run& b) {
          a.check(); b.check(); Run r; r.state = mergeTrapping(a.state, b.state); return r; },
        py::arg("a"), py::arg("b"),
        "Merges two runs of the same parameters over adjacent orbit ranges (core mergeTrapping).  ValueError if they do not fit.");
  m.def("start_range", [](std::uint64_t begin, std::uint64_t end, const py::object& spec, const py::kwargs& kw) {
          Run r = startRun(spec, kw);
          const TrappingParameters p = r.state.params;
          if (begin >= end || end > p.M) throw std::invalid_argument("orbit range must satisfy 0 <= begin < end <= M");
          r.state = startTrapping(p, begin, end);
          return r; },
        py::arg("begin"), py::arg("end"), py::arg("spec") = py::none(),
        "As start(), over the orbits [begin, end) only: the parts of a run merged with merge().");

  m.def("presets", [] {
          py::dict d;
          for (const Preset& p : presets()) d[py::str(p.id)] = runSpecJson(p.spec);
          return d; },
        "The paper's cases (resources/presets): id -> run spec JSON text, for start(spec).");

  // ---- b2, the area of the stochastic region (core/portrait/StochasticArea.hpp, appendix A) ----
  m.def("stochastic_area", [](double K, double xmin, double xmax, double Xr, std::uint32_t q, std::uint32_t orbits,
                              std::uint64_t seed, std::uint64_t iterations, int gridBits, const std::string& kernel) {
          StochasticAreaRequest r;
          r.map = mapOf(K, xmin, xmax); r.Xr = Xr; r.q = q; r.orbits = orbits; r.seed = seed;
          r.iterations = iterations; r.gridBits = gridBits; r.kernel = &selectKernel(kernel);
          r.firstCheckpoint = std::min<std::uint64_t>(r.firstCheckpoint, iterations);
          if (auto e = validationError(r)) throw std::invalid_argument(*e);
          const StochasticAreaResult res =
              interruptible([&](std::stop_token stop) { return computeStochasticArea(r, {}, stop); });
          std::vector<std::uint64_t> it, boxes; std::vector<double> frac;
          for (const auto& p : res.convergence) { it.push_back(p.iterations); boxes.push_back(p.boxesVisited); frac.push_back(p.b2); }
          const StochasticAreaValue v = stochasticAreaOf(r.map, res.b2());
          const auto side = py::ssize_t{1} << gridBits;
          py::dict d;
          d["fraction"] = v.fraction; d["box_area"] = v.boxArea; d["b2"] = v.area;
          d["iterations"] = toArray(it); d["boxes_visited"] = toArray(boxes); d["fractions"] = toArray(frac);
          d["visited"] = toArray(res.visited).reshape({side, side});
          return d; },
        py::arg("K") = 0.1, py::arg("xmin") = -0.8, py::arg("xmax") = 0.5, py::kw_only(), py::arg("Xr") = 0.02,
        py::arg("q") = 16, py::arg("orbits") = 64, py::arg("seed") = 1, py::arg("iterations") = std::uint64_t{1} << 28,
        py::arg("grid_bits") = 10, py::arg("kernel") = "auto",
        "b2, the area of the stochastic region (appendix A): the fraction of 2^grid_bits x 2^grid_bits boxes visited by\n"
        "randomized orbits, times the box area L^2; with its convergence curve and the visited map (rows = Y boxes).");
  m.def("box_invariant", [](double K, double xmin, double xmax, double fraction, double D, double DError) {
          if (!(fraction >= 0 && fraction <= 1)) throw std::invalid_argument("fraction must lie in [0, 1]");
          if (!std::isfinite(D) || !std::isfinite(DError)) throw std::invalid_argument("D and D_error must be finite");
          const BoxInvariantQuantities b = boxInvariantQuantities(stochasticAreaOf(mapOf(K, xmin, xmax), fraction), D, DError);
          py::dict d; d["b2"] = b.b2.area; d["b2_D"] = b.b2D; d["b2_D_error"] = b.b2DError;
          d["accelerator_factor"] = b.acceleratorFactor; d["enhancement_n1"] = b.enhancementN1; return d; },
        py::arg("K"), py::arg("xmin"), py::arg("xmax"), py::arg("fraction"), py::arg("D"), py::arg("D_error") = 0.0,
        "The b2-scaled, box-independent values (core/stats/StochasticAreaQuantities.hpp): b2 D with its error, the\n"
        "accelerator-mode factor (8/pi^2) b2 and the n = 1 enhancement, from the visited fraction and D of statistics().");

  // ---- the K scan (core/scan, section 5) ----
  m.def("scan_box", [](double K) { const MapParameters b = scanBox(K); return py::make_tuple(b.xmin, b.xmax); },
        py::arg("K"), "The box (xmin, xmax) the K scan of section 5 uses for K in [0, 4].");
  m.def("scan_values", &scanValues, py::arg("start"), py::arg("stop"), py::arg("step"),
        "The K values of a scan: start, start + step, ... up to stop (rounded to 12 significant digits).");
  m.def("scan_point", [](const Run& r, py::object fraction) {
          r.check();
          const TrappingStatistics st = statisticsOf(r.state);
          std::optional<StochasticAreaValue> b2;
          if (!fraction.is_none()) {
            const double f = fraction.cast<double>();
            if (!(f >= 0 && f <= 1)) throw std::invalid_argument("fraction must lie in [0, 1]");
            b2 = stochasticAreaOf(r.state.params.map, f);
          }
          const ScanPoint p = scanPointOf(r.state, st, b2);
          py::dict d;
          d["K"] = p.K; d["xmin"] = p.box.xmin; d["xmax"] = p.box.xmax; d["blocks_done"] = p.blocksDone;
          d["blocks_total"] = p.blocksTotal; d["segments"] = p.segments; d["D"] = p.D; d["D_error"] = p.DError;
          d["D_error_subsets"] = st.DError; d["longest_steps"] = p.longestSteps; d["long_fraction"] = p.longFraction;
          if (p.boxInvariant) { d["b2"] = p.boxInvariant->b2.area; d["b2_D"] = p.boxInvariant->b2D;
                                d["b2_D_error"] = p.boxInvariant->b2DError; }
          return d; },
        py::arg("run"), py::arg("fraction") = py::none(),
        "The K scan's summary of one run (section 5): D, the longest segment, the fraction of time in segments of at\n"
        "least 10^4 steps, and b2 D when the visited fraction of stochastic_area() is given.  D_error (and b2_D_error):\n"
        "the supported error of statistics(), NaN when the longest segments dominate D; D_error_subsets: the subsets'.");

  // ---- the Markov model of appendix C (core/markov/MarkovModel.hpp) ----
  m.def("markov", [](std::vector<std::int64_t> lengths, std::int64_t points, std::int64_t tauMax, double h0) {
          markov::MarkovModel model{std::move(lengths), points};
          markov::validate(model);
          if (!std::isfinite(h0)) throw std::invalid_argument("h0 must be finite");
          if (tauMax < 0) throw std::invalid_argument("tau_max must be >= 0");
          const markov::LumpedObservable h = markov::paperObservable(model, h0);
          py::dict d;
          std::vector<double> C, Cis, eps;
          double D = 0, Dmark = 0, Dis = 0;
          {
            py::gil_scoped_release release;
            C = markov::correlation(model, h, tauMax);
            Cis = markov::islandCorrelation(model, tauMax, h0);
            eps = markov::correlationDeviation(model, h, tauMax, h0);
            D = markov::diffusionCoefficient(model, h);
            Dmark = markov::diffusionCoefficientDmark(model, h);
            Dis = markov::islandDiffusionCoefficient(model, h0);
          }
          d["C"] = toArray(C); d["C_is"] = toArray(Cis); d["epsilon"] = toArray(eps);
          d["D"] = D; d["D_dmark"] = Dmark; d["D_is"] = Dis;
          return d; },
        py::arg("segment_lengths"), py::arg("points"), py::kw_only(), py::arg("tau_max") = 100, py::arg("h0") = 1.0,
        "The Markov model of appendix C: N points, trapped segments of lengths m_k, the paper's observable (h0 on the\n"
        "trapped points): C(tau) for tau = 0..tau_max (eq. cmark), the island term C_is, epsilon = (C - C_is)/C_is(0),\n"
        "and D by the lumped solve, by eq. (dmark), and D_is.");

  // ---- theory (core/theory/SmallKTheory.hpp, section 4) ----
  m.def("segment_shape", py::vectorize([](double t, double K) { checkShapeArguments(t, K); return smallk::segmentShape(t, K); }), py::arg("t"), py::arg("K"),
        "The small-K theory's shape of f_t (section 4; t in steps), up to its amplitude.");
  m.def("correlation_shape", py::vectorize([](double tau, double K) { checkShapeArguments(tau, K); return smallk::correlationShape(tau, K); }),
        py::arg("tau"), py::arg("K"), "The small-K theory's shape of C_tau (section 4; tau in steps), up to its amplitude.");

  // ---- periodic orbits and island chains (core/periodic) ----
  m.def("periodic_orbit", [](double K, int period, double x, double y, double radius, bool stableOnly) {
          if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("near must be finite");
          PeriodicOrbitSearch s;
          s.period = period; s.near = {x, y}; s.searchRadius = radius; s.stableOnly = stableOnly;
          validate(K, s);
          try {
            return periodicOrbitDict(interruptible([&](std::stop_token stop) { return findPeriodicOrbit(K, s, stop); }));
          } catch (const OperationStopped&) {
            throw;  // unreachable: a stop comes with a KeyboardInterrupt, raised first
          } catch (const std::runtime_error& e) {
            throw std::invalid_argument(e.what());
          } },
        py::arg("K"), py::arg("period"), py::arg("x"), py::arg("y"), py::arg("radius") = 0.01,
        py::arg("stable_only") = false,
        "The periodic orbit of Q of minimal period n nearest to (x, y): points, Greene's residue R = (2 - trace)/4,\n"
        "stability, rotation number W/n (clockwise turns about (-sqrt K, 0)).  ValueError when none is found.");
  m.def("island_chain", [](double K, py::array_t<double> x, py::array_t<double> y) {
          if (x.size() != y.size()) throw std::invalid_argument("x and y must have the same size");
          std::vector<PhysicalPoint> pts(static_cast<std::size_t>(x.size()));
          for (py::ssize_t i = 0; i < x.size(); ++i) pts[static_cast<std::size_t>(i)] = {x.at(i), y.at(i)};
          IslandChain c;
          { py::gil_scoped_release release; c = identifyIslandChain(K, pts); }
          py::dict d;
          d["period"] = c.period; d["hierarchy"] = c.hierarchy;
          std::vector<double> spreads(c.spreads.begin(), c.spreads.end());
          d["spreads"] = spreads;
          d["member"] = py::make_tuple(static_cast<double>(c.member.x), static_cast<double>(c.member.y));
          d["winding_turns"] = c.windingTurns; d["rotation_number"] = static_cast<double>(c.rotationNumber);
          d["centre"] = c.centre ? py::object(periodicOrbitDict(*c.centre)) : py::none();
          return d; },
        py::arg("K"), py::arg("x"), py::arg("y"),
        "The island chain a segment (consecutive iterates of Q, physical x, y) sticks to (core/periodic/IslandChain.hpp).\n"
        "Note: a replayed segment is of N^-1; reverse it (x[::-1], y[::-1]) for iterates of Q.");

  // ---- portraits (core/portrait/PortraitRenderer.hpp, fig. 1) ----
  m.def("portrait", [](double K, double xmin, double xmax, const std::string& mode, int width, int height,
                       std::uint64_t points, std::uint32_t orbits, std::uint64_t seed, double Xr, std::uint32_t q,
                       const std::string& kernel) {
          PortraitRequest r;
          r.map = mapOf(K, xmin, xmax);
          const auto pm = parsePortraitMode(mode);
          if (!pm) throw std::invalid_argument("mode must be density, orbits or stickiness, not " + mode);
          r.mode = *pm; r.width = width; r.height = height; r.points = points; r.orbits = orbits; r.seed = seed;
          r.Xr = Xr; r.q = q; r.passes = 1;
          r.kernel = &selectKernel(kernel);
          if (auto e = validationError(r)) throw std::invalid_argument(*e);
          const PortraitResult res = interruptible([&](std::stop_token stop) { return renderPortrait(r, {}, stop); });
          const PortraitRaster& ras = res.raster;
          py::dict d;
          auto shaped = [&](auto arr) { return arr.reshape({py::ssize_t{ras.height}, py::ssize_t{ras.width}}); };
          if (!ras.counts.empty()) d["counts"] = shaped(toArray(ras.counts));
          if (!ras.labels.empty()) d["labels"] = shaped(toArray(ras.labels));
          if (!ras.lengthSums.empty()) d["mean_length"] = shaped(toArray(ras.meanSegmentLengths()));
          d["points_iterated"] = ras.pointsIterated; d["points_binned"] = ras.pointsBinned;
          return d; },
        py::arg("K") = 0.1, py::arg("xmin") = -0.8, py::arg("xmax") = 0.5, py::kw_only(), py::arg("mode") = "density",
        py::arg("width") = 512, py::arg("height") = 512, py::arg("points") = 20'000'000, py::arg("orbits") = 256,
        py::arg("seed") = 1, py::arg("Xr") = 0.02, py::arg("q") = 16, py::arg("kernel") = "auto",
        "A portrait of the whole box (fig. 1): mode density (visits, counts), orbits (labels of seed orbits) or\n"
        "stickiness (mean trapped-segment length in steps per pixel); arrays of shape (height, width), row 0 at the top.");

  bindMeasures(m);  // rotation numbers, island chains, indicator maps (core/measures)
  bindTail(m);      // the tail of P_t beyond brute force (core/tail)
}
