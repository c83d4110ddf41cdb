#pragma once
/// \file RunFile.hpp
/// \brief Run files: a versioned JSON document holding a whole TrappingState (docs/design.md, "No silent wrong answer"; issue 3).
///
/// A run file holds the parameters, the integer map coefficients (A, B, C, m) that define the map exactly,
/// the run settings and seed, the subset histograms (integer counts and length sums per bin, with the bin
/// edges), the longest segments with their exact start states, every orbit's state (so that the run can be
/// resumed), timing, the kernel, the program version, and a SHA-256 checksum of all of that.  Integers are written as JSON integers (exact up
/// to 2^64); doubles with 17 significant digits (round-trip exact).
///
/// Writing is atomic: a temporary file in the same folder, fsync, rename over the target, fsync of the
/// folder.  A reader never sees a half-written file, and a crash leaves either the old or the new file.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/run/TrappingRun.hpp"

namespace archipelago {

namespace io {
class JsonField;  // core/io/Json.hpp
}

inline constexpr int kRunFileFormatVersion = 2;  ///< 2: with a checksum; version 1 files are still read
inline constexpr const char* kRunFileFormatName = "archipelago-run";
// kMaxRunFileBytes, the largest run file read: core/trapping/TrappingParameters.hpp (it also bounds M).

/// The JSON text of a run file.  Throws std::runtime_error for an unverified state (read with allowModified).
[[nodiscard]] std::string runFileText(const TrappingState& state);
struct RunFileReadOptions {
  /// Read a file whose checksum does not match its content (an edited file) or that has none (format
  /// version 1), for inspection.  The content is still validated whole, and the state is marked
  /// TrappingState::unverified: it can be analysed but never resumed into, merged into or saved as a
  /// checksummed run file.  Without it such files are refused.
  bool allowModified = false;
  /// How the front end names allowModified ("--allow-modified", Python's "allow_modified=True"), said in the refusal
  /// of an edited file; empty where the front end has no such setting (the GUI, a resume): the refusal then says
  /// nothing of reading it anyway (issue 51: core named a flag of the CLI to every front end).
  std::string allowModifiedName;
};

/// Parses run-file text and validates it whole: structure, parameters, the checksum (format version 2), and
/// the state's consistency (trapping/StateValidation.hpp).  Throws io::BadFile (a std::runtime_error) with a one-line
/// message for corrupt, truncated, edited or inconsistent content, a different format or an unsupported
/// version.
[[nodiscard]] TrappingState parseRunFile(const std::string& text, const RunFileReadOptions& options = {});
/// The same, from a parsed document (a session's embedded run): no second copy of its text.
[[nodiscard]] TrappingState runFileFromJson(nlohmann::json document, const RunFileReadOptions& options = {});

/// Writes atomically (temp file + fsync + rename).  Throws std::runtime_error naming the path on failure.
void saveRunFile(const std::filesystem::path& path, const TrappingState& state);
/// Reads and validates a run file (a regular file of at most kMaxRunFileBytes).  Throws std::runtime_error
/// naming the path on failure (io::BadFile for a file refused for its content).
[[nodiscard]] TrappingState loadRunFile(const std::filesystem::path& path, const RunFileReadOptions& options = {});

/// An orbit's state as run files and tail files write it: orbitStateRow()'s 9 numbers, a JSON array.
[[nodiscard]] nlohmann::json orbitStateJson(const OrbitState& state);
/// The state in the first 9 entries of `row`, an array of at least 9 (tuple() first): whole numbers, X and Y below
/// 2^52 (orbitStateRowMax).  Throws io::BadFile naming the entry.
[[nodiscard]] OrbitState orbitStateFromJson(const io::JsonField& row);

/// The run file of a run's q = 1 companion (issue #26): "k01.json" → "k01.short.json" (`run` writes it beside the
/// run when the spec asks for one; `stats RUN --short` reads it).
[[nodiscard]] std::filesystem::path companionRunFile(const std::filesystem::path& run);

}  // namespace archipelago
