#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli markov-tree`: the Meiss–Ott Markov tree of an atlas file and its exact P_t
/// (core/markovtree/MarkovTreeExport.hpp): the states and rates on stdout, the survival as CSV (--csv) and JSON (--json).
void addMarkovTreeCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
