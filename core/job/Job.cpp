#include "core/job/Job.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "core/io/NumberText.hpp"

namespace archipelago {

std::optional<std::string> checkpointIntervalError(std::string_view name, double seconds) {
  if (seconds >= 0) return std::nullopt;  // NaN is refused too
  return std::string(name) + " = " + io::shortestText(seconds) + " must be a number of seconds >= 0";
}

bool CheckpointClock::due() {
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - last_).count() < seconds_) return false;
  last_ = now;
  return true;
}

void writeCheckpoint(const std::function<void()>& write, const std::string& path, std::uint64_t blocks,
                     LastCheckpoint& last, double retrySeconds,
                     const std::function<void(const std::string& reason, double retrySeconds)>& warning) {
  try {
    write();
    last = {path, blocks};
  } catch (const std::exception& e) {
    if (warning) warning(e.what(), retrySeconds);
  }
}

std::vector<io::FileLock> lockJobFiles(const std::string& out, const std::string& checkpoint, const std::string& resume) {
  std::vector<io::FileLock> locks;
  std::vector<std::filesystem::path> held;
  const std::filesystem::path resumeFolder = std::filesystem::path(resume).parent_path();
  const bool lockResume = !resume.empty() && ::access(resumeFolder.empty() ? "." : resumeFolder.c_str(), W_OK) == 0;
  for (const std::string& path : {out, checkpoint, lockResume ? resume : std::string()}) {
    if (path.empty()) continue;
    std::error_code ec;  // a link the system alone can follow (/proc/self/fd/1 of a pipe) has no canonical path
    std::filesystem::path same = std::filesystem::weakly_canonical(path, ec);  // one lock per file, however named
    if (ec) same = path;
    if (std::find(held.begin(), held.end(), same) != held.end()) continue;
    locks.push_back(io::FileLock::acquire(path));
    held.push_back(same);
    io::removeStaleTemporaries(path);
  }
  return locks;
}

std::vector<std::filesystem::path> rescueFolders() {
  std::vector<std::filesystem::path> folders;
  const char* tmp = std::getenv("TMPDIR");
  folders.emplace_back(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp");
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') folders.emplace_back(home);
  return folders;
}

void saveOrRescue(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& save,
                  const std::string& noun, const std::string& amount, const std::string& kept) {
  try {
    save(path);
  } catch (const std::exception& e) {
    // The work must not be lost to a full disk or a vanished folder (issue #23): it goes to the temporary folder
    // or the home folder instead, and the error says where.
    std::string tried;
    for (const std::filesystem::path& folder : rescueFolders()) {
      const std::filesystem::path rescue =
          folder / (path.filename().string() + ".rescued-" + std::to_string(::getpid()) + ".json");
      try {
        save(rescue);
      } catch (const std::exception&) {
        tried += (tried.empty() ? "" : ", ") + folder.string();
        continue;
      }
      throw std::runtime_error(std::string(e.what()) + "; the " + noun + amount + " was saved instead to " +
                               rescue.string());
    }
    const std::string where = !kept.empty() ? kept
        : "no checkpoint was written" + (tried.empty() ? std::string() : " and the " + noun + " could not be saved in " + tried);
    throw std::runtime_error(std::string(e.what()) + "; " + where);
  }
}

}  // namespace archipelago
