#include "HyperbolicOrbitOptions.hpp"

#include <stdexcept>

#include "CliCommon.hpp"
#include "core/manifolds/HyperbolicOrbit.hpp"

namespace archipelago::cli {

void addHyperbolicOrbitOptions(CLI::App& command, HyperbolicOrbitOptions& o) {
  addNumberOption(command, "--period", o.period,
                  "period n of the hyperbolic orbit, [1, " + std::to_string(kMaxManifoldPeriod) +
                      "]; 1 without --near: the fixed point (sqrt K, 0)");
  command.add_option("--near", o.near,
                     "x,y: a guess for a point of the hyperbolic orbit, or a point inside an island of its chain (its "
                     "hyperbolic partner is used); use --near=-0.3,0 for x < 0");
  addNumberOption(command, "--radius", o.radius, "how far (physical units) from the guess's iterates to search");
  command.add_option("--side", o.side, "branch at the orbit point: inward, outward or auto (inward for the fixed point, "
                                       "outward for a periodic orbit)")
      ->default_str("auto");
}

std::optional<PeriodicOrbit> chosenOrbit(long double K, const HyperbolicOrbitOptions& o) {
  if (auto e = manifoldPeriodError(o.period)) throw std::invalid_argument(*e);
  if (o.near.empty() && o.period != 1)
    throw std::invalid_argument("--near x,y is required with --period " + std::to_string(o.period));
  std::optional<PhysicalPoint> near;
  if (!o.near.empty()) {
    const auto v = parseNumbers<long double>("--near", o.near, ',', 2, "two finite numbers x,y");
    near = PhysicalPoint{v[0], v[1]};
  }
  return hyperbolicOrbitNear(K, o.period, near, o.radius);
}

BranchSide chosenSide(const HyperbolicOrbitOptions& o, bool fixedPoint) { return parseBranchSide(o.side, fixedPoint, "--side"); }

}  // namespace archipelago::cli
