#pragma once
/// \file TrappingStatistics.hpp
/// \brief Trapping statistics derived from histograms: pure functions (Karney 1983, §3, §5, appendices A–B).
///
/// Units: lengths and times in steps of N (a histogram counts blocks of q steps; appendix B converts with
/// t = q·t_blocks and f_t = F/q²).  Definitions (paper equation labels):
///   f_t  = N_t / (M (T + 1 − t))                (appendix A, unbiased for a record of T blocks)
///   α    = 1 / Σ f_t                            mean segment length
///   p_t  = α f_t
///   P_t  = Σ_{τ>t} p_τ                          (eq. pdef), P_0 = 1
///   C_τ  = Σ_{t≥τ} (t − τ) f_t                  (eq. cdef), C_0 = Σ t f_t ≈ 1
///   D    = Σ ½ t² f_t                           (eq. ddef)
///   S_t  = t C_0 + 2 Σ_{τ=1}^{t} (t − τ) C_τ    (eq. spreaddef),  D_t = S_t / 2t
///   local exponent = −d log C_τ / d log τ        (fig. 6d)
///
/// How a histogram becomes f (see TrappingHistogram.hpp for the bins).  Bin i holds n_i segments whose
/// lengths sum to Σ_i blocks; its mean length is t̄_i = Σ_i/n_i blocks (exact for t ≤ 50 blocks, where a bin
/// holds one length).  T + 1 − t is evaluated at t̄_i.
///  - The plotted density (Series f) is the paper's F_i of appendix B per step: at t = q·t̄_i,
///      f = n_i / (M (T + 1 − t̄_i)) / width_i / q²,   width_i = binUpper(i) − binLower(i) blocks.
///  - Every sum (α, P, C, D, S) treats the bin's segments as a point mass at s_i = q·t̄_i steps with weight
///      w_i = n_i / (M (T + 1 − t̄_i)) / q        (a number of segment starts per step of record),
///    so that Σ s_i w_i = Σ t f_t = C_0 and α = 1/Σ w_i.  This is exact for the exact bins (t ≤ 50 blocks)
///    when the record is in steps of q; for a logarithmic bin it replaces the segments by their mean: the
///    first moment of the bin (hence C_0, and C_τ for τ below the bin) is kept, up to the change of
///    1/(T + 1 − t) across the bin (second order, and negligible while t ≪ T), while
///    second moments (D, S_t) miss the within-bin variance, a relative error below (width/t)²/12 ≈ 5·10⁻⁴
///    at 30 bins per decade.  Lengths in steps need not be integers (s_i is a mean); C_τ is piecewise
///    linear between the s_i.  With non-integer s_i, ½C_0 + Σ_{τ≥1} C_τ (the limit of D_t) exceeds
///    D = ½Σ s_i² w_i by Σ w_i δ_i(1 − δ_i)/2, δ_i = s_i − ⌊s_i⌋: only logarithmic bins (s_i > 50) have
///    δ_i ≠ 0, so each mass's share of D is raised by less than 1/(4 s_i²) < 10⁻⁴ in that limit.
///  - Closed forms (no loop over t): C_τ = Σ w_i (s_i − τ)₊, P_t = α Σ_{s_i > t} w_i, and
///      S_t = Σ w_i k(s_i, t),  k(s, t) = t s + 2 Σ_{τ=1}^{min(s,t)} (t − τ)(s − τ),
///    where k, a sum of polynomials, is linear in t on each side of s = t with non-negative coefficients
///    (k = t s² − (s³ − s)/3 for integer s ≤ t).  One sweep of the sorted grid over the sorted masses
///    evaluates all of them in O(grid + bins), in long double, by prefix/suffix sums and recurrences in
///    which every term is non-negative: no cancellation even for t, s ~ 10¹⁰.
///
/// Grid for P, C, S and D_t (steps, integers): 0, 1, …, min(50q, 4096) (every length in the exact bins when
/// q ≤ 81), then 30 points per decade, rounded to integers, up to twice the longest length the histogram can
/// hold.  D_t omits t = 0.  The local exponent has its own logarithmic grid (issue #26), τ_j = 10^(j/10) for
/// j = 0, 1, … up to the same end: C_τ, piecewise linear in τ, is evaluated exactly at each τ_j, and the
/// exponent is the centred difference of log C over log τ across τ_{j±1} (where C > 0); so it is exact for a
/// power law, and a kink of C at a multiple of q (the blocks) is averaged over ±0.1 decade instead of showing
/// as a spike (5.41 at τ = 100 for q = 100 on the old integer grid).
///
/// Errors: each quantity is also computed for every subset of orbits alone (with its own M_i, on the grid of
/// the total); the error is the standard error of the mean over the n subsets, s/√n with s the sample
/// standard deviation (n − 1 in the denominator) — the paper's method for D = 6400 ± 800 (§5).  Values come
/// from the total histogram.  With one subset, or one histogram, every error is 0.  For the local exponent
/// only the subsets where it is defined at that τ contribute.  An empty subset counts as f = C = S = D = 0
/// and has no α, p or P.  As the paper warns, a few very long segments make the subset values skewed, so
/// these errors may be underestimates.

