#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli stochastic-area`: the area b2 of the chaotic sea and its convergence (§5), as CSV or JSON.
void addStochasticAreaCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
