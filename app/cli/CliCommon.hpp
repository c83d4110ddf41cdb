#pragma once
// Shared option helpers of archipelago-cli's subcommands.

#include <CLI/CLI.hpp>

#include <string>

#include "map/MapParameters.hpp"

namespace archipelago::cli {

/// Adds --K, --xmin and --xmax (defaults: the paper's K = 0.1 box, §5) to a subcommand.
void addMapOptions(CLI::App& command, MapParameters& params);

/// Adds --kernel NAME (the instruction-set path; empty: $ARCHIPELAGO_KERNEL, else the fastest the CPU supports).
/// The command passes the name to selectKernel() (kernels/KernelDispatch.hpp), which validates it.
void addKernelOption(CLI::App& command, std::string& name);

}  // namespace archipelago::cli
