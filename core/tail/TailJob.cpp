#include "core/tail/TailJob.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/tail/TailFile.hpp"

namespace archipelago {

namespace {

/// The files of a session on this rank.
struct SessionFiles {
  std::string out;             ///< the tail file
  std::string checkpointBase;  ///< the checkpoint as given (the tail file unless named)
  std::string checkpoint;      ///< the file checkpointed into (sliced: this rank's slice file)
  std::string resume;          ///< the file resumed (sliced: this rank's slice file)
};

SessionFiles sessionFiles(const TailPlanOptions& plan, const Ranks& ranks) {
  SessionFiles f;
  f.out = plan.out;
  f.checkpointBase = plan.checkpoint.empty() ? plan.out : plan.checkpoint;
  f.checkpoint = ranks.sliced() ? tailSliceFileName(f.checkpointBase, ranks.rank(), ranks.size()) : f.checkpointBase;
  f.resume = ranks.sliced() && !plan.resume.empty() ? tailSliceFileName(plan.resume, ranks.rank(), ranks.size())
                                                     : plan.resume;
  return f;
}

/// ": resume with <the front end's name of resume> FILE" for the last checkpoint, or "" when there is none.
std::string howToResume(const TailPlanOptions& plan, const LastCheckpoint& last) {
  return last.path.empty() ? std::string() : ": resume with " + plan.nameOf("resume") + " " + last.path;
}

/// The plan of this rank: sliced, its slice of a new run, or its slice file to resume, checked to be its slice.
TailPlan planOnRank(TailPlanOptions plan, const SessionFiles& f, const Ranks& ranks) {
  if (!ranks.sliced() || plan.printLevels) return planTail(plan);
  const auto rank = static_cast<std::uint32_t>(ranks.rank());
  const auto size = static_cast<std::uint32_t>(ranks.size());
  if (!f.resume.empty() && !std::filesystem::exists(f.resume))
    throw std::invalid_argument("no slice file " + f.resume + ": resume " + plan.resume +
                                " on the number of ranks that wrote its slices (" + std::to_string(size) +
                                " ranks look for NAME.slice-r-of-" + std::to_string(size) + ".json)");
  if (plan.resume.empty()) plan.slice = replicaSlice(plan.request.replicas, rank, size);
  if (rank == 0) io::checkWritableTarget(plan.out);
  plan.resumeFile = f.resume;
  TailPlan planned = planTail(plan);
  const ReplicaRange mine = replicaSlice(planned.state.request.replicas, rank, size);
  if (planned.state.firstReplica != mine.first || planned.state.replicas.size() != mine.count)
    throw std::invalid_argument(f.resume + " is not slice " + std::to_string(rank) + " of " + std::to_string(size));
  return planned;
}

/// Runs `f` on every rank, an error on any being one on all; one process: its error as thrown.
template <class F>
void onEveryRank(Ranks& ranks, F&& f) {
  if (ranks.sliced()) together(ranks, std::forward<F>(f));
  else f();
}

/// The sampler run from the plan until it finishes or stops, on the kernel asked for; an error on any rank is one
/// error on all.
TailState runOnRank(TailPlan plan, const KernelInfo& kernel, const TailSessionOptions& o, const SessionFiles& f,
                    LastCheckpoint& last, Ranks& ranks, std::stop_token stop) {
  TailJobOptions job;
  job.run.threads = static_cast<int>(plan.threads);
  job.run.kernel = &kernel;
  job.checkpoint = f.checkpoint;
  job.checkpointSeconds = o.plan.checkpointSeconds;
  job.warning = o.view.checkpointWarning;
  job.optionName = o.plan.optionName;
  TailState state;
  onEveryRank(ranks, [&] { state = runTailJob(std::move(plan.state), job, last, o.view.progress, std::move(stop)); });
  if (o.view.runEnded) o.view.runEnded();
  return state;
}

/// A finished run's outputs besides its tail file (the CSV, the comparison's CSV) and the report's text.
TailSessionOutcome finishedOutcome(TailState state, const std::vector<TrappingState>& runs,
                                   const TailSessionOptions& o) {
  TailSessionOutcome r;
  r.result = tailResult(state);
  if (!o.plan.csv.empty()) io::writeFileAtomically(o.plan.csv, tailCsvText(state, r.result));
  if (!o.quiet) r.report = tailLevelsText(state, r.result);
  if (!runs.empty()) {
    const TailComparison c = compareWithRuns(state, r.result, runs);
    if (!o.plan.compareCsv.empty()) io::writeFileAtomically(o.plan.compareCsv, tailComparisonCsv(c));
    if (!o.quiet) r.report += tailComparisonText(c);
  }
  r.state = std::move(state);
  return r;
}

/// One process's end: a stopped run saved to the checkpoint; a finished one's tail file and outputs, all or nothing.
TailSessionOutcome endOnOneProcess(TailState state, const std::vector<TrappingState>& runs,
                                   const TailSessionOptions& o, const SessionFiles& f, const LastCheckpoint& last) {
  if (!state.finished()) {
    saveTailOrSayWhere(f.checkpoint, state, last, howToResume(o.plan, last));
    return {TailSessionOutcome::End::interrupted, std::move(state), f.checkpoint, {}, {}};
  }
  io::OutputBatch outputs;  // the tail file and its CSVs: all or nothing (issue 36, class 5)
  saveTailOrSayWhere(f.out, state, last, howToResume(o.plan, last));
  TailSessionOutcome r = finishedOutcome(std::move(state), runs, o);
  outputs.commit();
  return r;
}

/// Rank 0's end of a finished sliced run: the other ranks' slices (`texts`) merged with its own, the tail file and
/// its outputs written all at once, the slice files removed.
TailSessionOutcome mergeSlices(TailState mine, const std::vector<std::string>& texts,
                               const std::vector<TrappingState>& runs, const TailSessionOptions& o,
                               const SessionFiles& f, int size) {
  std::vector<TailState> slices;
  slices.push_back(std::move(mine));
  for (std::size_t r = 0; r < texts.size(); ++r) {
    try {
      slices.push_back(parseTailFile(texts[r]));
    } catch (const std::exception& e) {
      throw std::runtime_error("rank " + std::to_string(r + 1) + "'s slice: " + e.what());
    }
  }
  io::OutputBatch outputs;
  TailState merged = mergeTailSlices(std::move(slices));
  saveTailFile(f.out, merged);
  TailSessionOutcome r = finishedOutcome(std::move(merged), runs, o);
  outputs.commit();
  for (int rank = 0; rank < size; ++rank) {
    std::error_code ec;
    std::filesystem::remove(tailSliceFileName(f.checkpointBase, rank, size), ec);  // merged: the slices are in out
  }
  return r;
}

/// A sliced run's end: every rank writes its slice, finished or not (the resume point of a stopped job, and safe
/// until merged); when every rank has finished, rank 0 merges them.
TailSessionOutcome endSliced(TailState state, const std::vector<TrappingState>& runs, const TailSessionOptions& o,
                             const SessionFiles& f, const LastCheckpoint& last, Ranks& ranks) {
  together(ranks, [&] { saveTailOrSayWhere(f.checkpoint, state, last, howToResume(o.plan, last)); });
  if (!ranks.all(state.finished()))
    return {TailSessionOutcome::End::interrupted, std::move(state),
            tailSliceFileName(f.checkpointBase, 0, ranks.size()), {}, {}};
  const std::vector<std::string> texts = ranks.gather(ranks.rank() == 0 ? std::string() : tailFileText(state));
  TailSessionOutcome r;
  std::string error;
  if (ranks.rank() == 0) {
    try {
      r = mergeSlices(std::move(state), texts, runs, o, f, ranks.size());
    } catch (const std::exception& e) {
      error = std::string(e.what()) + " (the slices are kept: " + tailSliceFileName(f.checkpointBase, 0, ranks.size()) +
              ", …)";
    }
  }
  ranks.agree(error.empty(), error);
  return r;
}

}  // namespace

std::string tailSliceFileName(const std::string& name, int rank, int size) {
  const std::filesystem::path p(name);
  const std::string tag = ".slice-" + std::to_string(rank) + "-of-" + std::to_string(size);
  if (p.extension() == ".json") return (p.parent_path() / (p.stem().string() + tag + ".json")).string();
  return name + tag;
}

TailSessionOutcome runTailSession(const TailSessionOptions& options, Ranks& ranks, std::stop_token stop) {
  const SessionFiles files = sessionFiles(options.plan, ranks);
  TailPlan plan;
  std::vector<io::FileLock> locks;
  const KernelInfo* kernel = nullptr;
  onEveryRank(ranks, [&] {
    plan = planOnRank(options.plan, files, ranks);
    if (plan.printLevelsOnly) return;
    locks = lockJobFiles(ranks.sliced() ? files.checkpoint : files.out, files.checkpoint, files.resume);
    kernel = &selectKernel(options.plan.resume.empty() ? plan.kernel : options.kernel);
  });
  if (plan.printLevelsOnly) return {TailSessionOutcome::End::levelsOnly, std::move(plan.state), {}, {}, {}};
  LastCheckpoint last{files.resume, 0};
  std::vector<TrappingState> runs = std::move(plan.runs);
  TailState state = runOnRank(std::move(plan), *kernel, options, files, last, ranks, std::move(stop));
  return ranks.sliced() ? endSliced(std::move(state), runs, options, files, last, ranks)
                        : endOnOneProcess(std::move(state), runs, options, files, last);
}

std::string tailLevelsText(const TailState& s, const TailResult& r) {
  const auto text = [](double v) { return io::formatC("%.4g", v); };
  std::string out = io::formatC(
      "# tail: K = %s, q = %u, N = %u, R = %u, epsilon = %llu, clones = %s; %s steps%s\n",
      io::shortestText(s.request.run.map.K).c_str(), s.request.run.q, s.request.population, s.request.replicas,
      static_cast<unsigned long long>(s.request.epsilon), cloneRuleName(s.request.clones), text(r.steps).c_str(),
      r.finished ? "" : " (unfinished)");
  if (s.replicas.size() != s.request.replicas)
    out += io::formatC("# the slice of replicas [%u, %zu) of %u: P and its error are those of its replicas alone\n",
                       s.firstReplica, s.firstReplica + s.replicas.size(), s.request.replicas);
  out += io::formatC("%12s %12s %10s %10s %10s %8s %9s %12s\n", "t", "P", "P_error", "survivors", "ancestors", "fewest",
                     "reliable", "steps");
  for (const TailLevelResult& L : r.levels)
    out += io::formatC("%12.0f %12.5g %10.3g %10llu %10llu %8llu %9s %12.4g\n", L.t, L.P, L.PError,
                       static_cast<unsigned long long>(L.survivors), static_cast<unsigned long long>(L.ancestors),
                       static_cast<unsigned long long>(L.fewestAncestors), L.reliable ? "yes" : "no", L.steps);
  if (r.exponents.empty()) return out;
  out += "# running exponent gamma(t) = -dlnP/dlnt over decade windows (as stats: least squares on a log grid)\n";
  out += io::formatC("%12s %12s %12s %8s %8s\n", "t", "t_from", "t_to", "gamma", "error");
  for (const TailExponent& e : r.exponents)
    out += io::formatC("%12.4g %12.0f %12.0f %8.4f %8.3g\n", e.t, e.tFrom, e.tTo, e.gamma, e.gammaError);
  return out;
}

namespace {

/// The comparison's one test (pooledBias): the levels pooled with both estimators' covariance, and the bias it can see.
std::string pooledBiasText(const TailPooledBias& p) {
  if (p.levels == 0 || !std::isfinite(p.z)) return "# pooled: no level where both have data (reliable, 10 segments)\n";
  return io::formatC("# pooled: %zu levels (%.4g <= t <= %.4g) with the covariance of both estimators: ln(P/brute_P) = "
                     "%+.4f +- %.4f (z = %+.2f); a uniform bias of %.3g %% is found half of the time, %.3g %% 97.7 %% "
                     "of the time\n",
                     p.levels, p.tFrom, p.tTo, p.logRatio, p.logRatioError, p.z, 100 * p.detectableHalf,
                     100 * p.detectable);
}

}  // namespace

std::string tailComparisonText(const TailComparison& c) {
  std::string out = io::formatC("# against brute force: %s steps of run, alpha = %.4g steps\n",
                                io::formatC("%.4g", c.bruteSteps).c_str(), c.alpha);
  out += io::formatC("%12s %12s %10s %12s %10s %8s %7s %12s %14s\n", "t", "P", "P_error", "brute_P", "error",
                     "segments", "z", "tail_steps", "brute_steps*");
  for (const TailComparisonLevel& l : c.levels)
    out += io::formatC("%12.0f %12.5g %10.3g %12.5g %10.3g %8llu %7.2f %12.4g %13.4g%s\n", l.t, l.P, l.PError, l.bruteP,
                       l.bruteError, static_cast<unsigned long long>(l.bruteSegments), l.z, l.tailSteps,
                       l.bruteStepsSameError, l.bruteStepsMeasured ? "" : "e");
  out += "# brute_steps*: steps a brute-force run needs for the sampler's relative error at t (from the runs' own "
         "error; e: estimated alpha/(P r^2) where they have none)\n";
  return out + pooledBiasText(pooledBias(c));
}

TailState runTailJob(TailState state, const TailJobOptions& options, LastCheckpoint& last,
                     const TailObserver& progress, std::stop_token stop) {
  if (state.finished()) return state;
  CheckpointClock clock(options.checkpointSeconds);
  const auto observer = [&](const TailState& s, const TailProgress& p) {
    if (!options.checkpoint.empty() && !s.finished() && clock.due())
      writeCheckpoint([&] { saveTailFile(options.checkpoint, s); }, options.checkpoint.string(), 0, last,
                      options.checkpointSeconds, options.warning);
    if (progress) progress(s, p);
  };
  try {
    return runTail(std::move(state), options.run, observer, std::move(stop));
  } catch (const TailSettingOutOfReach& e) {
    if (!options.optionName) throw;
    throw std::invalid_argument(e.namedAs(options.optionName(e.role())));
  }
}

void saveTailOrSayWhere(const std::filesystem::path& path, const TailState& state, const LastCheckpoint& last,
                        const std::string& howToResume) {
  saveOrRescue(
      path, [&](const std::filesystem::path& p) { saveTailFile(p, state); }, "tail run",
      state.finished() ? " (finished)" : " (unfinished)",
      last.path.empty() ? std::string() : "the last checkpoint is in " + last.path + howToResume);
}

std::string tailComparisonCsv(const TailComparison& c) {
  std::string out = "# brute-force steps: " + io::formatC("%.17g", c.bruteSteps) + "\n# alpha: " +
                    io::formatC("%.17g", c.alpha) + "\n";
  out += "t,P,P_error,reliable,brute_P,brute_error,brute_segments,z,tail_steps,brute_steps_same_error,measured\n";
  const auto n = [](double v) { return std::isfinite(v) ? io::formatC("%.17g", v) : std::string(); };
  for (const TailComparisonLevel& l : c.levels)
    out += n(l.t) + "," + n(l.P) + "," + n(l.PError) + "," + (l.reliable ? "1" : "0") + "," + n(l.bruteP) + "," +
           n(l.bruteError) + "," + std::to_string(l.bruteSegments) + "," + n(l.z) + "," + n(l.tailSteps) + "," +
           n(l.bruteStepsSameError) + "," + (l.bruteStepsMeasured ? "1" : "0") + "\n";
  return out;
}

}  // namespace archipelago
