#include "TailScanCommand.hpp"

#include <memory>

#include "RunSession.hpp"
#include "TailScanSession.hpp"

namespace archipelago::cli {

void addTailScanCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<TailScanOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tail-scan", "the tail sampler over K (issue 55): a tail file per K in its scan box, then the local exponent "
                   "over fixed windows and its average over K");
  addTailScanOptions(*cmd, *o);
  cmd->callback([o, cmd, &status] {
    const TailScanRequest request = tailScanRequest(*o, *cmd);
    OneProcess process;
    const TailScanOutcome outcome = runTailScan(request, tailScanView(o->quiet), process, interruptToken());
    status = tailScanEnd(outcome, *o, "archipelago-cli tail-scan");
  });
}

}  // namespace archipelago::cli
