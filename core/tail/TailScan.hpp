#pragma once
/// \file TailScan.hpp
/// \brief The tail sampler scanned over K (issue 55, "the exponent atlas") as one job (core/job/Job.hpp): the K
/// list, the sampler's settings and a folder; a tail file per K, each the run of `tail` with the tail's spec in the
/// box of scanBox(K); and the summary over K, computed from the finished tail files alone (so that a rerun from the
/// files gives the same numbers, bit for bit).  archipelago-cli tail-scan, archipelago-mpi tail-scan and Python's
/// tail_scan() fill the request, show the progress and format the outcome.
///
/// The folder holds DIR/tail-K<scanKText(K)>.json for each K.  The plan of each K: a finished file is reused (read
/// and checked: a file of other settings is refused, naming the first that differs); an unfinished one is resumed;
/// an absent one is started.  The K are shared round-robin: over a task I of N (a Slurm array: K_i with
/// i mod N = I), then over the ranks (the m-th K of the task on rank m mod size).  Each process locks the files of
/// its K (lockJobFiles) before it reads them, so two scans on one folder never write the same file.  A stop (the
/// std::stop_token) leaves the running K's checkpoint in its file; the same request resumes it.
///
/// The summary (tailScanSummary), once every K's file is finished:
///   - per K, the levels of tailResult(): t, P_t and its error, reliable or not;
///   - windows fixed for every K: a decade wide, stepped by half a decade, [10^(j/2), 10^(j/2+1)], from the first
///     at or above lowest = max(the first level's t, 10, 2q) (as the running exponent's) to the last whose end is
///     at or below the last level's t (the levels depend on the settings, not on K: tailLevels());
///   - per K and window, γ = tailExponentOver() (TailResult.hpp: the running exponent's one definition, its error
///     from the replicas' covariance of P_r(t) at the levels, with the binomial floor), given when the K reaches the
///     window: a reliable level at or below its start and one at or above its end;
///   - per window, over the n K that reach it: the K-average γ̄ = Σγ/n, the spread s = √(Σ(γ − γ̄)²/(n − 1)) (the
///     standard deviation over K; NaN for n < 2), and the standard error of the average from each K's error,
///     √(Σσ²)/n (the K are independent runs; NaN when an error is).  The spread is how γ varies with K — physics,
///     not noise — so it is not divided into the error.
///
/// The figure γ(t, K) (issue 55): tailGammaHeatMap(), the summary's γ as a heat map of the K scan's kind
/// (core/scan/ScanHeatMap.hpp: K across, log t up, the one colour scale up to kTailGammaTop), written as
/// PREFIX_gamma.png beside the CSVs, and drawn with γ per window against the literature's exponents
/// (tailScanReferenceExponents()) by the GUI's K-scan dialog, which reads a scan's folder with loadTailScan().

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <string_view>
#include <vector>

#include "core/job/Ranks.hpp"
#include "core/runspec/RunSpec.hpp"
#include "core/scan/ScanHeatMap.hpp"
#include "core/stats/LogFits.hpp"
#include "core/stats/ReferenceSlopes.hpp"
#include "core/tail/TailResult.hpp"
#include "core/tail/TailSampler.hpp"

namespace archipelago {

/// The tail file of K in the scan folder `dir`: dir/tail-K<scanKText(K)>.json.
[[nodiscard]] std::filesystem::path tailScanFile(const std::filesystem::path& dir, double K);

/// What a front end filled.  Core's messages name each setting by its role ("K", "dir", "task", "clones",
/// "checkpoint-interval", "csv"); `optionName` maps a role to the front end's own name (TailPlanOptions::optionName's
/// way).
struct TailScanRequest {
  std::function<std::string(std::string_view role)> optionName;  ///< empty: the role itself
  [[nodiscard]] std::string nameOf(std::string_view role) const;

