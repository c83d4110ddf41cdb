// The MacKay–Meiss–Percival flux (core/manifolds/MmpFlux.hpp): ΔW_{p/q} of the two Birkhoff orbits about the central
// island against an independent mpmath computation; its limit over the convergents of a noble cantorus between the
// chains 5/31 and 1/6 at K = 0.1 against the turnstile flux of a convergent's chain (two methods, one number: docs/
// markov-tree.md, "The cantorus flux"); the well-ordering test and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/manifolds/MmpFlux.hpp"
#include "core/manifolds/TurnstileFlux.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {
namespace {

MmpActionDifference at(long p, int q) {
  MmpRequest r;  // K = 0.1, the annulus 0.19 … 0.44 about the centre: between the chains 1/6 and 5/31 (and them)
  r.p = p;
  r.q = q;
  return mmpActionDifference(r);
}

long double relative(quad a, quad b) { return static_cast<long double>(smooth::absolute(a - b) / smooth::absolute(b)); }

// Reference: scripts/mmp-periodic-action.py --K-long-double 1/6 5/31 6/37 11/68 17/105 (mpmath, 60 digits; its own
// float64 scan, well-ordering test and two-dimensional Newton on Q^q(z) − z, no code shared with core; K = 0.1L,
// the long double core uses, as the value differs from decimal 0.1 in the 20th digit and so does W).  Each value is
// stored as hi + lo (two long doubles, ~38 digits).  Measured agreement 28–32 digits; asserted 25.
TEST(MmpFlux, ActionDifferencesAgreeWithAnIndependentMpmathComputation) {
  struct Reference {
    long p;
    int q;
    long double hi, lo;
  };
  const std::vector<Reference> references{
      {1, 6, 0.001142674009253932718925625L, 2.63148427324253545842e-23L},  // 0.0011426740092539327189519398529434644
      {5, 31, 0.00003831224003022858582282929L, -8.89256406806125111932e-25L},
      {6, 37, 0.00002860891739381402718887826L, -1.90118013189779673461e-26L},
      {11, 68, 0.00001426995541606883134450426L, 1.97398773732080677779e-25L},
      {17, 105, 0.00001207639796535106103489790L, 3.53628642840805341412e-25L},
  };
  for (const Reference& ref : references) {
    const std::string pq = std::to_string(ref.p) + "/" + std::to_string(ref.q);
    const MmpActionDifference d = at(ref.p, ref.q);
    EXPECT_LT(relative(d.flux, quad(ref.hi) + quad(ref.lo)), 1e-25L) << pq;
    EXPECT_LT(d.fluxError, quad(1e-26L) * d.flux) << pq;
    // The labels: one orbit each side of R = 0, both with p turns and well ordered; the plane's W is larger on the
    // R < 0 orbit about this island (MmpFlux.hpp, "Sign").
    EXPECT_LT(d.minimizing.orbit.residue, 0) << pq;
    EXPECT_GT(d.minimax.orbit.residue, 0) << pq;
    EXPECT_LT(d.planeDifference, 0) << pq;
    EXPECT_EQ(d.birkhoffOrbits, 2) << pq;
    for (const BirkhoffOrbit* o : {&d.minimizing, &d.minimax}) {
      EXPECT_EQ(o->orbit.windingTurns, ref.p) << pq;
      EXPECT_TRUE(wellOrdered(o->orbit.points, {-std::sqrt(0.1L), 0.0L})) << pq;
      EXPECT_LT(o->mismatch, quad(1e-28L)) << pq;  // the forward half meets the reversed one
      EXPECT_LT(std::fabs(smooth::offsetFromLine(o->line, 0.1L, smooth::Point<long double>{o->orbit.points[0].x,
                                                                                            o->orbit.points[0].y})),
                1e-15L);
    }
  }
}

// Two methods, one number (issue 40).  The noble cantorus between 5/31 and 1/6, ω = [0; 6, 5, 1, 1, 1, …] ≈ 0.16186,
// has the convergents 5/31, 6/37, 11/68, 17/105, 28/173, 45/278, 73/451, …; ΔW over them converges faster than
// geometrically (docs/markov-tree.md: differences 4.3e−7, 1.4e−8, 9.5e−11, 1.7e−14 from 173 to 729).  Its limit, the
// MMP flux through the cantorus, is set against the turnstile flux of the chain 28/173 — the lobe of its minimizing
// orbit's separatrix on the side that faces the cantorus (28/173 < ω lies outside it: the inner separatrix), computed
// from the orbit's point on S₁ by core's TurnstileFlux (homoclinic orbits of the manifolds, nothing shared with the
// periodic orbits' actions but the map and L).  Measured: 1.163169182652e−5 against 1.163169182947e−5 (ΔW at
// 118/729, its tail bound 3e−18), 2.5e−10 apart; asserted 1e−9 (9 digits).  The separatrix facing away from the cantorus is another barrier: the chain 11/68's
// outer lobe (1.157719e−5) is 0.5 % off — asserted to disagree, so that the agreement is not a generic closeness.
TEST(MmpFlux, TheCantorusFluxAgreesWithTheTurnstileOfAConvergentsChainFacingIt) {
  // 45/278 … 118/729 come from the narrow windows about the previous convergent's points (cantorusFlux): the whole
  // annulus at 1e−6 misses 118/729's Birkhoff roots, which lie ~|λ|^(−1/2) ≈ 3e−8 from others.
  CantorusRequest request;
  request.convergents = {{17, 105}, {28, 173}, {45, 278}, {73, 451}, {118, 729}};
  const CantorusFlux cantorus = cantorusFlux(request);
  ASSERT_EQ(cantorus.terms.size(), 5u);
  EXPECT_TRUE(cantorus.narrowed[4]);
  std::vector<long double> sequence;
  for (const MmpActionDifference& t : cantorus.terms) sequence.push_back(static_cast<long double>(t.flux));
  const MmpActionDifference& d173 = cantorus.terms[1];
  // Decreasing, each step at least 10 times smaller than the previous one.
  for (std::size_t k = 2; k < sequence.size(); ++k) {
    EXPECT_LT(sequence[k], sequence[k - 1]);
    EXPECT_LT(std::fabs(sequence[k] - sequence[k - 1]), 0.1L * std::fabs(sequence[k - 1] - sequence[k - 2])) << k;
  }
  ASSERT_TRUE(cantorus.limit.has_value()) << cantorus.limitProblem;
  const ConvergentLimit limit = *cantorus.limit;
  // Measured 5.8e−16, 5.0e−11 of it, with the largest of the last three ratios (convergentLimit since 2026-12-07;
  // 3.1e−18 with the last ratio alone).
  EXPECT_LT(limit.uncertainty, 1e-10L * limit.value);

  // The turnstile of 28/173, inner separatrix, from the minimizing orbit's point on S₁.
  const PeriodicOrbit& orbit = d173.minimizing.orbit;
  std::size_t onS1 = 0;
  for (std::size_t k = 0; k < orbit.points.size(); ++k)
    if (std::fabs(smooth::offsetFromLine(smooth::SymmetryLine::S1, 0.1L,
                                         smooth::Point<long double>{orbit.points[k].x, orbit.points[k].y})) <
        std::fabs(smooth::offsetFromLine(smooth::SymmetryLine::S1, 0.1L,
                                         smooth::Point<long double>{orbit.points[onS1].x, orbit.points[onS1].y})))
      onS1 = k;
  TurnstileRequest turnstileRequest;
  turnstileRequest.K = 0.1L;
  turnstileRequest.orbit = orbit.rotatedToStart(onS1);
  turnstileRequest.side = BranchSide::Inward;
  turnstileRequest.maxVertices = 2048;  // the polygon check is not what is tested here (the action is)
  const TurnstileFlux turnstile = computeTurnstileFlux(turnstileRequest);
  EXPECT_LT(std::fabs(turnstile.lobeArea - limit.value), 1e-9L * limit.value)
      << static_cast<double>(turnstile.lobeArea) << " vs " << static_cast<double>(limit.value);

  // The chain 11/68 lies outside the cantorus too; its outer separatrix faces away from it.
  const MmpActionDifference d68 = at(11, 68);
  const PeriodicOrbit& o68 = d68.minimizing.orbit;
  std::size_t right = 0;  // its point on S₂ right of the centre (x ≈ 0.0341)
  for (std::size_t k = 0; k < o68.points.size(); ++k)
    if (std::fabs(o68.points[k].y) < 1e-15L && o68.points[k].x > 0) right = k;
  turnstileRequest.orbit = o68.rotatedToStart(right);
  turnstileRequest.side = BranchSide::Outward;
  const TurnstileFlux away = computeTurnstileFlux(turnstileRequest);
  EXPECT_GT(std::fabs(away.lobeArea - limit.value), 1e-3L * limit.value) << static_cast<double>(away.lobeArea);
}

// cantorusFlux: each term is mmpActionDifference of its p/q (the annulus for the first; later ones from the narrow
// windows where those hold the pair, else the annulus: 11/68's points lie 10⁻³ from 6/37's), the limit is
// convergentLimit of the fluxes; 5/31, 6/37, 11/68 (differences −9.7e−6, −1.4e−5: ratio 1.48) and two terms give none,
// with the reason.
TEST(MmpFlux, ACantorusSequenceIsItsTermsAndTheirLimit) {
  CantorusRequest request;
  request.convergents = {{6, 37}, {11, 68}, {17, 105}};
  const CantorusFlux c = cantorusFlux(request);
  ASSERT_EQ(c.terms.size(), 3u);
  EXPECT_FALSE(c.narrowed[0]);
  EXPECT_FALSE(c.narrowed[1]);
  std::vector<long double> fluxes;
  for (std::size_t i = 0; i < 3; ++i) {
    const MmpActionDifference one = at(request.convergents[i].first, request.convergents[i].second);
    EXPECT_EQ(c.terms[i].flux, one.flux) << i;
    fluxes.push_back(static_cast<long double>(one.flux));
  }
  ASSERT_TRUE(c.limit.has_value()) << c.limitProblem;
  EXPECT_EQ(c.limit->value, convergentLimit(fluxes).value);
  request.convergents = {{5, 31}, {6, 37}, {11, 68}};
  const CantorusFlux early = cantorusFlux(request);
  EXPECT_FALSE(early.limit.has_value());
  EXPECT_NE(early.limitProblem.find("not converging"), std::string::npos) << early.limitProblem;
  request.convergents.pop_back();
  const CantorusFlux two = cantorusFlux(request);
  EXPECT_FALSE(two.limit.has_value());
  EXPECT_NE(two.limitProblem.find("three terms"), std::string::npos) << two.limitProblem;
  request.convergents = {};
  EXPECT_THROW((void)cantorusFlux(request), std::invalid_argument);
  request.convergents = {{5, 31}};
  request.narrowSpacing = 0;
  EXPECT_THROW((void)cantorusFlux(request), std::invalid_argument);
}

TEST(MmpFlux, WellOrderedIsARotationOfTheCyclicOrder) {
  const PhysicalPoint c{0, 0};
  // Five points on a circle, each step turning 2/5 of a turn clockwise: well ordered.
  std::vector<PhysicalPoint> rotation;
  for (int k = 0; k < 5; ++k) {
    const long double a = -2 * 3.14159265358979323846L * 2 * k / 5;
    rotation.push_back({std::cos(a), std::sin(a)});
  }
  EXPECT_TRUE(wellOrdered(rotation, c));
  // Swap two of them: the same angles visited in another order is not a rotation.
  std::vector<PhysicalPoint> swapped = rotation;
  std::swap(swapped[1], swapped[2]);
  EXPECT_FALSE(wellOrdered(swapped, c));
  EXPECT_FALSE(wellOrdered(std::vector<PhysicalPoint>{}, c));
  EXPECT_FALSE(wellOrdered(std::vector<PhysicalPoint>{{1, 0}, {0, 0}}, c));  // a point at the centre
}

TEST(MmpFlux, TheLimitIsTheLastTermWithTheTailOfAGeometricSequence) {
  std::vector<long double> a;
  for (int k = 0; k < 5; ++k) a.push_back(2 + 3 * std::pow(0.25L, k));
  const ConvergentLimit l = convergentLimit(a);
  EXPECT_EQ(l.value, a.back());
  EXPECT_LT(fabsl(l.ratio - 0.25L), 1e-15L);
  EXPECT_LT(fabsl(l.uncertainty - (a.back() - 2)), 1e-15L);  // exactly the tail of a geometric sequence
  EXPECT_THROW((void)convergentLimit(std::vector<long double>{1, 2}), std::invalid_argument);
  EXPECT_THROW((void)convergentLimit(std::vector<long double>{1, 2, 4}), std::invalid_argument);  // not converging
  EXPECT_THROW((void)convergentLimit(std::vector<long double>{1, 1, 2}), std::invalid_argument);
}

// About an island (issue 50, 2026-12-07): the Birkhoff orbits of type p/q about an island of the six at K = 0.1 are
// Q-orbits of period 6q (MmpRequest::stride), sought on both lines wherever they pass one of the six's islands
// (lineWindowsAbout), kept when every sixth point turns p times about the island's member, is well ordered about it,
// and the orbit follows the chain (shadowsChain).  Reference: scripts/mmp-periodic-action.py --K-long-double --about
// 0.050902412809567206,0.09740894437016441 --stride 6 --rmin 0.02 --rmax 0.07 2/23 3/34 (mpmath, 60 digits, its own
// scan, tests and Newton): ΔW 1.75547467089419850105360168e−6 (R = −0.7172101592, 0.6890952616; the atlas's
// partner of 6 > 138 has R = −0.717) and 6.87692180431712691962758009e−7 (R = −0.9537979707, 0.9025520689).  The
// 3/34 pair's hyperbolic orbit crosses S₁ only at the island about (−0.602, −0.262), not at the member scanned.
// Without the chain's members the 2/23 windows hold well-ordered orbits with residues of 10⁴–10⁷ that wander between
// the islands: refused, as no pair can be chosen.
TEST(MmpFlux, FindsTheBirkhoffPairsAboutAnIslandOfTheSixAsIndependentCodeDoes) {
  const long double K = 0.1L;
  const std::vector<LineWindow> nearSix{{smooth::SymmetryLine::S1, 0.045L, 0.056L}};
  const std::vector<PeriodicOrbit> six = findSymmetricPeriodicOrbitsIn(K, 6, nearSix, 1e-7L);
  const PeriodicOrbit* elliptic = nullptr;
  for (const PeriodicOrbit& o : six)
    if (o.residue > 0 && o.residue < 1) elliptic = &o;
  ASSERT_NE(elliptic, nullptr) << six.size() << " orbits of period 6";
  const PhysicalPoint c{0.050902412809567206L, 0.09740894437016441L};
  const PeriodicOrbit members = elliptic->rotatedToStart(elliptic->nearestIndex(c));
  ASSERT_LT(std::hypot(members.points[0].x - c.x, members.points[0].y - c.y), 1e-12L);
  MmpRequest r;
  r.K = K;
  r.stride = 6;
  r.about = members.points[0];
  r.members = members.points;
  for (const PhysicalPoint& m : members.points)
    for (const LineWindow& w : lineWindowsAbout(K, m, 0.02L, 0.07L)) r.windows.push_back(w);
  struct Reference {
    long p;
    int q;
    long double flux, minimizing, minimax;
  };
  for (const Reference& ref : {Reference{2, 23, 1.75547467089419850105360168e-6L, -0.7172101592L, 0.6890952616L},
                               Reference{3, 34, 6.87692180431712691962758009e-7L, -0.9537979707L, 0.9025520689L}}) {
    r.p = ref.p;
    r.q = ref.q;
    ASSERT_FALSE(validationError(r).has_value()) << *validationError(r);
    const MmpActionDifference d = mmpActionDifference(r);
    EXPECT_EQ(d.stride, 6);
    EXPECT_EQ(d.minimax.points.size(), static_cast<std::size_t>(6 * ref.q));
    EXPECT_LT(std::fabs(static_cast<long double>(d.flux) / ref.flux - 1), 1e-20L) << ref.q << ": " << static_cast<double>(d.flux);
    EXPECT_NEAR(static_cast<double>(d.minimizing.orbit.residue), static_cast<double>(ref.minimizing), 1e-9) << ref.q;
    EXPECT_NEAR(static_cast<double>(d.minimax.orbit.residue), static_cast<double>(ref.minimax), 1e-9) << ref.q;
    EXPECT_EQ(d.birkhoffOrbits, 2) << ref.q;
    EXPECT_TRUE(shadowsChain(d.minimax.orbit.points, members.points));
    EXPECT_TRUE(wellOrdered(stridedAbout(d.minimizing.orbit.points, 6, c), c));
  }
  r.p = 2;
  r.q = 23;
  r.members.clear();
  EXPECT_THROW((void)mmpActionDifference(r), NotFound);
  // A chain's members in another order (one step on, reversed) are not followed.
  std::vector<PhysicalPoint> reversed(members.points.rbegin(), members.points.rend());
  r.members = members.points;
  const MmpActionDifference d = mmpActionDifference(r);
  EXPECT_FALSE(shadowsChain(d.minimax.orbit.points, reversed));
  r.members = {members.points[0]};
  EXPECT_TRUE(validationError(r).has_value());  // not stride points
}

// The ratio is the largest of the last three (2026-12-07).  Measured at K = 0.1 between 1/6 and 14/83 (ΔW over
// 14/83 … 117/694, docs/atlas.md): the ratios 0.082, 0.41, 0.17 and ΔW falling towards 0; the last ratio alone gave
// 3.5e−11 ± 2.1e−11, a bound that excluded the zero the sequence heads for.  Here a sequence with differences
// 1, 0.5, 0.05, 0.01 (ratios 0.5, 0.1, 0.2): r = 0.5, not 0.2.  An early ratio above 1 (the first two terms of a noble's
// convergents are the Farey pair's) is outside the last three and does not refuse it.
TEST(MmpFlux, TheTailBoundTakesTheLargestOfTheLastThreeRatios) {
  const std::vector<long double> a = {10, 10.01L, 9.01L, 8.51L, 8.46L, 8.45L};
  const ConvergentLimit l = convergentLimit(a);
  EXPECT_EQ(l.value, 8.45L);
  EXPECT_NEAR(static_cast<double>(l.ratio), 0.5, 1e-12);
  EXPECT_NEAR(static_cast<double>(l.uncertainty), 0.01 * 0.5 / 0.5, 1e-12);
  // Four terms: the ratio of the first two differences is among the last three, and it grows: not converging.
  EXPECT_THROW((void)convergentLimit(std::vector<long double>{10, 10.01L, 9.01L, 8.51L}), std::invalid_argument);
}

TEST(MmpFlux, RefusesBadRequestsAndSaysWhatTheScanFound) {
  auto message = [](MmpRequest r) {
    const auto e = validationError(r);
    return e ? *e : std::string("valid");
  };
  MmpRequest r;
  EXPECT_EQ(message(r), "valid");
  r.K = 0;
  EXPECT_NE(message(r).find("K"), std::string::npos);
  r = {};
  r.p = 2;
  r.q = 12;
  EXPECT_NE(message(r).find("lowest terms"), std::string::npos);
  r = {};
  r.p = 6;
  EXPECT_NE(message(r).find("p = 6"), std::string::npos);
  r = {};
  r.innerRadius = 0.3L;
  r.outerRadius = 0.2L;
  EXPECT_NE(message(r).find("0 < inner < outer"), std::string::npos);
  r = {};
  r.spacing = 0;
  EXPECT_NE(message(r).find("spacing"), std::string::npos);
  r = {};
  r.q = 1;
  EXPECT_THROW((void)mmpActionDifference(r), std::invalid_argument);
  // 5/31's orbits lie 0.207–0.432 from the centre: an annulus inside the central island has none.
  r = {};
  r.p = 5;
  r.q = 31;
  r.innerRadius = 0.05L;
  r.outerRadius = 0.15L;
  try {
    (void)mmpActionDifference(r);
    ADD_FAILURE() << "no Birkhoff orbits there";
  } catch (const NotFound& e) {
    EXPECT_NE(std::string(e.what()).find("0 well ordered"), std::string::npos) << e.what();
  }
}

}  // namespace
// The convergents in order of growing q: a repeated or reordered term is refused, not made into a "limit" (found by
// feeding `cantorus --convergents 5/31,5/31`, which returned a table).
TEST(MmpFlux, ConvergentsOutOfOrderAreRefused) {
  CantorusRequest r;
  r.convergents = {{5, 31}, {6, 37}};
  EXPECT_FALSE(validationError(r));
  for (const auto& bad : {std::vector<std::pair<long, int>>{{5, 31}, {5, 31}},
                          std::vector<std::pair<long, int>>{{6, 37}, {5, 31}}}) {
    r.convergents = bad;
    ASSERT_TRUE(validationError(r));
    EXPECT_NE(validationError(r)->find("order of growing q"), std::string::npos) << *validationError(r);
    EXPECT_THROW((void)cantorusFlux(r), std::invalid_argument);
  }
}

}  // namespace archipelago
