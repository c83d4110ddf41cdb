#include "core/runfile/RunFile.hpp"

#include <climits>
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

// --- reading, with one-line errors naming what is wrong (io::JsonField's wording) --------------------------

constexpr std::string_view kCorrupt = "corrupt run file: ";

[[noreturn]] void refuse(const std::string& what) { throw io::BadFile(what); }
[[noreturn]] void corrupt(const std::string& what) { refuse(std::string(kCorrupt) + what); }

UnitState unitState(const io::JsonField& z) {
  z.tuple(2, "[X, Y]");
  return {z[0].whole(FixedPointMap::kOne - 1), z[1].whole(FixedPointMap::kOne - 1)};
}

SegmentStart segmentStart(const io::JsonField& s) { return {unitState(s["z"]), s["block"].whole(), s["draws"].whole()}; }

TrappingHistogram histogram(const io::JsonField& h) {
  TrappingHistogram t;
  std::uint64_t previousBin = 0;
  for (std::size_t k = 0, n = h.array(); k < n; ++k) {
    const io::JsonField b = h[k];
    b.tuple(3, "[bin, count, lengthSum]");
    const auto i = b[0].whole(TrappingHistogram::kBins - 1, 1);
    if (i <= previousBin) corrupt("histogram bins must be listed once each, in increasing order");
    previousBin = i;
    const std::uint64_t count = b[1].whole(), sum = b[2].whole();
    const int bin = static_cast<int>(i);
    // Every length in the bin lies in [lower, upper): the sum must be consistent with the count.
    if (count == 0 || sum / count < TrappingHistogram::binLower(bin) ||
        (bin + 1 < TrappingHistogram::kBins && sum / count >= TrappingHistogram::binUpper(bin)))
      corrupt("histogram bin " + std::to_string(bin) + " has inconsistent count and length sum");
    t.setBin(bin, count, sum);
  }
  return t;
}

/// The checksum, format version 2: whether it matches the content (`j` without it).
bool checksumMatches(json& j, const io::JsonField& root) {
  const std::string stored = root["checksum"].string();
  j.erase("checksum");
  return stored == io::jsonChecksum(j);
}

TrappingParameters parameters(const io::JsonField& root) {
  TrappingParameters p;
  try {
    p = spec::parametersFromJson(root["parameters"].value(), /*complete=*/true);
  } catch (const io::BadFile& e) {
    corrupt(std::string("parameters: ") + e.what());
  }
  if (auto e = validationError(p)) corrupt("invalid parameters: " + *e);
  return p;
}

void checkCoefficientsAndBins(const io::JsonField& root, const MapCoefficients& derived) {
  const io::JsonField jc = root["coefficients"];
  const MapCoefficients stored{jc["A"].integer(), jc["B"].integer(), jc["C"].integer(),
                               static_cast<int>(jc["m"].integer(INT_MIN, INT_MAX))};
  if (!(stored == derived))
    refuse("run file coefficients (A, B, C, m) differ from those this program derives from K, xmin, xmax;"
           " the file was written by an incompatible program");
  const io::JsonField bins = root["histogramBins"];
  if (bins["exactMax"].integer() != TrappingHistogram::kExactMax ||
      bins["binsPerDecade"].integer() != TrappingHistogram::kBinsPerDecade)
    refuse("run file uses a different histogram binning");
  const json& edges = bins["logBinLowerEdges"].value();
  if (!edges.is_array() || edges.size() != static_cast<std::size_t>(TrappingHistogram::kBins - TrappingHistogram::kExactMax - 1))
    refuse("run file uses a different histogram binning");
  for (int i = TrappingHistogram::kExactMax + 1; i < TrappingHistogram::kBins; ++i)
    if (edges[static_cast<std::size_t>(i - TrappingHistogram::kExactMax - 1)] != TrappingHistogram::binLower(i))
      refuse("run file uses different histogram bin edges");
}

LongestSegments longestSegments(const io::JsonField& jl, std::uint32_t kept) {
  LongestSegments longest(kept);
  std::optional<SegmentRecord> previous;
  for (std::size_t i = 0, n = jl.array(kept); i < n; ++i) {
    const io::JsonField r = jl[i];
    const SegmentRecord rec{r["orbit"].whole(), r["length"].whole(), segmentStart(r["start"])};
    if (previous && !LongestSegments::ranksBefore(*previous, rec)) corrupt("the longest segments are not ranked");
    longest.insert(rec);
    previous = rec;
  }
  return longest;
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
    orbits.push_back(orbitStateJson(o));
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
  } catch (const io::BadFile& e) {
    refuse(std::string("corrupt or truncated run file: ") + e.what());
  }
  return runFileFromJson(std::move(j), options);
}

