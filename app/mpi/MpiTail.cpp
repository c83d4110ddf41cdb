#include "MpiTail.hpp"

#include <cstdio>
#include <string>

#include "MpiCommon.hpp"

namespace archipelago::mpi {

namespace {

/// The end of the session in archipelago-mpi's words, by rank 0: the outcome's text, then how to resume a stopped job
/// (status 130 on every rank), or what was done.
int tailEnd(const TailSessionOutcome& r, const cli::TailOptions& o, const Ranks& ranks) {
  const bool stopped = r.end == TailSessionOutcome::End::interrupted;
  if (ranks.rank() != 0) return stopped ? 130 : 0;
  cli::printTailOutcome(r);
  if (r.end == TailSessionOutcome::End::levelsOnly) return 0;
  if (stopped) {
    std::fprintf(stderr,
                 "interrupted: each rank's slice written to %s (resume with mpirun -n %d archipelago-mpi tail "
                 "--resume %s)\n",
                 r.checkpoint.c_str(), ranks.size(), (o.checkpoint.empty() ? o.out : o.checkpoint).c_str());
    return 130;
  }
  if (o.quiet) return 0;
  std::fprintf(stderr,
               "done: %zu levels, the largest reliable t = %.4g; %.3g steps in %.1f s of %d ranks (%s kernel); "
               "wrote %s\n",
               r.result.levels.size(), largestReliableT(r.result), r.result.steps, r.state.elapsedSeconds, ranks.size(),
               r.state.kernel.c_str(), o.out.c_str());
  return 0;
}

}  // namespace

int mpiTail(cli::TailOptions& o, const CLI::App& cmd) {
  MpiRanks ranks;
  if (ranks.rank() != 0) {  // rank 0 shows its own slice's progress, the merged result and the warnings, once
    o.quiet = true;
    o.warnings = false;
  }
  const TailSessionOptions session = cli::tailSession(o, cmd);
  const TailSessionOutcome outcome = runTailSession(session, ranks, cli::interruptToken());
  return tailEnd(outcome, o, ranks);
}

}  // namespace archipelago::mpi
