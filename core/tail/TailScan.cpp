#include "core/tail/TailScan.hpp"

#include <algorithm>
#include <cmath>
#include <regex>
#include <stdexcept>
#include <utility>

#include "core/atlas/BoxIslandCheck.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
#include "core/job/Job.hpp"
#include "core/limits/Limits.hpp"
#include "core/paper/PaperTable.hpp"
#include "core/scan/ScanBox.hpp"
#include "core/scan/ScanRun.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailJob.hpp"
#include "core/tail/TailPlan.hpp"

namespace archipelago {

namespace {

/// The scan's settings checked whole, and what follows from them.
struct ScanSettings {
  std::vector<double> K;
  std::vector<std::size_t> mine;   ///< the indices of this process's K
  std::vector<TailRequest> requests;  ///< per K
  const KernelInfo* kernel = nullptr;
};

/// Task "I/N" (role "task"): whole numbers with I < N.
std::pair<std::uint32_t, std::uint32_t> parseTask(const std::string& option, const std::string& text) {
  const std::string rule = "I/N, whole numbers with I < N (task I of N)";
  const std::vector<std::uint32_t> v = io::parseNumbers<std::uint32_t>(option, text, '/', 2, rule);
  if (!(v[0] < v[1])) throw std::invalid_argument(option + " '" + io::shortText(text) + "' must be " + rule);
  return {v[0], v[1]};
}

/// This process's K: those of its task (i mod N = I), then the m-th of them on rank m mod size.
std::vector<std::size_t> shareOf(std::size_t count, std::pair<std::uint32_t, std::uint32_t> task, const Ranks& ranks) {
  std::vector<std::size_t> mine;
  std::size_t m = 0;
  for (std::size_t i = task.first; i < count; i += task.second, ++m)
    if (m % static_cast<std::size_t>(ranks.size()) == static_cast<std::size_t>(ranks.rank())) mine.push_back(i);
  return mine;
}

/// The sampler's request at K: the base's process in the box of scanBox(K), the settings and the clone rule given.
TailRequest requestAt(const TailScanRequest& r, double K) {
  TailRequest request = r.request;
  request.run = r.base.parameters;
  request.run.map = scanBox(K);
  request.clones = parseCloneRule(r.clones, r.nameOf("clones"));
  return request;
}

ScanSettings checkedSettings(const TailScanRequest& r, const Ranks& ranks) {
  ScanSettings s;
  try {
    s.K = parseScanValues(r.K);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(r.nameOf("K") + ": " + e.what());
  }
  const auto task = r.task ? parseTask(r.nameOf("task"), *r.task) : std::pair<std::uint32_t, std::uint32_t>{0, 1};
  if (auto e = threadsError(r.base.threads)) throw std::invalid_argument(*e);
  if (auto e = checkpointIntervalError(r.nameOf("checkpoint-interval"), r.checkpointSeconds))
    throw std::invalid_argument(*e);
  for (const double K : s.K) {
    RunSpec spec = r.base;
    spec.parameters.map = scanBox(K);
    if (auto e = validationError(spec)) throw std::invalid_argument("K = " + scanKText(K) + ": " + *e);
    s.requests.push_back(requestAt(r, K));
    if (auto e = tailRequestError(s.requests.back())) throw std::invalid_argument(*e);
  }
  if (r.dir.empty()) throw std::invalid_argument(r.nameOf("dir") + " is empty: give a folder");
  s.mine = shareOf(s.K.size(), task, ranks);
  s.kernel = &selectKernel(r.base.kernel == "auto" ? std::string() : r.base.kernel);
  return s;
}

/// The first setting in which two requests differ: its role, or what it is.
std::string firstDifference(const TailRequest& file, const TailRequest& wanted) {
  if (!(file.run.map == wanted.run.map)) return "the map or its box";
  if (file.run.seed != wanted.run.seed) return "seed";
  if (file.population != wanted.population) return "population";
  if (file.replicas != wanted.replicas) return "replicas";
  if (file.maxSteps != wanted.maxSteps) return "t-max";
  if (file.firstSteps != wanted.firstSteps) return "first";
  if (file.clones != wanted.clones) return "clones";
  return "the process or the sampler's settings";
}

/// A role by the front end's name; a description (with a blank) as it is.
std::string nameOrWhat(const TailScanRequest& r, const std::string& role) {
  return role.find(' ') == std::string::npos ? r.nameOf(role) : role;
}

/// The run of K in its file, checked to be the scan's (a whole run of the same request); none when absent.
std::optional<TailState> readScanFile(const TailScanRequest& r, const std::filesystem::path& file, double K,
                                      const TailRequest& wanted) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  TailState state = loadTailFile(file);
  if (!(state.request == wanted))
    throw std::invalid_argument(file.string() + " holds a tail run of other settings than this scan's K = " +
                                scanKText(K) + " (" + nameOrWhat(r, firstDifference(state.request, wanted)) +
                                " differs): another folder, or remove the file");
  if (state.firstReplica != 0 || state.replicas.size() != wanted.replicas)
    throw std::invalid_argument(file.string() + " holds a slice of the replicas, not the whole run of K = " +
                                scanKText(K));
  return state;
}

/// One K of this process: its file and its run as planned.
struct ScanItem {
  std::size_t index = 0;
  std::filesystem::path file;
  TailState state;
  std::string how;  ///< reused, resumed, started
};

std::vector<ScanItem> planItems(const TailScanRequest& r, const ScanSettings& s) {
  std::vector<ScanItem> items;
  for (const std::size_t i : s.mine) {
    ScanItem item{i, tailScanFile(r.dir, s.K[i]), {}, {}};
    if (std::optional<TailState> state = readScanFile(r, item.file, s.K[i], s.requests[i])) {
      item.how = state->finished() ? "reused" : tailFirstLevelRefusal(*state) ? "out of reach" : "resumed";
      item.state = std::move(*state);
    } else {
      item.how = "started";
      item.state = startTail(s.requests[i]);
    }
    items.push_back(std::move(item));
  }
  return items;
}

/// Whether a K's run is done: finished, or its first level out of reach.
bool done(const TailState& state) { return state.finished() || tailFirstLevelRefusal(state).has_value(); }

/// Runs one K to its end (finished or out of reach) or the stop; the file holds it either way.  Whether it is done.
bool runItem(ScanItem& item, const TailScanRequest& r, const ScanSettings& s, const TailScanView& view,
             std::stop_token stop) {
  const double K = s.K[item.index];
  if (view.begins) view.begins(item.index, s.K.size(), K, item.how);
  if (item.how == "started" && r.warning)
    if (const BoxIslandCheck c = checkBoxAgainstIsland(item.state.request.run.map, item.state.request.run.Xr); c.cuts())
      r.warning("K = " + scanKText(K) + ": " + c.warning);
  if (!done(item.state)) {
    TailJobOptions job;
    job.run.threads = r.base.threads;
    job.run.returnRefused = true;
    job.run.kernel = s.kernel;
    job.checkpoint = item.file;
    job.checkpointSeconds = r.checkpointSeconds;
    job.warning = view.checkpointWarning;
    job.optionName = [&r](std::string_view role) { return r.nameOf(role); };
    LastCheckpoint last{item.how == "resumed" ? item.file.string() : std::string(), 0};
    TailObserver progress;
    if (view.progress)
      progress = [&](const TailState& state, const TailProgress& p) { view.progress(item.index, K, state, p); };
    try {
      item.state = runTailJob(std::move(item.state), job, last, progress, std::move(stop));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("K = " + scanKText(K) + ": " + e.what());
    }
    saveTailOrSayWhere(item.file, item.state, last, ": run the same scan again to resume it");
  }
  if (item.state.finished() && view.finished) view.finished(item.index, K, item.state);
  if (const std::optional<std::string> why = tailFirstLevelRefusal(item.state); why && view.outOfReach)
    view.outOfReach(item.index, K, *why);
  return done(item.state);
}

/// Every K's done run from the folder (finished, or out of reach), or the K not done yet.
std::vector<double> unfinished(const TailScanRequest& r, const ScanSettings& s, std::vector<TailState>& states) {
  std::vector<double> waiting;
  for (std::size_t i = 0; i < s.K.size(); ++i) {
    std::optional<TailState> state = readScanFile(r, tailScanFile(r.dir, s.K[i]), s.K[i], s.requests[i]);
    if (!state || !done(*state)) waiting.push_back(s.K[i]);
    else states.push_back(std::move(*state));
  }
  return waiting;
}

/// Rank 0's end of a scan whose K on every rank are finished: the summary when every K of the list is, its CSVs.
TailScanOutcome summaryOutcome(const TailScanRequest& r, const ScanSettings& s) {
  TailScanOutcome out;
  out.K = s.K;
  std::vector<TailState> states;
  out.waitingFor = unfinished(r, s, states);
  if (!out.waitingFor.empty()) {
    out.end = TailScanOutcome::End::waiting;
    return out;
  }
  if (std::all_of(states.begin(), states.end(), [](const TailState& x) { return !x.finished(); }))
    throw std::invalid_argument("no K of the scan reached its first level; K = " + scanKText(s.K.front()) + ": " +
                                *tailFirstLevelRefusal(states.front()) + " (" + r.nameOf("first") + ")");
  out.summary = tailScanSummary(s.K, std::move(states));
  if (!r.csv.empty()) {
    const std::vector<std::string> files = tailScanCsvFiles(r.csv);
    io::OutputBatch outputs;
    io::writeFileAtomically(files[0], tailScanPCsv(out.summary));
    io::writeFileAtomically(files[1], tailScanGammaCsv(out.summary));
    io::writeFileAtomically(files[2], tailScanAverageCsv(out.summary));
    writeHeatMapPng(tailScanPngFile(r.csv), tailGammaHeatMap(out.summary), "tail scan: gamma over K and t");
    outputs.commit();
  }
  return out;
}

/// Runs `f` on every rank, an error on any being one on all; one process: its error as thrown.
template <class F>
void onEveryRank(Ranks& ranks, F&& f) {
  if (ranks.sliced()) together(ranks, std::forward<F>(f));
  else f();
}

/// Whether K reaches window w: a reliable level at or below its start and one at or above its end.
bool reaches(const TailResult& result, const LogWindow& w) {
  bool below = false, above = false;
  for (const TailLevelResult& L : result.levels) {
    below = below || (L.reliable && L.t <= w.from);
    above = above || (L.reliable && L.t >= w.to);
  }
  return below && above;
}

/// The tail files of a scan's folder (tail-K<K>.json), sorted by name.
std::vector<std::filesystem::path> tailFilesIn(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) throw std::runtime_error(dir.string() + " is not a folder");
  static const std::regex name(R"(tail-K[^/]+\.json)");
  std::vector<std::filesystem::path> files;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (std::regex_match(it->path().filename().string(), name)) files.push_back(it->path());
  if (ec) throw std::runtime_error("cannot list " + dir.string() + ": " + ec.message());
  if (files.empty())
    throw std::runtime_error(dir.string() + " holds no tail file (tail-K<K>.json): not the folder of a tail scan");
  std::sort(files.begin(), files.end());
  return files;
}

