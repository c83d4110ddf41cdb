#include "MpiTailScan.hpp"

#include "MpiCommon.hpp"

namespace archipelago::mpi {

int mpiTailScan(cli::TailScanOptions& o, const CLI::App& cmd) {
  MpiRanks ranks;
  const bool quiet = o.quiet;
  if (ranks.rank() != 0) {  // rank 0 alone prints the warnings and the summary; every rank its K's progress
    o.quiet = true;
    o.warnings = false;
  }
  const TailScanRequest request = cli::tailScanRequest(o, cmd);
  const TailScanOutcome outcome = runTailScan(request, cli::tailScanView(quiet), ranks, cli::interruptToken());
  if (ranks.rank() != 0) return outcome.end == TailScanOutcome::End::interrupted ? 130 : 0;
  return cli::tailScanEnd(outcome, o, "mpirun archipelago-mpi tail-scan");
}

}  // namespace archipelago::mpi
