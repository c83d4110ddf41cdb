#include "core/runfile/CheckpointedRun.hpp"

#include "core/io/NumberText.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "core/io/AtomicFile.hpp"
#include "core/runfile/RunFile.hpp"

namespace archipelago {

namespace {
/// Where a run goes when its own file cannot be written: the temporary folder, then the home folder.
std::vector<std::filesystem::path> rescueFolders() {
  std::vector<std::filesystem::path> folders;
  const char* tmp = std::getenv("TMPDIR");
  folders.emplace_back(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp");
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') folders.emplace_back(home);
  return folders;
}
}  // namespace

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
    // The work must not be lost to a full disk or a vanished folder (issue #23): it goes to the temporary folder
    // or the home folder instead, and the error says where.
    std::string tried;
    for (const std::filesystem::path& folder : rescueFolders()) {
      const std::filesystem::path rescue =
          folder / (path.filename().string() + ".rescued-" + std::to_string(::getpid()) + ".json");
      try {
        saveRunFile(rescue, state);
      } catch (const std::exception&) {
        tried += (tried.empty() ? "" : ", ") + folder.string();
        continue;
      }
      throw std::runtime_error(std::string(e.what()) + "; the run (" + std::to_string(state.blocksDone) + " of " +
                               std::to_string(state.params.T) + " blocks) was saved instead to " + rescue.string());
    }
    const std::string kept = last.path.empty()
        ? "no checkpoint was written" + (tried.empty() ? std::string() : " and the run could not be saved in " + tried)
        : "the last checkpoint (" + std::to_string(last.blocks) + " of " + std::to_string(state.params.T) +
              " blocks) is in " + last.path + howToResume;
    throw std::runtime_error(std::string(e.what()) + "; " + kept);
  }
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

std::optional<std::string> checkpointIntervalError(std::string_view name, double seconds) {
  if (seconds >= 0) return std::nullopt;  // NaN is refused too
  return std::string(name) + " = " + io::shortestText(seconds) + " must be a number of seconds >= 0";
}

}  // namespace archipelago
