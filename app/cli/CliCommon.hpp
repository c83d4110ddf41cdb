#pragma once
// Shared option helpers of archipelago-cli's subcommands.

#include <CLI/CLI.hpp>

#include "map/MapParameters.hpp"

namespace archipelago::cli {

/// Adds --K, --xmin and --xmax (defaults: the paper's K = 0.1 box, §5) to a subcommand.
void addMapOptions(CLI::App& command, MapParameters& params);

}  // namespace archipelago::cli
