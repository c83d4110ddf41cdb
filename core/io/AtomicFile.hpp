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
#include <string>
#include <string_view>

namespace archipelago::io {

/// Replaces `path` by `content` atomically (mode 0644).  Throws std::runtime_error naming the path and the
/// failing step (open, write, fsync, rename) with the system's reason; the temporary file is removed then.
void writeFileAtomically(const std::filesystem::path& path, std::string_view content);

/// The whole content of the regular file `path`, of at most maxBytes bytes.  Throws std::runtime_error
/// naming the path: missing or unreadable, not a regular file (saying what it is), or larger than maxBytes.
[[nodiscard]] std::string readRegularFile(const std::filesystem::path& path, std::uintmax_t maxBytes);

}  // namespace archipelago::io
