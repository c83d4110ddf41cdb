#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli atlas`: the hierarchy of islands around islands (core/atlas/Atlas.hpp): a table on stdout, the
/// tree as JSON (--json) and CSV (--csv); Ctrl-C writes what is finished and exits 130.
void addAtlasCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
