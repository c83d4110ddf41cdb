/// \file TrappingStatistics.cpp
/// \brief Trapping statistics from histograms (Karney 1983, §3, §5, appendices A–B).
///
/// Notation (all lengths in steps unless "blocks" is said):
///   n_i, Σ_i   count and length sum of bin i (blocks);  t̄_i = Σ_i/n_i
///   s_i        q·t̄_i, the point at which the bin's segments are placed
///   w_i        n_i/(M(T + 1 − t̄_i))/q, their weight (segment starts per step of record)
///   grid       the τ (or t) at which P, C, S, D_t and the local exponent are sampled
/// Sums run over non-empty bins only, in long double, each term non-negative (see the header).  The masses
/// come out sorted by s (bins are disjoint ranges), which the sweep over the grid relies on.

#include "core/stats/TrappingStatistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/map/FixedPointMap.hpp"  // uint128

namespace archipelago {

namespace {

using Real = long double;

constexpr std::uint64_t kDenseGridMax = 4096;  // caps the integer part of the grid: cost ∝ grid × bins × subsets

struct PointMass {
  int key;  // the bin, plus kBins for the second piece of spliced statistics: the same key in every subset
  Real s;   // steps
  Real w;   // per step
  Real f;   // the plotted density at s (appendix B: F_i/q²)
};

// One histogram's share of the masses: the record behind it, and the range of s (steps) it contributes
// ([0, ∞) alone; below or above the crossover for spliced statistics).
struct Piece {
  const TrappingHistogram* h;
  std::uint64_t orbits, blocks;
  std::uint32_t q;
  Real from = 0, to = std::numeric_limits<Real>::infinity();
  int keyOffset = 0;
};

// The point masses of one histogram within [piece.from, piece.to), in increasing order of bin (hence of s).
std::vector<PointMass> pointMasses(const Piece& piece) {
  const TrappingHistogram& h = *piece.h;
  const std::uint64_t orbits = piece.orbits, blocks = piece.blocks;
  const std::uint32_t q = piece.q;
  std::vector<PointMass> masses;
  if (h.segments() == 0) return masses;
  if (orbits == 0 || blocks == 0 || q == 0)
    throw std::invalid_argument("trapping statistics need orbits, blocks and q all > 0 for a non-empty histogram");
  const Real records = static_cast<Real>(orbits);
  for (int i = 1; i < TrappingHistogram::kBins; ++i) {
    const std::uint64_t n = h.count(i);
    if (n == 0) continue;
    // Appendix A: no segment is longer than the record of T blocks, so Σ_i ≤ n_i T; beyond, T + 1 − t̄ ≤ 0.
    if (static_cast<uint128>(h.lengthSum(i)) > static_cast<uint128>(n) * blocks)
      throw std::invalid_argument("histogram bin " + std::to_string(i) + " has mean length " +
                                  std::to_string(static_cast<double>(h.lengthSum(i)) / static_cast<double>(n)) +
                                  " blocks, longer than the record of " + std::to_string(blocks) + " blocks");
    const Real meanBlocks = static_cast<Real>(h.lengthSum(i)) / static_cast<Real>(n);
    const Real s = q * meanBlocks;
    if (s < piece.from || s >= piece.to) continue;
    const Real opportunities = records * (static_cast<Real>(blocks) + 1 - meanBlocks);  // M(T + 1 − t̄)
    const Real w = static_cast<Real>(n) / opportunities / q;
    // Appendix B: F_i = B_i/(T+1−t)/width, then f = F_i/q²; w already holds one 1/q.
    const Real width = static_cast<Real>(TrappingHistogram::binUpper(i) - TrappingHistogram::binLower(i));
    masses.push_back({i + piece.keyOffset, s, w, w / width / q});
  }
  return masses;
}

// Integer grid in steps: 0..dense, then 30 per decade up to `top` (inclusive).
std::vector<Real> makeGrid(std::uint64_t dense, Real top) {
  std::vector<Real> grid;
  for (std::uint64_t t = 0; t <= dense; ++t) grid.push_back(static_cast<Real>(t));
  const Real start = static_cast<Real>(dense);
  for (int k = 1;; ++k) {
    const Real t = std::min(top, std::round(start * std::pow(Real(10), Real(k) / TrappingHistogram::kBinsPerDecade)));
    if (t <= start) break;  // top ≤ dense: the integer part already covers it
    if (t > grid.back()) grid.push_back(t);
    if (t >= top) break;
  }
  return grid;
}

// The local exponent's grid: τ = 10^(j/kLogGridPerDecade), j = 0, 1, …, up to `top` (issue #26).
std::vector<Real> makeLogGrid(Real top) {
  std::vector<Real> grid;
  for (int j = 0;; ++j) {
    const Real t = std::pow(Real(10), Real(j) / kLogGridPerDecade);
    if (t > top) break;
    grid.push_back(t);
  }
  return grid;
}

// eq. (spreaddef) for one point mass, S_t = Σ w k(s, t), split at s = t into two forms that are linear in t
// with non-negative coefficients (m = ⌊s⌋, δ = s − m; t an integer):
//   s > t:  k = t² (s − t) + (2t³ + t)/3
//   s ≤ t:  k = (t − s) a(s) + b(s),  a = s + 2mδ + m(m − 1),  b = s² + 2mδ² + 2δ m(m − 1) + (m − 1) m (2m − 1)/3
// (for integer s, k = t s² − (s³ − s)/3 when s ≤ t).  Sweeping the sorted grid over the sorted masses, the
// sums over masses become prefix and suffix sums; the differences t − s are folded in by recurrences on
// adjacent masses, so every addition is of non-negative terms.
Real spreadSlope(Real s) {
  const Real m = std::floor(s), frac = s - m;
  return s + 2 * m * frac + m * (m - 1);
}
Real spreadOffset(Real s) {
  const Real m = std::floor(s), frac = s - m;
  return s * s + 2 * m * frac * frac + 2 * frac * m * (m - 1) + (m - 1) * m * (2 * m - 1) / 3;
}

// Everything for one histogram, on a given grid; NaN marks an undefined local exponent.
struct Raw {
  std::vector<Real> f;  // per mass key (2 kBins), 0 where empty
  Real alpha = 0, D = 0, sumTf = 0;
  std::vector<Real> P, C, S;
  std::vector<Real> exponent;  // on the log grid; NaN where undefined
};

Raw computeRaw(const std::vector<Piece>& pieces, const std::vector<Real>& grid, const std::vector<Real>& logGrid) {
  Raw r;
  std::vector<PointMass> masses;
  for (const Piece& piece : pieces) {  // pieces are in increasing s: the masses stay sorted
    const auto part = pointMasses(piece);
    masses.insert(masses.end(), part.begin(), part.end());
  }
  r.f.assign(2 * TrappingHistogram::kBins, 0);
  r.P.assign(grid.size(), 0);
  r.C.assign(grid.size(), 0);
  r.S.assign(grid.size(), 0);
  r.exponent.assign(logGrid.size(), std::numeric_limits<Real>::quiet_NaN());
  if (masses.empty()) {  // no segment seen: f, C, S, D are 0, but α and P = α Σ w have no value
    r.alpha = std::numeric_limits<Real>::quiet_NaN();
    std::fill(r.P.begin(), r.P.end(), r.alpha);
    return r;
  }

  Real sumW = 0, sumSW = 0, sumS2W = 0;
  for (const auto& m : masses) {
    sumW += m.w;
    sumSW += m.s * m.w;
    sumS2W += m.s * m.s * m.w;
    r.f[m.key] = m.f;
  }
  r.alpha = 1 / sumW;
  r.sumTf = sumSW;  // = C_0
  r.D = sumS2W / 2;  // eq. (ddef)

  // Suffix sums over masses j..n−1: W_j = Σ w_i, G_j = Σ w_i (s_i − s_j).  Prefix sums over 0..j:
  // A_j = Σ w_i a_i, E_j = Σ w_i a_i (s_j − s_i), B_j = Σ w_i b_i.
  const std::size_t n = masses.size();
  std::vector<Real> W(n + 1, 0), G(n + 1, 0), A(n, 0), E(n, 0), B(n, 0);  // W[n] = 0: nothing above
  for (std::size_t j = n; j-- > 0;) {
    W[j] = W[j + 1] + masses[j].w;
    if (j + 1 < n) G[j] = G[j + 1] + (masses[j + 1].s - masses[j].s) * W[j + 1];
  }
  for (std::size_t j = 0; j < n; ++j) {
    const Real previousA = j > 0 ? A[j - 1] : 0;
    A[j] = previousA + masses[j].w * spreadSlope(masses[j].s);
    B[j] = (j > 0 ? B[j - 1] : 0) + masses[j].w * spreadOffset(masses[j].s);
    E[j] = j > 0 ? E[j - 1] + (masses[j].s - masses[j - 1].s) * previousA : 0;
  }
  std::size_t above = 0;  // first mass with s > t
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const Real t = grid[g];
    while (above < n && masses[above].s <= t) ++above;
    const Real c = above < n ? G[above] + (masses[above].s - t) * W[above] : 0;  // eq. (cdef)
    Real spread = t * t * c + (2 * t * t * t + t) / 3 * W[above];
    if (above > 0) {
      const std::size_t l = above - 1;
      spread += E[l] + (t - masses[l].s) * A[l] + B[l];
    }
    r.P[g] = r.alpha * W[above];  // eq. (pdef)
    r.C[g] = c;
    r.S[g] = spread;  // eq. (spreaddef)
  }
  // The local exponent on the log grid (issue #26): C_τ = Σ w (s − τ)₊ evaluated exactly at each τ_j (it is
  // piecewise linear), then centred differences of log C over log τ across ±1/kLogGridPerDecade decade.
  std::vector<Real> logC(logGrid.size(), 0);
  above = 0;
  for (std::size_t j = 0; j < logGrid.size(); ++j) {
    const Real t = logGrid[j];
    while (above < n && masses[above].s <= t) ++above;
    logC[j] = above < n ? G[above] + (masses[above].s - t) * W[above] : 0;
  }
  for (std::size_t j = 1; j + 1 < logGrid.size(); ++j) {
    if (!(logC[j - 1] > 0 && logC[j + 1] > 0)) continue;
    r.exponent[j] = -(std::log(logC[j + 1]) - std::log(logC[j - 1])) / (std::log(logGrid[j + 1]) - std::log(logGrid[j - 1]));
  }
  return r;
}

// Standard error of the mean of the finite values (0 for fewer than two).
double standardError(const std::vector<Real>& values) {
  Real sum = 0;
  std::size_t n = 0;
  for (const Real v : values)
    if (std::isfinite(v)) {
      sum += v;
      ++n;
    }
  if (n < 2) return 0;
  const Real mean = sum / static_cast<Real>(n);
  Real squares = 0;
  for (const Real v : values)
    if (std::isfinite(v)) squares += (v - mean) * (v - mean);
  return static_cast<double>(std::sqrt(squares / static_cast<Real>(n - 1)) / std::sqrt(static_cast<Real>(n)));
}

std::uint64_t longestLength(const TrappingHistogram& h) {
  const int last = h.lastUsedBin();
  if (last == 0) return 0;
  if (last == TrappingHistogram::kBins - 1)  // open above: the longest segment is at least its mean
    return (h.lengthSum(last) + h.count(last) - 1) / h.count(last);
  return TrappingHistogram::binUpper(last) - 1;
}

// The statistics of the masses of `total` (values) and of each entry of `subsets` (errors).
TrappingStatistics assemble(const std::vector<Piece>& total, const std::vector<std::vector<Piece>>& subsets,
                            std::uint64_t dense, Real top, std::uint64_t segments, std::uint64_t longestBlocks) {
  TrappingStatistics out;
  out.segments = segments;
  if (out.segments == 0) return out;
  out.longestBlocks = longestBlocks;
  const auto grid = makeGrid(dense, top);
  const auto logGrid = makeLogGrid(top);
  const Raw value = computeRaw(total, grid, logGrid);
  std::vector<Raw> parts;
  parts.reserve(subsets.size());
  for (const auto& pieces : subsets) parts.push_back(computeRaw(pieces, grid, logGrid));

  std::vector<Real> sample(parts.size());
  const auto errorOf = [&](auto&& pick) {
    for (std::size_t i = 0; i < parts.size(); ++i) sample[i] = pick(parts[i]);
    return standardError(sample);
  };
  const auto push = [](Series& series, Real x, Real v, double error) {
    series.x.push_back(static_cast<double>(x));
    series.value.push_back(static_cast<double>(v));
    series.error.push_back(error);
  };

  out.alpha = static_cast<double>(value.alpha);
  out.D = static_cast<double>(value.D);
  out.sumTf = static_cast<double>(value.sumTf);
  out.alphaError = errorOf([](const Raw& r) { return r.alpha; });
  out.DError = errorOf([](const Raw& r) { return r.D; });

  for (const Piece& piece : total)
    for (const PointMass& m : pointMasses(piece)) {
      const int k = m.key;
      push(out.f, m.s, value.f[k], errorOf([k](const Raw& r) { return r.f[k]; }));
      push(out.p, m.s, value.alpha * value.f[k], errorOf([k](const Raw& r) { return r.alpha * r.f[k]; }));
    }
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const Real t = grid[g];
    push(out.P, t, value.P[g], errorOf([g](const Raw& r) { return r.P[g]; }));
    push(out.C, t, value.C[g], errorOf([g](const Raw& r) { return r.C[g]; }));
    push(out.S, t, value.S[g], errorOf([g](const Raw& r) { return r.S[g]; }));
    if (t > 0) {
      const Real t32 = t * std::sqrt(t);
      push(out.Scompensated, t, value.S[g] / t32, errorOf([g, t32](const Raw& r) { return r.S[g] / t32; }));
      push(out.Dt, t, value.S[g] / (2 * t), errorOf([g, t](const Raw& r) { return r.S[g] / (2 * t); }));
    }
  }
  for (std::size_t j = 0; j < logGrid.size(); ++j)
    if (!std::isnan(value.exponent[j]))
      push(out.localExponent, logGrid[j], value.exponent[j], errorOf([j](const Raw& r) { return r.exponent[j]; }));
  return out;
}

