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
///
/// Every reader of a document (run files, tail files, run specs, sessions, manifests, atlases) refuses a bad one
/// with one exception type, BadFile, and reads its fields with one reader, JsonField: one wording of each kind of
/// field (a whole number, a real, a string, a bool, an object, an array), the field named by its path.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/io/BadFile.hpp"
#include "core/io/NumberText.hpp"  // shortText

namespace archipelago::io {

/// The deepest nesting of arrays and objects a document may have.
inline constexpr int kMaxJsonDepth = 32;

/// An upper bound of the heap a parsed document takes per byte of its text.  nlohmann's values are 16 bytes and
/// an object or array is a separate allocation: "{}," costs 16 + 64 bytes for 3 bytes of text.  Measured worst:
/// 28.3 bytes per byte for an array of empty objects (tests/core/io/test_json.cpp); a run file takes about 2.
inline constexpr std::uintmax_t kJsonBytesPerTextByte = 32;

/// Parses JSON text.  Throws BadFile with one line: "not valid JSON: <nlohmann's reason with
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
/// parsed in the memory available, BadFile (parseJson's message, without the path) for bad JSON.
[[nodiscard]] nlohmann::json loadJsonFile(const std::filesystem::path& path, std::uintmax_t maxBytes);

/// Throws std::runtime_error naming `what` when parsing `textBytes` bytes of JSON could need more memory than
/// the machine has available (MemAvailable of /proc/meminfo, and the address-space limit RLIMIT_AS).
void checkParseMemory(std::uintmax_t textBytes, const std::string& what);

/// One field of a document being read, named by its path from the top ("nodes[3].flux.zone_area"): the one reader of
/// every field of every document (issue 51: six readers had eleven helpers and two exception types).  Each reading
/// checks the field's kind and throws BadFile with one wording per kind, after the reader's prefix:
///   "<path> has no 'key'", "unknown key 'key' in <path>", "<path> must be a JSON object, not <value>",
///   "<path> must be an array, not <value>", "<path> has N entries; at most M", "<path> must be [x, y], not <value>",
///   "<path> = <value> must be a whole number in [min, max]" (wholeJson's rule), "… must be an integer in [min, max]",
///   "<path> must be a number, not <value>", "<path> = <value> must be ≥ 0", "<path> must be a string, not <value>",
///   "<path> is longer than N bytes", "<path> must be true or false, not <value>"
/// (<value> as describeJson says it).  The top level is called by the document's name ("the atlas has no 'nodes'");
/// its fields by their keys alone.  A field refers to the document and to the views given to it (`name`, `prefix`):
/// they outlive it.
class JsonField {
 public:
  /// The top of a document, called `name` in messages; every message begins with `prefix` ("corrupt run file: ").
  JsonField(const nlohmann::json& document, std::string_view name, std::string_view prefix = {});

  [[nodiscard]] const nlohmann::json& value() const noexcept { return *value_; }
  /// Its path ("portrait.orbits[2].start"), or the document's name at the top.
  [[nodiscard]] std::string name() const;
  [[nodiscard]] bool isNull() const noexcept { return value_->is_null(); }
  /// Whether it is an object holding `key`.
  [[nodiscard]] bool contains(std::string_view key) const;

  /// The member `key` of an object, which must hold it.
  [[nodiscard]] JsonField operator[](std::string_view key) const;
  /// The member `key` of an object, nothing when it has none.
  [[nodiscard]] std::optional<JsonField> find(std::string_view key) const;
  /// The entry `i` of an array (array() first).
  [[nodiscard]] JsonField operator[](std::size_t i) const;

  /// An object.
  const JsonField& object() const;
  /// An object with every key of `required` and none outside `required` and `optional`.
  const JsonField& keys(std::initializer_list<std::string_view> required,
                        std::initializer_list<std::string_view> optional = {}) const;
  /// An array of at most maxEntries entries; its size.
  std::size_t array(std::size_t maxEntries = SIZE_MAX) const;
  /// An array of exactly `entries` entries, written `shape` in the message ("[x, y]").
  void tuple(std::size_t entries, std::string_view shape) const;
  /// A whole number in [min, max] by wholeJson's rule (a JSON integer, never a real).
  [[nodiscard]] std::uint64_t whole(std::uint64_t max = UINT64_MAX, std::uint64_t min = 0) const;
  /// The rule of hand-written run specs, which may say 2e7: a whole number in [0, max], or a real that is exactly one.
  [[nodiscard]] std::uint64_t wholeOrExactReal(std::uint64_t max) const;
  /// A JSON integer, signed or not, in [min, max].
  [[nodiscard]] std::int64_t integer(std::int64_t min = INT64_MIN, std::int64_t max = INT64_MAX) const;
  /// A finite number.
  [[nodiscard]] double real() const;
  /// A finite number ≥ 0.
  [[nodiscard]] double nonNegative() const;
  /// A finite number, or `null` for the JSON null a writer writes for a value not finite.
  [[nodiscard]] double realOr(double null) const;
  [[nodiscard]] bool boolean() const;
  [[nodiscard]] std::string string(std::size_t maxBytes = SIZE_MAX) const;

  /// Throws BadFile: the prefix, the field's name, a space and `what` ("nodes[1].sense" "must be 1 or -1").
  [[noreturn]] void refuse(std::string_view what) const;
  /// Throws BadFile: the prefix, the field's name, " = ", its value and `rule` ("… = 7 must be 1 or -1").
  [[noreturn]] void refuseValue(std::string_view rule) const;
  /// Throws BadFile: the prefix and `what`, which names what it is about.
  [[noreturn]] void refuseDocument(std::string_view what) const;

 private:
  JsonField(const nlohmann::json& value, std::string path, const JsonField& parent);

  const nlohmann::json* value_;
  std::string path_;  // empty at the top
  std::string_view document_, prefix_;
};

/// The signature of a signed document (atlas and Markov-tree files; issue 54), the one rule for both: with a
/// format_version (which must be `version`) a "checksum" string equal to jsonChecksum of the rest — `j` loses its
/// checksum on the way; without one, no checksum (a file from before, read unsigned).  A breach goes to `refuse`,
/// worded "checksum: a signed <noun> (version N) must have one", "<subject> was modified after it was written (its
/// checksum does not match its content)" or "checksum without format_version" (should `refuse` return, BadFile).
void checkSignature(nlohmann::json& j, const JsonField& root, std::uint64_t version, std::string_view noun,
                    std::string_view subject, const std::function<void(const std::string&)>& refuse);

}  // namespace archipelago::io
