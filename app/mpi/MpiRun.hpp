#pragma once
/// \file MpiRun.hpp
/// \brief archipelago-mpi: `archipelago-cli run` distributed over MPI ranks (issue #15).
///
/// Partition: of R ranks, rank r runs orbits [⌊M·r/R⌋, ⌊M·(r+1)/R⌋) with OpenMP threads inside (--threads).
/// Each orbit depends only on (seed, orbit index), so the merge of the ranks' ranges (core/runfile/
/// RunFileMerge.hpp) is the single-process run, bit for bit, for any R and any threads.  The ranks advance in
/// rounds to a common block count (TrappingRunOptions::untilBlocks); after each round rank 0 decides, for all,
/// the next round's length (about one second for the slowest rank), whether to checkpoint, and whether to stop
/// (SIGINT/SIGTERM on any rank): one gather of {seconds, stop} and one broadcast a round, waited for by polling
/// and sleeping (no rank spins on a core).  Rank 0's closing "compute:" line is the rate measured inside the
/// program (MPI_Wtime, setup and final write excluded) with the ranks' idle share (scripts/bench-mpi.sh).
/// A checkpoint is one run file per rank, NAME.b<blocks>.r<rank>.json beside the manifest NAME, written
/// atomically before the manifest names them; --resume MANIFEST (or a plain run file)
/// continues on any number of ranks: every rank reads the whole checkpoint, takes its own orbits, and rank 0
/// carries the statistics so far (sliceRun).  At the end rank 0 gathers the ranks' states, merges and writes
/// --out.

#include "RunOptions.hpp"

namespace archipelago::mpi {
/// Runs on every rank (MPI initialized); returns the exit status (0, 1 or 130 when interrupted).
int mpiRun(const cli::RunOptions& o, const std::vector<std::string>& explicitParameters, const CLI::App& cmd);
}  // namespace archipelago::mpi
