#pragma once
// archipelago-cli limits: core's one table of limits (core/limits/Limits.hpp) as Markdown, as docs/cli.md holds it.

#include <CLI/CLI.hpp>

namespace archipelago::cli {

void addLimitsCommand(CLI::App& app, int& status);

}  // namespace archipelago::cli
