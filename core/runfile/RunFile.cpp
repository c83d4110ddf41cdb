#include "core/runfile/RunFile.hpp"

#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "core/io/AtomicFile.hpp"
#include "core/io/Json.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/run/StateValidation.hpp"
#include "core/runspec/RunSpecJson.hpp"

namespace archipelago {

using nlohmann::json;

namespace {

json toJson(const UnitState& z) { return json::array({z.X, z.Y}); }
json toJson(const SegmentStart& s) { return {{"z", toJson(s.z)}, {"block", s.block}, {"draws", s.draws}}; }

json toJson(const TrappingHistogram& h) {
  // Sparse: [bin, count, lengthSum] for every non-empty bin.
  json bins = json::array();
  for (int i = 1; i < TrappingHistogram::kBins; ++i)
    if (h.count(i) != 0) bins.push_back(json::array({i, h.count(i), h.lengthSum(i)}));
  return bins;
}

// --- reading, with one-line errors naming what is wrong -------------------------------------------------

[[noreturn]] void corrupt(const std::string& what) { throw std::runtime_error("corrupt run file: " + what); }

const json& field(const json& j, const char* key) {
  if (!j.is_object()) corrupt(std::string("expected an object holding '") + key + "'");
  const auto it = j.find(key);
  if (it == j.end()) corrupt(std::string("missing field '") + key + "'");
  return *it;
}

std::uint64_t u64(const json& j, const char* key) {
  const json& v = field(j, key);
  const std::optional<std::uint64_t> n = io::wholeJson(v);  // the documents' one rule of whole numbers
  if (!n) corrupt(std::string("field '") + key + "' must be a non-negative integer");
  return *n;
}

std::int64_t i64(const json& j, const char* key) {
  const json& v = field(j, key);
  if (!v.is_number_integer()) corrupt(std::string("field '") + key + "' must be an integer");
  return v.get<std::int64_t>();
}

double f64(const json& j, const char* key) {
  const json& v = field(j, key);
  if (!v.is_number()) corrupt(std::string("field '") + key + "' must be a number");
  return v.get<double>();
}

UnitState unitState(const json& j) {
  if (!j.is_array() || j.size() != 2 || !j[0].is_number_unsigned() || !j[1].is_number_unsigned())
    corrupt("a state must be [X, Y] with non-negative integers");
  const UnitState z{j[0].get<std::uint64_t>(), j[1].get<std::uint64_t>()};
  if (z.X >= FixedPointMap::kOne || z.Y >= FixedPointMap::kOne) corrupt("a state lies outside [0, 2^52)");
  return z;
}

SegmentStart segmentStart(const json& j) { return {unitState(field(j, "z")), u64(j, "block"), u64(j, "draws")}; }

TrappingHistogram histogram(const json& j) {
  if (!j.is_array()) corrupt("a histogram must be an array of [bin, count, lengthSum]");
  TrappingHistogram h;
  std::uint64_t previousBin = 0;
  for (const json& b : j) {
    if (!b.is_array() || b.size() != 3 || !b[0].is_number_unsigned() || !b[1].is_number_unsigned() ||
        !b[2].is_number_unsigned())
      corrupt("a histogram bin must be [bin, count, lengthSum] with non-negative integers");
    const auto i = b[0].get<std::uint64_t>();
    if (i < 1 || i >= static_cast<std::uint64_t>(TrappingHistogram::kBins)) corrupt("histogram bin out of range");
    if (i <= previousBin) corrupt("histogram bins must be listed once each, in increasing order");
    previousBin = i;
    const auto count = b[1].get<std::uint64_t>();
    const auto sum = b[2].get<std::uint64_t>();
    const int bin = static_cast<int>(i);
    // Every length in the bin lies in [lower, upper): the sum must be consistent with the count.
    if (count == 0 || sum / count < TrappingHistogram::binLower(bin) ||
        (bin + 1 < TrappingHistogram::kBins && sum / count >= TrappingHistogram::binUpper(bin)))
      corrupt("histogram bin " + std::to_string(bin) + " has inconsistent count and length sum");
    h.setBin(bin, count, sum);
  }
  return h;
}

/// "; <name> reads it anyway<how>" with the front end's name of allowModified, or nothing when it has none.
std::string readAnyway(const RunFileReadOptions& options, const char* how) {
  return options.allowModifiedName.empty() ? std::string() : "; " + options.allowModifiedName + " reads it anyway" + how;
}

}  // namespace

std::string runFileText(const TrappingState& s) {
  if (s.unverified)
    throw std::runtime_error("this run was read from a file whose checksum did not match (or that had none, format "
                             "version 1), for inspection: it cannot be written as a verified run file");
  const TrappingParameters& p = s.params;
  json j;
  j["format"] = kRunFileFormatName;
  j["version"] = kRunFileFormatVersion;
  j["program"] = programDescription();
  j["parameters"] = spec::parametersJson(p);
  j["coefficients"] = {{"A", s.coefficients.A}, {"B", s.coefficients.B}, {"C", s.coefficients.C},
                       {"m", s.coefficients.m}};
  j["orbitBegin"] = s.orbitBegin;
  j["orbitEnd"] = s.orbitEnd;
  j["blocksDone"] = s.blocksDone;
  j["finished"] = s.finished();
  j["elapsedSeconds"] = s.elapsedSeconds;
  j["kernel"] = s.kernel;
  json edges = json::array();
  for (int i = TrappingHistogram::kExactMax + 1; i < TrappingHistogram::kBins; ++i)
    edges.push_back(TrappingHistogram::binLower(i));
  j["histogramBins"] = {{"exactMax", TrappingHistogram::kExactMax},
                        {"binsPerDecade", TrappingHistogram::kBinsPerDecade},
                        {"logBinLowerEdges", edges}};
  json subsets = json::array();
  for (const auto& h : s.subsets) subsets.push_back(toJson(h));
  j["subsets"] = subsets;
  json longest = json::array();
  for (const auto& r : s.longest.items())
    longest.push_back({{"orbit", r.orbit}, {"length", r.length}, {"start", toJson(r.start)}});
  j["longest"] = longest;
  json orbits = json::array();
  for (const auto& o : s.orbits)
    orbits.push_back(json::array({o.z.X, o.z.Y, o.block, o.draws, o.length, o.start.z.X, o.start.z.Y,
                                  o.start.block, o.start.draws}));
  j["orbits"] = orbits;
  // The checksum covers the document without itself, as dumped here: parse + dump reproduces those bytes
  // (sorted keys, exact integers, shortest round-trip reals), so any edit of a value is detected on reading.
  j["checksum"] = io::jsonChecksum(j);
  return j.dump(1) + "\n";
}

TrappingState parseRunFile(const std::string& text, const RunFileReadOptions& options) {
  json j;
  try {
    j = io::parseJson(text);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("corrupt or truncated run file: ") + e.what());
  }
  return runFileFromJson(std::move(j), options);
}