/// The first tail file of a folder read, whose settings the others must have.
struct FolderSettings {
  std::filesystem::path file;
  TailRequest request;
};

/// The run of a scan folder's file, checked to be a tail scan's run of its K (loadTailScan's rules), with the
/// settings of `first` but the box; none given: the first file.
TailState folderRun(const std::filesystem::path& file, const std::optional<FolderSettings>& first) {
  TailState state = loadTailFile(file);
  const double K = state.request.run.map.K;
  const std::string where = file.string() + " ";
  if (!(state.request.run.map == scanBox(K)))
    throw std::runtime_error(where + "is not a tail scan's file: its box is not the scan's box of K = " + scanKText(K));
  if (file.filename() != tailScanFile({}, K).filename())
    throw std::runtime_error(where + "holds the run of K = " + scanKText(K) + ", not that of its name");
  if (state.firstReplica != 0 || state.replicas.size() != state.request.replicas)
    throw std::runtime_error(where + "holds a slice of the replicas, not the whole run of K = " + scanKText(K));
  if (first) {
    TailRequest wanted = first->request;
    wanted.run.map = state.request.run.map;
    if (!(state.request == wanted))
      throw std::runtime_error(where + "holds a tail run of other settings than " + first->file.filename().string() +
                               " (" + firstDifference(state.request, wanted) + " differs): not one scan");
  }
  return state;
}

