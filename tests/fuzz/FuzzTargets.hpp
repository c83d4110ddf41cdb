#pragma once
// The fuzzed entry points: each takes untrusted bytes and must either succeed or throw one of the exceptions
// its contract names.  Anything else (a crash, a sanitizer report, a hang, another exception) is a bug.  The
// same functions are called by the libFuzzer targets (clang, `cmake --preset fuzz`) and by the corpus
// replayer of the ordinary test suite (any compiler).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/runfile/RunFile.hpp"
#include "core/io/Json.hpp"
#include "core/io/NumberText.hpp"
#include "core/runfile/RunFileMerge.hpp"
#include "core/session/SessionFile.hpp"
#include "core/spec/RunSpec.hpp"
#include "core/tail/TailFile.hpp"

namespace archipelago::fuzz {

/// Run files: parseRunFile() throws std::runtime_error for any bad content.  A file it accepts must be
/// written back identically (the parse is exact) and validated again.
inline void runFile(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool allowModified : {false, true}) {
    try {
      TrappingState s = parseRunFile(text, {.allowModified = allowModified});
      if (s.unverified != allowModified && s.unverified) throw std::logic_error("unverified without the opt-in");
      // An unverified state is never written as a verified file (issue #23): check that, then round-trip the
      // content as if it were verified.
      if (s.unverified) {
        try {
          (void)runFileText(s);
          throw std::logic_error("an unverified state was written");
        } catch (const std::runtime_error&) {
        }
        s.unverified = false;
      }
      const std::string again = runFileText(s);
      if (!(parseRunFile(again).params == s.params)) throw std::logic_error("run file round trip changed it");
    } catch (const std::runtime_error&) {
    }
  }
}

/// Run specs (presets, --spec files, saved settings): parseRunSpec() throws std::invalid_argument.  An
/// accepted spec round-trips exactly.
inline void runSpec(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const RunSpec s = parseRunSpec(text);
    if (!(parseRunSpec(runSpecJson(s)) == s)) throw std::logic_error("run spec round trip changed it");
  } catch (const std::invalid_argument&) {
  }
}

/// The one number reader (core/io/NumberText.hpp, used by the CLI, the GUI and Python): any text is either refused (nothing / an
/// std::invalid_argument naming the option) or read as a value that prints back to a text read as the same
/// value — never a wrapped, saturated or non-finite number.
inline void numbers(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (const auto v = io::toNumber<std::uint64_t>(text)) {
    if (io::toNumber<std::uint64_t>(io::shortestText(*v)) != v) throw std::logic_error("uint64 round trip");
    // A sign is the text's first character (no blanks are read); a '-' elsewhere is an exponent's ("11e-0" is 11).
    if (text.starts_with('-') && *v != 0) throw std::logic_error("a negative text read as unsigned");
  }
  if (const auto v = io::toNumber<std::int32_t>(text)) {
    if (io::toNumber<std::int32_t>(io::shortestText(*v)) != v) throw std::logic_error("int32 round trip");
  }
  if (const auto v = io::toNumber<double>(text)) {
    if (!std::isfinite(*v)) throw std::logic_error("a non-finite double was accepted");
    if (io::toNumber<double>(io::shortestText(*v)) != v) throw std::logic_error("double round trip");
  }
  try {
    (void)io::parseNumbers<double>("--view", text, ',', 4, "four numbers");
    (void)io::parseNumbers<std::uint32_t>("--size", text, 'x', 2, "WxH");
  } catch (const std::invalid_argument&) {
  }
}

/// Session files (.archipelago): parseSession() throws std::invalid_argument.  An accepted session is written
/// back to the same text (the codec is exact) and parsed again.
inline void session(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const Session s = parseSession(text);
    const std::string again = sessionText(s);
    if (sessionText(parseSession(again)) != again) throw std::logic_error("session round trip changed it");
  } catch (const std::invalid_argument&) {
  }
}

/// Run manifests (MPI checkpoints, core/runfile/RunFileMerge.hpp): parseRunManifest() throws std::runtime_error;
/// an accepted manifest is written back to a manifest that reads the same.
inline void manifest(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const RunManifest m = parseRunManifest(text, "manifest");
    const RunManifest again = parseRunManifest(runManifestText(m), "manifest");
    if (again.parts.size() != m.parts.size() || again.blocksDone != m.blocksDone)
      throw std::logic_error("manifest round trip changed it");
  } catch (const std::runtime_error&) {
  }
}

/// Tail files (core/tail/TailFile.hpp, the rare-event sampler's checkpoints): parseTailFile() throws
/// std::runtime_error.  A JSON object's checksum is first signed again over its content, as the writer does, so
/// that the fuzzer reaches the fields behind it (an edited file is refused by the checksum before any of them is
/// read).  An accepted file is written back to a text that reads the same.
inline void tailFile(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  try {
    nlohmann::json j = io::parseJson(text);
    if (j.is_object() && j.contains("checksum")) {
      j.erase("checksum");
      j["checksum"] = io::jsonChecksum(j);
      text = j.dump(1);
    }
  } catch (const std::invalid_argument&) {
  }
  try {
    const TailState s = parseTailFile(text);
    const std::string again = tailFileText(s);
    if (tailFileText(parseTailFile(again)) != again) throw std::logic_error("tail file round trip changed it");
  } catch (const std::runtime_error&) {
  }
}

}  // namespace archipelago::fuzz
