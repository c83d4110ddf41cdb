#include "core/runfile/CheckpointedRun.hpp"

#include <stdexcept>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/runfile/RunFile.hpp"

namespace archipelago {

TrappingState runWithCheckpoints(TrappingState state, const CheckpointedRunOptions& options, LastCheckpoint& last,
                                 const TrappingObserver& progress, std::stop_token stop) {
  std::stop_source stopper;
  std::stop_callback forward(stop, [&] { stopper.request_stop(); });
  CheckpointClock clock(options.checkpointSeconds);
  auto observer = [&](const TrappingState& s, const TrappingProgress& p) {
    if (options.stopRequested && options.stopRequested()) stopper.request_stop();
    if (!s.finished() && clock.due())
      writeCheckpoint([&] { saveRunFile(options.checkpoint, s); }, options.checkpoint.string(), s.blocksDone, last,
                      options.checkpointSeconds, options.warning);
    if (progress) progress(s, p);
  };
  return runTrapping(std::move(state), options.run, observer, stopper.get_token());
}

void saveRunFileOrSayWhere(const std::filesystem::path& path, const TrappingState& state, const LastCheckpoint& last,
                           const std::string& howToResume) {
  const std::string of = std::to_string(state.params.T) + " blocks";
  saveOrRescue(
      path, [&](const std::filesystem::path& p) { saveRunFile(p, state); }, "run",
      " (" + std::to_string(state.blocksDone) + " of " + of + ")",
      last.path.empty() ? std::string()
                        : "the last checkpoint (" + std::to_string(last.blocks) + " of " + of + ") is in " + last.path +
                              howToResume);
}

RunFileAction runFileAction(const std::filesystem::path& file, const TrappingState* held,
                            const TrappingParameters& wanted) {
  if (!held) return RunFileAction::start;
  if (!(held->params == wanted)) throw std::runtime_error(file.string() + " holds a run of other parameters");
  return held->finished() ? RunFileAction::reuse : RunFileAction::resume;
}

RunFileOutcome runOrResumeFile(const std::filesystem::path& file, const TrappingParameters& params,
                               CheckpointedRunOptions options, const TrappingObserver& progress, std::stop_token stop,
                               std::uint64_t orbitBegin, std::uint64_t orbitEnd) {
  const io::FileLock lock = io::FileLock::acquire(file);
  io::removeStaleTemporaries(file);
  RunFileOutcome outcome;
  std::error_code ec;
  const bool exists = std::filesystem::exists(file, ec);
  if (exists) outcome.state = loadRunFile(file);
  switch (runFileAction(file, exists ? &outcome.state : nullptr, params)) {
    case RunFileAction::reuse:
      outcome.reused = true;
      return outcome;
    case RunFileAction::resume:
      outcome.resumed = true;
      break;
    case RunFileAction::start:
      outcome.state = startTrapping(params, orbitBegin, orbitEnd);
      break;
  }
  options.checkpoint = file;
  LastCheckpoint last{outcome.resumed ? file.string() : std::string(), outcome.state.blocksDone};  // the file read
  outcome.state = runWithCheckpoints(std::move(outcome.state), options, last, progress, stop);
  saveRunFileOrSayWhere(file, outcome.state, last);
  return outcome;
}

}  // namespace archipelago