  std::string K;                   ///< the K list as given (parseScanValues)
  RunSpec base;                    ///< the tail's spec (threads, kernel too); K and the box are scanBox(K)'s
  TailRequest request;             ///< the sampler's settings (request.run is base's in the box of each K)
  std::string clones = "perturb";
  std::string dir;                 ///< the scan folder (created when missing; its parent must exist)
  double checkpointSeconds = 60;   ///< checkpointIntervalError()'s rule
  std::optional<std::string> task; ///< "I/N", whole numbers with I < N: this task's K (i mod N = I); none: all
  std::string csv;                 ///< PREFIX: the summary's CSVs PREFIX_P.csv, PREFIX_gamma.csv, PREFIX_average.csv
                                   ///< and its figure PREFIX_gamma.png
  /// Core's warning about a K whose box or zone cuts the central island (checkBoxAgainstIsland), once per K
  /// started; empty: none is looked for.
  std::function<void(const std::string& warning)> warning;
};

/// A window's K-average (the file comment).
struct TailScanWindow {
  double from = 0, to = 0, t = 0;  ///< steps; t = √(from·to)
  std::size_t count = 0;           ///< the K that reach it
  double mean = std::numeric_limits<double>::quiet_NaN();
  double spread = std::numeric_limits<double>::quiet_NaN();
  double error = std::numeric_limits<double>::quiet_NaN();
};

/// A K of the scan whose first level is out of the map's reach (no P_t there beyond the fast decay: at K = 0.55 …
/// 0.65, 1.2 and 1.3 no segment of 8·10⁹ steps lasted 10³, docs/tail.md).
struct TailScanRefusal {
  double K = 0;
  std::string reason;  ///< tailFirstLevelRefusal()'s
};

struct TailScanSummary {
  std::vector<double> K;                        ///< the K whose run is finished (the rest below are of these)
  std::vector<TailState> states;                ///< per K: its finished run (the process, the settings)
  std::vector<TailResult> results;              ///< per K: tailResult()
  std::vector<LogWindow> windows;               ///< common to every K
  std::vector<std::vector<TailExponent>> gamma; ///< [K][window]; gamma NaN where the K does not reach the window
  std::vector<TailScanWindow> average;          ///< per window
  std::vector<TailScanRefusal> outOfReach;      ///< the K whose first level is out of reach, in the list's order
};

/// The windows [10^(j/2), 10^(j/2+1)] from the first at or above `lowest` to the last ending at or below `largest`.
[[nodiscard]] std::vector<LogWindow> tailScanWindows(double lowest, double largest);

/// γ of one K over window w (the file comment): tailExponentOver() when the K reaches it (a reliable level at or below
/// its start and one at or above its end), else gamma NaN.  The summary's windows and any other (the report's
/// tail-gamma-K: [10⁴, 10⁶]) by the one rule.
[[nodiscard]] TailExponent tailScanExponentOver(const TailResult& result, const LogWindow& w);

/// The K-average of window w over the K whose γ there (`ofK`, one per K) is finite (the file comment).
[[nodiscard]] TailScanWindow tailScanAverage(const std::vector<TailExponent>& ofK, const LogWindow& w);

/// The summary of the runs, one per K (the file comment): each finished, or refused (its first level out of reach:
/// tailFirstLevelRefusal(), listed in outOfReach).  A pure function.  Throws std::invalid_argument when the runs are
/// not of one scan's settings (their levels differ), one is neither finished nor refused, or none is finished.
[[nodiscard]] TailScanSummary tailScanSummary(const std::vector<double>& K, std::vector<TailState> states);

/// The summary as the command prints it: the settings, P per K and level, γ per K and window, the K-average.
[[nodiscard]] std::string tailScanText(const TailScanSummary& s);
/// The summary's CSVs (numbers with 17 significant digits, empty when not finite): K,t,P,P_error,reliable;
/// K,t_from,t_to,t,points,gamma,gamma_error (every K and window); t_from,t_to,t,K_count,gamma_mean,gamma_spread,
/// gamma_mean_error.
[[nodiscard]] std::string tailScanPCsv(const TailScanSummary& s);
[[nodiscard]] std::string tailScanGammaCsv(const TailScanSummary& s);
[[nodiscard]] std::string tailScanAverageCsv(const TailScanSummary& s);
/// PREFIX_P.csv, PREFIX_gamma.csv, PREFIX_average.csv.
[[nodiscard]] std::vector<std::string> tailScanCsvFiles(const std::string& prefix);
/// PREFIX_gamma.png: the figure γ(t, K) (tailGammaHeatMap() as writeHeatMapPng() draws it).
[[nodiscard]] std::string tailScanPngFile(const std::string& prefix);

/// The colour scale's top for γ: 0 white, 1.5 orange (the literature's exponents lie about it), 3 and more dark red.
inline constexpr double kTailGammaTop = 3;
/// The figure γ(t, K) as a heat map: K[column] the summary's K and those out of reach, by increasing K, tau[row] the
/// centre t of window row (the summary's windows, increasing), value[row · K.size() + column] = γ of that K over
/// that window (NaN where the K does not reach it, and in every row of a K out of reach), top kTailGammaTop.  The
/// summary's numbers, none computed here.
[[nodiscard]] ScanHeatMap tailGammaHeatMap(const TailScanSummary& s);
/// The asymptotic exponents γ is set against: 1.57 (Cristadoro & Ketzmerick, PRL 100 (2008) 184101; Alus, Fishman
/// & Meiss, PRE 96 (2017) 032204) and 1.44, the ultrametric estimate ln 2/ln(1 + r_g) (Avetisov & Nechaev,
/// arXiv:0909.4513), from core/paper's table.
[[nodiscard]] const std::vector<ReferenceExponent>& tailScanReferenceExponents();

/// A scan's folder as loadTailScan() read it.
struct TailScanFolder {
  TailScanSummary summary;          ///< of the finished K (and those out of reach), by increasing K
  std::vector<double> unfinished;   ///< the K whose file is not finished yet (a scan still running): not summarized
};
/// The summary of the finished tail files of a folder written by tail-scan (its files tail-K<K>.json; other files
/// are ignored), for a front end that shows a scan.  Each file is read whole and checked: a run of K in the scan's
/// box of K (scanBox) under the name of its K, every replica, the sampler's settings of the folder's other files.
/// Throws std::runtime_error with one line naming the folder or the file: not a folder, no tail file in it, none
/// finished yet (or every one out of reach), a file unreadable, truncated or edited (loadTailFile's reason), a file of another box, K or
/// settings.
[[nodiscard]] TailScanFolder loadTailScan(const std::filesystem::path& dir);

/// How a front end shows a scan (every member may be empty); `index` is the K's place in the list.
struct TailScanView {
  /// A K of this process begins: "reused", "resumed" or "started".
  std::function<void(std::size_t index, std::size_t count, double K, const std::string& how)> begins;
  std::function<void(std::size_t index, double K, const TailState&, const TailProgress&)> progress;
  std::function<void(std::size_t index, double K, const TailState&)> finished;  ///< just now, or reused
  /// The K's first level is out of reach (just now, or a file that says so): the scan goes on to the next K.
  std::function<void(std::size_t index, double K, const std::string& reason)> outOfReach;
  std::function<void(const std::string& reason, double retrySeconds)> checkpointWarning;
};

struct TailScanOutcome {
  enum class End {
    interrupted,  ///< stopped: the running K's checkpoint is in `checkpoint`
    waiting,      ///< this task's K are finished, others' not yet (`waitingFor`): no summary
    finished,     ///< every K finished; the summary (rank 0) and its CSVs written
  };
  End end = End::finished;
  std::vector<double> K;           ///< the whole list
  std::string checkpoint;          ///< interrupted: the file of the K stopped (on this rank)
  std::vector<double> waitingFor;  ///< waiting: the K not finished
  TailScanSummary summary;         ///< finished, on rank 0
};

/// The scan on `ranks` until this process's K are finished or `stop` is requested: every setting checked first
/// (the K list, the task, the threads, the checkpoint interval, the clone rule, each K's request, the folder), the
/// folder created, this process's files locked and planned (reused, resumed or started; a file refused names its
/// reason), each K run with checkpoints into its file (runTailJob) and written finished.  Then, when every K of the
/// list is finished, rank 0 reads all the files, and returns the summary and writes its CSVs (csv).  An error on any
/// rank is one error on all (Ranks::agree), thrown as std::invalid_argument or std::runtime_error.
[[nodiscard]] TailScanOutcome runTailScan(const TailScanRequest& request, const TailScanView& view, Ranks& ranks,
                                          std::stop_token stop = {});

}  // namespace archipelago
