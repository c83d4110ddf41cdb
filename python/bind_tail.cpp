// The tail of P_t beyond brute force (core/tail, issue #29) as NumPy arrays: the same sampler as archipelago-cli's
// `tail`, the same tail files.  No maths here.  The computation releases the GIL and stops at the next chunk on
// Ctrl-C (KeyboardInterrupt), saving the resumable state to `out` when one was given.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/runspec/RunSpec.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailJob.hpp"
#include "core/tail/TailPlan.hpp"
#include "python/Conversions.hpp"
#include "python/Interruption.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

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

// Python's name of a setting core names by its role: the keyword ("compare-csv" → compare_csv).
std::string keywordOf(std::string_view role) {
  std::string keyword(role);
  for (char& c : keyword) c = c == '-' ? '_' : c;
  return keyword;
}

// A whole number of the request (an int, or a float such as 1e7: wholeArgument) that fits its field.
std::uint64_t whole64(const py::object& v, const char* name) { return unsignedArgument(v, name, UINT64_MAX, "[0, 2^64)"); }
std::uint32_t whole32(const py::object& v, const char* name) {
  return static_cast<std::uint32_t>(unsignedArgument(v, name, UINT32_MAX, "[0, 2^32)"));
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
  d["t"] = toArray(t);
  d["P"] = toArray(P);
  d["P_error"] = toArray(PError);
  d["survivors"] = toArray(survivors);
  d["ancestors"] = toArray(ancestors);
  d["fewest_ancestors"] = toArray(fewest);
  d["population"] = toArray(population);
  d["reliable"] = rel;
  d["steps"] = toArray(steps);
  std::vector<double> et, from, to, gamma, gammaError;
  for (const TailExponent& e : r.exponents) {
    et.push_back(e.t);
    from.push_back(e.tFrom);
    to.push_back(e.tTo);
    gamma.push_back(e.gamma);
    gammaError.push_back(e.gammaError);
  }
  py::dict ex;
  ex["t"] = toArray(et);
  ex["t_from"] = toArray(from);
  ex["t_to"] = toArray(to);
  ex["gamma"] = toArray(gamma);
  ex["gamma_error"] = toArray(gammaError);
  d["exponents"] = ex;
  d["total_steps"] = r.steps;
  d["finished"] = r.finished;
  d["largest_reliable_t"] = largestReliableT(r);
  std::vector<double> levels;
  for (const std::uint64_t L : s.levels) levels.push_back(static_cast<double>(L * s.request.run.q));
  d["level_t"] = toArray(levels);
  return d;
}

// Runs the sampler on a worker thread with the GIL released, this thread checking for Ctrl-C every 50 ms; between
// chunks the observer takes the GIL to call progress(dict).  A pending Python exception stops the sampler at a consistent point: the state is saved to `out`
// (when given) and the exception raised.
py::dict runAndReport(TailState state, int threads, const std::string& kernelName, const py::object& progress,
                      const std::optional<std::string>& out) {
  if (auto e = threadsError(threads)) throw std::invalid_argument(*e);
  TailRunOptions options;
  options.threads = threads;
  options.kernel = &selectKernel(kernelName);
  Interruption interruption;
  const auto observer = [&](const TailState&, const TailProgress& p) {
    interruption.check(progress, [&] {
      py::dict d;
      d["level"] = p.level;
      d["levels"] = p.levels;
      d["t"] = p.t;
      d["fraction"] = p.fraction;
      d["steps"] = p.steps;
      d["steps_per_second"] = p.stepsPerSecond;
      d["alive"] = p.alive;
      return d;
    });
  };
  // Core's tail job (core/tail/TailJob.hpp), as the CLI runs it.  Saved (when `out` is given) before the exception
  // that stopped the sampler is raised: the state is resumable; a failing write rescues it and says where.
  std::string saveError;
  state = interruption.withoutGilPolled([&](std::stop_token stop) {
    TailJobOptions job;
    job.run = options;
    LastCheckpoint last;
    TailState done = runTailJob(std::move(state), job, last, observer, stop);
    if (out) {
      try {
        saveTailOrSayWhere(*out, done, last);
      } catch (const std::exception& e) {
        saveError = e.what();
      }
    }
    return done;
  });
  if (!saveError.empty()) raiseOSError(saveError);
  interruption.raisePending();
  return resultDict(state);
}

// The CLI's plan (core/tail/TailPlan.hpp) filled with tail()'s arguments and Python's names: the same checks, in the
// same order and words.
TailPlanOptions pythonPlan(const TailRequest& r, const std::string& clones, int threads,
                           const std::optional<std::string>& path, const py::object& slice) {
  TailPlanOptions plan;
  plan.optionName = keywordOf;
  plan.request = r;
  plan.clones = clones;
  plan.spec = [run = r.run, threads] {
    RunSpec spec;
    spec.parameters = run;
    spec.threads = threads;
    return spec;
  };
  plan.threads = threads;
  plan.out = path.value_or(std::string());
  if (!slice.is_none()) {
    if (!py::isinstance<py::tuple>(slice) || py::len(slice) != 2)
      throw py::type_error("slice must be a tuple (i, n): slice i of n of the replicas");
    const py::tuple in = slice.cast<py::tuple>();
    plan.slice = replicaSlice(r.replicas, whole32(in[0], "slice i"), whole32(in[1], "slice n"));
  }
  return plan;
}

}  // namespace

