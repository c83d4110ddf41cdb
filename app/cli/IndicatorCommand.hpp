#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli indicator`: a chaos-indicator map (dig, rotation, fli, megno, lyapunov) of a view to .npy
/// (+ JSON sidecar) and/or PNG.
void addIndicatorCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
