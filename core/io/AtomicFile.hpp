#pragma once
/// \file AtomicFile.hpp
/// \brief Every file core writes or reads whole: atomic replacement, and bounded reads of regular files.
///
/// writeFileAtomically() writes a temporary file in the target's folder, fsyncs it, renames it over the
/// target and fsyncs the folder: a reader never sees a half-written file, and a crash or a full disk leaves
/// either the old file or the new one, never a truncated one.  readRegularFile() refuses what cannot be the
/// file asked for (a folder, a FIFO, a device, a file larger than the caller's bound) before reading a byte,
/// so that a wrong path gives a clear message instead of a hang or an exhausted memory.
///
/// An output path is resolved first (resolveOutputTarget()): a symbolic link is followed, and the file it leads to
/// is replaced atomically (the link stays a link); a character device or a FIFO (/dev/null, /dev/stdout, a pipe) is
/// written through, never renamed over; a folder, a block device or a socket is refused.  The temporary and lock
/// files beside a file of a long name (up to the 255 bytes of a file name) have a short hashed name.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace archipelago::io {

/// What an output path leads to, its symbolic links followed: how the writers of this file write it.
struct OutputTarget {
  enum class Kind {
    File,    ///< a regular file, or none yet: `path` is replaced atomically (a temporary beside it, renamed over it)
    Stream,  ///< a character device or a FIFO (or a link the system alone can follow, /proc/self/fd/N): written through
  };
  Kind kind = Kind::File;
  /// File: the path to replace (the last target of a chain of links, which may not exist yet); Stream: as given.
  std::filesystem::path path;
  bool exists = false;
};

/// Resolves `path` as above.  Throws std::runtime_error naming the path when nothing can be written there: a
/// folder, a block device, a socket, a loop of links.
[[nodiscard]] OutputTarget resolveOutputTarget(const std::filesystem::path& path);

/// Replaces `path` by `content` atomically (mode 0644).  Throws std::runtime_error naming the path and the
/// failing step (open, write, fsync, rename) with the system's reason; the temporary file is removed then.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content);

/// A file written as a stream and published atomically, for outputs too long to hold in memory (a replayed
/// segment's CSV, a PNG): the stream writes a temporary file ".NAME.XXXXXX" in the target's folder; commit()
/// flushes, fsyncs, renames it over the target and fsyncs the folder.  Until commit() readers see the old file
/// (or none); an object destroyed without commit() (an exception, a full disk) removes its temporary, and a
/// process killed before commit() leaves one that removeStaleTemporaries() cleans.  writeFileAtomically() is
/// this class with one write.  A Stream target (resolveOutputTarget()) is written through instead: the stream
/// writes into the device or FIFO, and commit() flushes it and reports a failed write.
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
  /// (write, fsync, rename) with the system's reason; the temporary file is removed then.  While an OutputBatch is
  /// open in this thread, the temporary is written and synced but its rename is left to OutputBatch::commit().
  void commit();

 private:
  class Buffer;
  std::filesystem::path path_;       // as given, for messages
  OutputTarget target_;
  std::string temporary_;            // empty for a Stream target
  std::unique_ptr<Buffer> buffer_;
  std::ostream out_;
  bool committed_ = false;
};

/// The outputs of one command, published together (all or nothing): while an OutputBatch is open in a thread,
/// every AtomicOutputFile::commit() and writeFileAtomically() of that thread writes and syncs its temporary file but
/// does not rename it; commit() then renames them all.  Destroyed without commit() (a later output failed: a full
/// disk, an exception), the batch removes every temporary and no file of the command changes.  (A device or FIFO
/// output is written through when its writer runs: it cannot wait.)  One batch per thread at a time.
class OutputBatch {
 public:
  OutputBatch();
  OutputBatch(const OutputBatch&) = delete;
  OutputBatch& operator=(const OutputBatch&) = delete;
  ~OutputBatch();
  /// Renames every file written since the batch opened over its target, in the order they were written.  Throws
  /// std::runtime_error naming the file whose rename failed; the temporaries not yet renamed are removed then.
  void commit();

 private:
  friend class AtomicOutputFile;
  struct Staged {
    std::string temporary;
    std::filesystem::path target;
  };
  std::vector<Staged> staged_;
  bool done_ = false;
};

/// Checks, before any work starts, that writeFileAtomically(path, …) can succeed: the folder exists and is
/// writable, and the target is neither a folder nor a read-only file (which a rename would silently
/// replace); a device or FIFO must be writable (resolveOutputTarget()).  Throws std::runtime_error naming the
/// path and the reason.  Commands check all their files at once with checkCommandFiles() (io/CommandFiles.hpp).
void checkWritableTarget(const std::filesystem::path& path);

/// Removes the temporary files writeFileAtomically(path, …) leaves when its process is killed mid-write
/// (".NAME.XXXXXX" beside NAME; none for a device or FIFO).  Call it only while holding the FileLock of `path`: no
/// other writer can then be using one.  Returns how many were removed.
std::size_t removeStaleTemporaries(const std::filesystem::path& path);

/// The same for every file of `folder` (a report's figures): call it only while holding a lock that keeps every
/// other writer of that folder away.  Returns how many were removed.
std::size_t removeStaleTemporariesIn(const std::filesystem::path& folder);

/// An advisory lock (flock) that keeps two processes from writing the same file: held on ".NAME.lock" beside
/// NAME (the file a link leads to) from acquire() until destruction; the lock file is removed then.  A device or
/// FIFO is not locked (nothing is replaced there, and no lock file is made beside it, e.g. in /dev).  Released by
/// the kernel when the process dies, even by SIGKILL, so a killed run never blocks the next one.
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
