// Trapping runs (core/run, core/runfile, core/runspec, core/stats; section 3 and appendix B) as archipelago.Run: start
// from a run spec or keyword parameters (core's one table of keys and ranges), advance with the GIL released and
// Ctrl-C checked at each chunk, save and load run files, merge orbit ranges, read the histogram, the longest segments
// (replayed bit for bit) and the statistics under the statistics table's keys.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "core/io/BadFile.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/run/TrappingRun.hpp"
#include "core/trapping/LongestSegments.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/runspec/RunSpec.hpp"
#include "core/stats/RunEnsemble.hpp"
#include "core/stats/RunStatistics.hpp"
#include "core/stats/RunSummary.hpp"
#include "core/stats/StatisticsTable.hpp"
#include "core/stats/TailAnalysis.hpp"
#include "python/Conversions.hpp"
#include "python/Interruption.hpp"
#include "python/Run.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

// Keyword arguments -> TrappingParameters, through core's one table of keys and ranges (parameterRules()).
void applyParameters(TrappingParameters& p, const py::dict& kwargs) {
  for (auto item : kwargs) {
    const std::string key = py::str(item.first);
    const ParameterRule* rule = findParameterRule(key);
    if (rule == nullptr) throw std::invalid_argument("unknown parameter " + key);
    py::handle v = item.second;
    if (rule->integer) setParameterValue(p, key, ParameterValue{unsignedArgument(v, key, UINT64_MAX, std::string(rule->range))});
    else setParameterValue(p, key, ParameterValue{realArgument(v, key)});
  }
  if (auto e = validationError(p)) throw std::invalid_argument(*e);
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

Run startRun(const py::object& spec, const py::kwargs& kwargs) {
  TrappingParameters params;
  if (!spec.is_none()) {
    std::string text;
    if (py::isinstance<py::dict>(spec)) text = py::module_::import("json").attr("dumps")(spec).cast<std::string>();
    else text = spec.cast<std::string>();
    try {
      params = parseRunSpec(text).parameters;
    } catch (const io::BadFile& e) {
      throw std::invalid_argument(e.what());  // a spec given as text or a dict: ValueError, as for its keywords
    }
  }
  applyParameters(params, kwargs);
  if (auto e = memoryError(params, 0)) throw std::invalid_argument(*e);
  Run r;
  r.state = startTrapping(params);
  warnIfBoxCutsIsland(params.map, params.Xr);
  return r;
}

// Advances the run with the GIL released; at each chunk boundary the observer is a progress point of the
// Interruption: the progress callback, then Ctrl-C (KeyboardInterrupt after the chunk, the run saved first).
void advanceRun(Run& run, int threads, const std::string& kernelName, const py::object& progress,
                std::uint64_t maxChunk, double chunkSeconds, const py::object& checkpoint) {
  run.check();
  // The checkpoint's path is checked before the work, not found wrong after it.
  const std::optional<std::string> checkpointPath =
      checkpoint.is_none() ? std::nullopt : std::optional<std::string>(pathArgument(checkpoint, "checkpoint"));
  if (auto e = threadsError(threads)) throw std::invalid_argument(*e);
  if (auto e = chunkSecondsError(chunkSeconds)) throw std::invalid_argument(*e);
  if (auto e = memoryError(run.state.params, threads)) throw std::invalid_argument(*e);
  const KernelInfo& kernel = selectKernel(kernelName);
  TrappingRunOptions options;
  options.threads = threads;
  options.kernel = &kernel;
  options.maxChunkBlocks = maxChunk;
  options.chunkSeconds = chunkSeconds;
  Interruption interruption;
  const auto observer = [&](const TrappingState& s, const TrappingProgress& p) {
    interruption.check(progress, [&] {
      py::dict d;
      d["blocks_done"] = p.blocksDone;
      d["blocks_total"] = p.blocksTotal;
      d["fraction"] = p.fraction;
      d["steps_per_second"] = p.stepsPerSecond;
      d["eta_seconds"] = p.etaSeconds;
      d["session_seconds"] = p.sessionSeconds;
      d["segments"] = s.total().segments();
      return d;
    });
  };
  run.valid = false;
  run.busy = true;
  try {
    run.state = interruption.withoutGil(
        [&] { return runTrapping(std::move(run.state), options, observer, interruption.token()); });
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
  interruption.raisePending();
}

py::dict histogramDict(const Run& r, const py::object& subset) {
  r.check();
  const TrappingHistogram h = subset.is_none() ? r.state.total() : [&] {
    const auto i = subset.cast<std::size_t>();
    if (auto e = subsetIndexError(i, r.state.subsets.size())) throw std::invalid_argument(*e);
    return r.state.subsets[i]; }();
  const int n = TrappingHistogram::kBins;
  py::array_t<std::uint64_t> counts(n), sums(n), lower(n), upper(n);
  for (int i = 0; i < n; ++i) {
    counts.mutable_at(i) = h.count(i);
    sums.mutable_at(i) = h.lengthSum(i);
    lower.mutable_at(i) = TrappingHistogram::binLower(i);
    upper.mutable_at(i) = TrappingHistogram::binUpper(i);
  }
  py::dict d;
  d["counts"] = counts;
  d["length_sums"] = sums;
  d["lower"] = lower;
  d["upper"] = upper;
  return d;
}

py::array_t<std::uint64_t> orbitStates(const Run& r) {
  r.check();
  const auto n = static_cast<py::ssize_t>(r.state.orbits.size());
  constexpr auto columns = static_cast<py::ssize_t>(kOrbitStateRowSize);
  py::array_t<std::uint64_t> a({n, columns});
  for (py::ssize_t i = 0; i < n; ++i) {
    const OrbitStateRow row = orbitStateRow(r.state.orbits[static_cast<std::size_t>(i)]);  // core's one order
    for (py::ssize_t j = 0; j < columns; ++j) a.mutable_at(i, j) = row[static_cast<std::size_t>(j)];
  }
  return a;
}

py::dict longestDict(const Run& r) {
  r.check();
  std::vector<std::uint64_t> orbit, length, X, Y, block, draws;
  for (const SegmentRecord& s : r.state.longest.items()) {
    orbit.push_back(s.orbit);
    length.push_back(s.length * r.state.params.q);
    X.push_back(s.start.z.X);
    Y.push_back(s.start.z.Y);
    block.push_back(s.start.block);
    draws.push_back(s.start.draws);
  }
  py::dict d;
  d["orbit"] = toArray(orbit);
  d["length_steps"] = toArray(length);
  d["X"] = toArray(X);
  d["Y"] = toArray(Y);
  d["block"] = toArray(block);
  d["draws"] = toArray(draws);
  return d;
}

py::dict replay(const Run& r, std::size_t rank) {
  r.check();
  if (auto e = longestRankError("rank", rank, r.state.longest.items().size())) throw std::invalid_argument(*e);
  const TrappingParameters params = r.state.params;  // copies: the replay runs without the GIL
  const SegmentRecord rec = r.state.longest.items()[rank];
  const std::uint64_t n = rec.length * params.q + 1;
  if (n > (std::uint64_t{1} << 31)) throw std::invalid_argument("segment too long to replay into arrays");
  OrbitArrays points(FixedPointMap(params.map), static_cast<py::ssize_t>(n));
  {
    py::gil_scoped_release release;
    replaySegment(params, rec, [&](std::uint64_t step, const UnitState& z) { points.set(step, z); });
  }
  return points.dict();
}

py::dict statisticsDict(const Run& r, const py::object& shortRun) {
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
  // D, its error and where it comes from, as `stats` prints them: core's one run summary (issue 35), never
  // assembled here (this function once paired the spliced D with the bootstrap error of the run alone).
  const RunSummary summary = summarizeRun(r.state, s);
  py::dict d;
  // The series under the statistics table's keys (core/stats/StatisticsTable: f_t, p_t, P_t, C_tau, …), the
  // same names as the CSV files' value columns and the sessions'.
  for (const StatisticInfo& info : statisticsTable())
    d[py::str(std::string(info.key))] = seriesDict(seriesOf(s, info.statistic));
  d["alpha"] = summary.alpha;
  d["alpha_error"] = summary.alphaError;
  d["D"] = summary.D;
  d["D_error"] = summary.DError;
  d["D_error_source"] = std::string(keyOf(summary.errorSource));
  d["D_error_note"] = summary.DErrorNote;
  d["D_error_subsets"] = summary.DSubsetsError;
  d["D_run"] = summary.runD;
  d["D_run_error"] = summary.runDError;
  d["D_dominated"] = summary.dominated;
  d["D_verdict"] = summary.verdict;
  d["gamma_P"] = summary.gammaP;
  d["sum_t_f"] = s.sumTf;
  d["segments"] = s.segments;
  d["longest_blocks"] = s.longestBlocks;
  d["blocks_affected_below"] = s.blockAffectedBelow;
  d["spliced_at"] = s.splicedAt;
  return d;
}

}  // namespace

void bindRun(py::module_& m) {
  py::class_<Run>(m, "Run",
                  "A trapping-statistics run (Karney 1983, section 3, appendix B): M orbits of N^-1 in blocks of q steps,\n"
                  "segments between visits of the randomizing zone 0 <= X <= Xr, lengths in steps.")
      .def_property_readonly("parameters", [](const Run& r) { r.check(); return parametersDict(r.state.params); })
      .def_property_readonly("blocks_done", [](const Run& r) { r.check(); return r.state.blocksDone; })
      .def_property_readonly("finished", [](const Run& r) { r.check(); return r.state.finished(); })
      .def_property_readonly("kernel", [](const Run& r) { r.check(); return r.state.kernel; })
      .def_property_readonly("elapsed_seconds", [](const Run& r) { r.check(); return r.state.elapsedSeconds; })
      .def_property_readonly("orbit_range", [](const Run& r) { r.check(); return py::make_tuple(r.state.orbitBegin, r.state.orbitEnd); })
      .def_property_readonly("coefficients", [](const Run& r) { r.check(); return coefficientsDict(r.state.coefficients); })
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
      .def("histogram", &histogramDict, py::arg("subset") = py::none(),
           "The histogram of segment lengths (blocks of q steps): counts and length sums per bin, bin edges in blocks\n"
           "[lower, upper).  subset=None: the total of the subsets.")
      .def("orbit_states", &orbitStates,
           "Every orbit's exact state, one row each: X, Y, block, draws, length, start X, start Y, start block, start draws.")
      .def("longest", &longestDict,
           "The longest segments, longest first: orbit, length in steps, exact start state (X, Y, block, draws).")
      .def("replay", &replay, py::arg("rank") = 0,
           "Replays the rank-th longest segment bit for bit: dict of arrays X, Y (unit) and x, y (physical), one point per\n"
           "step of N^-1 (q*length + 1 points).")
      .def("statistics", &statisticsDict, py::arg("short") = py::none(),
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
        "A fresh run from a run spec (JSON text or dict, format archipelago-spec: core/runspec/RunSpec.hpp) and/or keyword\n"
        "parameters K, xmin, xmax, Xr, q, T, M, seed, subsets, longestKept (defaults: the paper's K = 0.1 case, section 5).\n"
        "ValueError with the CLI's message for a bad parameter.");
  m.def("load", [](const py::object& path, bool allowModified) {
          Run r;
          const std::string file = pathArgument(path, "path");
          try { r.state = loadRunFile(file, {allowModified, "allow_modified=True"}); }
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
          r.state = startTrapping(r.state.params, begin, end);  // core's rule and message (orbitRangeError)
          return r; },
        py::arg("begin"), py::arg("end"), py::arg("spec") = py::none(),
        "As start(), over the orbits [begin, end) only: the parts of a run merged with merge().");

  m.def("presets", [] {
          py::dict d;
          for (const Preset& p : presets()) d[py::str(p.id)] = runSpecJson(p.spec);
          return d; },
        "The paper's cases (resources/presets): id -> run spec JSON text, for start(spec).");
}
