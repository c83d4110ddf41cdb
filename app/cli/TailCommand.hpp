#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli tail`: P_t beyond brute force by splitting on segment age (core/tail, issue #29), for the
/// process of `run` (the same spec options).  Checkpoints and resumes bit for bit; SIGINT saves and exits 130.
/// With --compare RUN.json…: the brute-force P_t of those runs at the same levels, and the steps each needs.
void addTailCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