TrappingState runFileFromJson(nlohmann::json j, const RunFileReadOptions& options) {
  if (!j.is_object() || !j.contains("format") || j["format"] != kRunFileFormatName)
    refuse("not an Archipelago run file (missing \"format\": \"archipelago-run\")");
  const io::JsonField root(j, "the run file", kCorrupt);
  const std::int64_t version = root["version"].integer();
  if (version != kRunFileFormatVersion && version != 1)
    refuse("run file format version " + std::to_string(version) + " is not supported (this program reads versions 1 and " +
           std::to_string(kRunFileFormatVersion) + ")");
  // Format 1 had no checksum: deleting the checksum and declaring version 1 must not bypass it (issue #23).
  if (version == 1 && !options.allowModified)
    refuse("run file format version 1 has no checksum, so edits cannot be detected" +
           readAnyway(options, " (for inspection only: it cannot be resumed, merged or saved as a verified file)"));
  const bool verified = version != 1 && checksumMatches(j, root);
  if (version != 1 && !verified && !options.allowModified)
    refuse("run file was modified after it was written (its checksum does not match its content)" +
           readAnyway(options, ", still checking its consistency"));

  TrappingState s;
  s.params = parameters(root);
  const TrappingParameters& p = s.params;
  s.coefficients = computeCoefficients(p.map);
  checkCoefficientsAndBins(root, s.coefficients);
  s.orbitBegin = root["orbitBegin"].whole();
  s.orbitEnd = root["orbitEnd"].whole();
  if (s.orbitBegin >= s.orbitEnd || s.orbitEnd > p.M) corrupt("orbit range outside [0, M)");
  s.blocksDone = root["blocksDone"].whole();
  s.elapsedSeconds = root["elapsedSeconds"].real();
  s.kernel = root["kernel"].string();

  const io::JsonField js = root["subsets"];
  if (js.array() != p.subsets) corrupt("expected one histogram per subset");
  for (std::size_t i = 0; i < p.subsets; ++i) s.subsets.push_back(histogram(js[i]));
  s.longest = longestSegments(root["longest"], p.longestKept);

  const io::JsonField jo = root["orbits"];
  if (jo.array() != s.orbitEnd - s.orbitBegin) corrupt("expected one state per orbit");
  s.orbits.reserve(s.orbitEnd - s.orbitBegin);
  for (std::size_t i = 0; i < s.orbitEnd - s.orbitBegin; ++i) {
    const io::JsonField o = jo[i];
    o.tuple(kOrbitStateRowSize, "[X, Y, block, draws, length, start X, start Y, start block, start draws]");
    s.orbits.push_back(orbitStateFromJson(o));
  }
  if (auto e = consistencyError(s)) corrupt(*e);
  s.unverified = !verified;
  return s;
}

json orbitStateJson(const OrbitState& state) { return orbitStateRow(state); }

OrbitState orbitStateFromJson(const io::JsonField& row) {
  OrbitStateRow r{};
  for (std::size_t i = 0; i < kOrbitStateRowSize; ++i) {
    // The whole-number rule on the value first: a run file holds millions of rows, and naming an entry builds its path.
    const std::optional<std::uint64_t> n = io::wholeJson(row.value()[i], orbitStateRowMax(i));
    r[i] = n ? *n : row[i].whole(orbitStateRowMax(i));  // the latter refuses, naming the entry
  }
  return orbitStateOfRow(r);
}

void saveRunFile(const std::filesystem::path& path, const TrappingState& state) {
  io::writeFileAtomically(path, runFileText(state));
}

TrappingState loadRunFile(const std::filesystem::path& path, const RunFileReadOptions& options) {
  json j;
  try {
    j = io::loadJsonFile(path, kMaxRunFileBytes);  // a file that cannot be read: a std::runtime_error naming it
  } catch (const io::BadFile& e) {
    refuse(path.string() + ": corrupt or truncated run file: " + e.what());
  }
  try {
    return runFileFromJson(std::move(j), options);
  } catch (const std::exception& e) {
    refuse(path.string() + ": " + e.what());
  }
}

std::filesystem::path companionRunFile(const std::filesystem::path& run) {
  std::filesystem::path p = run;
  const std::string stem = run.extension() == ".json" ? run.stem().string() : run.filename().string();
  return p.replace_filename(stem + ".short.json");
}

}  // namespace archipelago
