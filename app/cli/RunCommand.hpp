#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli run`: a trapping-statistics run with checkpoints, resumable.
/// Exit status to `status`: 0, or 130 when interrupted (SIGINT/SIGTERM) after writing a checkpoint.
void addRunCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