// The defaults are the request's own (issue 35: a front end restates no default).
const TailRequest kTail{};

void bindTail(py::module_& m) {
  m.def(
      "tail",
      [](double K, double xmin, double xmax, double Xr, const py::object& q, const py::object& seed,
         const py::object& population, const py::object& replicas, const py::object& first, const py::object& tMax,
         const py::object& levelBins, const py::object& epsilon, const std::string& clones,
         const py::object& metropolisSteps, const py::object& warmup, const py::object& minAncestors, int threads,
         const std::string& kernel, const py::object& progress, const py::object& out, const py::object& slice) {
        TailRequest r;
        r.run.map = {K, xmin, xmax};
        r.run.Xr = Xr;
        r.run.q = whole32(q, "q");
        r.run.seed = whole64(seed, "seed");
        r.population = whole32(population, "population");
        r.replicas = whole32(replicas, "replicas");
        r.firstSteps = whole64(first, "first");
        r.maxSteps = whole64(tMax, "t_max");
        r.binsPerLevel = whole32(levelBins, "level_bins");
        r.epsilon = whole64(epsilon, "epsilon");
        r.metropolisSteps = whole32(metropolisSteps, "metropolis_steps");
        r.warmupBlocks = whole64(warmup, "warmup");
        r.minAncestors = whole64(minAncestors, "min_ancestors");
        const std::optional<std::string> path = out.is_none() ? std::nullopt : std::optional(pathArgument(out, "out"));
        if (path) checkWritable(*path);  // before the work, not after it
        TailPlan planned = planTail(pythonPlan(r, clones, threads, path, slice));
        warnIfBoxCutsIsland(r.run.map, r.run.Xr);
        return runAndReport(std::move(planned.state), threads, kernel, progress, path);
      },
      py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin, py::arg("xmax") = kDefaultMap.xmax, py::arg("Xr") = kTail.run.Xr,
      py::arg("q") = kTail.run.q, py::arg("seed") = kTail.run.seed, py::arg("population") = kTail.population,
      py::arg("replicas") = kTail.replicas, py::arg("first") = kTail.firstSteps, py::arg("t_max") = kTail.maxSteps,
      py::arg("level_bins") = kTail.binsPerLevel, py::arg("epsilon") = kTail.epsilon,
      py::arg("clones") = cloneRuleName(kTail.clones), py::arg("metropolis_steps") = kTail.metropolisSteps,
      py::arg("warmup") = kTail.warmupBlocks, py::arg("min_ancestors") = kTail.minAncestors,
      py::arg("threads") = 0, py::arg("kernel") = "", py::arg("progress") = py::none(), py::arg("out") = py::none(),
      py::arg("slice") = py::none(),
      "P_t beyond brute force by splitting on the age of trapped segments, for the process of a run with these\n"
      "parameters (archipelago-cli tail; docs/tail.md).  Returns a dict of arrays per level: t (steps), P, P_error,\n"
      "survivors, ancestors, fewest_ancestors, population, reliable, steps; 'exponents' (the running exponent\n"
      "gamma(t) = -dlnP/dlnt over decade windows, as stats defines it: t, t_from, t_to, gamma, gamma_error); total_steps, finished,\n"
      "largest_reliable_t, level_t.  out: a tail file written at the end (or when stopped by Ctrl-C), which\n"
      "tail_resume() continues bit for bit.  slice=(i, n): only slice i of n of the replicas, [R*i/n, R*(i+1)/n)\n"
      "(archipelago-cli tail --slice); merge_tails() joins the slices' files into the whole run's, bit for bit.");
  m.def(
      "tail_resume",
      [](const py::object& path, int threads, const std::string& kernel, const py::object& progress,
         const py::object& out) {
        const std::string in = pathArgument(path, "path");
        TailState s = loadOrRaise(in);
        if (s.finished()) throw std::invalid_argument(in + " is already finished");
        const std::string target = out.is_none() ? in : pathArgument(out, "out");
        checkWritable(target);
        return runAndReport(std::move(s), threads, kernel, progress, target);
      },
      py::arg("path"), py::arg("threads") = 0, py::arg("kernel") = "", py::arg("progress") = py::none(),
      py::arg("out") = py::none(),
      "Continues the sampler run of a tail file (to `out`, default: the same file); returns what tail() returns.");
  m.def(
      "merge_tails",
      [](const py::list& paths, const py::object& out) {
        std::vector<TailState> slices;
        for (const py::handle& p : paths) slices.push_back(loadOrRaise(pathArgument(py::reinterpret_borrow<py::object>(p), "paths")));
        const std::string target = pathArgument(out, "out");
        checkWritable(target);
        const TailState merged = mergeTailSlices(std::move(slices));
        try {
          saveTailFile(target, merged);
        } catch (const std::exception& e) {
          raiseOSError(e.what());
        }
        return resultDict(merged);
      },
      py::arg("paths"), py::arg("out"),
      "Joins the tail files of the slices of one sampler run (tail(slice=(i, n)), archipelago-cli tail --slice) into\n"
      "the whole run's tail file `out`, bit for bit (archipelago-cli merge); returns what tail() returns.");
  m.def(
      "load_tail",
      [](const py::object& path) {
        return resultDict(loadOrRaise(pathArgument(path, "path")));
      },
      py::arg("path"), "The results of a tail file (finished or not), as tail() returns them.");
}
