#include "core/tail/TailFile.hpp"

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/io/AtomicFile.hpp"
#include "core/io/Json.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/runspec/RunSpecJson.hpp"

namespace archipelago {

using nlohmann::json;

namespace {

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

[[noreturn]] void corrupt(const std::string& what) { throw std::runtime_error("corrupt tail file: " + what); }

const json& field(const json& j, const char* key) {
  if (!j.is_object()) corrupt(std::string("expected an object holding '") + key + "'");
  const auto it = j.find(key);
  if (it == j.end()) corrupt(std::string("missing field '") + key + "'");
  return *it;
}

std::uint64_t valueU64(const json& v, const std::string& what) {
  const std::optional<std::uint64_t> n = io::wholeJson(v);  // the documents' one rule of whole numbers
  if (!n) corrupt(what + " must be a non-negative integer");
  return *n;
}
std::uint64_t u64(const json& j, const char* key) { return valueU64(field(j, key), std::string("field '") + key + "'"); }

std::uint64_t bounded(const json& j, const char* key, std::uint64_t max) {
  const std::uint64_t v = u64(j, key);
  if (v > max) corrupt(std::string("field '") + key + "' = " + std::to_string(v) + " is out of range");
  return v;
}

json samplerJson(const TailRequest& r) {
  return {{"population", r.population},   {"replicas", r.replicas},
          {"first", r.firstSteps},        {"t_max", r.maxSteps},
          {"level_bins", r.binsPerLevel}, {"epsilon", r.epsilon},
          {"clones", cloneRuleName(r.clones)}, {"metropolis_steps", r.metropolisSteps},
          {"warmup", r.warmupBlocks},     {"min_ancestors", r.minAncestors}};
}

json stateJson(const TailState& s) {
  json replicas = json::array();
  for (const TailReplica& x : s.replicas) {
    json levels = json::array();
    for (const TailLevelCount& c : x.levels)
      levels.push_back(json::array({c.population, c.survivors, c.ancestors, c.proposals, c.accepted}));
    json walkers = json::array();
    for (std::size_t w = 0; w < x.walkers.size(); ++w) {
      const OrbitState& o = x.walkers[w].state;
      walkers.push_back(json::array({o.z.X, o.z.Y, o.block, o.draws, o.length, o.start.z.X, o.start.z.Y, o.start.block,
                                     o.start.draws, x.walkers[w].ancestor,
                                     w < x.alive.size() ? static_cast<unsigned>(x.alive[w]) : 0u}));
    }
    replicas.push_back({{"orbits_done", x.orbitsDone}, {"trials", x.trials}, {"levels", levels}, {"walkers", walkers},
                        {"alive", !x.alive.empty()}});
  }
  return {{"next", s.next},
          {"age", s.age},
          {"first_replica", s.firstReplica},
          {"pilot", {{"orbits", s.pilotOrbits}, {"trials", s.pilotTrials}, {"successes", s.pilotSuccesses}}},
          {"entry_orbits", s.entryOrbits},
          {"steps_at_level", s.stepsAtLevel},
          {"replicas", replicas}};
}

UnitState unitState(const json& a, std::size_t i) {
  const UnitState z{valueU64(a[i], "a walker's X"), valueU64(a[i + 1], "a walker's Y")};
  if (z.X >= fixedpoint::kOne || z.Y >= fixedpoint::kOne) corrupt("a walker's state lies outside [0, 2^52)");
  return z;
}

}  // namespace

std::string tailFileText(const TailState& s) {
  const TailResult result = tailResult(s);
  json j;
  j["format"] = kTailFileFormatName;
  j["version"] = kTailFileFormatVersion;
  j["program"] = programDescription();
  j["parameters"] = spec::parametersJson(s.request.run);
  j["coefficients"] = {{"A", s.coefficients.A}, {"B", s.coefficients.B}, {"C", s.coefficients.C},
                       {"m", s.coefficients.m}};
  j["sampler"] = samplerJson(s.request);
  j["level_blocks"] = s.levels;
  j["finished"] = s.finished();
  j["steps"] = s.steps;
  j["elapsedSeconds"] = s.elapsedSeconds;
  j["kernel"] = s.kernel;
  json levels = json::array();
  for (const TailLevelResult& L : result.levels) {
    json replicaP = json::array();
    for (double p : L.replicaP) replicaP.push_back(p);
    levels.push_back({{"t", L.t},
                      {"P", L.P},
                      {"P_error", number(L.PError)},
                      {"survivors", L.survivors},
                      {"ancestors", L.ancestors},
                      {"reliable", L.reliable},
                      {"fewest_ancestors", L.fewestAncestors},
                      {"population", L.population},
                      {"P_replicas", replicaP},
                      {"steps", L.steps},
                      {"acceptance", number(L.acceptance)}});
  }
  j["levels"] = levels;
  json exponents = json::array();
  for (const TailExponent& e : result.exponents)
    exponents.push_back({{"t", e.t}, {"t_from", e.tFrom}, {"t_to", e.tTo}, {"gamma", e.gamma},
                         {"gamma_error", number(e.gammaError)}});
  j["exponents"] = exponents;
  j["state"] = stateJson(s);
  j["checksum"] = io::jsonChecksum(j);
  return j.dump(1) + "\n";
}

TailState parseTailFile(const std::string& text) {
  json j;
  try {
    j = io::parseJson(text);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("corrupt or truncated tail file: ") + e.what());
  }
  if (!j.is_object() || !j.contains("format") || j["format"] != kTailFileFormatName)
    throw std::runtime_error("not an Archipelago tail file (missing \"format\": \"archipelago-tail\")");
  const json& version = field(j, "version");
  if (!version.is_number_unsigned() || version.get<std::uint64_t>() != kTailFileFormatVersion)
    throw std::runtime_error("tail file version " + io::describeJson(version) + " is not supported (this program reads version " +
                             std::to_string(kTailFileFormatVersion) + ")");
  const json& sum = field(j, "checksum");
  if (!sum.is_string()) corrupt("field 'checksum' must be a string");
  const std::string stored = sum.get<std::string>();
  j.erase("checksum");
  if (stored != io::jsonChecksum(j))
    throw std::runtime_error("tail file was modified after it was written (its checksum does not match its content)");

