// The tail of P_t beyond brute force (core/tail, issue #29) as NumPy arrays: the same sampler as archipelago-cli's
// `tail`, the same tail files.  No maths here.  The computation releases the GIL and stops at the next chunk on
// Ctrl-C (KeyboardInterrupt), saving the resumable state to `out` when one was given.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/spec/RunSpec.hpp"
#include "core/tail/TailFile.hpp"

namespace py = pybind11;
using namespace archipelago;

namespace {

[[noreturn]] void raiseOSError(const std::string& message) {
  PyErr_SetString(PyExc_OSError, message.c_str());
  throw py::error_already_set();
}

// A tail file read with the GIL released; OSError naming the path for a missing, corrupt or edited file.
TailState loadOrRaise(const std::string& path) {
  std::string error;
  TailState s;
  {
    py::gil_scoped_release release;
    try {
      s = loadTailFile(path);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!error.empty()) raiseOSError(error);
  return s;
}

// OSError now when `path` cannot be written (a missing folder, a read-only file), not after the computation.
void checkWritable(const std::string& path) {
  try {
    io::checkWritableTarget(path);
  } catch (const std::exception& e) {
    raiseOSError(e.what());
  }
}

template <class T>
py::array_t<T> array(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// A path: str or os.PathLike, not empty, no NUL (as every path of the module).
std::string pathOf(const py::object& path, const char* name) {
  if (path.is_none() || !(py::isinstance<py::str>(path) || py::hasattr(path, "__fspath__")))
    throw py::type_error(std::string(name) + " must be a path (str or os.PathLike)");
  const py::object text = py::module_::import("os").attr("fspath")(path);
  if (!py::isinstance<py::str>(text)) throw py::type_error(std::string(name) + " must be a text path, not bytes");
  const std::string s = text.cast<std::string>();
  if (s.empty() || s.find('\0') != std::string::npos)
    throw std::invalid_argument(std::string(name) + " must be a non-empty path without NUL characters");
  return s;
}

// A whole number given as int or as a float such as 1e7; a bool, NaN, a fraction or a negative value is refused.
std::uint64_t wholeOf(const py::handle& v, const char* name) {
  if (py::isinstance<py::bool_>(v) || !(py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)))
    throw py::type_error(std::string(name) + " must be a whole number");
  if (py::isinstance<py::int_>(v)) {
    const py::int_ i = py::reinterpret_borrow<py::int_>(v);
    if (i < py::int_(0) || i > py::int_(UINT64_MAX)) throw std::invalid_argument(std::string(name) + " must be >= 0");
    return i.cast<std::uint64_t>();
  }
  const double d = v.cast<double>();
  if (!(std::isfinite(d) && d >= 0 && d == std::floor(d) && d < 1.8e19))
    throw std::invalid_argument(std::string(name) + " = " + std::string(py::str(v)) + " must be a whole number >= 0");
  return static_cast<std::uint64_t>(d);
}

py::dict resultDict(const TailState& s) {
  const TailResult r = tailResult(s);
  std::vector<double> t, P, PError, steps;
  std::vector<std::uint64_t> survivors, ancestors, fewest, population;
  std::vector<bool> reliable;
  for (const TailLevelResult& L : r.levels) {
    t.push_back(L.t);
    P.push_back(L.P);
    PError.push_back(L.PError);
    steps.push_back(L.steps);
    survivors.push_back(L.survivors);
    ancestors.push_back(L.ancestors);
    fewest.push_back(L.fewestAncestors);
    population.push_back(L.population);
    reliable.push_back(L.reliable);
  }
  py::array_t<bool> rel(static_cast<py::ssize_t>(reliable.size()));
  for (std::size_t i = 0; i < reliable.size(); ++i) rel.mutable_data()[i] = reliable[i];
  py::dict d;
  d["t"] = array(t);
  d["P"] = array(P);
  d["P_error"] = array(PError);
  d["survivors"] = array(survivors);
  d["ancestors"] = array(ancestors);
  d["fewest_ancestors"] = array(fewest);
  d["population"] = array(population);
  d["reliable"] = rel;
  d["steps"] = array(steps);
  std::vector<double> et, from, to, gamma, gammaError;
  for (const TailExponent& e : r.exponents) {
    et.push_back(e.t);
    from.push_back(e.tFrom);
    to.push_back(e.tTo);
    gamma.push_back(e.gamma);
    gammaError.push_back(e.gammaError);
  }
  py::dict ex;
  ex["t"] = array(et);
  ex["t_from"] = array(from);
  ex["t_to"] = array(to);
  ex["gamma"] = array(gamma);
  ex["gamma_error"] = array(gammaError);
  d["exponents"] = ex;
  d["total_steps"] = r.steps;
  d["finished"] = r.finished;
  d["largest_reliable_t"] = largestReliableT(r);
  std::vector<double> levels;
  for (const std::uint64_t L : s.levels) levels.push_back(static_cast<double>(L * s.request.run.q));
  d["level_t"] = array(levels);
  return d;
}

// Runs the sampler with the GIL released; between chunks the observer takes the GIL to check for Ctrl-C and call
// progress(dict).  A pending Python exception stops the sampler at a consistent point: the state is saved to `out`
// (when given) and the exception raised.
py::dict runAndReport(TailState state, int threads, const std::string& kernelName, const py::object& progress,
                      const std::optional<std::string>& out) {
  if (threads < 0 || threads > kMaxThreads)
    throw std::invalid_argument("threads = " + std::to_string(threads) + " must lie in [0, " + std::to_string(kMaxThreads) + "]");
  TailRunOptions options;
  options.threads = threads;
  options.kernel = &selectKernel(kernelName);
  std::stop_source stopper;
  py::object type, value, trace;
  bool failed = false;
  const auto observer = [&](const TailState&, const TailProgress& p) {
    py::gil_scoped_acquire gil;
    if (failed) return;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (!progress.is_none()) {
        py::dict d;
        d["level"] = p.level;
        d["levels"] = p.levels;
        d["t"] = p.t;
        d["fraction"] = p.fraction;
        d["steps"] = p.steps;
        d["steps_per_second"] = p.stepsPerSecond;
        d["alive"] = p.alive;
        progress(d);
      }
    } catch (py::error_already_set& e) {
      failed = true;
      e.restore();
      PyObject *t, *v, *tb;
      PyErr_Fetch(&t, &v, &tb);
      type = py::reinterpret_steal<py::object>(t);
      value = py::reinterpret_steal<py::object>(v);
      trace = py::reinterpret_steal<py::object>(tb);
      stopper.request_stop();
    }
  };
  std::string saveError;
  {
    py::gil_scoped_release release;
    state = runTail(std::move(state), options, observer, stopper.get_token());
    if (out) {
      try {
        saveTailFile(*out, state);
      } catch (const std::exception& e) {
        saveError = e.what();
      }
    }
  }
  if (!saveError.empty()) {
    raiseOSError(saveError);
  }
  if (failed) {
    PyErr_Restore(type.release().ptr(), value.release().ptr(), trace.release().ptr());
    throw py::error_already_set();
  }
  return resultDict(state);
}

}  // namespace

