#pragma once
/// \file HyperbolicOrbitOptions.hpp
/// \brief The options `manifold` and `flux` share: which hyperbolic orbit (--period, --near, --radius) and which
/// branch side (--side).

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

#include "core/manifolds/HyperbolicOrbit.hpp"
#include "core/manifolds/ManifoldParameterization.hpp"
#include "core/periodic/PeriodicOrbit.hpp"

namespace archipelago::cli {

struct HyperbolicOrbitOptions {
  int period = 1;
  std::string near;
  long double radius = 0.01L;
  std::string side = "auto";
};

/// Adds --period, --near, --radius and --side to `command`.
void addHyperbolicOrbitOptions(CLI::App& command, HyperbolicOrbitOptions& options);

/// The orbit the options name: none for period 1 without --near (the fixed point (√K, 0)); otherwise the hyperbolic
/// orbit of that period nearest to --near (findHyperbolicOrbit).  Throws std::invalid_argument naming the option.
[[nodiscard]] std::optional<PeriodicOrbit> chosenOrbit(long double K, const HyperbolicOrbitOptions& options);

/// --side: "inward", "outward", or "auto" (inward for the fixed point, whose inner branch bounds the central island's
/// zone; outward for a periodic orbit, whose outer separatrix faces the chaotic sea).
[[nodiscard]] BranchSide chosenSide(const HyperbolicOrbitOptions& options, bool fixedPoint);

}  // namespace archipelago::cli
