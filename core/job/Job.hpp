#pragma once
/// \file Job.hpp
/// \brief What every long computation of core shares (issue 51, "one kind of job"): the time between checkpoints
/// and its rule, the clock that says when one is due (a failed write is retried at the next interval, never at every
/// chunk), where the last good copy of the work is, and the final write that rescues the work when its own file
/// cannot be written.  A job stops through one mechanism, the std::stop_token it is given (each program turns
/// Ctrl-C/SIGTERM into that token in one place).  The trapping run (runfile/CheckpointedRun.hpp) and the tail
/// sampler (tail/TailJob.hpp) are built on these pieces.
///
/// Core names files and quantities by their role in its messages; how to resume (an option, a button) is the front
/// end's, so the final write takes that text from its caller.

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/AtomicFile.hpp"

namespace archipelago {

/// Where the last good copy of a job's work is (the file resumed from, until a checkpoint is written).
struct LastCheckpoint {
  std::string path;          ///< empty: none was written and none was resumed from
  std::uint64_t blocks = 0;  ///< a run's blocks done at it (a trapping run's count; 0 for other jobs)
};

/// The rule of a time between checkpoints (run, scan, tail and archipelago-mpi): "<name> = <s> must be a number of
/// seconds >= 0" (0: at every chunk), or nothing.  `name` is the front end's name of the setting.
[[nodiscard]] std::optional<std::string> checkpointIntervalError(std::string_view name, double seconds);

/// When a checkpoint is due: `seconds` after the last attempt, written or not (a failed write is retried at the
/// next interval, not at every chunk).  The first is due `seconds` after construction.
class CheckpointClock {
public:
  explicit CheckpointClock(double seconds) : seconds_(seconds), last_(std::chrono::steady_clock::now()) {}
  /// True when `seconds` have passed since the last attempt; the attempt is then counted as made now.
  [[nodiscard]] bool due();
  [[nodiscard]] double seconds() const noexcept { return seconds_; }

private:
  double seconds_;
  std::chrono::steady_clock::time_point last_;
};

/// One checkpoint attempt: `write()`; on success `last` becomes `path` (with `blocks`), on failure `warning` (when
/// given) receives the reason and the seconds until the next attempt, and the job goes on.
void writeCheckpoint(const std::function<void()>& write, const std::string& path, std::uint64_t blocks,
                     LastCheckpoint& last, double retrySeconds,
                     const std::function<void(const std::string& reason, double retrySeconds)>& warning);

/// The final write of a job: `save(path)`.  When that fails (a full disk, a vanished folder) the work is saved with
/// `save` to "<temporary folder>/NAME.rescued-PID.json" or, failing that, to the same name in $HOME, and a
/// std::runtime_error says "<the failure>; the <noun><amount> was saved instead to <rescue>" (amount: e.g.
/// " (20000 of 20000 blocks)", or empty).  When that fails too, the error says where the work done so far is:
/// "<the failure>; <kept>" (e.g. where the last checkpoint is), or, with `kept` empty, "<the failure>; no checkpoint
/// was written and the <noun> could not be saved in <the folders tried>".
void saveOrRescue(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& save,
                  const std::string& noun, const std::string& amount, const std::string& kept);

/// A job's files, locked for the whole job (issue #12, finding 7): a second process on the same output, checkpoint
/// or resumed file is refused before it reads or writes anything, and the temporaries a killed writer left beside
/// them are removed once the lock is held.  The resumed file is locked too (resuming the checkpoint of a live job
/// would fork it), unless its folder is read-only.  Empty paths are skipped; a file named twice is locked once.
[[nodiscard]] std::vector<io::FileLock> lockJobFiles(const std::string& out, const std::string& checkpoint,
                                                     const std::string& resume);

/// The rescue folders tried by saveOrRescue(), in order: $TMPDIR (else /tmp), then $HOME when set.
[[nodiscard]] std::vector<std::filesystem::path> rescueFolders();

}  // namespace archipelago