void bindTail(py::module_& m) {
  m.def(
      "tail",
      [](double K, double xmin, double xmax, double Xr, const py::object& q, const py::object& seed,
         const py::object& population, const py::object& replicas, const py::object& first, const py::object& tMax,
         const py::object& levelBins, const py::object& epsilon, const std::string& clones,
         const py::object& metropolisSteps, const py::object& warmup, const py::object& minAncestors, int threads,
         const std::string& kernel, const py::object& progress, const py::object& out) {
        TailRequest r;
        r.run.map = {K, xmin, xmax};
        r.run.Xr = Xr;
        const auto narrow = [](std::uint64_t v, const char* name) {
          if (v > UINT32_MAX) throw std::invalid_argument(std::string(name) + " is out of range");
          return static_cast<std::uint32_t>(v);
        };
        r.run.q = narrow(wholeOf(q, "q"), "q");
        r.run.seed = wholeOf(seed, "seed");
        r.population = narrow(wholeOf(population, "population"), "population");
        r.replicas = narrow(wholeOf(replicas, "replicas"), "replicas");
        r.firstSteps = wholeOf(first, "first");
        r.maxSteps = wholeOf(tMax, "t_max");
        r.binsPerLevel = narrow(wholeOf(levelBins, "level_bins"), "level_bins");
        r.epsilon = wholeOf(epsilon, "epsilon");
        const auto rule = cloneRuleByName(clones);
        if (!rule) throw std::invalid_argument("clones must be 'perturb' or 'metropolis'");
        r.clones = *rule;
        r.metropolisSteps = narrow(wholeOf(metropolisSteps, "metropolis_steps"), "metropolis_steps");
        r.warmupBlocks = wholeOf(warmup, "warmup");
        r.minAncestors = wholeOf(minAncestors, "min_ancestors");
        if (auto e = tailRequestError(r)) throw std::invalid_argument(*e);
        const std::optional<std::string> path = out.is_none() ? std::nullopt : std::optional(pathOf(out, "out"));
        if (path) checkWritable(*path);  // before the work, not after it
        return runAndReport(startTail(r), threads, kernel, progress, path);
      },
      py::arg("K") = 0.1, py::arg("xmin") = -0.8, py::arg("xmax") = 0.5, py::arg("Xr") = 0.02, py::arg("q") = 16,
      py::arg("seed") = 1, py::arg("population") = 200, py::arg("replicas") = 4, py::arg("first") = 1000,
      py::arg("t_max") = 10'000'000, py::arg("level_bins") = 10, py::arg("epsilon") = 1'000'000, py::arg("clones") = "perturb",
      py::arg("metropolis_steps") = 1, py::arg("warmup") = 64, py::arg("min_ancestors") = kDefaultMinAncestors,
      py::arg("threads") = 0, py::arg("kernel") = "", py::arg("progress") = py::none(), py::arg("out") = py::none(),
      "P_t beyond brute force by splitting on the age of trapped segments, for the process of a run with these\n"
      "parameters (archipelago-cli tail; docs/tail.md).  Returns a dict of arrays per level: t (steps), P, P_error,\n"
      "survivors, ancestors, fewest_ancestors, population, reliable, steps; 'exponents' (the local exponent\n"
      "-dlnP/dlnt between neighbouring reliable levels: t, t_from, t_to, gamma, gamma_error); total_steps, finished,\n"
      "largest_reliable_t, level_t.  out: a tail file written at the end (or when stopped by Ctrl-C), which\n"
      "tail_resume() continues bit for bit.");
  m.def(
      "tail_resume",
      [](const py::object& path, int threads, const std::string& kernel, const py::object& progress,
         const py::object& out) {
        const std::string in = pathOf(path, "path");
        TailState s = loadOrRaise(in);
        if (s.finished()) throw std::invalid_argument(in + " is already finished");
        const std::string target = out.is_none() ? in : pathOf(out, "out");
        checkWritable(target);
        return runAndReport(std::move(s), threads, kernel, progress, target);
      },
      py::arg("path"), py::arg("threads") = 0, py::arg("kernel") = "", py::arg("progress") = py::none(),
      py::arg("out") = py::none(),
      "Continues the sampler run of a tail file (to `out`, default: the same file); returns what tail() returns.");
  m.def(
      "load_tail",
      [](const py::object& path) {
        return resultDict(loadOrRaise(pathOf(path, "path")));
      },
      py::arg("path"), "The results of a tail file (finished or not), as tail() returns them.");
}
