#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli merge PART.json... --out RUN.json`: the run files of separate orbit ranges of one run
/// (`run --orbits BEGIN:END`, e.g. scheduler array jobs) merged into the run file of the whole run
/// (core/runfile/RunFileMerge.hpp); mismatched parts are one ERROR naming the file and the field, nothing written.
void addMergeCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
