#include "core/report/TheoryStatements.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/markov/MarkovModel.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/report/ReportRuns.hpp"
#include "core/theory/PaperNumbers.hpp"
#include "core/theory/SmallKTheory.hpp"

namespace archipelago::report {

namespace {

/// The residue of the period-1 orbit (the elliptic fixed point) the finder converges to near (−√K, 0).
std::optional<long double> fixedPointResidue(long double K) {
  PeriodicOrbitSearch s;
  s.period = 1;
  s.near = {-std::sqrt(K), 0};
  s.searchRadius = 0.05L;
  try {
    return findPeriodicOrbit(K, s).residue;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

std::optional<PeriodicOrbit> chain138Orbit() {
  PeriodicOrbitSearch s;
  s.period = paper::kChain138Period;
  s.near = {kChain138X, kChain138Y};
  s.stableOnly = true;
  try {
    return findPeriodicOrbit(0.1L, s);
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

double markovEpsilonRatio(std::int64_t m, std::int64_t N, std::int64_t tauMax) {
  const markov::MarkovModel model{{m}, N};
  const auto eps = markov::correlationDeviation(model, markov::paperObservable(model), tauMax);
  double largest = 0;
  for (std::size_t tau = 1; tau < eps.size(); ++tau) largest = std::max(largest, std::abs(eps[tau]));
  return largest / (static_cast<double>(m) / static_cast<double>(N));
}

MarkovCurve markovEpsilon() {
  const markov::MarkovModel model{{20}, 1000};
  MarkovCurve c;
  c.epsilon = markov::correlationDeviation(model, markov::paperObservable(model), 200);
  for (std::size_t i = 0; i < c.epsilon.size(); ++i) c.tau.push_back(static_cast<double>(i));
  c.command = cliCommand("markov --m 20 --N 1000 --tau-max 200");
  return c;
}

namespace {

/// A statement of the theory: computed at the paper's size, whatever the run.
ReportItem theoryItem(std::string_view id, std::optional<double> ours, double error, std::string command,
                      std::string note) {
  return makeItem(id, ours, error, true, std::move(command), std::move(note));
}

/// §2: the fixed point's rotation, found by the periodic-orbit finder (not the formula it is compared with).
ReportItem fixedPointRotationItem() {
  PeriodicOrbitSearch s;
  s.period = 1;
  s.near = {-std::sqrt(0.1L), 0};
  std::optional<double> cosine;
  std::string note;
  try {
    const PeriodicOrbit o = findPeriodicOrbit(0.1L, s);
    cosine = static_cast<double>(o.trace / 2);  // ½ trace DQ = cos α at an elliptic point
    note = io::formatC("the finder's fixed point (%.15Lg, %.3Lg), residue %.12Lg", o.points.front().x,
                       o.points.front().y, o.residue);
  } catch (const std::exception& e) {
    note = std::string("the finder failed: ") + e.what();
  }
  return theoryItem("cos-alpha", cosine, 0, cliCommand("periodic --K 0.1 --period 1 --near=-0.3162,0"), note);
}

/// pd-first: bisection on R(K) − 1 of the finder's fixed point, between K = 0.9 (R < 1) and 1.1 (R > 1).
ReportItem firstPeriodDoublingItem() {
  double lo = 0.9, hi = 1.1;
  std::optional<double> K;
  const auto rLo = fixedPointResidue(lo), rHi = fixedPointResidue(hi);
  if (rLo && rHi && *rLo < 1 && *rHi > 1) {
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      const auto r = fixedPointResidue(mid);
      if (!r) break;
      (*r < 1 ? lo : hi) = mid;
    }
    K = 0.5 * (lo + hi);
  }
  return theoryItem("pd-first", K, 0, cliCommand("periodic --K 1 --period 1 --near=-1,0"),
                    "the residue R of the finder's period-1 orbit near (−√K, 0) crosses 1 (Greene: R > 1 is unstable)");
}

/// The accumulation point of the period-doubling cascade of the symmetric orbits.
ReportItem periodDoublingAccumulationItem() {
  const auto cascade = paper::periodDoublingCascade(6);
  return theoryItem("pd-accumulation", cascade.accumulation, cascade.accumulationChange, onlyCommand("pd-accumulation"),
                    "K₀ … K₅ from the symmetric-orbit finder; error: the change of the extrapolation from the last level");
}

/// §4: the closed forms of the small-K theory, by their own numerics (elliptic integrals, Gauss–Legendre).
std::vector<ReportItem> smallKItems() {
  const auto& mx = smallk::negativeKMaximum();
  return {theoryItem("tmax", mx.T, 0, onlyCommand("tmax"),
                     "smallk::negativeKMaximum(): the root of T'(X₀) by complete elliptic integrals"),
          theoryItem("tmax-X0", mx.X0, 0, onlyCommand("tmax-X0"), "the argument of that maximum"),
          theoryItem("F-smallT", smallk::negativeKSmallTCoefficient(), 0, onlyCommand("F-smallT"),
                     "112 A⁶, A = Γ(1/3)√π/Γ(5/6)"),
          theoryItem("F-cutoff", smallk::negativeKCutoffCoefficient(), 0, onlyCommand("F-cutoff"),
                     "2√2 (X₀² + 1)/√|T''(X₀)| at the maximum"),
          theoryItem("A-const", smallk::zeroKTimeConstant(), 0, onlyCommand("A-const"), "Γ(1/3)√π/Γ(5/6)")};
}

/// §7: the 138-chain's member, by the periodic-orbit finder: its x + √K and its y.
std::vector<ReportItem> chain138Items() {
  std::optional<double> x, y;
  std::string note;
  if (const auto o = chain138Orbit()) {
    x = static_cast<double>(o->points.front().x) + std::sqrt(0.1);
    y = static_cast<double>(o->points.front().y);
    note = io::formatC("elliptic period-%d orbit, residue %.3Lf, member at (%.6f, %.6f)", o->period, o->residue,
                       static_cast<double>(o->points.front().x), *y);
  } else {
    note = "no elliptic orbit of period 138 found near the paper's point";
  }
  const std::string command = cliCommand("periodic --K 0.1 --period 138 --near 0.0358,0.034 --stable");
  return {theoryItem("chain138-x", x, 0, command, note), theoryItem("chain138-y", y, 0, command, note)};
}

/// Appendix C: eq. (dmark) against the O(m) solve for m = 20, N = 1000.
ReportItem markovDmarkItem() {
  const markov::MarkovModel model{{20}, 1000};
  const auto h = markov::paperObservable(model);
  const double dExact = markov::diffusionCoefficient(model, h);
  const double dMark = markov::diffusionCoefficientDmark(model, h);
  return theoryItem("markov-dmark", std::abs(dMark - dExact) / std::abs(dExact), 0, cliCommand("markov --m 20 --N 1000"),
                    io::formatC("D = %.15g by the O(m) solve, %.15g by eq. (dmark)", dExact, dMark));
}

/// Appendix C: the largest |ε(τ)|/(m/N) over the paper's grid m = 10, 20, 50; N = 10m … 10⁶m.  ε decays as
/// n^(−τ/m) after a transient: τ ≤ 20m covers its largest values.  The bound holds where N ≥ m²; below, ε(1) =
/// (m − 1)/(N − m) exceeds m/N.
ReportItem markovEpsilonItem() {
  double worstWhereHolds = 0, worstBelow = 0;
  for (const std::int64_t m : {10, 20, 50})
    for (std::int64_t N = 10 * m; N <= 1'000'000 * m; N *= 10) {
      const double ratio = markovEpsilonRatio(m, N, 20 * m);
      (N >= m * m ? worstWhereHolds : worstBelow) = std::max(N >= m * m ? worstWhereHolds : worstBelow, ratio);
    }
  return theoryItem("markov-eps", worstWhereHolds, 0, cliCommand("markov --m 20 --N 1000"),
                    io::formatC("max over τ > 0 of |ε(τ)|/(m/N) for N ≥ m²; for N < m² (N = 10m) it "
                                "reaches %.4f: ε(1) = (m − 1)/(N − m) > m/N there",
                                worstBelow));
}

/// Appendix C: the half-period of ε(τ)'s oscillation for m = 20, N = 1000: the mean distance between its sign
/// changes over 2m < τ ≤ 10m (after the transient).
ReportItem markovPeriodItem() {
  const MarkovCurve c = markovEpsilon();
  std::vector<double> changes;
  for (std::size_t tau = 41; tau < c.epsilon.size(); ++tau)
    if ((c.epsilon[tau - 1] < 0) != (c.epsilon[tau] < 0)) changes.push_back(static_cast<double>(tau));
  std::optional<double> half;
  if (changes.size() >= 2) half = (changes.back() - changes.front()) / static_cast<double>(changes.size() - 1);
  return theoryItem("markov-period", half, 0, c.command,
                    io::formatC("%zu sign changes over 40 < τ ≤ 200", changes.size()));
}

}  // namespace

std::vector<ReportItem> theoryStatements() {
  std::vector<ReportItem> items{fixedPointRotationItem(), firstPeriodDoublingItem(), periodDoublingAccumulationItem()};
  for (ReportItem& item : smallKItems()) items.push_back(std::move(item));
  for (ReportItem& item : chain138Items()) items.push_back(std::move(item));
  items.push_back(markovDmarkItem());
  items.push_back(markovEpsilonItem());
  items.push_back(markovPeriodItem());
  return items;
}

}  // namespace archipelago::report
