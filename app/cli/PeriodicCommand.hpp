#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli periodic`: find a periodic orbit of Q near a point; print its residue, stability, rotation
/// number and points (core/periodic/PeriodicOrbitFinder.hpp).
void addPeriodicCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