  TailRequest r;
  try {
    r.run = spec::parametersFromJson(field(j, "parameters"), /*complete=*/true);
  } catch (const std::invalid_argument& e) {
    corrupt(std::string("parameters: ") + e.what());
  }
  const json& js = field(j, "sampler");
  r.population = static_cast<std::uint32_t>(bounded(js, "population", kMaxTailPopulation));
  r.replicas = static_cast<std::uint32_t>(bounded(js, "replicas", kMaxTailReplicas));
  r.firstSteps = u64(js, "first");
  r.maxSteps = u64(js, "t_max");
  r.binsPerLevel = static_cast<std::uint32_t>(bounded(js, "level_bins", kMaxBinsPerLevel));
  r.epsilon = u64(js, "epsilon");
  const json& clones = field(js, "clones");
  const auto rule = clones.is_string() ? cloneRuleByName(clones.get<std::string>()) : std::nullopt;
  if (!rule) corrupt("field 'clones' must be \"perturb\" or \"metropolis\"");
  r.clones = *rule;
  r.metropolisSteps = static_cast<std::uint32_t>(bounded(js, "metropolis_steps", kMaxMetropolisSteps));
  r.warmupBlocks = bounded(js, "warmup", kMaxWarmupBlocks);
  r.minAncestors = u64(js, "min_ancestors");
  if (auto e = tailRequestError(r)) corrupt("invalid sampler settings: " + *e);

  TailState s = startTail(r);
  const json& jc = field(j, "coefficients");
  const auto i64 = [&](const char* key) {
    const json& v = field(jc, key);
    if (!v.is_number_integer()) corrupt(std::string("field '") + key + "' must be an integer");
    return v.get<std::int64_t>();
  };
  const MapCoefficients stored_{i64("A"), i64("B"), i64("C"), static_cast<int>(i64("m"))};
  if (!(stored_ == s.coefficients))
    throw std::runtime_error("tail file coefficients (A, B, C, m) differ from those this program derives from K, xmin, xmax");
  const json& jl = field(j, "level_blocks");
  if (!jl.is_array() || jl.size() != s.levels.size()) corrupt("the levels differ from those of the sampler's settings");
  for (std::size_t k = 0; k < s.levels.size(); ++k)
    if (valueU64(jl[k], "a level") != s.levels[k]) corrupt("the levels differ from those of the sampler's settings");
  s.steps = u64(j, "steps");
  const json& elapsed = field(j, "elapsedSeconds");
  if (!elapsed.is_number() || !(elapsed.get<double>() >= 0)) corrupt("field 'elapsedSeconds' must be a number >= 0");
  s.elapsedSeconds = elapsed.get<double>();
  const json& kernel = field(j, "kernel");
  if (!kernel.is_string()) corrupt("field 'kernel' must be a string");
  s.kernel = kernel.get<std::string>();

