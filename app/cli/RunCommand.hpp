#pragma once
/// \file RunCommand.hpp
/// \brief `archipelago-cli run` (its options: app/shared/RunOptions.hpp, shared with archipelago-mpi).
#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

#include "RunOptions.hpp"
#include "core/run/TrappingRun.hpp"

namespace archipelago::cli {

/// `archipelago-cli run`: a trapping-statistics run with checkpoints, resumable.
/// Exit status to `status`: 0, or 130 when interrupted (SIGINT/SIGTERM) after writing a checkpoint.
void addRunCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
