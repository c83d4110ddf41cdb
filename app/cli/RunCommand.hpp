#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli run`: a trapping-statistics run with checkpoints, resumable.
void addRunCommand(CLI::App& app);
/// `archipelago-cli replay`: replay one of a run file's longest segments bit for bit, as CSV.
void addReplayCommand(CLI::App& app);
}  // namespace archipelago::cli
