#include "core/runfile/CheckpointedRun.hpp"

#include <chrono>
#include <stdexcept>

#include "core/runfile/RunFile.hpp"

namespace archipelago {

TrappingState runWithCheckpoints(TrappingState state, const CheckpointedRunOptions& options, LastCheckpoint& last,
                                 const TrappingObserver& progress, std::stop_token stop) {
  std::stop_source stopper;
  std::stop_callback forward(stop, [&] { stopper.request_stop(); });
  auto lastCheckpointTime = std::chrono::steady_clock::now();
  auto observer = [&](const TrappingState& s, const TrappingProgress& p) {
    if (options.stopRequested && options.stopRequested()) stopper.request_stop();
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - lastCheckpointTime).count() >= options.checkpointSeconds && !s.finished()) {
      lastCheckpointTime = now;  // a failed write is retried at the next interval, not at every chunk
      try {
        saveRunFile(options.checkpoint, s);
        last = {options.checkpoint.string(), s.blocksDone};
      } catch (const std::exception& e) {
        if (options.warning) options.warning(e.what(), options.checkpointSeconds);
      }
    }
    if (progress) progress(s, p);
  };
  return runTrapping(std::move(state), options.run, observer, stopper.get_token());
}

void saveRunFileOrSayWhere(const std::filesystem::path& path, const TrappingState& state, const LastCheckpoint& last,
                           const std::string& howToResume) {
  try {
    saveRunFile(path, state);
  } catch (const std::exception& e) {
    const std::string kept = last.path.empty()
        ? std::string("no checkpoint was written")
        : "the last checkpoint (" + std::to_string(last.blocks) + " of " + std::to_string(state.params.T) +
              " blocks) is in " + last.path + howToResume;
    throw std::runtime_error(std::string(e.what()) + "; " + kept);
  }
}

}  // namespace archipelago
