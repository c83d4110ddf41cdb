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
#include "app/cli/CliCommon.hpp"
#include "core/session/SessionFile.hpp"
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

/// The CLI's one number parser (app/cli/CliCommon.hpp): any text is either refused (nothing / an
/// std::invalid_argument naming the option) or read as a value that prints back to a text read as the same
/// value — never a wrapped, saturated or non-finite number.
inline void numbers(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (const auto v = cli::toNumber<std::uint64_t>(text)) {
    if (cli::toNumber<std::uint64_t>(cli::formatNumber(*v)) != v) throw std::logic_error("uint64 round trip");
    if (text.find('-') != std::string::npos && *v != 0) throw std::logic_error("a negative text read as unsigned");
  }
  if (const auto v = cli::toNumber<std::int32_t>(text)) {
    if (cli::toNumber<std::int32_t>(cli::formatNumber(*v)) != v) throw std::logic_error("int32 round trip");
  }
  if (const auto v = cli::toNumber<double>(text)) {
    if (!std::isfinite(*v)) throw std::logic_error("a non-finite double was accepted");
    if (cli::toNumber<double>(cli::formatNumber(*v)) != v) throw std::logic_error("double round trip");
  }
  try {
    (void)cli::parseNumbers<double>("--view", text, ',', 4, "four numbers");
    (void)cli::parseNumbers<std::uint32_t>("--size", text, 'x', 2, "WxH");
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

}  // namespace archipelago::fuzz