  const json& st = field(j, "state");
  s.next = static_cast<std::size_t>(bounded(st, "next", s.levels.size()));
  s.age = u64(st, "age");
  const json& pilot = field(st, "pilot");
  s.pilotOrbits = u64(pilot, "orbits");
  s.pilotTrials = u64(pilot, "trials");
  s.pilotSuccesses = u64(pilot, "successes");
  s.entryOrbits = u64(st, "entry_orbits");
  const json& sal = field(st, "steps_at_level");
  if (!sal.is_array() || sal.size() > s.levels.size()) corrupt("field 'steps_at_level' must list one count per level reached");
  for (const json& v : sal) s.stepsAtLevel.push_back(valueU64(v, "a level's steps"));
  // A slice's replicas (TailSampler.hpp, "slice"); files written before slices existed hold every replica from 0.
  s.firstReplica = st.contains("first_replica")
                       ? static_cast<std::uint32_t>(bounded(st, "first_replica", s.request.replicas - 1))
                       : 0;
  const json& reps = field(st, "replicas");
  if (!reps.is_array() || reps.empty() || reps.size() > s.request.replicas - s.firstReplica)
    corrupt("expected one entry per replica of the run or of its slice");
  s.replicas.resize(reps.size());
  for (std::size_t rep = 0; rep < s.replicas.size(); ++rep) {
    TailReplica& x = s.replicas[rep];
    const json& jr = reps[rep];
    x.orbitsDone = u64(jr, "orbits_done");
    x.trials = u64(jr, "trials");
    const json& lv = field(jr, "levels");
    if (!lv.is_array() || lv.size() > s.levels.size()) corrupt("a replica lists more levels than the sampler has");
    for (const json& c : lv) {
      if (!c.is_array() || c.size() != 5) corrupt("a level count must be [population, survivors, ancestors, proposals, accepted]");
      x.levels.push_back({valueU64(c[0], "a count"), valueU64(c[1], "a count"), valueU64(c[2], "a count"), valueU64(c[3], "a count"),
                          valueU64(c[4], "a count")});
    }
    const json& jw = field(jr, "walkers");
    // Stage 0 may hold more successes than N (about 2N); a walker takes ~200 bytes of text, so the file's size
    // (kMaxTailFileBytes) bounds their number.
    if (!jw.is_array()) corrupt("a replica's walkers must be an array");
    const json& hasAlive = field(jr, "alive");
    if (!hasAlive.is_boolean()) corrupt("field 'alive' must be true or false");
    for (const json& w : jw) {
      if (!w.is_array() || w.size() != 11) corrupt("a walker must have 11 non-negative integers");
      TailWalker t;
      t.state.z = unitState(w, 0);
      t.state.block = valueU64(w[2], "a walker's block");
      t.state.draws = valueU64(w[3], "a walker's draws");
      t.state.length = valueU64(w[4], "a walker's age");
      t.state.start = {unitState(w, 5), valueU64(w[7], "a walker's start block"), valueU64(w[8], "a walker's start draws")};
      const std::uint64_t ancestor = valueU64(w[9], "a walker's ancestor");
      if (ancestor > UINT32_MAX) corrupt("a walker's ancestor is out of range");
      t.ancestor = static_cast<std::uint32_t>(ancestor);
      const std::uint64_t alive = valueU64(w[10], "a walker's alive flag");
      if (alive > 1) corrupt("a walker's alive flag must be 0 or 1");
      x.walkers.push_back(t);
      if (hasAlive.get<bool>()) x.alive.push_back(static_cast<std::uint8_t>(alive));
    }
  }
  if (auto e = tailStateError(s)) corrupt(*e);
  return s;
}

void saveTailFile(const std::filesystem::path& path, const TailState& state) {
  io::writeFileAtomically(path, tailFileText(state));
}

bool isTailFile(const std::filesystem::path& path) {
  try {
    const json j = io::loadJsonFile(path, kMaxTailFileBytes);
    return j.is_object() && j.contains("format") && j["format"] == kTailFileFormatName;
  } catch (const std::exception&) {
    return false;
  }
}

TailState loadTailFile(const std::filesystem::path& path) {
  std::string text;
  try {
    text = io::readRegularFile(path, kMaxTailFileBytes);
    io::checkParseMemory(text.size(), path.string());
    return parseTailFile(text);
  } catch (const std::exception& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

namespace {
std::string csvNumber(double v) {
  if (!std::isfinite(v)) return std::string();  // an undefined cell
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, 17);
  return std::string(buffer, r.ptr);
}
}  // namespace

std::string tailCsvText(const TailState& s, const TailResult& result) {
  std::string out;
  const auto line = [&](const std::string& key, const std::string& value) { out += "# " + key + ": " + value + "\n"; };
  line("program", programDescription());
  const json parameters = spec::parametersJson(s.request.run);
  for (const char* key : {"K", "xmin", "xmax", "Xr", "q", "seed"}) line(key, parameters.at(key).dump());
  const json sampler = samplerJson(s.request);
  for (auto it = sampler.begin(); it != sampler.end(); ++it)
    line(it.key(), it->is_string() ? it->get<std::string>() : it->dump());
  line("steps", std::to_string(s.steps));
  line("finished", s.finished() ? "true" : "false");
  out += "t,P,P_error,survivors,ancestors,fewest_ancestors,reliable,steps\n";
  for (const TailLevelResult& L : result.levels)
    out += csvNumber(L.t) + "," + csvNumber(L.P) + "," + csvNumber(L.PError) + "," + std::to_string(L.survivors) + "," +
           std::to_string(L.ancestors) + "," + std::to_string(L.fewestAncestors) + "," + (L.reliable ? "1" : "0") +
           "," + csvNumber(L.steps) + "\n";
  out += "\nt,t_from,t_to,gamma,gamma_error\n";
  for (const TailExponent& e : result.exponents)
    out += csvNumber(e.t) + "," + csvNumber(e.tFrom) + "," + csvNumber(e.tTo) + "," + csvNumber(e.gamma) + "," +
           csvNumber(e.gammaError) + "\n";
  return out;
}

}  // namespace archipelago
