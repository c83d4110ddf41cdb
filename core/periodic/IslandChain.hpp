#pragma once
/// \file IslandChain.hpp
/// \brief Which island chain a trapped segment sticks to: its period (e.g. 6 or 138), a member, its centre orbit.
///
/// Karney (1983), §6: long trapped segments stay close to chains of islands around islands — at K = 0.1 the
/// longest one (≈ 6·10⁷ steps) spends its time around a chain of order 6 × 23 = 138.  An orbit stuck to a
/// chain of period n visits the chain's n islands in turn, so the n sub-sequences z_{φ + kn} (phases
/// φ = 0 … n−1) each stay near one island, while for a lag that is not a multiple of n they jump between
/// islands.  Islands around islands give a hierarchy 1 | n₁ | n₂ | … (the central island, its six islands,
/// the 23 islands around each of those).
///
/// Method (all distances physical):
///   - spread σ(n): for up to `phasesSampled` phases, the 90th percentile of the distances of (up to
///     `pointsPerPhase`, evenly spaced) points z_{φ+kn} from their coordinate-wise median; σ(n) is the median
///     over the phases.  Quantiles and medians make it robust to short excursions of the orbit.
///   - levels: start with n = 1 (the whole segment around the central island); the next level is the smallest
///     multiple n' = j·n (j ≥ 2, n' ≤ maxPeriod, at least `minPointsPerPhase` points per phase) such that, as
///     medians over the sampled phases φ of n',
///       (a) the sub-sequence shrinks: σ(n', φ) ≤ confinementRatio · σ(n, φ mod n), and
///       (b) it circles its median point (an island centre): the first `pointsPerPhase` consecutive points
///           z_{φ+kn'} turn at least `minTurns` times about it (a count that linear maps leave unchanged, so
///           thin islands count like round ones).
///     The last level is the chain's period.  Return distances |z_{t+n} − z_t|, or the spread alone, are fooled
///     by quasi-periodic near-returns (an orbit turning by ≈ p/j per step around its island nearly returns
///     after j steps: its sub-sequence is a short arc, which (b) rejects; two clusters visited alternately,
///     for a lag of half the period, fail (a)).
///   - member: the median point of the sub-sequence that contains z_0 (the centre of the island it surrounds);
///   - centre orbit: the periodic orbit of period n nearest to the member (PeriodicOrbitFinder.hpp), preferring
///     a stable (elliptic) one, searched within max(2σ(n), 1e-4) of the member's iterates.
/// A segment that circulates the central island on a KAM curve gives period 1 and the central fixed point.

#include <optional>
#include <span>
#include <vector>

#include "core/map/FixedPointMap.hpp"  // PhysicalPoint
#include "core/periodic/PeriodicOrbit.hpp"

namespace archipelago {

/// Tuning of identifyIslandChain(); the defaults suit segments of 10³ … 10⁸ points.
struct IslandChainOptions {
  int maxPeriod = 1000;                  ///< largest chain period considered (also capped by the segment length)
  long double confinementRatio = 0.5L;   ///< a deeper level must shrink the spread at least this much, (0, 1)
  long double minTurns = 1;              ///< > 0: its sub-sequences must turn this often about their centres
  int minPointsPerPhase = 16;            ///< sub-sequences shorter than this are not trusted
  int phasesSampled = 16;                ///< phases per lag used for σ(n)
  int pointsPerPhase = 256;              ///< points per phase used for σ(n)
  bool findCentreOrbit = true;           ///< also find the periodic orbit at the chain's centre
};

/// The chain a segment sticks to.
struct IslandChain {
  int period = 1;                          ///< n, the chain's order (1: the central island itself)
  std::vector<int> hierarchy;              ///< the levels found, e.g. {1, 6, 138}
  std::vector<long double> spreads;        ///< σ at each level of `hierarchy`
  PhysicalPoint member;                    ///< centre of the chain member that z_0 is near (median of z_{kn})
  long windingTurns = 0;                   ///< clockwise turns of the segment about (−√K, 0)
  long double rotationNumber = 0;          ///< windingTurns / (T − 1): turns per step about the central point
  std::optional<PeriodicOrbit> centre;     ///< the periodic orbit at the chain's centre, z_0 nearest to member
};

/// Identifies the chain of the segment z_0 … z_{T−1} (consecutive iterates of Q, physical coordinates).
/// Throws std::invalid_argument when K or a point is not finite, the options are out of range, or the
/// segment has fewer than 2·minPointsPerPhase points.
[[nodiscard]] IslandChain identifyIslandChain(long double K, std::span<const PhysicalPoint> segment,
                                              const IslandChainOptions& options = {});

/// σ(n) as defined above (exposed for tests and diagnostics).
[[nodiscard]] long double subsequenceSpread(std::span<const PhysicalPoint> segment, int lag,
                                            const IslandChainOptions& options = {});

}  // namespace archipelago
