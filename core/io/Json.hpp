#pragma once
/// \file Json.hpp
/// \brief The one JSON reader of every file core reads (run files, run specs, manifests, sessions, presets).
///
/// Every Archipelago document is shallow (a session embedding a run file nests 6 levels), so a document
/// nested deeper than kMaxJsonDepth is refused by a linear scan of the text before anything is built: no
/// reader ever recurses deeply (nlohmann's dump() and its destructor would, and a 60,000-level array once
/// overflowed the stack of every reader, issue #23), and the cost of reading stays linear in the size.
/// A key repeated within one object is an error (nlohmann keeps the last one silently).
///
/// Memory: the parsed document takes at most kJsonBytesPerTextByte bytes per byte of text (measured on the
/// densest shapes JSON allows: arrays of empty objects and arrays, one-digit numbers, one-key objects, run-file
/// rows; tests/core/io/test_json.cpp).  checkParseMemory() compares that bound with the memory available
/// (core/io/Memory.hpp) before a large file is read, so that a file that cannot be parsed is refused with a
/// reason instead of exhausting the machine.
///
/// Numbers are read by nlohmann's own lexer, which does not depend on the process locale.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/io/NumberText.hpp"  // shortText

namespace archipelago::io {

/// The deepest nesting of arrays and objects a document may have.
inline constexpr int kMaxJsonDepth = 32;

/// An upper bound of the heap a parsed document takes per byte of its text.  nlohmann's values are 16 bytes and
/// an object or array is a separate allocation: "{}," costs 16 + 64 bytes for 3 bytes of text.  Measured worst:
/// 28.3 bytes per byte for an array of empty objects (tests/core/io/test_json.cpp); a run file takes about 2.
inline constexpr std::uintmax_t kJsonBytesPerTextByte = 32;

/// Parses JSON text.  Throws std::invalid_argument with one line: "not valid JSON: <nlohmann's reason with
/// line and column>", "JSON nested deeper than 32 levels (at byte N) …", or "the key 'k' appears twice in one object".
[[nodiscard]] nlohmann::json parseJson(std::string_view text);

/// The value of the "checksum" field of Archipelago's checksummed files (run files, tail files): "sha256:" and the
/// SHA-256 of `content`, the file's object without that field, dumped with an indent of 1.  The one definition the
/// writers sign with and the readers verify against.
[[nodiscard]] std::string jsonChecksum(const nlohmann::json& content);

/// The one rule of a whole number in Archipelago's documents (run files, tail files, sessions, manifests; issue 35:
/// five readers had four rules): a JSON integer ≥ 0, whether nlohmann holds it signed or unsigned, and at most
/// `max`; nothing for a negative integer, a real (even 2.0), a string or any other value.  Each reader words its
/// own error around it (its file's name and field).  Hand-written run specs, which may say 2e7, read their whole
/// numbers by their own documented rule (core/runspec/RunSpec.cpp).
[[nodiscard]] std::optional<std::uint64_t> wholeJson(const nlohmann::json& value,
                                                     std::uint64_t max = UINT64_MAX) noexcept;

/// A short description of a value for an error message: a number, bool or null as JSON, a string quoted and
/// cut at 40 characters, otherwise "an array of N entries" / "an object of N keys".  Never long, never deep.
[[nodiscard]] std::string describeJson(const nlohmann::json& value);

/// Reads and parses the JSON file `path` (io::readRegularFile: a regular file of at most maxBytes), after
/// checkParseMemory() on its size.  Throws std::runtime_error naming the path for a file that cannot be read or
/// parsed in the memory available, std::invalid_argument (parseJson's message, without the path) for bad JSON.
[[nodiscard]] nlohmann::json loadJsonFile(const std::filesystem::path& path, std::uintmax_t maxBytes);

/// Throws std::runtime_error naming `what` when parsing `textBytes` bytes of JSON could need more memory than
/// the machine has available (MemAvailable of /proc/meminfo, and the address-space limit RLIMIT_AS).
void checkParseMemory(std::uintmax_t textBytes, const std::string& what);

}  // namespace archipelago::io
