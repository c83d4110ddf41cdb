#pragma once
/// \file TailAnalysis.hpp
/// \brief Honest errors for D and the tail of P_t and C_τ (Karney 1983, §5; issue #14, items 2 and 7).
///
/// The paper's D = 6400 ± 800 comes from the spread over subsets of orbits, and the paper warns that a few
/// very long segments make that error "severely underestimated".  Eight independent runs of 5·10¹⁰ steps at
/// K = 0.1 gave D from 1047 to 9000, each quoting ±120–330.  This file gives what the data can support:
///
///  - A bootstrap over segments.  Replicate r of a histogram draws every bin's count from a Poisson law of
///    mean n_i (independently per bin: the number of segments of a run is random too) and keeps the bin's
///    mean length, Σ*_i = round(n*_i Σ_i/n_i); the statistics of a replicate are computeStatistics() of it,
///    the one definition of f, P, C and D.  The random numbers are core/random's counter generator:
///    key = orbitKey(seed, r), the k-th uniform of a replicate (orbitDraw(key, k) + ½)/2⁵²; Poisson variates
///    by multiplication below a mean of 10 and by Hörmann's transformed rejection (PTRS, 1993) above.  So a
///    bootstrap is reproducible from its seed (BootstrapOptions::seed, printed with every result).  The
///    interval is the percentile interval of the replicates.  A bootstrap cannot draw a segment longer than
///    the longest seen: when the longest few segments carry D, no resampling of this run measures D's error,
///    and the verdict below says so.
///  - The share of D carried by the longest k segments: D = Σ ½ s_i² w_i (TrappingStatistics.hpp), each
///    segment of bin i carrying ½ s_i² w_i/n_i; segments taken from the top bin down.
///  - D as a function of the steps sampled: the run keeps no time-resolved record, only subset histograms of
///    the whole length T, so the honest "steps sampled" is orbits × T × q over the first k subsets (and then
///    over the next seed's subsets): D of the union of subsets 1..k.  Every point uses whole orbits of the
///    full record, so each point is an unbiased D of fewer orbits, not of shorter orbits.
///  - Tail fits.  γ_P = −d log P/d log t and γ_C = −d log C/d log τ over a window [from, to]: the least-squares
///    slope of log value on log t on a log grid (LogFits.hpp: equal weight per unit of log t) in the window,
///    where the value is > 0.  The
///    tail end t_end is the largest grid t with at least minTailSegments segments beyond it (counted in the
///    histogram as segments whose bin mean is > t, the masses P_t counts); the tail fit is the last decade
///    [t_end/10, t_end]; the windows are decades ending at t_end·10^(−k/2), k = 0, 1, …, while their lower end
///    is at least max(10, 2q) steps (the tail fit alone may start there, when t_end < 100 steps; none when
///    t_end < 3 max(10, 2q)).  Each has a bootstrap interval.
///  - The verdict.  D is "dominated by its longest segments" when any of:
///      (a) the longest segment carries more than dominanceShare (20 %) of D;
///      (b) the bootstrap interval of D is wider than D itself;
///      (c) the tail fit's upper bound on γ_P is below 2: if P_t ~ t^−γ goes on, f_t ~ t^−γ−1 and
///          D = Σ ½ t² f_t diverges for γ ≤ 2 (the paper's argument, §5, with α_C = γ − 1 ≤ 1), so every
///          finite run's D is a lower bound of a quantity that grows with the steps sampled.
///    Then no error is printed for D (the message says why); otherwise the bootstrap error.  With several
///    seeds the spread over seeds (standard error of the mean of the per-seed D) is given too, and it is the
///    error of choice when the tail does not dominate the pooled run.
///  - The running exponent γ(t): the windows above, log-spaced (decades ending at t_end·10^(−k/2)), each with its
///    bootstrap interval; plotted against the later literature's asymptotic exponents (ReferenceSlopes.hpp), which
///    no finite window is said to be "consistent" with (issue #26).
///  - A forward estimate (issue #26; it replaced a "steps to decide" that asked for 9.2 times the steps already
///    run whatever the run: it anchored at t_end, the very point that moves out as the run grows).  Segments
///    longer than t_end start at the measured rate r = n(t_end)/steps, n(t_end) the segments longer than t_end in
///    the data (≥ minTailSegments) and steps = M T q.  If P_t ∝ t^−γ beyond t_end, segments longer than a target t
///    start at r (t/t_end)^−γ, so N of them need
///        steps(t, γ) = N / r · (t/t_end)^γ
///    steps of record (and orbits longer than t: q T > t).  Given for N = 100, the targets 10⁸, 10⁹, 10¹⁰ and each
///    literature exponent: what each hypothesis would cost, not a verdict.

