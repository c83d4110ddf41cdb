#pragma once
// archipelago-cli presets [ID]: the paper's presets (core's runspec/RunSpec.hpp), listed or printed as a run spec.

#include <CLI/CLI.hpp>

namespace archipelago::cli {

void addPresetsCommand(CLI::App& app, int& status);

}  // namespace archipelago::cli