/// A number with 17 significant digits, empty when not finite (the CSVs').
std::string csvNumber(double v) { return std::isfinite(v) ? io::formatC("%.17g", v) : std::string(); }

}  // namespace

std::string TailScanRequest::nameOf(std::string_view role) const {
  return optionName ? optionName(role) : std::string(role);
}

std::filesystem::path tailScanFile(const std::filesystem::path& dir, double K) {
  return dir / ("tail-K" + scanKText(K) + ".json");
}

std::vector<std::string> tailScanCsvFiles(const std::string& prefix) {
  return {prefix + "_P.csv", prefix + "_gamma.csv", prefix + "_average.csv"};
}

std::string tailScanPngFile(const std::string& prefix) { return prefix + "_gamma.png"; }

ScanHeatMap tailGammaHeatMap(const TailScanSummary& s) {
  // The columns: every K of the scan by increasing K, a K out of reach with no γ (so that its neighbours' cells do
  // not stretch over it).  column → its index in s.K, or none.
  std::vector<std::pair<double, std::optional<std::size_t>>> columns;
  for (std::size_t k = 0; k < s.K.size(); ++k) columns.emplace_back(s.K[k], k);
  for (const TailScanRefusal& r : s.outOfReach) columns.emplace_back(r.K, std::nullopt);
  std::stable_sort(columns.begin(), columns.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  ScanHeatMap map;
  for (const auto& c : columns) map.K.push_back(c.first);
  map.top = kTailGammaTop;
  for (const TailScanWindow& w : s.average) map.tau.push_back(w.t);
  map.value.assign(map.tau.size() * map.K.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (const std::optional<std::size_t> k = columns[c].second)
      for (std::size_t w = 0; w < map.tau.size(); ++w) map.value[w * map.K.size() + c] = s.gamma[*k][w].gamma;
  return map;
}

const std::vector<ReferenceExponent>& tailScanReferenceExponents() {
  static const std::vector<ReferenceExponent> table = {
      {paper::kGammaCristadoroKetzmerick, "Cristadoro & Ketzmerick 2008; Alus, Fishman & Meiss 2017"},
      {paper::kGammaUltrametric, "ultrametric, ln 2/ln(1 + r_g)"},
  };
  return table;
}

TailScanFolder loadTailScan(const std::filesystem::path& dir) {
  TailScanFolder out;
  std::vector<TailState> finished;
  std::optional<FolderSettings> first;
  for (const std::filesystem::path& file : tailFilesIn(dir)) {
    TailState state = folderRun(file, first);
    if (!first) first = FolderSettings{file, state.request};
    if (done(state)) finished.push_back(std::move(state));
    else out.unfinished.push_back(state.request.run.map.K);
  }
  if (finished.empty())
    throw std::runtime_error(dir.string() + " holds no finished tail file yet (" +
                             std::to_string(out.unfinished.size()) + " unfinished)");
  std::sort(finished.begin(), finished.end(), [](const TailState& a, const TailState& b) {
    return a.request.run.map.K < b.request.run.map.K;
  });
  std::sort(out.unfinished.begin(), out.unfinished.end());
  std::vector<double> K;
  for (const TailState& s : finished) K.push_back(s.request.run.map.K);
  try {
    out.summary = tailScanSummary(K, std::move(finished));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(dir.string() + ": " + e.what());
  }
  return out;
}

TailExponent tailScanExponentOver(const TailResult& result, const LogWindow& w) {
  return reaches(result, w) ? tailExponentOver(result, w.from, w.to)
                            : TailExponent{w.from, w.to, std::sqrt(w.from * w.to), 0,
                                           std::numeric_limits<double>::quiet_NaN()};
}

TailScanWindow tailScanAverage(const std::vector<TailExponent>& ofK, const LogWindow& window) {
  TailScanWindow a;
  a.from = window.from;
  a.to = window.to;
  a.t = std::sqrt(window.from * window.to);
  double sum = 0, variance = 0;
  for (const TailExponent& e : ofK)
    if (std::isfinite(e.gamma)) {
      ++a.count;
      sum += e.gamma;
      variance += e.gammaError * e.gammaError;
    }
  if (a.count == 0) return a;
  const auto n = static_cast<double>(a.count);
  a.mean = sum / n;
  a.error = std::sqrt(variance) / n;
  if (a.count < 2) return a;
  double squares = 0;
  for (const TailExponent& e : ofK)
    if (std::isfinite(e.gamma)) squares += (e.gamma - a.mean) * (e.gamma - a.mean);
  a.spread = std::sqrt(squares / (n - 1));
  return a;
}

std::vector<LogWindow> tailScanWindows(double lowest, double largest) {
  std::vector<LogWindow> windows;
  if (!(lowest > 0 && largest > 0 && std::isfinite(lowest) && std::isfinite(largest))) return windows;
  for (int j = static_cast<int>(std::ceil(2 * std::log10(lowest) - 1e-9));; ++j) {
    const LogWindow w{std::pow(10.0, j / 2.0), std::pow(10.0, j / 2.0 + 1)};
    if (w.from < lowest) continue;  // rounding of the logarithm
    if (w.to > largest) break;
    windows.push_back(w);
  }
  return windows;
}

TailScanSummary tailScanSummary(const std::vector<double>& allK, std::vector<TailState> all) {
  if (all.empty() || all.size() != allK.size()) throw std::invalid_argument("a tail scan's summary needs a run per K");
  TailScanSummary out;
  std::vector<TailState> states;
  const std::vector<std::uint64_t> levels = all.front().levels;
  const std::uint32_t q = all.front().request.run.q;
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k].levels != levels || all[k].request.run.q != q)
      throw std::invalid_argument("the runs of a tail scan's summary must have the same levels");
    if (const std::optional<std::string> why = tailFirstLevelRefusal(all[k])) {
      out.outOfReach.push_back({allK[k], *why});
      continue;
    }
    if (!all[k].finished()) throw std::invalid_argument("a tail scan's summary needs finished runs");
    out.K.push_back(allK[k]);
    states.push_back(std::move(all[k]));
  }
  if (states.empty())
    throw std::invalid_argument("no K of the scan reached its first level: K = " + scanKText(out.outOfReach.front().K) +
                                ": " + out.outOfReach.front().reason);
  const double lowest = std::max({static_cast<double>(levels.front()) * q, 10.0, 2.0 * q});
  out.windows = tailScanWindows(lowest, static_cast<double>(levels.back()) * q);
  for (const TailState& s : states) {
    out.results.push_back(tailResult(s));
    std::vector<TailExponent>& of = out.gamma.emplace_back();
    for (const LogWindow& w : out.windows) of.push_back(tailScanExponentOver(out.results.back(), w));
  }
  for (std::size_t w = 0; w < out.windows.size(); ++w) {
    std::vector<TailExponent> ofK;
    for (const std::vector<TailExponent>& of : out.gamma) ofK.push_back(of[w]);
    out.average.push_back(tailScanAverage(ofK, out.windows[w]));
  }
  out.states = std::move(states);
  return out;
}

