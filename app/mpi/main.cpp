// archipelago-mpi: `archipelago-cli run` over MPI ranks (issue #15, MpiRun.hpp), and with the subcommand tail,
// `archipelago-cli tail` with its replicas over the ranks (issue #29, MpiTail.hpp); with tail-scan, `archipelago-cli
// tail-scan` with its K over the ranks (issue 55, MpiTailScan.hpp).  The options are `run`'s (shared/RunOptions.hpp),
// `tail`'s (shared/TailSession.hpp) and `tail-scan`'s (shared/TailScanSession.hpp).  An error every rank finds alike (a bad option) is
// printed once, by rank 0; an error of one rank (its file, its memory) is agreed by every rank and printed by rank 0
// with the rank's number; the job then ends with its status and nothing after the ERROR line (endJob).

#include <mpi.h>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

#include "MpiCommon.hpp"
#include "MpiRun.hpp"
#include "MpiTail.hpp"
#include "MpiTailScan.hpp"
#include "CliCommon.hpp"
#include "RunSession.hpp"

int main(int argc, char** argv) {
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);  // OpenMP threads never call MPI
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  archipelago::cli::installInterruptHandlers();  // at once: a stop asked before the first round is honoured too
  CLI::App app{"archipelago-mpi " ARCHIPELAGO_VERSION
               " -- `archipelago-cli run` distributed over MPI ranks, bit-identical to one process"};
  app.set_version_flag("--version", std::string("archipelago-mpi ") + ARCHIPELAGO_VERSION);
  archipelago::cli::RunOptions o;
  archipelago::cli::addRunOptions(app, o);
  // archipelago-mpi tail …: `archipelago-cli tail` with its replicas over the ranks (MpiTail.hpp).
  archipelago::cli::TailOptions tail;
  CLI::App* tailCmd = app.add_subcommand(
      "tail", "`archipelago-cli tail` (P_t beyond brute force) with its replicas distributed over the ranks");
  archipelago::cli::addTailOptions(*tailCmd, tail, /*withSlice=*/false);
  // archipelago-mpi tail-scan …: `archipelago-cli tail-scan` with its K over the ranks (MpiTailScan.hpp).
  archipelago::cli::TailScanOptions scan;
  CLI::App* scanCmd = app.add_subcommand(
      "tail-scan", "`archipelago-cli tail-scan` (the tail sampler over K) with its K shared round-robin over the ranks");
  archipelago::cli::addTailScanOptions(*scanCmd, scan);
  int status = 0;
  try {
    app.parse(argc, argv);
    status = tailCmd->parsed()   ? archipelago::mpi::mpiTail(tail, *tailCmd)
             : scanCmd->parsed() ? archipelago::mpi::mpiTailScan(scan, *scanCmd)
                                 : archipelago::mpi::mpiRun(o, archipelago::cli::givenSpecOptions(app), app);
  } catch (const CLI::ParseError& e) {
    if (rank == 0) status = archipelago::cli::parseErrorStatus(app, e);  // one "ERROR:" line, as archipelago-cli
    MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);                  // rank 0's (--help: 0) on every rank
  } catch (const std::exception& e) {  // every rank's alike, or agreed by the ranks (MpiCommon.hpp: agree)
    if (rank == 0) std::fprintf(stderr, "ERROR: %s\n", e.what());
    status = 1;
  }
  return archipelago::mpi::endJob(status);  // the ERROR line, and no banner of MPI's after it
}
