#include "core/runfile/RunFileMerge.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <variant>

#include <nlohmann/json.hpp>

#include "core/io/AtomicFile.hpp"
#include "core/io/Json.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago {

namespace {

std::string valueText(const ParameterValue& v) {
  if (const auto* u = std::get_if<std::uint64_t>(&v)) return std::to_string(*u);
  std::ostringstream out;
  out.precision(17);
  out << std::get<double>(v);
  return out.str();
}

std::string rangeText(const TrappingState& s) {
  return "[" + std::to_string(s.orbitBegin) + ", " + std::to_string(s.orbitEnd) + ")";
}

[[noreturn]] void mismatch(const std::string& message) { throw std::invalid_argument("cannot merge: " + message); }

/// The first field in which `b` differs from `a` (the reference part), as an error.
void checkSameRun(const RunPart& a, const RunPart& b) {
  for (const ParameterRule& rule : parameterRules()) {
    const ParameterValue va = parameterValue(a.state.params, rule.key);
    const ParameterValue vb = parameterValue(b.state.params, rule.key);
    const bool same = va.index() == vb.index() &&
                      (std::holds_alternative<std::uint64_t>(va)
                           ? std::get<std::uint64_t>(va) == std::get<std::uint64_t>(vb)
                           : std::get<double>(va) == std::get<double>(vb));
    if (!same)
      mismatch(b.name + ": field '" + std::string(rule.key) + "' is " + valueText(vb) + " but " + a.name + " has " +
               valueText(va) + " (the parts of one run have one spec)");
  }
  if (!(a.state.params == b.state.params) || !(a.state.coefficients == b.state.coefficients))
    mismatch(b.name + ": field 'parameters' differs from " + a.name + "'s");
  if (a.state.blocksDone != b.state.blocksDone)
    mismatch(b.name + ": field 'blocksDone' is " + std::to_string(b.state.blocksDone) + " but " + a.name + " has " +
             std::to_string(a.state.blocksDone) + " (merge parts at the same progress: resume the shorter ones)");
}

}  // namespace

TrappingState mergeRunParts(std::vector<RunPart> parts) {
  if (parts.empty()) throw std::invalid_argument("cannot merge: no run files given");
  for (std::size_t i = 1; i < parts.size(); ++i) checkSameRun(parts.front(), parts[i]);
  std::stable_sort(parts.begin(), parts.end(), [](const RunPart& x, const RunPart& y) {
    return x.state.orbitBegin < y.state.orbitBegin;
  });
  const std::uint64_t M = parts.front().state.params.M;
  if (parts.front().state.orbitBegin != 0)
    mismatch(parts.front().name + ": field 'orbitBegin' is " + std::to_string(parts.front().state.orbitBegin) +
             ": orbits [0, " + std::to_string(parts.front().state.orbitBegin) + ") are in no file");
  for (std::size_t i = 1; i < parts.size(); ++i) {
    const RunPart& lo = parts[i - 1];
    const RunPart& hi = parts[i];
    if (hi.state.orbitBegin < lo.state.orbitEnd)
      mismatch(hi.name + ": field 'orbitBegin' is " + std::to_string(hi.state.orbitBegin) + ": its orbits " +
               rangeText(hi.state) + " overlap " + lo.name + "'s " + rangeText(lo.state));
    if (hi.state.orbitBegin > lo.state.orbitEnd)
      mismatch(hi.name + ": field 'orbitBegin' is " + std::to_string(hi.state.orbitBegin) + " but " + lo.name +
               " ends at " + std::to_string(lo.state.orbitEnd) + ": orbits [" + std::to_string(lo.state.orbitEnd) +
               ", " + std::to_string(hi.state.orbitBegin) + ") are in no file");
  }
  if (parts.back().state.orbitEnd != M)
    mismatch(parts.back().name + ": field 'orbitEnd' is " + std::to_string(parts.back().state.orbitEnd) +
             " but M = " + std::to_string(M) + ": orbits [" + std::to_string(parts.back().state.orbitEnd) + ", " +
             std::to_string(M) + ") are in no file");
  TrappingState merged = std::move(parts.front().state);
  merged.orbits.reserve(M);
  for (std::size_t i = 1; i < parts.size(); ++i) appendTrappingRange(merged, parts[i].state);
  return merged;
}

