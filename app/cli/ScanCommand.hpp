#pragma once
#include <CLI/CLI.hpp>

namespace archipelago::cli {
/// `archipelago-cli scan`: the K scan of §5 — a run file per K (resumable, the same file `run` makes with that
/// spec), then summary CSVs of f_t, the local exponent over τ and K (and a PNG heat map), D, the longest segment,
/// the time in long segments and, optionally, b₂.  Exit status 130 when interrupted after a checkpoint.
void addScanCommand(CLI::App& app, int& status);
}  // namespace archipelago::cli
