#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli flux`: the turnstile flux through the separatrix of the fixed point (√K, 0) or of a symmetric
/// hyperbolic periodic orbit, by the action difference and by the polygon area, the zone's area, and the Kac check
/// (core/manifolds/TurnstileFlux.hpp, KacCheck.hpp).
void addFluxCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