#include <cstdint>
#include <limits>
#include <vector>

#include "core/trapping/TrappingHistogram.hpp"

namespace archipelago {

/// The value of a quantity the data do not define (a fit with too few points, an error that cannot be estimated).
inline constexpr double kTailUndefined = std::numeric_limits<double>::quiet_NaN();

/// A sampled curve: value[i] at abscissa x[i], with a one-sigma error (0 when unknown); the three vectors
/// always have the same size.
struct Series {
  std::vector<double> x;
  std::vector<double> value;
  std::vector<double> error;
};

/// What the estimator needs to know about the record behind a histogram.
struct RecordShape {
  std::uint64_t orbits = 0;  ///< M: orbits that fed the histogram
  std::uint64_t blocks = 0;  ///< T: blocks per orbit (blocks done so far, for a run in progress)
  std::uint32_t q = 1;       ///< steps per block
};

struct TrappingStatistics {
  Series f;               ///< f_t at the mean length of each non-empty bin (steps), a density per step
  Series p;               ///< p_t = α f_t, same abscissae as f
  Series P;               ///< P_t on the grid
  Series C;               ///< C_τ on the grid
  Series localExponent;   ///< −d log C / d log τ on the grid points where defined (log-linear plot)
  Series S;               ///< S_t on the grid
  Series Scompensated;    ///< S_t / t^{3/2} on the grid without t = 0 (fig. 7b: flat where S_t ~ t^{3/2})
  Series Dt;              ///< D_t = S_t / 2t on the grid without t = 0
  double alpha = 0, alphaError = 0;  ///< mean segment length α (steps)
  double D = 0, DError = 0;          ///< diffusion coefficient (eq. ddef)
  double sumTf = 0;                  ///< Σ t f_t = C_0 (≈ 1; exactly 1 for an exact f)
  std::uint64_t segments = 0;        ///< segments in the histogram
  std::uint64_t longestBlocks = 0;   ///< longest length the highest non-empty bin can hold, in blocks
  /// Below this t (steps) the statistics describe the process of blocks of q steps, not the paper's q = 1 process
  /// (docs/design.md, "Blocks of q steps"): 10 q for a run of q > 1 without a q = 1 companion, 0 otherwise.  Plots
  /// shade it, CSV files mark it.
  double blockAffectedBelow = 0;
  /// Spliced statistics (computeSplicedStatistics): the crossover t_c (steps) below which f_t is the q = 1
  /// companion's; 0 for the statistics of one run.
  double splicedAt = 0;
};

/// t < kBlockAffectedBlocks · q steps is affected by the blocks of a run of q > 1.
inline constexpr double kBlockAffectedBlocks = 10;

/// The points per decade of the local exponent's grid (and of every power-law fit, core/stats/LogFits.hpp).
inline constexpr int kLogGridPerDecade = 10;

/// Statistics of one histogram (every error 0).  An empty histogram gives empty series and zeros.
/// Throws std::invalid_argument when the histogram is not empty and shape.orbits, shape.blocks or shape.q is
/// 0, or when a bin's mean length exceeds shape.blocks (no segment can be longer than the record).
[[nodiscard]] TrappingStatistics computeStatistics(const TrappingHistogram& h, const RecordShape& shape);

/// Statistics of the union of subset histograms, with errors from the spread over subsets.
/// `orbitsPerSubset[i]` is the number of orbits that fed subsets[i]; all subsets share `blocks` and `q`.
/// Throws std::invalid_argument when there are no subsets, the two vectors differ in size, or for the
/// conditions of the overload above (checked for the total and for every non-empty subset).
[[nodiscard]] TrappingStatistics computeStatistics(const std::vector<TrappingHistogram>& subsets,
                                                   const std::vector<std::uint64_t>& orbitsPerSubset,
                                                   std::uint64_t blocks, std::uint32_t q);

/// A run of q > 1 and its q = 1 companion (same map, Xr and number of subsets), to be spliced at `crossover`.
struct SplicedRecord {
  std::vector<TrappingHistogram> longSubsets;
  std::vector<std::uint64_t> longOrbits;
  std::uint64_t longBlocks = 0;
  std::uint32_t longQ = 1;
  std::vector<TrappingHistogram> shortSubsets;
  std::vector<std::uint64_t> shortOrbits;
  std::uint64_t shortBlocks = 0;
  std::uint32_t shortQ = 1;
  double crossover = 0;  ///< t_c in steps, ≥ 10 longQ
};

/// Composite statistics (issue #26, docs/design.md, "Blocks of q steps"): f_t from the companion's masses below t_c
/// and from the run's at and above it (each estimated per step of its own record, so they join without a
/// factor), and every other statistic (α, p_t, P_t, C_τ, the local exponent, S_t, D_t, D) from that spliced f_t.
/// Subset i of the run is paired with subset i of the companion for the errors.  Throws std::invalid_argument when
/// the subsets do not pair, the companion's q is not 1, or t_c < 10 q.
[[nodiscard]] TrappingStatistics computeSplicedStatistics(const SplicedRecord& record);

}  // namespace archipelago
