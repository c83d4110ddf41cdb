#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli orbit`: iterate N or N⁻¹ from a physical point and print the orbit as CSV.
/// The command's exit status goes to `status`.
void addOrbitCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
