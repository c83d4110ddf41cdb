#include "core/io/AtomicFile.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <streambuf>
#include <vector>

#include "core/io/Sha256.hpp"

namespace archipelago::io {

namespace {
bool isReadOnly(const std::filesystem::file_status& status) {
  using std::filesystem::perms;
  return std::filesystem::exists(status) &&
         (status.permissions() & (perms::owner_write | perms::group_write | perms::others_write)) == perms::none;
}

std::filesystem::path folderOf(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

/// ".NAME." before a temporary's six characters or "lock": a NAME too long for that within a file name's 255 bytes
/// (NAME_MAX of Linux' file systems) is cut and given a hash of the whole, so that each name keeps its own.
std::string siblingPrefix(const std::filesystem::path& target) {
  constexpr std::size_t kNameMax = 255, kSuffix = 6, kKept = 200;
  const std::string name = target.filename().string();
  if (1 + name.size() + 1 + kSuffix <= kNameMax) return "." + name + ".";
  return "." + name.substr(0, kKept) + "~" + sha256Hex(name).substr(0, 16) + ".";
}

[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& why) {
  throw std::runtime_error("cannot write " + path.string() + ": " + why);
}

/// Writes all of [data, data + size) to `fd`; false (and errno) on failure.
bool writeAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return false;
    if (n == 0) {
      errno = EIO;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

/// The batch open in this thread, if any (OutputBatch).
thread_local OutputBatch* gBatch = nullptr;

void syncFolder(const std::filesystem::path& file) {
  const int dfd = ::open(folderOf(file).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {  // make the rename itself durable
    ::fsync(dfd);
    ::close(dfd);
  }
}
}  // namespace

OutputTarget resolveOutputTarget(const std::filesystem::path& path) {
  OutputTarget t;
  t.path = path;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {  // follows the links, the system's own (/proc/self/fd/N) too
    t.exists = true;
    if (S_ISDIR(st.st_mode)) refuse(path, "it is a folder");
    if (S_ISBLK(st.st_mode)) refuse(path, "it is a block device (write to a file)");
    if (S_ISSOCK(st.st_mode)) refuse(path, "it is a socket");
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
      t.kind = OutputTarget::Kind::Stream;
      return t;
    }
    struct stat link {};
    if (::lstat(path.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) return t;  // a regular file
    // A link to a regular file: the file it leads to is replaced, not the link.  A link whose text is no path to
    // that file (/proc/self/fd/1 of a deleted file) is written through.
    char* real = ::realpath(path.c_str(), nullptr);
    struct stat resolved {};
    if (real != nullptr && ::stat(real, &resolved) == 0 && resolved.st_dev == st.st_dev && resolved.st_ino == st.st_ino)
      t.path = real;
    else
      t.kind = OutputTarget::Kind::Stream;
    std::free(real);
    return t;
  }
  if (errno == ELOOP) refuse(path, "its symbolic links make a loop");
  // Missing: a dangling link is followed to the file it names, which is then created.
  std::filesystem::path p = path;
  for (int depth = 0; depth < 40; ++depth) {
    struct stat link {};
    if (::lstat(p.c_str(), &link) != 0 || !S_ISLNK(link.st_mode)) {
      t.path = p;
      return t;
    }
    std::error_code ec;
    const std::filesystem::path next = std::filesystem::read_symlink(p, ec);
    if (ec) refuse(path, ec.message());
    p = next.is_absolute() ? next : folderOf(p) / next;
  }
  refuse(path, "its symbolic links make a loop");
}

class AtomicOutputFile::Buffer : public std::streambuf {
 public:
  explicit Buffer(int fd) : fd_(fd), data_(std::size_t{1} << 16) { setp(data_.data(), data_.data() + data_.size()); }
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  ~Buffer() override { close(); }
  /// Writes what is buffered; false (and error()) once any write failed.
  bool drain() {
    if (error_ == 0 && pptr() > pbase() && !writeAll(fd_, pbase(), static_cast<std::size_t>(pptr() - pbase())))
      error_ = errno;
    setp(data_.data(), data_.data() + data_.size());
    return error_ == 0;
  }
  [[nodiscard]] int fd() const noexcept { return fd_; }
  [[nodiscard]] int error() const noexcept { return error_; }
  /// Closes the file; false (and error()) when the close reports a failed write.
  bool close() {
    if (fd_ < 0) return error_ == 0;
    if (::close(fd_) != 0 && error_ == 0 && errno != EINTR) error_ = errno;
    fd_ = -1;
    return error_ == 0;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    if (n <= epptr() - pptr()) {
      traits_type::copy(pptr(), s, static_cast<std::size_t>(n));
      pbump(static_cast<int>(n));
      return n;
    }
    if (!drain()) return 0;
    if (!writeAll(fd_, s, static_cast<std::size_t>(n))) {
      error_ = errno;
      return 0;
    }
    return n;
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  int fd_;
  std::vector<char> data_;
  int error_ = 0;
};

AtomicOutputFile::AtomicOutputFile(std::filesystem::path path)
    : path_(std::move(path)), target_(resolveOutputTarget(path_)), out_(nullptr) {
  int fd = -1;
  if (target_.kind == OutputTarget::Kind::Stream) {
    // Written through: a device or FIFO is never replaced by a file.  (Opening a FIFO waits for its reader.)
    fd = ::open(target_.path.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd < 0) refuse(path_, std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && ::ftruncate(fd, 0) != 0) {
      const std::string reason = std::strerror(errno);
      ::close(fd);
      refuse(path_, reason);
    }
  } else {
    std::error_code ec;
    if (isReadOnly(std::filesystem::status(target_.path, ec)))  // protected on purpose: a rename would replace it
      refuse(path_, "the file is read-only");
    temporary_ = (folderOf(target_.path) / (siblingPrefix(target_.path) + "XXXXXX")).string();
    fd = ::mkstemp(temporary_.data());
    if (fd < 0) refuse(path_, std::strerror(errno));
    ::fcntl(fd, F_SETFD, FD_CLOEXEC);
  }
  buffer_ = std::make_unique<Buffer>(fd);
  out_.rdbuf(buffer_.get());
}

AtomicOutputFile::~AtomicOutputFile() {
  if (committed_) return;
  buffer_->close();
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
}

void AtomicOutputFile::commit() {
  if (committed_) throw std::logic_error("AtomicOutputFile::commit called twice for " + path_.string());
  auto fail = [&](const char* what, int error) {
    buffer_->close();
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
    committed_ = true;  // nothing left for the destructor
    throw std::runtime_error(std::string("cannot write ") + path_.string() + " (" + what + "): " +
                             (error != 0 ? std::strerror(error) : "the disk may be full"));
  };
  if (!buffer_->drain() || !out_) fail("write", buffer_->error());
  if (temporary_.empty()) {  // written through
    if (!buffer_->close()) fail("write", buffer_->error());
    committed_ = true;
    return;
  }
  if (::fchmod(buffer_->fd(), 0644) != 0 || ::fsync(buffer_->fd()) != 0) fail("fsync", errno);
  if (!buffer_->close()) fail("write", buffer_->error());
  if (gBatch != nullptr) {  // published with the command's other outputs
    gBatch->staged_.push_back({temporary_, target_.path});
    committed_ = true;
    return;
  }
  if (::rename(temporary_.c_str(), target_.path.c_str()) != 0) fail("rename", errno);
  committed_ = true;
  syncFolder(target_.path);
}

void writeFileAtomically(const std::filesystem::path& path, std::string_view content) {
  AtomicOutputFile file(path);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

OutputBatch::OutputBatch() {
  if (gBatch != nullptr) throw std::logic_error("an OutputBatch is already open in this thread");
  gBatch = this;
}

OutputBatch::~OutputBatch() {
  if (gBatch == this) gBatch = nullptr;
  if (done_) return;
  for (const Staged& s : staged_) ::unlink(s.temporary.c_str());
}

void OutputBatch::commit() {
  if (done_) throw std::logic_error("OutputBatch::commit called twice");
  gBatch = nullptr;
  done_ = true;
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    if (::rename(staged_[i].temporary.c_str(), staged_[i].target.c_str()) != 0) {
      const std::string reason = std::strerror(errno);
      for (std::size_t j = i; j < staged_.size(); ++j) ::unlink(staged_[j].temporary.c_str());
      std::string published;
      for (std::size_t j = 0; j < i; ++j) published += (published.empty() ? "" : ", ") + staged_[j].target.string();
      throw std::runtime_error("cannot write " + staged_[i].target.string() + " (rename): " + reason +
                               (published.empty() ? "" : " (already written: " + published + ")"));
    }
    syncFolder(staged_[i].target);
  }
}

void checkWritableTarget(const std::filesystem::path& given) {
  const OutputTarget target = resolveOutputTarget(given);
  if (target.kind == OutputTarget::Kind::Stream) {
    if (::access(given.c_str(), W_OK) != 0) refuse(given, std::string("not writable (") + std::strerror(errno) + ")");
    return;
  }
  const std::filesystem::path& path = target.path;
  const std::filesystem::path dir = folderOf(path);
  const std::string via = path == given ? "" : " (where the link " + given.string() + " leads)";
  std::error_code ec;
  const auto dirStatus = std::filesystem::status(dir, ec);
  if (!std::filesystem::exists(dirStatus)) refuse(given, "the folder " + dir.string() + via + " does not exist");
  if (!std::filesystem::is_directory(dirStatus)) refuse(given, dir.string() + via + " is not a folder");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    refuse(given, "the folder " + dir.string() + via + " is not writable (" + std::strerror(errno) + ")");
  // A name longer than the folder's file system takes fails only when the file is written, after the command's work
  // and its other outputs (issue 54, item 8: `tail --csv` with a 259-byte name failed at the end): say so now.
  const std::string name = path.filename().string();
  const long nameMax = ::pathconf(dir.c_str(), _PC_NAME_MAX);
  if (nameMax > 0 && name.size() > static_cast<std::size_t>(nameMax))
    refuse(given, "its name is " + std::to_string(name.size()) + " bytes, longer than the folder's file system takes (" +
                      std::to_string(nameMax) + ")");
  const auto status = std::filesystem::status(path, ec);
  // A file nobody may write (mode 0444) was protected on purpose: refuse it even where the rename would
  // succeed (the folder is writable, or we are root).
  if (isReadOnly(status) || (std::filesystem::exists(status) && ::access(path.c_str(), W_OK) != 0))
    refuse(given, "the file is read-only");
}

std::size_t removeStaleTemporaries(const std::filesystem::path& given) {
  std::error_code ec;
  OutputTarget target;
  try {
    target = resolveOutputTarget(given);
  } catch (const std::runtime_error&) {
    return 0;  // nothing can have been written there
  }
  if (target.kind == OutputTarget::Kind::Stream) return 0;
  const std::string prefix = siblingPrefix(target.path);
  std::size_t removed = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folderOf(target.path), ec)) {
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
  const OutputTarget target = resolveOutputTarget(path);
  if (target.kind == OutputTarget::Kind::Stream) return FileLock(-1, {});  // nothing is replaced there
  const std::filesystem::path lockPath = folderOf(target.path) / (siblingPrefix(target.path) + "lock");
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
