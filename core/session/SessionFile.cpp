#include "core/session/SessionFile.hpp"

#include <algorithm>
#include <cmath>
#include <charconv>
#include <set>
#include <stdexcept>

#include "core/atlas/AtlasExport.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/Json.hpp"
#include "core/limits/Limits.hpp"
#include "core/runfile/RunFile.hpp"
#include "core/runspec/RunSpecJson.hpp"

namespace archipelago {

namespace {

using nlohmann::json;

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }

void onlyKeys(const json& j, const std::string& where, std::initializer_list<const char*> keys) {
  if (!j.is_object()) bad(where + " must be a JSON object");
  const std::set<std::string> known(keys.begin(), keys.end());
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key())) bad("unknown key '" + io::shortText(it.key()) + "' in " + where);
}

double finite(const json& v, const std::string& key) {
  if (!v.is_number()) bad(key + " must be a number, not " + io::describeJson(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) bad(key + " must be finite");
  return d;
}

std::uint64_t whole(const json& v, const std::string& key, std::uint64_t max) {
  const std::optional<std::uint64_t> n = io::wholeJson(v, max);  // the documents' one rule of whole numbers
  if (!n) bad(key + " = " + io::describeJson(v) + " must be a whole number in [0, " + std::to_string(max) + "]");
  return *n;
}

std::string string(const json& v, const std::string& key, std::size_t maxLength = 256) {
  if (!v.is_string()) bad(key + " must be a string");
  std::string s = v.get<std::string>();
  if (s.size() > maxLength) bad(key + " is longer than " + std::to_string(maxLength) + " characters");
  return s;
}

const json& array(const json& v, const std::string& key, std::size_t maxSize) {
  if (!v.is_array()) bad(key + " must be an array");
  if (v.size() > maxSize) bad(key + " has " + std::to_string(v.size()) + " entries; at most " + std::to_string(maxSize));
  return v;
}

json rectJson(const SessionRect& r) { return json::array({r.xmin, r.xmax, r.ymin, r.ymax}); }

SessionRect rect(const json& v, const std::string& key) {
  array(v, key, 4);
  if (v.size() != 4) bad(key + " must be [xmin, xmax, ymin, ymax]");
  SessionRect r{finite(v[0], key + "[0]"), finite(v[1], key + "[1]"), finite(v[2], key + "[2]"), finite(v[3], key + "[3]")};
  if (!(r.xmin < r.xmax) || !(r.ymin < r.ymax)) bad(key + " must have xmin < xmax and ymin < ymax");
  return r;
}

std::array<double, 2> point(const json& v, const std::string& key) {
  if (!v.is_array() || v.size() != 2) bad(key + " must be [x, y]");
  return {finite(v[0], key + "[0]"), finite(v[1], key + "[1]")};
}

/// 21 significant digits round-trip a long double's 64-bit mantissa; std::to_chars never uses the locale (a
/// decimal comma once made sessions unreadable in another locale, issue #23).
std::string longDoubleText(long double v) {
  char text[64];
  const auto r = std::to_chars(text, text + sizeof text, v, std::chars_format::general, 21);
  return std::string(text, r.ptr);
}

json viewJson(const Viewport& v) {
  return {{"centre", json::array({v.centre().X, v.centre().Y})},
          {"size", json::array({longDoubleText(v.widthUnits()), longDoubleText(v.heightUnits())})}};
}

Viewport view(const json& v, const std::string& key) {
  onlyKeys(v, key, {"centre", "size"});
  const auto c = v.find("centre"), z = v.find("size");
  if (c == v.end() || z == v.end()) bad(key + " needs 'centre' and 'size'");
  if (!c->is_array() || c->size() != 2) bad(key + ".centre must be [X, Y] in grid units");
  if (!z->is_array() || z->size() != 2) bad(key + ".size must be [\"width\", \"height\"] in grid units");
  const UnitState centre{whole((*c)[0], key + ".centre[0]", FixedPointMap::kOne - 1),
                         whole((*c)[1], key + ".centre[1]", FixedPointMap::kOne - 1)};
  long double size[2];
  for (int i = 0; i < 2; ++i) {
    const std::string k = key + ".size[" + std::to_string(i) + "]";
    const std::string t = string((*z)[i], k, 64);
    const auto r = std::from_chars(t.data(), t.data() + t.size(), size[i]);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
      bad(k + " = \"" + io::shortText(t) + "\" is not a number");
  }
  try {
    return Viewport::fromUnits(centre, size[0], size[1]);
  } catch (const std::invalid_argument& e) {
    bad(key + ": " + e.what());
  }
}

json pointsJson(const std::vector<std::array<double, 2>>& points) {
  json a = json::array();
  for (const auto& p : points) a.push_back(json::array({p[0], p[1]}));
  return a;
}

json orbitJson(const SessionOrbit& o) {
  return {{"start", json::array({o.start[0], o.start[1]})}, {"steps", o.steps}, {"backward", o.backward}, {"number", o.number}};
}

/// An entry of portrait.orbits: {"start", "steps", "backward", "number"}, or an old session's [x, y].
SessionOrbit orbit(const json& v, const std::string& key) {
  SessionOrbit o;
  if (v.is_array()) {
    o.start = point(v, key);
    return o;
  }
  onlyKeys(v, key, {"start", "steps", "backward", "number"});
  const auto start = v.find("start");
  if (start == v.end()) bad(key + " has no 'start'");
  o.start = point(*start, key + ".start");
  if (const auto steps = v.find("steps"); steps != v.end()) {
    o.steps = whole(*steps, key + ".steps", limits::kOrbitLength);
    if (o.steps < 1) bad(key + ".steps = 0 must be a whole number in [1, " + std::to_string(limits::kOrbitLength) + "]");
  }
  if (const auto backward = v.find("backward"); backward != v.end()) {
    if (!backward->is_boolean()) bad(key + ".backward must be true or false");
    o.backward = backward->get<bool>();
  }
  if (const auto number = v.find("number"); number != v.end()) o.number = whole(*number, key + ".number", kMaxSessionOrbitNumber);
  return o;
}

}  // namespace