TrappingState sliceRun(const TrappingState& whole, std::uint64_t begin, std::uint64_t end, bool withStatistics) {
  if (!(whole.orbitBegin <= begin && begin < end && end <= whole.orbitEnd))
    throw std::invalid_argument("sliceRun: orbits [" + std::to_string(begin) + ", " + std::to_string(end) +
                                ") are not inside " + rangeText(whole));
  TrappingState s;
  s.params = whole.params;
  s.coefficients = whole.coefficients;
  s.orbitBegin = begin;
  s.orbitEnd = end;
  s.blocksDone = whole.blocksDone;
  s.orbits.assign(whole.orbits.begin() + static_cast<std::ptrdiff_t>(begin - whole.orbitBegin),
                  whole.orbits.begin() + static_cast<std::ptrdiff_t>(end - whole.orbitBegin));
  s.kernel = whole.kernel;
  if (withStatistics) {
    s.subsets = whole.subsets;
    s.longest = whole.longest;
    s.elapsedSeconds = whole.elapsedSeconds;
  } else {
    s.subsets.assign(whole.subsets.size(), TrappingHistogram{});
    s.longest = LongestSegments(whole.longest.capacity());
  }
  return s;
}

using json = nlohmann::json;

std::string runManifestText(const RunManifest& m) {
  json parts = json::array();
  for (const auto& p : m.parts)
    parts.push_back({{"file", p.file}, {"orbitBegin", p.orbitBegin}, {"orbitEnd", p.orbitEnd}});
  const json j = {{"format", kRunManifestFormatName}, {"version", kRunManifestFormatVersion},
                  {"blocksDone", m.blocksDone}, {"parts", parts}};
  return j.dump(1) + "\n";
}

bool looksLikeRunManifest(const std::string& text) {
  return text.find(std::string("\"") + kRunManifestFormatName + "\"") != std::string::npos &&
         text.find("\"archipelago-run\"") == std::string::npos;
}

RunManifest parseRunManifest(const std::string& text, const std::string& name) {
  json j;
  try {
    j = io::parseJson(text);
  } catch (const std::exception& e) {
    throw io::BadFile(name + ": not a manifest of run parts (" + e.what() + ")");
  }
  // Compared as JSON: a "format" of another type (an array, found by the fuzzer) is a wrong format, not a type error.
  if (!j.is_object() || !j.contains("format") || j["format"] != kRunManifestFormatName)
    throw io::BadFile(name + ": field 'format' is not \"" + kRunManifestFormatName + "\"");
  const std::string prefix = name + ": corrupt manifest: ";
  const io::JsonField root(j, "the manifest", prefix);
  if (root["version"].whole() != static_cast<std::uint64_t>(kRunManifestFormatVersion))
    throw io::BadFile(name + ": field 'version' is not " + std::to_string(kRunManifestFormatVersion));
  RunManifest m;
  m.blocksDone = root["blocksDone"].whole();
  const io::JsonField parts = root["parts"];
  if (parts.array() == 0) parts.refuse("is empty");
  for (std::size_t i = 0; i < parts.value().size(); ++i) {
    const io::JsonField p = parts[i];
    m.parts.push_back({p["file"].string(), p["orbitBegin"].whole(), p["orbitEnd"].whole()});
    const std::string& file = m.parts.back().file;
    if (file.empty() || file.find('/') != std::string::npos || file.find('\0') != std::string::npos || file == "." || file == "..")
      throw io::BadFile(name + ": field 'parts[].file' '" + io::shortText(file) + "' must be a file beside the manifest");
  }
  return m;
}

TrappingState loadRunManifest(const std::filesystem::path& path) {
  const RunManifest m = parseRunManifest(io::readRegularFile(path, kMaxManifestBytes), path.string());
  std::vector<RunPart> parts;
  for (const auto& p : m.parts) {
    const std::filesystem::path file = path.parent_path() / p.file;
    TrappingState s = loadRunFile(file);
    if (s.blocksDone != m.blocksDone)
      throw io::BadFile(file.string() + ": field 'blocksDone' is " + std::to_string(s.blocksDone) +
                               " but the manifest " + path.string() + " says " + std::to_string(m.blocksDone));
    if (s.orbitBegin != p.orbitBegin || s.orbitEnd != p.orbitEnd)
      throw io::BadFile(file.string() + ": field 'orbitBegin'/'orbitEnd' is " + rangeText(s) +
                               " but the manifest " + path.string() + " says [" + std::to_string(p.orbitBegin) + ", " +
                               std::to_string(p.orbitEnd) + ")");
    parts.push_back({file.string(), std::move(s)});
  }
  try {
    return mergeRunParts(std::move(parts));
  } catch (const std::invalid_argument& e) {
    throw io::BadFile(path.string() + ": " + e.what());
  }
}

}  // namespace archipelago
