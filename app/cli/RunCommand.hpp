#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli run`: a trapping-statistics run with checkpoints, resumable.
void addRunCommand(CLI::App& app);
}  // namespace archipelago::cli
