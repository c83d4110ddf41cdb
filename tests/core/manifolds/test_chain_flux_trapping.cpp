// The flux through the outer separatrix of the period-6 chain (Karney 1983, §6) against the residence times of the
// trapping engine's orbits in that chain (core/trapping/BlockKernel.hpp: advanceBlockVisiting, the block every
// kernel, run and replay matches bit for bit).
//
// How we compare.  Z₆ is the zone inside the chain's outer separatrix (TurnstileFlux.hpp), Φ₆ its flux per step, X₆
// and E₆ its exit and entry lobes for Q.  The engine iterates N⁻¹ (the exact Q*⁻¹; Q* = Q inside the box) and redraws
// Y uniformly whenever a block starts in the strip X ≤ Xr: a process that preserves the area of the sea it explores.
//   1. Gates (exact): N⁻¹ enters Z₆ exactly from the points of Q(X₆) and leaves it exactly into E₆.  Along the engine's
//      orbits, the inside/outside state tracked through these two small lobes must equal zone membership at every
//      step (checked on a prefix of every orbit with the zone polygon): 0 mismatches.
//   2. Residence (statistical): a visit of the engine's orbit to Z₆ lasts τ steps (points inside).  In the
//      stationary process the visits' entry points are uniform over Q(X₆), so by Kac's lemma at finite horizon T
//      (KacCheck.hpp, which holds for Q⁻¹ as for Q)
//          ⟨min(τ, T)⟩_visits = area{w ∈ Z₆ : τ_f(w) ≤ T} / Φ₆,
//      the right side measured independently by uniform points of Z₆ iterated with the plane map Q (runKacCheck).
//      The flux enters as the divisor: a wrong Φ₆ shifts the right side by the same factor.  Capping at T keeps each
//      visit's contribution bounded: the untruncated residence (mean ~1500 steps, heavy tail of sticky visits) and the
//      raw entry rate converge far too slowly for a test (their seed-to-seed scatter exceeds any in-run error
//      estimate; docs/manifolds.md).  Errors: jackknife over the engine's independent orbits; binomial for the
//      zone's fraction.  Also asserted: the same identity for orbits started uniformly in E₆ (the plane map's own
//      Kac check for the chain).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "core/manifolds/KacCheck.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/trapping/BlockKernel.hpp"

namespace archipelago {
namespace {

TEST(ChainFluxTrapping, EngineResidenceInTheChainZoneIsTransitAreaOverFlux) {
  const MapParameters map{0.1, -0.8, 0.5};
  const long double K = map.K;
  constexpr std::uint64_t kHorizon = 300;  // T
  PeriodicOrbitSearch search;
  search.period = 6;
  search.near = {0.0157L, 0};
  KacRequest kac;
  kac.K = K;
  kac.orbit = findPeriodicOrbit(K, search);
  kac.side = BranchSide::Outward;
  kac.entrySamples = 4000;
  kac.zoneSamples = 40000;  // most of Z₆ is islands; 1.4 % of it leaves within T: ±4 % from 40000 points
  kac.maxSteps = kHorizon;
  kac.threads = 2;
  const KacResult plane = runKacCheck(kac);
  EXPECT_EQ(plane.inconsistent, 0u);
  EXPECT_LT(std::fabs(plane.discrepancy()), 4);

  TurnstileRequest request;
  request.K = K;
  request.orbit = kac.orbit;
  request.side = kac.side;
  request.maxVertices = 1 << 10;
  const TurnstileFlux six = computeTurnstileFlux(request);
  std::vector<PhysicalPoint> imageOfExit;  // Q(X₆): the vertices mapped by Q lie on the image arcs
  for (const PhysicalPoint& v : six.exitLobe) {
    const smooth::Point<long double> w = smooth::step(K, smooth::Point<long double>{v.x, v.y});
    imageOfExit.push_back({w.x, w.y});
  }
  const PolygonRegion entry(six.entryLobe), gateIn(imageOfExit), zone(six.zoneBoundary);

  const FixedPointMap fixed(map);
  const KernelSettings settings = blockSettings(fixed.coefficients(), 0.02, 1, 1);
  constexpr std::uint64_t kOrbits = 32, kBlocks = 800000, kChecked = 200000;
  struct Visits {
    double capped = 0, count = 0, mismatches = 0;
  };
  std::vector<Visits> visits(kOrbits);
  (void)parallelFor(kOrbits, [&](std::size_t orbit, int) {
    OrbitState s;  // the engine's start: (0, 0), outside Z₆
    bool inside = false, entering = false;
    std::uint64_t tau = 0, step = 0;
    Visits& v = visits[orbit];
    for (std::uint64_t b = 0; b < kBlocks; ++b)
      (void)advanceBlockVisiting(settings, orbit, s, [&](const UnitState& z) {
        const PhysicalPoint p = fixed.toPhysical(z);
        if (entering) {
          inside = true;
          tau = 1;
          entering = false;
        } else if (inside) {
          if (entry.contains(p.x, p.y)) {  // left into E₆: the visit is over
            v.capped += static_cast<double>(std::min(tau, kHorizon));
            v.count += 1;
            inside = false;
          } else {
            ++tau;
          }
        }
        if (!inside && gateIn.contains(p.x, p.y)) entering = true;
        if (++step <= kChecked && inside != zone.contains(p.x, p.y)) v.mismatches += 1;
      });
  }, {}, 2);

  Visits total;
  for (const Visits& v : visits) {
    total.capped += v.capped;
    total.count += v.count;
    total.mismatches += v.mismatches;
  }
  const double mean = total.capped / total.count;
  double jackknife = 0;
  for (const Visits& v : visits) {
    const double m = (total.capped - v.capped) / (total.count - v.count);
    jackknife += (m - mean) * (m - mean);
  }
  const double error = std::sqrt(jackknife * (kOrbits - 1) / kOrbits);
  std::printf("period-6 chain, K = 0.1, T = %llu: the engine's %.0f visits stay <min(tau, T)> = %.1f +- %.1f steps; "
              "transit area %.4g +- %.2g / flux %.6g = %.1f +- %.1f; orbits entering uniformly: %.1f +- %.1f\n",
              static_cast<unsigned long long>(kHorizon), total.count, mean, error, plane.transitArea,
              plane.transitAreaError, static_cast<double>(plane.flux), plane.predictedResidence,
              plane.predictedResidenceError, plane.meanResidence, plane.meanResidenceError);
  EXPECT_EQ(total.mismatches, 0);
  EXPECT_GT(total.count, 150);  // enough visits to mean something
  // ~N(0, 1) in units of the combined error: |z| < 4 fails by chance with p = 6e−5.
  EXPECT_LT(std::fabs(mean - plane.predictedResidence), 4 * std::hypot(error, plane.predictedResidenceError));
}

}  // namespace
}  // namespace archipelago