std::string sessionText(const Session& s) {
  json j = json::object();
  j["format"] = kSessionFormatName;
  j["version"] = kSessionFormatVersion;
  j["spec"] = json::parse(runSpecJson(s.spec));
  if (s.embeddedRun) j["run"] = {{"embedded", json::parse(runFileText(*s.embeddedRun))}};
  else if (s.runFile) j["run"] = {{"file", s.runFile->generic_string()}};
  else j["run"] = nullptr;
  if (s.runStopped && !j["run"].is_null()) j["run"]["stopped"] = true;
  j["tab"] = s.tab;
  json portrait = json::object();
  portrait["history"] = json::array();
  for (const Viewport& v : s.portrait.history) portrait["history"].push_back(viewJson(v));
  portrait["current"] = s.portrait.current;
  portrait["mode"] = std::string(toString(s.portrait.mode));
  portrait["colours"] = std::string(toString(s.portrait.colours));
  portrait["budget"] = s.portrait.budget;
  portrait["orbits"] = json::array();
  for (const SessionOrbit& o : s.portrait.orbits) portrait["orbits"].push_back(orbitJson(o));
  portrait["periodic"] = json::array();
  for (const SessionPeriodicOverlay& o : s.portrait.periodic)
    portrait["periodic"].push_back({{"label", o.label}, {"points", pointsJson(o.points)}});
  if (s.portrait.manifolds)
    portrait["manifolds"] = {{"orbit", s.portrait.manifoldOrbit.empty() ? json(nullptr) : pointsJson(s.portrait.manifoldOrbit)}};
  j["portrait"] = portrait;
  j["segment"] = s.segmentRank < 0 ? json(nullptr) : json{{"rank", s.segmentRank}, {"position", s.segmentPosition}};
  j["plots"] = json::array();
  for (const SessionPlotZoom& z : s.plots) j["plots"].push_back({{"name", z.name}, {"zoom", rectJson(z.zoom)}});
  if (s.atlas) j["atlas"] = json::parse(atlasJson(*s.atlas));
  return j.dump(1) + "\n";
}