TrappingState runFileFromJson(nlohmann::json j, const RunFileReadOptions& options) {
  if (!j.is_object() || !j.contains("format") || j["format"] != kRunFileFormatName)
    throw std::runtime_error("not an Archipelago run file (missing \"format\": \"archipelago-run\")");
  const std::int64_t version = i64(j, "version");
  if (version != kRunFileFormatVersion && version != 1)
    throw std::runtime_error("run file format version " + std::to_string(version) +
                             " is not supported (this program reads versions 1 and " +
                             std::to_string(kRunFileFormatVersion) + ")");
  bool verified = false;
  if (version == 1) {
    // Format 1 had no checksum: deleting the checksum and declaring version 1 must not bypass it (issue #23).
    if (!options.allowModified)
      throw std::runtime_error("run file format version 1 has no checksum, so edits cannot be detected" +
                               readAnyway(options, " (for inspection only: it cannot be resumed, merged or saved as a "
                                                   "verified file)"));
  } else {
    const json& sum = field(j, "checksum");
    if (!sum.is_string()) corrupt("field 'checksum' must be a string");
    const std::string stored = sum.get<std::string>();
    j.erase("checksum");
    verified = stored == io::jsonChecksum(j);
    if (!verified && !options.allowModified)
      throw std::runtime_error("run file was modified after it was written (its checksum does not match its content)" +
                               readAnyway(options, ", still checking its consistency"));
  }
  const json& jp = field(j, "parameters");
  TrappingParameters p;
  try {
    p = spec::parametersFromJson(jp, /*complete=*/true);
  } catch (const std::invalid_argument& e) {
    corrupt(std::string("parameters: ") + e.what());
  }
  if (auto e = validationError(p)) corrupt("invalid parameters: " + *e);

  TrappingState s;
  s.params = p;
  s.coefficients = computeCoefficients(p.map);
  const json& jc = field(j, "coefficients");
  const MapCoefficients stored{i64(jc, "A"), i64(jc, "B"), i64(jc, "C"), static_cast<int>(i64(jc, "m"))};
  if (!(stored == s.coefficients))
    throw std::runtime_error("run file coefficients (A, B, C, m) differ from those this program derives from K, xmin, xmax;"
                             " the file was written by an incompatible program");
  const json& bins = field(j, "histogramBins");
  if (i64(bins, "exactMax") != TrappingHistogram::kExactMax || i64(bins, "binsPerDecade") != TrappingHistogram::kBinsPerDecade)
    throw std::runtime_error("run file uses a different histogram binning");
  const json& edges = field(bins, "logBinLowerEdges");
  if (!edges.is_array() || edges.size() != static_cast<std::size_t>(TrappingHistogram::kBins - TrappingHistogram::kExactMax - 1))
    throw std::runtime_error("run file uses a different histogram binning");
  for (int i = TrappingHistogram::kExactMax + 1; i < TrappingHistogram::kBins; ++i)
    if (edges[static_cast<std::size_t>(i - TrappingHistogram::kExactMax - 1)] != TrappingHistogram::binLower(i))
      throw std::runtime_error("run file uses different histogram bin edges");

  s.orbitBegin = u64(j, "orbitBegin");
  s.orbitEnd = u64(j, "orbitEnd");
  if (s.orbitBegin >= s.orbitEnd || s.orbitEnd > p.M) corrupt("orbit range outside [0, M)");
  s.blocksDone = u64(j, "blocksDone");
  s.elapsedSeconds = f64(j, "elapsedSeconds");
  const json& kernel = field(j, "kernel");
  if (!kernel.is_string()) corrupt("field 'kernel' must be a string");
  s.kernel = kernel.get<std::string>();

  const json& js = field(j, "subsets");
  if (!js.is_array() || js.size() != p.subsets) corrupt("expected one histogram per subset");
  for (const json& h : js) s.subsets.push_back(histogram(h));

  s.longest = LongestSegments(p.longestKept);
  const json& jl = field(j, "longest");
  if (!jl.is_array() || jl.size() > p.longestKept) corrupt("too many longest segments");
  std::optional<SegmentRecord> previous;
  for (const json& r : jl) {
    const SegmentRecord rec{u64(r, "orbit"), u64(r, "length"), segmentStart(field(r, "start"))};
    if (previous && !LongestSegments::ranksBefore(*previous, rec)) corrupt("the longest segments are not ranked");
    s.longest.insert(rec);
    previous = rec;
  }

  const json& jo = field(j, "orbits");
  if (!jo.is_array() || jo.size() != s.orbitEnd - s.orbitBegin) corrupt("expected one state per orbit");
  s.orbits.reserve(jo.size());
  for (const json& o : jo) {
    if (!o.is_array() || o.size() != 9) corrupt("an orbit state must have 9 integers");
    for (const json& v : o)
      if (!v.is_number_unsigned()) corrupt("an orbit state must have 9 non-negative integers");
    OrbitState st;
    st.z = unitState(json::array({o[0], o[1]}));
    st.block = o[2].get<std::uint64_t>();
    st.draws = o[3].get<std::uint64_t>();
    st.length = o[4].get<std::uint64_t>();
    st.start = {unitState(json::array({o[5], o[6]})), o[7].get<std::uint64_t>(), o[8].get<std::uint64_t>()};
    s.orbits.push_back(st);
  }
  if (auto e = consistencyError(s)) corrupt(*e);
  s.unverified = !verified;
  return s;
}

void saveRunFile(const std::filesystem::path& path, const TrappingState& state) {
  io::writeFileAtomically(path, runFileText(state));
}

TrappingState loadRunFile(const std::filesystem::path& path, const RunFileReadOptions& options) {
  json j;
  try {
    j = io::loadJsonFile(path, kMaxRunFileBytes);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path.string() + ": corrupt or truncated run file: " + e.what());
  }
  try {
    return runFileFromJson(std::move(j), options);
  } catch (const std::exception& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

std::filesystem::path companionRunFile(const std::filesystem::path& run) {
  std::filesystem::path p = run;
  const std::string stem = run.extension() == ".json" ? run.stem().string() : run.filename().string();
  return p.replace_filename(stem + ".short.json");
}

}  // namespace archipelago
