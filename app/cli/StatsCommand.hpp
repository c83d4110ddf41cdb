#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli stats RUN.json [--csv DIR]`: the derived statistics of a run file.
void addStatsCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