std::string tailScanText(const TailScanSummary& s) {
  const TailRequest& r = s.states.front().request;
  std::string out = io::formatC("# tail-scan: %zu K; q = %u, seed = %llu, N = %u, R = %u, clones = %s, t_max = %s\n",
                                s.K.size(), r.run.q, static_cast<unsigned long long>(r.run.seed), r.population,
                                r.replicas, cloneRuleName(r.clones), io::shortestText(r.maxSteps).c_str());
  if (!s.outOfReach.empty())
    out += io::formatC("# and %zu K whose first level is out of reach (listed at the end)\n", s.outOfReach.size());
  out += "# P_t per K and level\n" + io::formatC("%8s %12s %12s %10s %9s\n", "K", "t", "P", "P_error", "reliable");
  for (std::size_t k = 0; k < s.K.size(); ++k)
    for (const TailLevelResult& L : s.results[k].levels)
      out += io::formatC("%8s %12.0f %12.5g %10.3g %9s\n", scanKText(s.K[k]).c_str(), L.t, L.P, L.PError,
                         L.reliable ? "yes" : "no");
  out += "# gamma = -dlnP/dlnt per K over the windows (reached: a reliable level at or below t_from and one at or "
         "above t_to)\n" +
         io::formatC("%8s %12s %12s %8s %8s\n", "K", "t_from", "t_to", "gamma", "error");
  for (std::size_t k = 0; k < s.K.size(); ++k)
    for (const TailExponent& e : s.gamma[k])
      if (std::isfinite(e.gamma))
        out += io::formatC("%8s %12.0f %12.0f %8.4f %8.3g\n", scanKText(s.K[k]).c_str(), e.tFrom, e.tTo, e.gamma,
                           e.gammaError);
  out += "# the K-average of gamma per window: over the K that reach it; spread: standard deviation over K; error: "
         "sqrt(sum of the K's error^2)/K\n" +
         io::formatC("%12s %12s %4s %8s %8s %8s\n", "t_from", "t_to", "K", "gamma", "spread", "error");
  for (const TailScanWindow& a : s.average)
    out += io::formatC("%12.0f %12.0f %4zu %8.4f %8.3g %8.3g\n", a.from, a.to, a.count, a.mean, a.spread, a.error);
  if (!s.outOfReach.empty()) out += "# K whose first level is out of reach (no P_t, no gamma; not in the averages)\n";
  for (const TailScanRefusal& k : s.outOfReach) out += "#   K = " + scanKText(k.K) + ": " + k.reason + "\n";
  return out;
}

