#pragma once
// The fuzzed entry points: each takes untrusted bytes and must either succeed or throw one of the exceptions
// its contract names.  Anything else (a crash, a sanitizer report, a hang, another exception) is a bug.  The
// same functions are called by the libFuzzer targets (clang, `cmake --preset fuzz`) and by the corpus
// replayer of the ordinary test suite (any compiler).

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "core/runfile/RunFile.hpp"
#include "core/spec/RunSpec.hpp"

namespace archipelago::fuzz {

/// Run files: parseRunFile() throws std::runtime_error for any bad content.  A file it accepts must be
/// written back identically (the parse is exact) and validated again.
inline void runFile(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool allowModified : {false, true}) {
    try {
      const TrappingState s = parseRunFile(text, {.allowModified = allowModified});
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

}  // namespace archipelago::fuzz