/// Reference slopes for the P_t plot: t^−1.57 (Cristadoro & Ketzmerick, PRL 100, 184101, 2008), t^−3/2
/// (Venegeroles, PRL 102, 064101, 2009), t^−1.3 (Shepelyansky 2010, few degrees of freedom) and t^−3
/// (Chirikov & Shepelyansky, PRL 82, 528, 1999), anchored at the data (referenceSlopes()).
///
/// Everything here is a pure function of its arguments (thread-safe, no Qt).

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/stats/Bootstrap.hpp"
#include "core/stats/RunEnsemble.hpp"
#include "core/stats/TrappingStatistics.hpp"
#include "core/trapping/TrappingHistogram.hpp"

namespace archipelago {

/// A window of the tail with its exponents and their bootstrap intervals.
struct TailWindow {
  double from = 0, to = 0;                ///< steps
  double gammaP = kTailUndefined;                   ///< −d log P_t/d log t
  ConfidenceInterval gammaPInterval;
  double exponentC = kTailUndefined;                ///< −d log C_τ/d log τ
  ConfidenceInterval exponentCInterval;
  std::size_t points = 0;                 ///< grid points of P in the window
  std::uint64_t segmentsBeyondFrom = 0;   ///< segments longer than `from`
  std::uint64_t segmentsBeyondTo = 0;     ///< segments longer than `to`
};

/// One point of D as a function of the steps sampled.
struct DPoint {
  double steps = 0;            ///< orbits × T × q
  std::uint64_t orbits = 0;
  std::uint64_t segments = 0;
  double D = 0;
  double gammaTail = kTailUndefined;     ///< γ_P over the tail fit's window (of the whole sample)
  double longestSteps = 0;     ///< the longest segment so far (its bin's mean length), steps
};

/// The share of D carried by the k longest segments.
struct LongestShare {
  std::size_t k = 0;
  double share = 0;            ///< in [0, 1]
  double shortestOfThem = 0;   ///< length of the k-th longest (its bin's mean), steps
};

/// The steps a run would need for `segments` segments longer than `target`, if P_t ∝ t^−γ beyond t_end.
struct TailForecast {
  double target = 0;       ///< t, steps
  double gamma = 0;        ///< the hypothesis (a literature exponent)
  double segments = 100;   ///< N
  double steps = kTailUndefined;
};

/// Segments longer than t, on P's grid.
struct SegmentsBeyond {
  double t = 0;
  double P = 0;
  std::uint64_t segments = 0;
};

struct TailOptions {
  BootstrapOptions bootstrap;
  std::uint64_t minTailSegments = 10;   ///< segments beyond t_end
  double dominanceShare = 0.2;          ///< criterion (a)
  double forecastSegments = 100;        ///< N of the forecast
};

struct TailAnalysis {
  BootstrapOptions bootstrap;           ///< as used
  double D = kTailUndefined;                      ///< of the pooled sample (eq. ddef)
  double DSubsetError = 0;              ///< the paper's error: standard error over the subsets
  double DBootstrapError = kTailUndefined;        ///< standard deviation of the replicates
  ConfidenceInterval DInterval;                   ///< percentile interval of the replicates
  // Over seeds (members); empty / NaN for one member.
  std::vector<std::uint64_t> seeds;
  std::vector<double> seedD;
  double seedMean = kTailUndefined, seedMedian = kTailUndefined, seedError = kTailUndefined, seedMin = kTailUndefined, seedMax = kTailUndefined;

  std::vector<LongestShare> shares;     ///< k = 1, 2, 3, 5, 10 (those the sample has)
  std::vector<DPoint> DvsSteps;
  double tailEnd = kTailUndefined;                ///< t_end, steps (NaN: no tail with minTailSegments beyond)
  TailWindow tailFit;                   ///< [t_end/10, t_end]
  std::vector<TailWindow> windows;      ///< decades ending at t_end, t_end/√10, …
  std::vector<SegmentsBeyond> beyond;
  double stepsDone = 0;                 ///< M T q summed over members
  std::vector<TailForecast> forecast;   ///< targets 10⁸, 10⁹, 10¹⁰ × referenceExponents(); empty without t_end

  bool shareDominates = false;          ///< (a)
  bool intervalTooWide = false;         ///< (b)
  bool tailDiverges = false;            ///< (c)
  [[nodiscard]] bool dominated() const noexcept { return shareDominates || intervalTooWide || tailDiverges; }
};

/// Everything above for an ensemble (one member: one run).  Throws std::invalid_argument for an empty
/// ensemble, replicates outside [20, 100000], a confidence outside (0, 1), or as computeStatistics().
[[nodiscard]] TailAnalysis analyseTail(const Ensemble& e, const TailOptions& options = {});

/// D's one-sigma error where the data support one: the bootstrap over segments, unless the tail dominates D
/// (then, and when the bootstrap could not be done, NaN).  Never the 16-subset error, which the heavy tail makes
/// far too small (issue #14, item 2).  Every printed or exported error of D comes from here.
[[nodiscard]] double supportedDError(const TailAnalysis& a) noexcept;

/// The verdict on D in words, one line: "D is dominated by its longest segments; its error cannot be estimated
/// from this run (...)" with the reasons, or an empty string when the bootstrap error stands.
[[nodiscard]] std::string dominanceMessage(const TailAnalysis& a);

}  // namespace archipelago