std::string tailScanPCsv(const TailScanSummary& s) {
  std::string out = "K,t,P,P_error,reliable\n";
  for (std::size_t k = 0; k < s.K.size(); ++k)
    for (const TailLevelResult& L : s.results[k].levels)
      out += csvNumber(s.K[k]) + "," + csvNumber(L.t) + "," + csvNumber(L.P) + "," + csvNumber(L.PError) + "," +
             (L.reliable ? "1" : "0") + "\n";
  return out;
}

std::string tailScanGammaCsv(const TailScanSummary& s) {
  std::string out = "K,t_from,t_to,t,points,gamma,gamma_error\n";
  for (std::size_t k = 0; k < s.K.size(); ++k)
    for (const TailExponent& e : s.gamma[k])
      out += csvNumber(s.K[k]) + "," + csvNumber(e.tFrom) + "," + csvNumber(e.tTo) + "," + csvNumber(e.t) + "," +
             std::to_string(e.points) + "," + csvNumber(e.gamma) + "," + csvNumber(e.gammaError) + "\n";
  return out;
}

std::string tailScanAverageCsv(const TailScanSummary& s) {
  std::string out = "t_from,t_to,t,K_count,gamma_mean,gamma_spread,gamma_mean_error\n";
  for (const TailScanWindow& a : s.average)
    out += csvNumber(a.from) + "," + csvNumber(a.to) + "," + csvNumber(a.t) + "," + std::to_string(a.count) + "," +
           csvNumber(a.mean) + "," + csvNumber(a.spread) + "," + csvNumber(a.error) + "\n";
  return out;
}