// The dense part of one run's grid: every length of the exact bins when q ≤ 81.
std::uint64_t denseGrid(std::uint32_t q) {
  return std::min<std::uint64_t>(static_cast<std::uint64_t>(TrappingHistogram::kExactMax) * q, kDenseGridMax);
}

}  // namespace

TrappingStatistics computeStatistics(const TrappingHistogram& h, const RecordShape& shape) {
  const std::uint64_t longest = longestLength(h);
  TrappingStatistics s = assemble({Piece{&h, shape.orbits, shape.blocks, shape.q}}, {}, denseGrid(shape.q),
                                  2 * static_cast<Real>(shape.q) * static_cast<Real>(longest), h.segments(), longest);
  s.blockAffectedBelow = shape.q > 1 ? kBlockAffectedBlocks * static_cast<double>(shape.q) : 0;
  return s;
}

TrappingStatistics computeStatistics(const std::vector<TrappingHistogram>& subsets,
                                     const std::vector<std::uint64_t>& orbitsPerSubset, std::uint64_t blocks,
                                     std::uint32_t q) {
  if (subsets.empty()) throw std::invalid_argument("trapping statistics need at least one subset");
  if (subsets.size() != orbitsPerSubset.size())
    throw std::invalid_argument("trapping statistics: " + std::to_string(subsets.size()) + " subsets but " +
                                std::to_string(orbitsPerSubset.size()) + " orbit counts");
  TrappingHistogram total;
  std::uint64_t orbits = 0;
  for (std::size_t i = 0; i < subsets.size(); ++i) {
    total.merge(subsets[i]);
    orbits += orbitsPerSubset[i];
  }
  std::vector<std::vector<Piece>> parts;
  for (std::size_t i = 0; i < subsets.size(); ++i) parts.push_back({Piece{&subsets[i], orbitsPerSubset[i], blocks, q}});
  const std::uint64_t longest = longestLength(total);
  TrappingStatistics s = assemble({Piece{&total, orbits, blocks, q}}, parts, denseGrid(q),
                                  2 * static_cast<Real>(q) * static_cast<Real>(longest), total.segments(), longest);
  s.blockAffectedBelow = q > 1 ? kBlockAffectedBlocks * static_cast<double>(q) : 0;
  return s;
}

