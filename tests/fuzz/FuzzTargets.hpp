#pragma once
// The fuzzed entry points: each takes untrusted bytes and must either succeed or throw one of the exceptions
// its contract names.  Anything else (a crash, a sanitizer report, a hang, another exception) is a bug.  The
// same functions are called by the libFuzzer targets (clang, `cmake --preset fuzz`) and by the corpus
// replayer of the ordinary test suite (any compiler).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "core/runfile/RunFile.hpp"
#include "core/io/Json.hpp"
#include "core/io/NumberText.hpp"
#include "core/runfile/RunFileMerge.hpp"
#include "core/session/SessionFile.hpp"
#include "core/runspec/RunSpec.hpp"
#include "core/tail/TailFile.hpp"
#include "core/tail/TailSampler.hpp"

namespace archipelago::fuzz {

/// Run files: parseRunFile() throws io::BadFile for any bad content.  A file it accepts must be
/// written back identically (the parse is exact) and validated again.
inline void runFile(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool allowModified : {false, true}) {
    try {
      TrappingState s = parseRunFile(text, {.allowModified = allowModified, .allowModifiedName = "--allow-modified"});
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
    } catch (const io::BadFile&) {
    }
  }
}

/// Run specs (presets, --spec files, saved settings): parseRunSpec() throws io::BadFile.  An
/// accepted spec round-trips exactly.
inline void runSpec(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const RunSpec s = parseRunSpec(text);
    if (!(parseRunSpec(runSpecJson(s)) == s)) throw std::logic_error("run spec round trip changed it");
  } catch (const io::BadFile&) {
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

/// Session files (.archipelago): parseSession() throws io::BadFile.  An accepted session is written
/// back to the same text (the codec is exact) and parsed again.
inline void session(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const Session s = parseSession(text);
    const std::string again = sessionText(s);
    if (sessionText(parseSession(again)) != again) throw std::logic_error("session round trip changed it");
  } catch (const io::BadFile&) {
  }
}

/// Run manifests (MPI checkpoints, core/runfile/RunFileMerge.hpp): parseRunManifest() throws io::BadFile;
/// an accepted manifest is written back to a manifest that reads the same.
inline void manifest(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const RunManifest m = parseRunManifest(text, "manifest");
    const RunManifest again = parseRunManifest(runManifestText(m), "manifest");
    if (again.parts.size() != m.parts.size() || again.blocksDone != m.blocksDone)
      throw std::logic_error("manifest round trip changed it");
  } catch (const io::BadFile&) {
  }
}

/// Tail files (core/tail/TailFile.hpp, the rare-event sampler's checkpoints): parseTailFile() throws
/// io::BadFile.  A JSON object's checksum is first signed again over its content, as the writer does, so
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
  } catch (const io::BadFile&) {
  }
  try {
    const TailState s = parseTailFile(text);
    const std::string again = tailFileText(s);
    if (tailFileText(parseTailFile(again)) != again) throw std::logic_error("tail file round trip changed it");
  } catch (const io::BadFile&) {
  }
}