TailScanOutcome runTailScan(const TailScanRequest& r, const TailScanView& view, Ranks& ranks, std::stop_token stop) {
  ScanSettings s;
  std::vector<io::FileLock> locks;
  std::vector<ScanItem> items;
  onEveryRank(ranks, [&] {
    s = checkedSettings(r, ranks);
    if (ranks.rank() != 0) return;  // rank 0 makes the folder, then the others find it
    if (auto e = scanFolderError(r.dir)) throw std::runtime_error(*e);
    std::filesystem::create_directory(r.dir);
  });
  onEveryRank(ranks, [&] {
    if (!std::filesystem::is_directory(r.dir)) throw std::runtime_error("cannot find the folder " + r.dir);
    for (const std::string& csv : r.csv.empty() ? std::vector<std::string>{} : tailScanCsvFiles(r.csv))
      io::checkWritableTarget(csv);  // after the folder is made: the CSVs may be in it
    if (!r.csv.empty()) io::checkWritableTarget(tailScanPngFile(r.csv));
    for (const std::size_t i : s.mine) {
      const std::string file = tailScanFile(r.dir, s.K[i]).string();
      for (io::FileLock& lock : lockJobFiles(file, file, {})) locks.push_back(std::move(lock));
    }
    items = planItems(r, s);
  });
  bool finished = true;
  std::string stoppedFile;
  onEveryRank(ranks, [&] {
    for (ScanItem& item : items) {
      if (runItem(item, r, s, view, stop)) continue;
      finished = false;
      stoppedFile = item.file.string();
      break;
    }
  });
  if (!ranks.all(finished)) return {TailScanOutcome::End::interrupted, s.K, stoppedFile, {}, {}};
  TailScanOutcome out{TailScanOutcome::End::finished, s.K, {}, {}, {}};
  onEveryRank(ranks, [&] {
    if (ranks.rank() == 0) out = summaryOutcome(r, s);
  });
  return out;
}

}  // namespace archipelago
