#include "core/tail/TailFile.hpp"

#include <charconv>
#include <climits>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "core/io/AtomicFile.hpp"
#include "core/io/Json.hpp"
#include "core/provenance/Provenance.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/runspec/RunSpecJson.hpp"

namespace archipelago {

using nlohmann::json;

namespace {

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

constexpr std::string_view kCorrupt = "corrupt tail file: ";

[[noreturn]] void refuse(const std::string& what) { throw io::BadFile(what); }
[[noreturn]] void corrupt(const std::string& what) { refuse(std::string(kCorrupt) + what); }

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
      json walker = orbitStateJson(x.walkers[w].state);  // then its ancestor and its alive flag
      walker.push_back(x.walkers[w].ancestor);
      walker.push_back(w < x.alive.size() ? static_cast<unsigned>(x.alive[w]) : 0u);
      walkers.push_back(std::move(walker));
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

/// The sampler's settings ("sampler" and the run's "parameters"), checked as a request.
TailRequest requestFrom(const io::JsonField& root) {
  TailRequest r;
  try {
    r.run = spec::parametersFromJson(root["parameters"].value(), /*complete=*/true);
  } catch (const io::BadFile& e) {
    corrupt(std::string("parameters: ") + e.what());
  }
  const io::JsonField js = root["sampler"];
  r.population = static_cast<std::uint32_t>(js["population"].whole(kMaxTailPopulation));
  r.replicas = static_cast<std::uint32_t>(js["replicas"].whole(kMaxTailReplicas));
  r.firstSteps = js["first"].whole();
  r.maxSteps = js["t_max"].whole();
  r.binsPerLevel = static_cast<std::uint32_t>(js["level_bins"].whole(kMaxBinsPerLevel));
  r.epsilon = js["epsilon"].whole();
  const io::JsonField clones = js["clones"];
  const auto rule = clones.value().is_string() ? cloneRuleByName(clones.value().get<std::string>()) : std::nullopt;
  if (!rule) clones.refuseValue("must be \"perturb\" or \"metropolis\"");
  r.clones = *rule;
  r.metropolisSteps = static_cast<std::uint32_t>(js["metropolis_steps"].whole(kMaxMetropolisSteps));
  r.warmupBlocks = js["warmup"].whole(kMaxWarmupBlocks);
  r.minAncestors = js["min_ancestors"].whole();
  if (auto e = tailRequestError(r)) corrupt("invalid sampler settings: " + *e);
  return r;
}

/// The coefficients and the levels, as this program derives them from the request (in `s`).
void checkCoefficientsAndLevels(const io::JsonField& root, const TailState& s) {
  const io::JsonField jc = root["coefficients"];
  const MapCoefficients stored{jc["A"].integer(), jc["B"].integer(), jc["C"].integer(),
                               static_cast<int>(jc["m"].integer(INT_MIN, INT_MAX))};
  if (!(stored == s.coefficients))
    refuse("tail file coefficients (A, B, C, m) differ from those this program derives from K, xmin, xmax");
  const io::JsonField jl = root["level_blocks"];
  if (!jl.value().is_array() || jl.value().size() != s.levels.size())
    corrupt("the levels differ from those of the sampler's settings");
  for (std::size_t k = 0; k < s.levels.size(); ++k)
    if (jl[k].whole() != s.levels[k]) corrupt("the levels differ from those of the sampler's settings");
}

/// A walker: orbitStateJson's 9 numbers, its ancestor and its alive flag (0 or 1, kept when the replica keeps flags).
void readWalker(const io::JsonField& w, TailReplica& x, bool hasAlive) {
  w.tuple(kOrbitStateRowSize + 2, "[X, Y, block, draws, length, X0, Y0, block0, draws0, ancestor, alive]");
  TailWalker t;
  t.state = orbitStateFromJson(w);
  t.ancestor = static_cast<std::uint32_t>(w[kOrbitStateRowSize].whole(UINT32_MAX));
  const std::uint64_t alive = w[kOrbitStateRowSize + 1].whole(1);
  x.walkers.push_back(t);
  if (hasAlive) x.alive.push_back(static_cast<std::uint8_t>(alive));
}

TailReplica replicaFrom(const io::JsonField& jr, std::size_t levels) {
  TailReplica x;
  x.orbitsDone = jr["orbits_done"].whole();
  x.trials = jr["trials"].whole();
  const io::JsonField lv = jr["levels"];
  for (std::size_t k = 0, n = lv.array(levels); k < n; ++k) {
    const io::JsonField c = lv[k];
    c.tuple(5, "[population, survivors, ancestors, proposals, accepted]");
    x.levels.push_back({c[0].whole(), c[1].whole(), c[2].whole(), c[3].whole(), c[4].whole()});
  }
  // Stage 0 may hold more successes than N (about 2N); a walker takes ~200 bytes of text, so the file's size
  // (kMaxTailFileBytes) bounds their number.
  const io::JsonField jw = jr["walkers"];
  const bool hasAlive = jr["alive"].boolean();
  for (std::size_t k = 0, n = jw.array(); k < n; ++k) readWalker(jw[k], x, hasAlive);
  return x;
}

/// The sampler's state ("state"), into `s` started from its request.
void readState(const io::JsonField& st, TailState& s) {
  s.next = static_cast<std::size_t>(st["next"].whole(s.levels.size()));
  s.age = st["age"].whole();
  const io::JsonField pilot = st["pilot"];
  s.pilotOrbits = pilot["orbits"].whole();
  s.pilotTrials = pilot["trials"].whole();
  s.pilotSuccesses = pilot["successes"].whole();
  s.entryOrbits = st["entry_orbits"].whole();
  const io::JsonField sal = st["steps_at_level"];
  for (std::size_t k = 0, n = sal.array(s.levels.size()); k < n; ++k) s.stepsAtLevel.push_back(sal[k].whole());
  // A slice's replicas (TailSampler.hpp, "slice"); files written before slices existed hold every replica from 0.
  const auto first = st.find("first_replica");
  s.firstReplica = first ? static_cast<std::uint32_t>(first->whole(s.request.replicas - 1)) : 0;
  const io::JsonField reps = st["replicas"];
  const std::size_t n = reps.array(s.request.replicas - s.firstReplica);
  if (n == 0) reps.refuse("must hold one entry per replica of the run or of its slice");
  s.replicas.clear();
  for (std::size_t rep = 0; rep < n; ++rep) s.replicas.push_back(replicaFrom(reps[rep], s.levels.size()));
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
  } catch (const io::BadFile& e) {
    refuse(std::string("corrupt or truncated tail file: ") + e.what());
  }
  if (!j.is_object() || !j.contains("format") || j["format"] != kTailFileFormatName)
    refuse("not an Archipelago tail file (missing \"format\": \"archipelago-tail\")");
  const io::JsonField root(j, "the tail file", kCorrupt);
  const json& version = root["version"].value();
  if (!version.is_number_unsigned() || version.get<std::uint64_t>() != kTailFileFormatVersion)
    refuse("tail file version " + io::describeJson(version) + " is not supported (this program reads version " +
           std::to_string(kTailFileFormatVersion) + ")");
  const std::string stored = root["checksum"].string();
  j.erase("checksum");
  if (stored != io::jsonChecksum(j))
    refuse("tail file was modified after it was written (its checksum does not match its content)");

  TailState s = startTail(requestFrom(root));
  checkCoefficientsAndLevels(root, s);
  s.steps = root["steps"].whole();
  s.elapsedSeconds = root["elapsedSeconds"].nonNegative();
  s.kernel = root["kernel"].string();
  readState(root["state"], s);
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
  } catch (const io::BadFile& e) {
    refuse(path.string() + ": " + e.what());
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
