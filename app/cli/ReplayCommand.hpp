#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli replay`: replay one of a run file's longest segments bit for bit, as CSV.
void addReplayCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
