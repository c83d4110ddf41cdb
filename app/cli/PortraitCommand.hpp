#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli portrait`: render a phase portrait of Q* to PNG (and .npy + JSON).
void addPortraitCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
