#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli cantorus`: the MacKay–Meiss–Percival flux ΔW_{p/q} of the Birkhoff orbits over a cantorus's
/// convergents about the central island, and its limit (core/manifolds/MmpFlux.hpp).
void addCantorusCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
