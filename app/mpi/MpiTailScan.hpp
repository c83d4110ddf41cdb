#pragma once
/// \file MpiTailScan.hpp
/// \brief archipelago-mpi tail-scan: `archipelago-cli tail-scan` with its K shared round-robin over MPI ranks
/// (issue 55): rank r runs the m-th K of its task when m mod R = r, each K's tail file checkpointed and written as one
/// process writes it; when every rank has finished, rank 0 reads every K's file and prints and writes the summary.
/// Stopped, each rank's running K is in its file, and the same command resumes (on any number of ranks: the files
/// are whole runs, not slices).  The job is core's (core/tail/TailScan.hpp: runTailScan on MpiRanks).

#include "TailScanSession.hpp"

namespace archipelago::mpi {
/// Runs on every rank (MPI initialized); returns the exit status (0, 1 or 130 when interrupted).
int mpiTailScan(cli::TailScanOptions& o, const CLI::App& cmd);
}  // namespace archipelago::mpi
