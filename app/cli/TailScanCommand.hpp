#pragma once
/// \file TailScanCommand.hpp
/// \brief `archipelago-cli tail-scan`: the tail sampler scanned over K (core/tail/TailScan.hpp, issue 55): a tail
/// file per K in a folder, each started, resumed or reused, then the summary over K (P per K and level, γ per K over
/// fixed windows, its K-average).  Ctrl-C exits 130; the same command resumes.  What it shares with
/// `archipelago-mpi tail-scan` is in app/shared/TailScanSession.hpp.

#include <CLI/CLI.hpp>

namespace archipelago::cli {

void addTailScanCommand(CLI::App& app, int& status);

}  // namespace archipelago::cli
