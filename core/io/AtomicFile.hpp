#pragma once
/// \file AtomicFile.hpp
/// \brief Every file core writes or reads whole: atomic replacement, and bounded reads of regular files.
///
/// writeFileAtomically() writes a temporary file in the target's folder, fsyncs it, renames it over the
/// target and fsyncs the folder: a reader never sees a half-written file, and a crash or a full disk leaves
/// either the old file or the new one, never a truncated one.  readRegularFile() refuses what cannot be the
/// file asked for (a folder, a FIFO, a device, a file larger than the caller's bound) before reading a byte,
/// so that a wrong path gives a clear message instead of a hang or an exhausted memory.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>

namespace archipelago::io {

/// Replaces `path` by `content` atomically (mode 0644).  Throws std::runtime_error naming the path and the
/// failing step (open, write, fsync, rename) with the system's reason; the temporary file is removed then.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content);

/// A file written as a stream and published atomically, for outputs too long to hold in memory (a replayed
/// segment's CSV, a PNG): the stream writes a temporary file ".NAME.XXXXXX" in the target's folder; commit()
/// flushes, fsyncs, renames it over the target and fsyncs the folder.  Until commit() readers see the old file
/// (or none); an object destroyed without commit() (an exception, a full disk) removes its temporary, and a
/// process killed before commit() leaves one that removeStaleTemporaries() cleans.  writeFileAtomically() is
/// this class with one write.
class AtomicOutputFile {
 public:
  /// Opens the temporary file.  Throws std::runtime_error naming `path` when it cannot, or when `path` is a
  /// read-only file (a rename would silently replace it).
  explicit AtomicOutputFile(std::filesystem::path path);
  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;
  /// Without commit(): removes the temporary file; the target is untouched.
  ~AtomicOutputFile();

  /// The stream to write to (binary: bytes are written as given).
  [[nodiscard]] std::ostream& stream() noexcept { return out_; }
  /// Publishes what was written (mode 0644).  Throws std::runtime_error naming the path and the failing step
  /// (write, fsync, rename) with the system's reason; the temporary file is removed then.
  void commit();

 private:
  std::filesystem::path path_;
  std::string temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

/// Checks, before any work starts, that writeFileAtomically(path, …) can succeed: the folder exists and is
/// writable, and the target is neither a folder nor a read-only file (which a rename would silently
/// replace).  Throws std::runtime_error naming the path and the reason.
void checkWritableTarget(const std::filesystem::path& path);

/// Removes the temporary files writeFileAtomically(path, …) leaves when its process is killed mid-write
/// (".NAME.XXXXXX" beside NAME).  Call it only while holding the FileLock of `path`: no other writer can
/// then be using one.  Returns how many were removed.
std::size_t removeStaleTemporaries(const std::filesystem::path& path);

/// The same for every file of `folder` (a report's figures): call it only while holding a lock that keeps every
/// other writer of that folder away.  Returns how many were removed.
std::size_t removeStaleTemporariesIn(const std::filesystem::path& folder);

/// An advisory lock (flock) that keeps two processes from writing the same file: held on ".NAME.lock" beside
/// NAME from acquire() until destruction; the lock file is removed then.  Released by the kernel when the
/// process dies, even by SIGKILL, so a killed run never blocks the next one.
class FileLock {
 public:
  /// Takes the lock of `path` or throws std::runtime_error naming the path ("in use by another process").
  [[nodiscard]] static FileLock acquire(const std::filesystem::path& path);
  FileLock(FileLock&& other) noexcept;
  FileLock& operator=(FileLock&& other) noexcept;
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock();

 private:
  FileLock(int fd, std::filesystem::path lockPath) noexcept : fd_(fd), lockPath_(std::move(lockPath)) {}
  void release() noexcept;
  int fd_ = -1;
  std::filesystem::path lockPath_;
};

/// The whole content of the regular file `path`, of at most maxBytes bytes.  Throws std::runtime_error
/// naming the path: missing or unreadable, not a regular file (saying what it is), or larger than maxBytes.
[[nodiscard]] std::string readRegularFile(const std::filesystem::path& path, std::uintmax_t maxBytes);

}  // namespace archipelago::io
