#pragma once
/// \file TailScanSession.hpp
/// \brief What `archipelago-cli tail-scan` (app/cli/TailScanCommand.hpp) and `archipelago-mpi tail-scan` share: the
/// options (tail's spec and sampler options, the K list, the folder, the task), filled into core's scan
/// (core/tail/TailScan.hpp: runTailScan), its progress per K on stderr, and the outcome's text.  Parse, fill, call and
/// format: the plan of each K, the locks, the checkpoints, the stop and the summary are core's.

#include <CLI/CLI.hpp>

#include <string>

#include "RunSession.hpp"
#include "core/tail/TailScan.hpp"

namespace archipelago::cli {

struct TailScanOptions : SpecOptions {
  TailRequest request;
  std::string clones = "perturb";
  std::string K;           // --K: FROM:TO:STEP or K1,K2,…
  std::string dir = "tail-scan";
  double checkpointSeconds = 60;
  std::string task;        // --task I/N
  std::string csv;         // --csv PREFIX
  bool quiet = false;
  bool warnings = true;    // core's warnings about each K's box on stderr: archipelago-mpi's rank 0 only
};

/// Every option of `tail-scan` on `cmd`.
void addTailScanOptions(CLI::App& cmd, TailScanOptions& o);

/// The options filled into core's scan request, named as the command line names them (flagOf); the spec resolved
/// from the command line (tail's spec options but K and the box, which are the scan's).
[[nodiscard]] TailScanRequest tailScanRequest(const TailScanOptions& o, const CLI::App& cmd);

/// The scan on stderr: a line when each K begins and ends, the sampler's progress within it (unless quiet: a line
/// every 10 s, or a line redrawn on a terminal), checkpoint warnings.
[[nodiscard]] TailScanView tailScanView(bool quiet);

/// The end of a scan in the command line's words, by rank 0: the summary on stdout, then how to resume a stopped
/// scan (`resume`: the program and command to run again, e.g. "archipelago-cli tail-scan"; status 130), the K still waiting for other tasks, or what was done.
int tailScanEnd(const TailScanOutcome& r, const TailScanOptions& o, const std::string& resume);

}  // namespace archipelago::cli
