#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli orbit`: iterate N or N⁻¹ from a physical point and print the orbit as CSV.
void addOrbitCommand(CLI::App& app);
}  // namespace archipelago::cli
