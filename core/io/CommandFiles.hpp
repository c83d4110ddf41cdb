#pragma once
/// \file CommandFiles.hpp
/// \brief The one output-path policy of every command that writes files (issue 36, class 3): before any work,
/// the files a command names are checked together, so that no output overwrites another output or an input.
///
/// A file is known by what it is, not by how it is spelt: its device and inode when it exists, else the path its
/// links lead to in a resolved folder ("./a.json", "a.json" and a link to it are one file).  A device or FIFO
/// (/dev/null, /dev/stdout) is written through and replaces nothing: it may be named more than once.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace archipelago::io {

/// What a command does with a file it names.
enum class FileUse {
  Input,        ///< read, never written; an input named twice would be counted twice
  Output,       ///< written; checked writable before the work (checkWritableTarget())
  ResumedState, ///< read as the state of a resumable run (--resume): the run may write its state back there
  SavedState,   ///< written as the state of a resumable run (--out, --checkpoint): checked writable
};

/// One file of a command: the option that names it (as errors show it: "--out", "--compare", "the sidecar of
/// --npy"), its path (empty: the option was not given, and the entry is skipped) and its use.
struct CommandFile {
  std::string option;
  std::filesystem::path path;
  FileUse use = FileUse::Input;
};

/// The first rule the files break, as one line for "ERROR: ", or nothing: an output that cannot be written; two
/// outputs that are one file; an output that is an input; an input named twice.  The files of one run's state
/// (ResumedState, SavedState) may be one file: a run continues in its checkpoint.
[[nodiscard]] std::optional<std::string> commandFilesError(const std::vector<CommandFile>& files);

/// commandFilesError() as a std::invalid_argument.
void checkCommandFiles(const std::vector<CommandFile>& files);

}  // namespace archipelago::io