TrappingStatistics computeSplicedStatistics(const SplicedRecord& r) {
  if (r.longSubsets.empty() || r.longSubsets.size() != r.longOrbits.size() ||
      r.shortSubsets.size() != r.longSubsets.size() || r.shortOrbits.size() != r.longSubsets.size())
    throw std::invalid_argument("spliced statistics need the same number of subsets in the run and its companion");
  if (r.shortQ != 1) throw std::invalid_argument("the short-time companion must have q = 1");
  if (!(r.crossover >= kBlockAffectedBlocks * static_cast<double>(r.longQ)))
    throw std::invalid_argument("the crossover must be at least 10 q steps");
  TrappingHistogram longTotal, shortTotal;
  std::uint64_t longOrbits = 0, shortOrbits = 0;
  for (std::size_t i = 0; i < r.longSubsets.size(); ++i) {
    longTotal.merge(r.longSubsets[i]);
    shortTotal.merge(r.shortSubsets[i]);
    longOrbits += r.longOrbits[i];
    shortOrbits += r.shortOrbits[i];
  }
  const Real cut = r.crossover;
  const auto pieces = [&](const TrappingHistogram& s, std::uint64_t so, const TrappingHistogram& l, std::uint64_t lo) {
    return std::vector<Piece>{Piece{&s, so, r.shortBlocks, 1, 0, cut, 0},
                              Piece{&l, lo, r.longBlocks, r.longQ, cut, std::numeric_limits<Real>::infinity(),
                                    TrappingHistogram::kBins}};
  };
  std::vector<std::vector<Piece>> parts;
  for (std::size_t i = 0; i < r.longSubsets.size(); ++i)
    parts.push_back(pieces(r.shortSubsets[i], r.shortOrbits[i], r.longSubsets[i], r.longOrbits[i]));
  const std::uint64_t longest = longestLength(longTotal);
  const std::uint64_t dense = std::min<std::uint64_t>(
      std::max<std::uint64_t>(TrappingHistogram::kExactMax, static_cast<std::uint64_t>(std::ceil(r.crossover))),
      kDenseGridMax);
  TrappingStatistics s = assemble(pieces(shortTotal, shortOrbits, longTotal, longOrbits), parts, dense,
                                  std::max(2 * static_cast<Real>(r.longQ) * static_cast<Real>(longest), 2 * cut),
                                  longTotal.segments() + shortTotal.segments(), longest);
  s.splicedAt = r.crossover;
  return s;
}

}  // namespace archipelago
