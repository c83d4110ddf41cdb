#include "core/io/AtomicFile.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace archipelago::io {

namespace {
bool isReadOnly(const std::filesystem::file_status& status) {
  using std::filesystem::perms;
  return std::filesystem::exists(status) &&
         (status.permissions() & (perms::owner_write | perms::group_write | perms::others_write)) == perms::none;
}
}  // namespace

AtomicOutputFile::AtomicOutputFile(std::filesystem::path path) : path_(std::move(path)) {
  const std::filesystem::path dir = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  if (isReadOnly(std::filesystem::status(path_, ec)))  // protected on purpose: a rename would replace it
    throw std::runtime_error("cannot write " + path_.string() + ": the file is read-only");
  temporary_ = (dir / ("." + path_.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkstemp(temporary_.data());
  if (fd < 0) throw std::runtime_error("cannot write " + path_.string() + ": " + std::strerror(errno));
  ::close(fd);
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    const std::string reason = std::strerror(errno);
    ::unlink(temporary_.c_str());
    throw std::runtime_error("cannot write " + path_.string() + ": " + reason);
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  if (committed_) return;
  out_.close();
  ::unlink(temporary_.c_str());
}

void AtomicOutputFile::commit() {
  if (committed_) throw std::logic_error("AtomicOutputFile::commit called twice for " + path_.string());
  auto fail = [&](const char* what, int error) {
    out_.close();
    ::unlink(temporary_.c_str());
    committed_ = true;  // nothing left for the destructor
    throw std::runtime_error(std::string("cannot write ") + path_.string() + " (" + what + "): " +
                             (error != 0 ? std::strerror(error) : "the disk may be full"));
  };
  errno = 0;
  out_.flush();
  if (!out_) fail("write", errno);
  out_.close();
  if (!out_) fail("write", errno);
  const int fd = ::open(temporary_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) fail("open", errno);
  if (::fchmod(fd, 0644) != 0 || ::fsync(fd) != 0) {
    const int error = errno;
    ::close(fd);
    fail("fsync", error);
  }
  ::close(fd);
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) fail("rename", errno);
  committed_ = true;
  const std::filesystem::path dir = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (dfd >= 0) {  // make the rename itself durable
    ::fsync(dfd);
    ::close(dfd);
  }
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view content) {
  AtomicOutputFile file(path);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

void checkWritableTarget(const std::filesystem::path& path) {
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  const auto dirStatus = std::filesystem::status(dir, ec);
  if (!std::filesystem::exists(dirStatus))
    throw std::runtime_error("cannot write " + path.string() + ": the folder " + dir.string() + " does not exist");
  if (!std::filesystem::is_directory(dirStatus))
    throw std::runtime_error("cannot write " + path.string() + ": " + dir.string() + " is not a folder");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw std::runtime_error("cannot write " + path.string() + ": the folder " + dir.string() + " is not writable (" +
                             std::strerror(errno) + ")");
  const auto status = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(status))
    throw std::runtime_error("cannot write " + path.string() + ": it is a folder");
  // A file nobody may write (mode 0444) was protected on purpose: refuse it even where the rename would
  // succeed (the folder is writable, or we are root).
  if (isReadOnly(status) || (std::filesystem::exists(status) && ::access(path.c_str(), W_OK) != 0))
    throw std::runtime_error("cannot write " + path.string() + ": the file is read-only");
}

std::size_t removeStaleTemporaries(const std::filesystem::path& path) {
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::string prefix = "." + path.filename().string() + ".";
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    // mkstemp's suffix: exactly six characters after the prefix (".lock" is the lock, not a temporary).
    if (name.size() != prefix.size() + 6 || name.compare(0, prefix.size(), prefix) != 0 || !entry.is_regular_file(ec))
      continue;
    if (std::filesystem::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

std::size_t removeStaleTemporariesIn(const std::filesystem::path& folder) {
  std::size_t removed = 0;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    // ".NAME.XXXXXX": a dot, a name, a dot and mkstemp's six characters (not ".NAME.lock").
    if (name.size() < 9 || name[0] != '.' || name[name.size() - 7] != '.' || !entry.is_regular_file(ec)) continue;
    const std::string suffix = name.substr(name.size() - 6);
    if (suffix.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789") !=
                                std::string::npos)
      continue;
    if (std::filesystem::remove(entry.path(), ec)) ++removed;
  }
  return removed;
}

FileLock FileLock::acquire(const std::filesystem::path& path) {
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::filesystem::path lockPath = dir / ("." + path.filename().string() + ".lock");
  for (;;) {
    const int fd = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw std::runtime_error("cannot lock " + path.string() + ": " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd);
      if (error == EWOULDBLOCK)
        throw std::runtime_error(path.string() + " is in use by another process (its lock " + lockPath.string() +
                                 " is held); two runs must not write the same file");
      throw std::runtime_error("cannot lock " + path.string() + ": " + std::strerror(error));
    }
    // The holder before us may have removed the lock file between our open and our flock: then we hold a
    // lock on a file nobody else can find, and must try again on the current one.
    struct stat held {}, current {};
    if (::fstat(fd, &held) == 0 && ::stat(lockPath.c_str(), &current) == 0 && held.st_ino == current.st_ino &&
        held.st_dev == current.st_dev)
      return FileLock(fd, lockPath);
    ::close(fd);
  }
}

FileLock::FileLock(FileLock&& other) noexcept : fd_(other.fd_), lockPath_(std::move(other.lockPath_)) { other.fd_ = -1; }

FileLock& FileLock::operator=(FileLock&& other) noexcept {
  if (this != &other) {
    release();
    fd_ = other.fd_;
    lockPath_ = std::move(other.lockPath_);
    other.fd_ = -1;
  }
  return *this;
}

FileLock::~FileLock() { release(); }

void FileLock::release() noexcept {
  if (fd_ < 0) return;
  ::unlink(lockPath_.c_str());  // while still held: a process that opened it before retries (see acquire)
  ::close(fd_);
  fd_ = -1;
}

std::string readRegularFile(const std::filesystem::path& path, std::uintmax_t maxBytes) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then says what was opened.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("cannot read " + path.string() + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    throw std::runtime_error("cannot read " + path.string() + ": " + reason);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    const char* kind = S_ISDIR(st.st_mode) ? "a folder" : S_ISFIFO(st.st_mode) ? "a FIFO" :
                       S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device" : S_ISSOCK(st.st_mode) ? "a socket" : "not a regular file";
    throw std::runtime_error("cannot read " + path.string() + ": it is " + kind + ", not a regular file");
  }
  if (static_cast<std::uintmax_t>(st.st_size) > maxBytes) {
    ::close(fd);
    throw std::runtime_error("cannot read " + path.string() + ": " + std::to_string(st.st_size) +
                             " bytes, more than the " + std::to_string(maxBytes) + " such a file can hold");
  }
  std::string content(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t got = 0;
  while (got < content.size()) {
    const ssize_t n = ::read(fd, content.data() + got, content.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const std::string reason = std::strerror(errno);
      ::close(fd);
      throw std::runtime_error("cannot read " + path.string() + ": " + reason);
    }
    if (n == 0) break;  // the file shrank while read: what was read is parsed (and found truncated)
    got += static_cast<std::size_t>(n);
  }
  content.resize(got);
  ::close(fd);
  return content;
}

}  // namespace archipelago::io
