// The tail sampler scanned over K (core/tail/TailScan.hpp, issue 55) as NumPy arrays: the same job as
// archipelago-cli's `tail-scan`, the same folder of tail files.  No maths here.  The scan runs without the GIL and
// stops at the next chunk on Ctrl-C (KeyboardInterrupt), the running K's checkpoint left in its file.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <string_view>
#include <vector>

#include "core/io/NumberText.hpp"
#include "core/tail/TailScan.hpp"
#include "python/Conversions.hpp"
#include "python/Interruption.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

// Python's name of a setting core names by its role: the keyword ("checkpoint-interval" → checkpoint_interval,
// "dir" → directory).
std::string keywordOf(std::string_view role) {
  if (role == "dir") return "directory";
  std::string keyword(role);
  for (char& c : keyword) c = c == '-' ? '_' : c;
  return keyword;
}

// The K list as core's one reader takes it: a text as given, or a sequence of numbers each by its shortest text.
std::string kListText(const py::object& K) {
  if (py::isinstance<py::str>(K)) return K.cast<std::string>();
  if (!py::isinstance<py::sequence>(K)) throw py::type_error("K must be a text (\"0.1,0.15\", \"0.05:0.3:0.05\") or a sequence of numbers");
  std::string text;
  for (const py::handle k : K) text += (text.empty() ? "" : ",") + io::shortestText(realArgument(k, "K"));
  return text;
}

// A (K, n) array of `of(k, i)` for every K and every i < n.
template <class T, class F>
py::array_t<T> table(std::size_t count, std::size_t n, F&& of) {
  std::vector<T> v;
  for (std::size_t k = 0; k < count; ++k)
    for (std::size_t i = 0; i < n; ++i) v.push_back(of(k, i));
  return toArray(v, static_cast<py::ssize_t>(count), static_cast<py::ssize_t>(n));
}

py::dict summaryDict(const TailScanSummary& s) {
  const std::size_t nK = s.K.size(), levels = s.results.front().levels.size(), windows = s.windows.size();
  std::vector<double> t, from, to, mid, mean, spread, error;
  std::vector<std::uint64_t> count;
  for (const TailLevelResult& L : s.results.front().levels) t.push_back(L.t);
  for (const TailScanWindow& a : s.average) {
    from.push_back(a.from);
    to.push_back(a.to);
    mid.push_back(a.t);
    mean.push_back(a.mean);
    spread.push_back(a.spread);
    error.push_back(a.error);
    count.push_back(a.count);
  }
  py::dict d;
  d["K"] = toArray(s.K);
  d["t"] = toArray(t);
  d["P"] = table<double>(nK, levels, [&](std::size_t k, std::size_t i) { return s.results[k].levels[i].P; });
  d["P_error"] = table<double>(nK, levels, [&](std::size_t k, std::size_t i) { return s.results[k].levels[i].PError; });
  d["reliable"] = table<bool>(nK, levels, [&](std::size_t k, std::size_t i) { return s.results[k].levels[i].reliable; });
  d["t_from"] = toArray(from);
  d["t_to"] = toArray(to);
  d["t_window"] = toArray(mid);
  d["gamma"] = table<double>(nK, windows, [&](std::size_t k, std::size_t w) { return s.gamma[k][w].gamma; });
  d["gamma_error"] = table<double>(nK, windows, [&](std::size_t k, std::size_t w) { return s.gamma[k][w].gammaError; });
  d["gamma_mean"] = toArray(mean);
  d["gamma_spread"] = toArray(spread);
  d["gamma_mean_error"] = toArray(error);
  d["K_count"] = toArray(count);
  std::vector<double> outK;
  py::list reasons;
  for (const TailScanRefusal& k : s.outOfReach) {
    outK.push_back(k.K);
    reasons.append(k.reason);
  }
  d["out_of_reach_K"] = toArray(outK);
  d["out_of_reach_reason"] = reasons;
  return d;
}