namespace {
Session sessionFromJson(json j) {
  spec::checkVersionedDocument(j, kSessionFormatName, kSessionFormatVersion, "an", "Archipelago session");
  onlyKeys(j, "the session", {"format", "version", "spec", "run", "tab", "portrait", "segment", "plots", "atlas"});

  Session s;
  const auto spec = j.find("spec");
  if (spec == j.end()) bad("the session has no 'spec'");
  try {
    s.spec = parseRunSpec(spec->dump());
  } catch (const std::invalid_argument& e) {
    bad(std::string("spec: ") + e.what());
  }

  if (const auto run = j.find("run"); run != j.end() && !run->is_null()) {
    onlyKeys(*run, "run", {"file", "embedded", "stopped"});
    if (const auto stopped = run->find("stopped"); stopped != run->end()) {
      if (!stopped->is_boolean()) bad("run.stopped must be true or false");
      s.runStopped = stopped->get<bool>();
    }
    if (run->size() - run->count("stopped") != 1) bad("run must hold exactly one of 'file' and 'embedded'");
    if (const auto f = run->find("file"); f != run->end()) {
      const std::string path = string(*f, "run.file", 4096);
      if (path.empty()) bad("run.file must not be empty");
      if (path.find('\0') != std::string::npos) bad("run.file must not contain a NUL character");
      s.runFile = std::filesystem::path(path);
    } else {
      try {
        s.embeddedRun = runFileFromJson(std::move(run->at("embedded")));
      } catch (const std::exception& e) {
        bad(std::string("run.embedded: ") + e.what());
      }
    }
  }

  if (const auto tab = j.find("tab"); tab != j.end()) s.tab = string(*tab, "tab");

  if (const auto p = j.find("portrait"); p != j.end()) {
    onlyKeys(*p, "portrait", {"history", "current", "mode", "colours", "budget", "orbits", "periodic", "manifolds"});
    if (const auto m = p->find("manifolds"); m != p->end() && !m->is_null()) {
      onlyKeys(*m, "portrait.manifolds", {"orbit"});
      s.portrait.manifolds = true;
      if (const auto o = m->find("orbit"); o != m->end() && !o->is_null()) {
        array(*o, "portrait.manifolds.orbit", kMaxSessionPeriodicPoints);
        if (o->empty()) bad("portrait.manifolds.orbit must hold the orbit's points (null: the fixed point)");
        for (std::size_t i = 0; i < o->size(); ++i)
          s.portrait.manifoldOrbit.push_back(point((*o)[i], "portrait.manifolds.orbit[" + std::to_string(i) + "]"));
      }
    }
    if (const auto h = p->find("history"); h != p->end()) {
      array(*h, "portrait.history", kMaxSessionHistory);
      for (std::size_t i = 0; i < h->size(); ++i)
        s.portrait.history.push_back(view((*h)[i], "portrait.history[" + std::to_string(i) + "]"));
    }
    if (const auto c = p->find("current"); c != p->end()) {
      s.portrait.current = whole(*c, "portrait.current", kMaxSessionHistory);
      if (s.portrait.current >= std::max<std::size_t>(s.portrait.history.size(), 1))
        bad("portrait.current = " + std::to_string(s.portrait.current) + " is not an entry of portrait.history");
    }
    if (const auto m = p->find("mode"); m != p->end()) {
      const std::string name = string(*m, "portrait.mode");
      const auto mode = parsePortraitMode(name);
      if (!mode) bad("portrait.mode '" + name + "' is not a portrait mode");
      s.portrait.mode = *mode;
    }
    if (const auto c = p->find("colours"); c != p->end()) {
      const std::string name = string(*c, "portrait.colours");
      const auto colours = parseColourMap(name);
      if (!colours) bad("portrait.colours '" + name + "' is not a colour map");
      s.portrait.colours = *colours;
    }
    if (const auto b = p->find("budget"); b != p->end()) s.portrait.budget = whole(*b, "portrait.budget", std::uint64_t{1} << 50);
    if (const auto o = p->find("orbits"); o != p->end()) {
      array(*o, "portrait.orbits", kMaxSessionOrbits);
      std::set<std::uint64_t> numbers;
      for (std::size_t i = 0; i < o->size(); ++i) {
        const std::string key = "portrait.orbits[" + std::to_string(i) + "]";
        s.portrait.orbits.push_back(orbit((*o)[i], key));
        const std::uint64_t n = s.portrait.orbits.back().number;
        if (n > 0 && !numbers.insert(n).second) bad(key + ".number = " + std::to_string(n) + " is another orbit's number too");
      }
    }
    if (const auto per = p->find("periodic"); per != p->end()) {
      array(*per, "portrait.periodic", kMaxSessionPeriodicPoints);
      std::size_t total = 0;
      for (std::size_t i = 0; i < per->size(); ++i) {
        const std::string key = "portrait.periodic[" + std::to_string(i) + "]";
        const json& e = (*per)[i];
        onlyKeys(e, key, {"label", "points"});
        SessionPeriodicOverlay overlay;
        if (const auto l = e.find("label"); l != e.end()) overlay.label = string(*l, key + ".label");
        const auto pts = e.find("points");
        if (pts == e.end()) bad(key + " has no 'points'");
        array(*pts, key + ".points", kMaxSessionPeriodicPoints);
        total += pts->size();
        if (total > kMaxSessionPeriodicPoints)
          bad("portrait.periodic holds more than " + std::to_string(kMaxSessionPeriodicPoints) + " points");
        for (std::size_t k = 0; k < pts->size(); ++k)
          overlay.points.push_back(point((*pts)[k], key + ".points[" + std::to_string(k) + "]"));
        s.portrait.periodic.push_back(std::move(overlay));
      }
    }
  }

  if (const auto seg = j.find("segment"); seg != j.end() && !seg->is_null()) {
    onlyKeys(*seg, "segment", {"rank", "position"});
    const auto rank = seg->find("rank");
    if (rank == seg->end()) bad("segment has no 'rank'");
    s.segmentRank = static_cast<int>(whole(*rank, "segment.rank", kMaxLongestKept - 1));
    if (const auto pos = seg->find("position"); pos != seg->end())
      s.segmentPosition = whole(*pos, "segment.position", std::uint64_t{1} << 62);
  }

  if (const auto plots = j.find("plots"); plots != j.end()) {
    array(*plots, "plots", kMaxSessionPlots);
    std::set<std::string> seen;
    for (std::size_t i = 0; i < plots->size(); ++i) {
      const std::string key = "plots[" + std::to_string(i) + "]";
      const json& e = (*plots)[i];
      onlyKeys(e, key, {"name", "zoom"});
      if (!e.contains("name") || !e.contains("zoom")) bad(key + " needs 'name' and 'zoom'");
      SessionPlotZoom z{string(e["name"], key + ".name"), rect(e["zoom"], key + ".zoom")};
      if (!seen.insert(z.name).second) bad("plot '" + z.name + "' is zoomed twice");
      s.plots.push_back(std::move(z));
    }
  }

  // The atlas of the islands, as core/atlas writes and reads it (no recomputation), of the map the session shows.
  if (const auto a = j.find("atlas"); a != j.end()) {
    try {
      s.atlas = atlasFromJson(a->dump());
    } catch (const std::exception& e) {
      bad(std::string("atlas: ") + e.what());
    }
    const MapParameters& map = s.embeddedRun ? s.embeddedRun->params.map : s.spec.parameters.map;
    if (!(s.atlas->request.map == map))
      bad("atlas: of K = " + shortestDecimal(s.atlas->request.map.K) + " in [" + shortestDecimal(s.atlas->request.map.xmin) +
          ", " + shortestDecimal(s.atlas->request.map.xmax) + "), not the session's map (K = " + shortestDecimal(map.K) +
          " in [" + shortestDecimal(map.xmin) + ", " + shortestDecimal(map.xmax) + "))");
  }
  return s;
}

}  // namespace

Session parseSession(std::string_view text) { return sessionFromJson(io::parseJson(text)); }

void saveSession(const std::filesystem::path& path, const Session& session) {
  io::writeFileAtomically(path, sessionText(session));
}

Session loadSession(const std::filesystem::path& path) {
  json j;
  try {
    j = io::loadJsonFile(path, kMaxSessionFileBytes);
  } catch (const std::runtime_error& e) {
    bad(e.what());
  } catch (const std::invalid_argument& e) {
    bad(path.string() + ": " + e.what());
  }
  Session s;
  try {
    s = sessionFromJson(std::move(j));
  } catch (const std::invalid_argument& e) {
    bad(path.string() + ": " + e.what());
  }
  if (s.runFile && s.runFile->is_relative()) s.runFile = path.parent_path() / *s.runFile;
  if (s.runFile && !std::filesystem::is_regular_file(*s.runFile))
    bad(path.string() + ": its run file " + s.runFile->string() + " does not exist");
  return s;
}

}  // namespace archipelago
