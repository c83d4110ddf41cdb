#pragma once
/// \file TailCommand.hpp
/// \brief `archipelago-cli tail`: P_t beyond brute force by splitting on segment age (core/tail, issue #29), for
/// the process of `run` (the same spec options).  Checkpoints and resumes bit for bit; SIGINT saves and exits 130.
/// With --compare RUN.json…: the brute-force P_t of those runs at the same levels, and the steps each needs.
/// With --slice I/N: replicas [⌊R·I/N⌋, ⌊R·(I+1)/N⌋) only, a tail file that `merge` joins with the other slices.
/// What it shares with `archipelago-mpi tail` is in app/shared/TailSession.hpp.

#include <CLI/CLI.hpp>

namespace archipelago::cli {

void addTailCommand(CLI::App& app, int& status);

}  // namespace archipelago::cli
