#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli portrait`: render a phase portrait of Q* to PNG (and .npy + JSON);
/// `archipelago-cli stochastic-area`: the area b2 of the chaotic sea and its convergence (§5), as CSV or JSON.
void addPortraitCommand(CLI::App& app);
}  // namespace archipelago::cli
