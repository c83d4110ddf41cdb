#pragma once
/// \file TheoryStatements.hpp
/// \brief The statements of the paper's table that need no trapping run (§2, §4's closed forms, §7's periodic
/// orbit, appendix C): each value from the module that defines it (smallk:: elliptic integrals, the periodic-orbit
/// finder, the Markov model).  No maths here.

#include <optional>
#include <vector>

#include "core/paper/PaperTable.hpp"
#include "core/periodic/PeriodicOrbit.hpp"
#include "core/report/ReportItem.hpp"

namespace archipelago::report {

/// Every statement of this kind: tmax, tmax-X0, F-smallT, F-cutoff, A-const, cos-alpha, pd-first, pd-accumulation,
/// chain138-x, chain138-y, markov-dmark, markov-eps, markov-period.  A few seconds (the cascade, the 138-orbit).
[[nodiscard]] std::vector<ReportItem> theoryStatements();

/// The member of the period-138 = 6 × 23 chain the paper names (§7: "at x + √K ≈ 0.352 and y ≈ 0.034"): where the
/// report looks for it, and the elliptic orbit the periodic-orbit finder converges to from there.
inline constexpr double kChain138X = paper::kChain138XPlusRootK - 0.31622776601683794;  // x, not x + √K (√0.1)
inline constexpr double kChain138Y = paper::kChain138Y;
[[nodiscard]] std::optional<PeriodicOrbit> chain138Orbit();

/// Appendix C: the Markov model's ε(τ) for one segment of m = 20 points among N = 1000, τ = 0 … 200 (the report's
/// figure C), and the command that prints it.
struct MarkovCurve {
  std::vector<double> tau, epsilon;
  std::string command;
};
[[nodiscard]] MarkovCurve markovEpsilon();

/// The largest |ε(τ)| over τ = 1 … tauMax relative to m/N, for one segment of m points among N (appendix C).
[[nodiscard]] double markovEpsilonRatio(std::int64_t m, std::int64_t N, std::int64_t tauMax);

}  // namespace archipelago::report
