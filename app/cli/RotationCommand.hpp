#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli rotation`: the rotation number and island chain of one orbit (text or --json), or the
/// rotation profile along a segment (--line … --csv).
void addRotationCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
