#include "TailCommand.hpp"

#include <cstdio>
#include <memory>

#include "RunSession.hpp"
#include "TailSession.hpp"

namespace archipelago::cli {

namespace {

/// The end of the session in the command line's words: the outcome's text, then how to resume a stopped run (status
/// 130), or what was done.
int tailEnd(const TailSessionOutcome& r, const TailOptions& o) {
  printTailOutcome(r);
  if (r.end == TailSessionOutcome::End::levelsOnly) return 0;
  if (r.end == TailSessionOutcome::End::interrupted) {
    std::fprintf(stderr, "interrupted: checkpoint written to %s (resume with --resume %s)\n", r.checkpoint.c_str(),
                 r.checkpoint.c_str());
    return 130;
  }
  if (o.quiet) return 0;
  const TailState& state = r.state;
  std::fprintf(stderr, "done: %zu levels, the largest reliable t = %.4g; %.3g steps in %.1f s (%s kernel); wrote %s\n",
               r.result.levels.size(), largestReliableT(r.result), r.result.steps, state.elapsedSeconds,
               state.kernel.c_str(), o.out.c_str());
  if (state.replicas.size() != state.request.replicas)
    std::fprintf(stderr, "this is replicas [%u, %zu) of %u: merge the slices with archipelago-cli merge\n",
                 state.firstReplica, state.firstReplica + state.replicas.size(), state.request.replicas);
  return 0;
}

int tailCommand(const TailOptions& o, const CLI::App& cmd) {
  const TailSessionOptions session = tailSession(o, cmd);
  OneProcess process;
  const TailSessionOutcome outcome = runTailSession(session, process, interruptToken());
  return tailEnd(outcome, o);
}

}  // namespace

void addTailCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<TailOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tail", "P_t beyond brute force: splitting on the age of trapped segments, for the process of run (issue 29)");
  addTailOptions(*cmd, *o, /*withSlice=*/true);
  cmd->callback([o, cmd, &status] { status = tailCommand(*o, *cmd); });
}

}  // namespace archipelago::cli
