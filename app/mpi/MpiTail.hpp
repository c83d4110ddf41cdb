#pragma once
/// \file MpiTail.hpp
/// \brief archipelago-mpi tail: `archipelago-cli tail` with its replicas distributed over MPI ranks (issue #29).
///
/// Of R ranks, rank r runs slice r of R of the replicas ([⌊R_rep·r/R⌋, ⌊R_rep·(r+1)/R⌋), TailSampler.hpp "slice")
/// with OpenMP threads inside (--threads); replicas are independent, so the ranks never wait for each other while
/// they compute.  Each rank checkpoints its slice to NAME.slice-r-of-R.json beside the checkpoint NAME (the --out
/// file unless --checkpoint), and writes it when it stops, finished or not.  When every rank has finished, rank 0
/// gathers the slices, merges them (mergeTailSlices: the one-process run, bit for bit, steps included), writes
/// --out and removes the slice files; otherwise it says how to resume: --resume NAME on the same number of ranks
/// (each rank reads its own slice file; a finished slice is not run again).  The session is core's
/// (core/tail/TailJob.hpp: runTailSession on MpiRanks), as archipelago-cli's is on one process.

#include "TailSession.hpp"

namespace archipelago::mpi {
/// Runs on every rank (MPI initialized); returns the exit status (0, 1 or 130 when interrupted).
int mpiTail(cli::TailOptions& o, const CLI::App& cmd);
}  // namespace archipelago::mpi