/// Tail files' state behind a valid checksum (issue 36: a re-signed file whose replica had survivors and no
/// walkers was resumed, and its P was wrong).  The input is a program of edits to the JSON "state" of a sampler
/// run — walkers removed, duplicated or cleared, alive flags, lineages and ages, a level's counts, stage 0's —
/// applied to one of the states a small run passes through; the file is signed again and read.  It must be
/// refused, or be a state that holds the sampler's invariants (checked here in their own words, not by
/// tailStateError()), round-trips, and resumes one step into a state that reads back.
namespace detail {
inline const std::vector<std::string>& tailStates() {
  static const std::vector<std::string> texts = [] {
    TailRequest r;  // the process of `run` at K = 0.1, q = 16: levels 112 … 1168 steps, N = 4, R = 2
    r.population = 4;
    r.replicas = 2;
    r.firstSteps = 100;
    r.maxSteps = 1000;
    r.binsPerLevel = 10;
    r.warmupBlocks = 4;
    r.minAncestors = 1;
    std::vector<std::string> out{tailFileText(startTail(r))};
    TailRunOptions o;
    o.threads = 1;
    const TailState end = runTail(startTail(r), o, [&](const TailState& s, const TailProgress&) {
      out.push_back(tailFileText(s));
    });
    out.push_back(tailFileText(end));
    return out;
  }();
  return texts;
}

/// The invariants a state of the sampler holds between two of its steps (TailSampler.cpp), stated independently.
inline void checkTailInvariants(const TailState& s) {
  const std::uint64_t N = s.request.population;
  for (const TailReplica& x : s.replicas) {
    if (x.levels.size() != s.next || x.alive.size() != (s.next == 0 && s.age == 0 ? 0 : x.walkers.size()))
      throw std::logic_error("levels or alive flags per replica");
    for (const TailLevelCount& c : x.levels)
      if (c.survivors > c.population || c.ancestors > c.survivors) throw std::logic_error("a level's counts");
    if (s.next == 0) continue;
    const TailLevelCount& last = x.levels.back();
    if (!s.finished() && x.walkers.size() != (last.survivors > 0 ? N : 0))
      throw std::logic_error("walkers under way differ from N or none");
    std::uint64_t alive = 0;
    for (std::size_t w = 0; w < x.walkers.size(); ++w) {
      if (x.alive[w] && x.walkers[w].state.length != s.age) throw std::logic_error("a live walker of another age");
      if (x.walkers[w].ancestor >= x.levels[0].survivors) throw std::logic_error("a lineage from nowhere");
      alive += x.alive[w] != 0;
    }
    if (s.finished() && alive != last.survivors) throw std::logic_error("survivors of the last level");
  }
}
}  // namespace detail

inline void tailState(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  const std::vector<std::string>& bases = detail::tailStates();
  if (size == 1) {  // no edit: every state of the run is read back as written (no false refusal)
    for (const std::string& text : bases) {
      const TailState s = parseTailFile(text);
      detail::checkTailInvariants(s);
      if (tailFileText(s) != text) throw std::logic_error("a state of the run did not read back as written");
    }
    return;
  }
  nlohmann::json j = nlohmann::json::parse(bases[data[0] % bases.size()]);
  nlohmann::json& state = j["state"];
  nlohmann::json& replicas = state["replicas"];
  const auto number = [](std::uint8_t v) -> std::int64_t { return v < 200 ? v : std::int64_t{v} * 1000; };
  for (std::size_t i = 1; i + 3 < size; i += 4) {
    const std::uint8_t op = data[i], a = data[i + 1], b = data[i + 2], v = data[i + 3];
    nlohmann::json& x = replicas[a % replicas.size()];
    nlohmann::json& walkers = x["walkers"];
    nlohmann::json& levels = x["levels"];
    const std::size_t w = walkers.empty() ? 0 : b % walkers.size();
    switch (op % 12) {
      case 0: if (!walkers.empty()) walkers.erase(w); break;
      case 1: if (!walkers.empty()) walkers.push_back(walkers[w]); break;
      case 2: walkers = nlohmann::json::array(); break;
      case 3: if (!walkers.empty()) walkers[w][10] = v % 3; break;                  // alive
      case 4: if (!walkers.empty()) walkers[w][9] = number(v); break;               // ancestor
      case 5: if (!walkers.empty()) walkers[w][4] = number(v); break;               // length (age)
      case 6: if (!levels.empty()) levels[b % levels.size()][v % 5] = number(a); break;  // a level's count
      case 7: x[v % 2 ? "orbits_done" : "trials"] = number(b); break;
      case 8: state[v % 2 ? "next" : "age"] = number(b); break;
      case 9: if (!levels.empty()) levels.erase(b % levels.size()); break;
      case 10: if (!walkers.empty()) walkers[w][b % 4] = walkers[(w + 1) % walkers.size()][b % 4]; break;
      case 11: if (replicas.size() > 1) replicas.erase(a % replicas.size()); break;
    }
  }
  j.erase("checksum");
  j["checksum"] = io::jsonChecksum(j);
  TailState s;
  try {
    s = parseTailFile(j.dump(1));
  } catch (const io::BadFile&) {
    return;  // refused: what an inconsistent state must be
  }
  detail::checkTailInvariants(s);
  const std::string again = tailFileText(s);
  if (!(parseTailFile(again) == s)) throw std::logic_error("tail state round trip changed it");
  std::stop_source stop;
  TailRunOptions o;
  o.threads = 1;
  const TailState next = runTail(s, o, [&](const TailState&, const TailProgress&) { stop.request_stop(); }, stop.get_token());
  detail::checkTailInvariants(parseTailFile(tailFileText(next)));
}

}  // namespace archipelago::fuzz
