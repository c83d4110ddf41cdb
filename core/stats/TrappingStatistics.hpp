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
///   local exponent = −d log C_τ / d log τ        (fig. 5d)
/// Errors: each quantity is also computed for every subset of orbits alone; the error is the standard
/// error of the mean over the subsets (the paper's method for D = 6400 ± 800, §5).

#include <cstdint>
#include <vector>

#include "trapping/TrappingHistogram.hpp"

namespace archipelago {

/// A sampled curve: value[i] at abscissa x[i], with a one-sigma error (0 when unknown).
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
  Series f;               ///< f_t at the mean length of each non-empty bin (steps)
  Series p;               ///< p_t = α f_t
  Series P;               ///< P_t on a grid of t
  Series C;               ///< C_τ on a grid of τ
  Series localExponent;   ///< −d log C / d log τ on the same grid (log-linear plot)
  Series S;               ///< S_t on the grid
  Series Dt;              ///< D_t = S_t / 2t on the grid
  double alpha = 0, alphaError = 0;  ///< mean segment length α (steps)
  double D = 0, DError = 0;          ///< diffusion coefficient (eq. ddef)
  double sumTf = 0;                  ///< Σ t f_t = C_0 (≈ 1; exactly 1 for an exact f)
  std::uint64_t segments = 0;        ///< segments in the histogram
  std::uint64_t longestBlocks = 0;   ///< upper edge of the highest non-empty bin, in blocks
};

/// Statistics of one histogram (no errors).
[[nodiscard]] TrappingStatistics computeStatistics(const TrappingHistogram& h, const RecordShape& shape);

/// Statistics of the union of subset histograms, with errors from the spread over subsets.
/// `orbitsPerSubset[i]` is the number of orbits that fed subsets[i].
[[nodiscard]] TrappingStatistics computeStatistics(const std::vector<TrappingHistogram>& subsets,
                                                   const std::vector<std::uint64_t>& orbitsPerSubset,
                                                   std::uint64_t blocks, std::uint32_t q);

}  // namespace archipelago