// The scan on a worker thread without the GIL, this thread checking for Ctrl-C every 50 ms; progress(dict) between
// chunks.  A pending exception stops the running K at a consistent point, saved in its file, then is raised.  Core's
// warnings about a K's box are kept and given as RuntimeWarning once the scan has returned (this thread holds the GIL).
py::dict runScan(TailScanRequest request, const py::object& progress) {
  Interruption interruption;
  std::vector<std::string> warnings;
  request.warning = [&warnings](const std::string& w) { warnings.push_back(w); };
  TailScanView view;
  view.progress = [&](std::size_t index, double K, const TailState&, const TailProgress& p) {
    interruption.check(progress, [&] {
      py::dict d;
      d["index"] = index;
      d["K"] = K;
      d["level"] = p.level;
      d["levels"] = p.levels;
      d["t"] = p.t;
      d["steps"] = p.steps;
      return d;
    });
  };
  const TailScanOutcome outcome = interruption.withoutGilPolled([&](std::stop_token stop) {
    OneProcess process;
    return runTailScan(request, view, process, stop);
  });
  for (const std::string& w : warnings)
    if (PyErr_WarnEx(PyExc_RuntimeWarning, w.c_str(), 1) != 0) throw py::error_already_set();
  interruption.raisePending();
  if (outcome.end == TailScanOutcome::End::interrupted)
    throw std::runtime_error("the scan stopped: " + outcome.checkpoint + " holds the checkpoint");
  if (outcome.end == TailScanOutcome::End::waiting) {
    py::dict d;
    d["K"] = toArray(outcome.K);
    d["waiting_for"] = toArray(outcome.waitingFor);
    return d;
  }
  return summaryDict(outcome.summary);
}

}  // namespace

// The defaults are the request's own (issue 35: a front end restates no default).
namespace {
const TailRequest kScanTail{};
const TrappingParameters kScanRun{};
}  // namespace

void bindTailScan(py::module_& m) {
  m.def(
      "tail_scan",
      [](const py::object& K, const py::object& directory, const py::object& tMax, const py::object& population,
         const py::object& replicas, const py::object& first, const py::object& seed, const py::object& q, double Xr,
         const py::object& minAncestors, const std::string& clones, int threads, const std::string& kernel,
         double checkpointInterval, const py::object& task, const py::object& csv, const py::object& progress) {
        TailScanRequest r;
        r.optionName = keywordOf;
        r.K = kListText(K);
        r.dir = pathArgument(directory, "directory");
        r.request.maxSteps = unsignedArgument(tMax, "t_max", UINT64_MAX, "[0, 2^64)");
        r.request.population = static_cast<std::uint32_t>(unsignedArgument(population, "population", UINT32_MAX, "[0, 2^32)"));
        r.request.replicas = static_cast<std::uint32_t>(unsignedArgument(replicas, "replicas", UINT32_MAX, "[0, 2^32)"));
        r.request.firstSteps = unsignedArgument(first, "first", UINT64_MAX, "[0, 2^64)");
        r.request.minAncestors = unsignedArgument(minAncestors, "min_ancestors", UINT64_MAX, "[0, 2^64)");
        r.base.parameters.seed = unsignedArgument(seed, "seed", UINT64_MAX, "[0, 2^64)");
        r.base.parameters.q = static_cast<std::uint32_t>(unsignedArgument(q, "q", UINT32_MAX, "[0, 2^32)"));
        r.base.parameters.Xr = Xr;
        r.base.threads = threads;
        r.base.kernel = kernel.empty() ? "auto" : kernel;
        r.clones = clones;
        r.checkpointSeconds = checkpointInterval;
        if (!task.is_none()) r.task = task.cast<std::string>();
        if (!csv.is_none()) r.csv = pathArgument(csv, "csv");
        return runScan(r, progress);
      },
      py::arg("K"), py::arg("directory"), py::arg("t_max") = kScanTail.maxSteps,
      py::arg("population") = kScanTail.population, py::arg("replicas") = kScanTail.replicas,
      py::arg("first") = kScanTail.firstSteps, py::arg("seed") = kScanRun.seed, py::arg("q") = kScanRun.q,
      py::arg("Xr") = kScanRun.Xr, py::arg("min_ancestors") = kScanTail.minAncestors,
      py::arg("clones") = cloneRuleName(kScanTail.clones), py::arg("threads") = 0, py::arg("kernel") = "",
      py::arg("checkpoint_interval") = 60.0, py::arg("task") = py::none(), py::arg("csv") = py::none(),
      py::arg("progress") = py::none(),
      "The tail sampler over K (archipelago-cli tail-scan; docs/tail.md, 'The exponent atlas'): a tail file per K in\n"
      "`directory` (tail-K0.1.json, ...), each in the box of scan_box(K), started, resumed or reused; then the summary\n"
      "from the files.  Returns a dict: K; t (the levels, steps); P, P_error, reliable (K x levels); the windows\n"
      "t_from, t_to, t_window; gamma, gamma_error (K x windows, NaN where a K does not reach the window); gamma_mean,\n"
      "gamma_spread, gamma_mean_error, K_count per window; out_of_reach_K and out_of_reach_reason: the K whose first\n"
      "level is out of reach (the pilot's reason; not in K).  With task='I/N' and other K unfinished: K and waiting_for.");
}
