#include "TailCommand.hpp"

#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "TailSession.hpp"
#include "core/tail/TailPlan.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"

namespace archipelago::cli {

namespace {

int tailCommand(TailOptions& o, const CLI::App& cmd) {
  std::optional<ReplicaRange> slice;
  const CLI::Option* sliceGiven = cmd.get_option_no_throw("--slice");
  if (sliceGiven && sliceGiven->count() > 0) {  // given empty is an error too, not the whole run (issue 36)
    if (!o.resume.empty()) throw std::invalid_argument("--resume takes the slice from the tail file; do not also give --slice");
    slice = parseReplicaSlice("--slice", o.slice, o.request.replicas);
  }
  PreparedTail job = prepareTail(o, cmd, slice);
  if (job.printedLevels) return 0;
  const std::string checkpoint = o.checkpoint.empty() ? o.out : o.checkpoint;
  const std::vector<io::FileLock> locks = lockRunFiles(o.out, checkpoint, o.resume);
  LastCheckpoint last{o.resume, 0};
  TailState state = runTailSession(std::move(job.state), o, checkpoint, last);
  if (!state.finished()) {
    saveTail(checkpoint, state, last);
    std::fprintf(stderr, "interrupted: checkpoint written to %s (resume with --resume %s)\n", checkpoint.c_str(),
                 checkpoint.c_str());
    return 130;
  }
  io::OutputBatch outputs;  // the tail file and its CSVs: all or nothing (issue 36, class 5)
  saveTail(o.out, state, last);
  reportTail(state, o, job.runs);
  outputs.commit();
  if (!o.quiet) {
    const TailResult result = tailResult(state);
    std::fprintf(stderr, "done: %zu levels, the largest reliable t = %.4g; %.3g steps in %.1f s (%s kernel); wrote %s\n",
                 result.levels.size(), largestReliableT(result), result.steps, state.elapsedSeconds,
                 state.kernel.c_str(), o.out.c_str());
    if (state.replicas.size() != state.request.replicas)
      std::fprintf(stderr, "this is replicas [%u, %zu) of %u: merge the slices with archipelago-cli merge\n",
                   state.firstReplica, state.firstReplica + state.replicas.size(), state.request.replicas);
  }
  return 0;
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
