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

[[noreturn]] void bad(const std::string& what) { throw io::BadFile(what); }

json rectJson(const SessionRect& r) { return json::array({r.xmin, r.xmax, r.ymin, r.ymax}); }

SessionRect rect(const io::JsonField& v) {
  v.tuple(4, "[xmin, xmax, ymin, ymax]");
  const SessionRect r{v[0].real(), v[1].real(), v[2].real(), v[3].real()};
  if (!(r.xmin < r.xmax) || !(r.ymin < r.ymax)) v.refuse("must have xmin < xmax and ymin < ymax");
  return r;
}

std::array<double, 2> point(const io::JsonField& v) {
  v.tuple(2, "[x, y]");
  return {v[0].real(), v[1].real()};
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

Viewport view(const io::JsonField& v) {
  v.keys({"centre", "size"});
  const io::JsonField c = v["centre"], z = v["size"];
  c.tuple(2, "[X, Y] in grid units");
  z.tuple(2, "[\"width\", \"height\"] in grid units");
  const UnitState centre{c[0].whole(FixedPointMap::kOne - 1), c[1].whole(FixedPointMap::kOne - 1)};
  long double size[2];
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string t = z[i].string(64);
    const auto r = std::from_chars(t.data(), t.data() + t.size(), size[i]);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size()) z[i].refuseValue("is not a number");
  }
  try {
    return Viewport::fromUnits(centre, size[0], size[1]);
  } catch (const std::invalid_argument& e) {
    v.refuseDocument(v.name() + ": " + e.what());
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
SessionOrbit orbit(const io::JsonField& v) {
  SessionOrbit o;
  if (v.value().is_array()) {
    o.start = point(v);
    return o;
  }
  v.keys({"start"}, {"steps", "backward", "number"});
  o.start = point(v["start"]);
  if (const auto steps = v.find("steps")) o.steps = steps->whole(limits::kOrbitLength, 1);
  if (const auto backward = v.find("backward")) o.backward = backward->boolean();
  if (const auto number = v.find("number")) o.number = number->whole(kMaxSessionOrbitNumber);
  return o;
}

/// "run": a run file's path, or the run embedded (moved out of `value`, the field's JSON), and whether it was stopped.
void readRun(const io::JsonField& run, json& value, Session& s) {
  run.keys({}, {"file", "embedded", "stopped"});
  if (const auto stopped = run.find("stopped")) s.runStopped = stopped->boolean();
  if (value.size() - value.count("stopped") != 1) run.refuse("must hold exactly one of 'file' and 'embedded'");
  if (const auto f = run.find("file")) {
    const std::string path = f->string(4096);
    if (path.empty()) f->refuse("must not be empty");
    if (path.find('\0') != std::string::npos) f->refuse("must not contain a NUL character");
    s.runFile = std::filesystem::path(path);
    return;
  }
  try {
    s.embeddedRun = runFileFromJson(std::move(value.at("embedded")));
  } catch (const std::exception& e) {
    bad(std::string("run.embedded: ") + e.what());
  }
}

/// "portrait.manifolds": shown, with the periodic orbit whose manifolds they are (null: the fixed point's).
void readManifolds(const io::JsonField& m, SessionPortrait& p) {
  m.keys({}, {"orbit"});
  p.manifolds = true;
  const auto o = m.find("orbit");
  if (!o || o->isNull()) return;
  const std::size_t n = o->array(kMaxSessionPeriodicPoints);
  if (n == 0) o->refuse("must hold the orbit's points (null: the fixed point)");
  for (std::size_t i = 0; i < n; ++i) p.manifoldOrbit.push_back(point((*o)[i]));
}

void readOrbits(const io::JsonField& o, SessionPortrait& p) {
  std::set<std::uint64_t> numbers;
  for (std::size_t i = 0, n = o.array(kMaxSessionOrbits); i < n; ++i) {
    p.orbits.push_back(orbit(o[i]));
    const std::uint64_t number = p.orbits.back().number;
    if (number > 0 && !numbers.insert(number).second) o[i]["number"].refuseValue("is another orbit's number too");
  }
}

void readPeriodic(const io::JsonField& per, SessionPortrait& p) {
  std::size_t total = 0;
  for (std::size_t i = 0, n = per.array(kMaxSessionPeriodicPoints); i < n; ++i) {
    const io::JsonField e = per[i];
    e.keys({"points"}, {"label"});
    SessionPeriodicOverlay overlay;
    if (const auto l = e.find("label")) overlay.label = l->string(256);
    const io::JsonField pts = e["points"];
    total += pts.array(kMaxSessionPeriodicPoints);
    if (total > kMaxSessionPeriodicPoints) per.refuse("holds more than " + std::to_string(kMaxSessionPeriodicPoints) + " points");
    for (std::size_t k = 0; k < pts.value().size(); ++k) overlay.points.push_back(point(pts[k]));
    p.periodic.push_back(std::move(overlay));
  }
}

/// A name of an enum (a portrait mode, a colour map) by its parser: "portrait.mode 'sketch' is not a portrait mode".
template <class Parse>
auto enumValue(const io::JsonField& v, Parse parse, const char* what) {
  const std::string name = v.string(256);
  const auto value = parse(name);
  if (!value) v.refuseDocument(v.name() + " '" + io::shortText(name) + "' is not " + what);
  return *value;
}

void readPortrait(const io::JsonField& p, SessionPortrait& s) {
  p.keys({}, {"history", "current", "mode", "colours", "budget", "orbits", "periodic", "manifolds"});
  if (const auto m = p.find("manifolds"); m && !m->isNull()) readManifolds(*m, s);
  if (const auto h = p.find("history"))
    for (std::size_t i = 0, n = h->array(kMaxSessionHistory); i < n; ++i) s.history.push_back(view((*h)[i]));
  if (const auto c = p.find("current")) {
    s.current = c->whole(kMaxSessionHistory);
    if (s.current >= std::max<std::size_t>(s.history.size(), 1)) c->refuseValue("is not an entry of portrait.history");
  }
  if (const auto m = p.find("mode")) s.mode = enumValue(*m, parsePortraitMode, "a portrait mode");
  if (const auto c = p.find("colours")) s.colours = enumValue(*c, parseColourMap, "a colour map");
  if (const auto b = p.find("budget")) s.budget = b->whole(std::uint64_t{1} << 50);
  if (const auto o = p.find("orbits")) readOrbits(*o, s);
  if (const auto per = p.find("periodic")) readPeriodic(*per, s);
}

void readPlots(const io::JsonField& plots, std::vector<SessionPlotZoom>& zooms) {
  std::set<std::string> seen;
  for (std::size_t i = 0, n = plots.array(kMaxSessionPlots); i < n; ++i) {
    const io::JsonField e = plots[i];
    e.keys({"name", "zoom"});
    SessionPlotZoom z{e["name"].string(256), rect(e["zoom"])};
    if (!seen.insert(z.name).second) bad("plot '" + z.name + "' is zoomed twice");
    zooms.push_back(std::move(z));
  }
}

/// The atlas of the islands, as core/atlas writes and reads it (no recomputation), of the map the session shows.
void readAtlas(const io::JsonField& a, Session& s) {
  try {
    s.atlas = atlasFromJson(a.value().dump());
  } catch (const std::exception& e) {
    bad(std::string("atlas: ") + e.what());
  }
  const MapParameters& map = s.embeddedRun ? s.embeddedRun->params.map : s.spec.parameters.map;
  if (!(s.atlas->request.map == map))
    bad("atlas: of K = " + shortestDecimal(s.atlas->request.map.K) + " in [" + shortestDecimal(s.atlas->request.map.xmin) +
        ", " + shortestDecimal(s.atlas->request.map.xmax) + "), not the session's map (K = " + shortestDecimal(map.K) +
        " in [" + shortestDecimal(map.xmin) + ", " + shortestDecimal(map.xmax) + "))");
}

/// "markovTree": the model's α and b₂, which need the session's atlas.
void readMarkovTree(const io::JsonField& m, Session& s) {
  m.keys({"alpha", "b2"});
  if (!s.atlas) m.refuse("needs the session's atlas");
  SessionMarkovTree t{m["alpha"].real(), m["b2"].real()};
  if (!(t.alpha > 0)) m["alpha"].refuseValue("must be positive");
  if (!(t.b2 > 0)) m["b2"].refuseValue("must be positive");
  s.markovTree = t;
}

/// "tail": the tail file drawn on P_t.
void readTail(const io::JsonField& t, Session& s) {
  t.keys({"file"});
  const std::string path = t["file"].string(4096);
  if (path.empty()) t["file"].refuse("must not be empty");
  if (path.find('\0') != std::string::npos) t["file"].refuse("must not contain a NUL character");
  s.tailFile = std::filesystem::path(path);
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
  if (s.atlas && s.markovTree) j["markovTree"] = {{"alpha", s.markovTree->alpha}, {"b2", s.markovTree->b2}};
  if (s.tailFile) j["tail"] = {{"file", s.tailFile->generic_string()}};
  if (!s.sidePage.empty()) j["sidePage"] = s.sidePage;
  return j.dump(1) + "\n";
}

namespace {
Session sessionFromJson(json j) {
  spec::checkVersionedDocument(j, kSessionFormatName, kSessionFormatVersion, "an", "Archipelago session");
  const io::JsonField root(j, "the session");
  root.keys({"spec"}, {"format", "version", "run", "tab", "portrait", "segment", "plots", "atlas",
                          "markovTree", "tail", "sidePage"});
  Session s;
  try {
    s.spec = parseRunSpec(root["spec"].value().dump());
  } catch (const io::BadFile& e) {
    bad(std::string("spec: ") + e.what());
  }
  if (const auto run = root.find("run"); run && !run->isNull()) readRun(*run, j["run"], s);
  if (const auto tab = root.find("tab")) s.tab = tab->string(256);
  if (const auto p = root.find("portrait")) readPortrait(*p, s.portrait);
  if (const auto seg = root.find("segment"); seg && !seg->isNull()) {
    seg->keys({"rank"}, {"position"});
    s.segmentRank = static_cast<int>((*seg)["rank"].whole(kMaxLongestKept - 1));
    if (const auto pos = seg->find("position")) s.segmentPosition = pos->whole(std::uint64_t{1} << 62);
  }
  if (const auto plots = root.find("plots")) readPlots(*plots, s.plots);
  if (const auto a = root.find("atlas")) readAtlas(*a, s);
  if (const auto m = root.find("markovTree")) readMarkovTree(*m, s);
  if (const auto t = root.find("tail")) readTail(*t, s);
  if (const auto page = root.find("sidePage")) s.sidePage = page->string(256);
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
  } catch (const io::BadFile& e) {
    bad(path.string() + ": " + e.what());
  } catch (const std::runtime_error& e) {  // a file that cannot be read, its message naming it
    bad(e.what());
  }
  Session s;
  try {
    s = sessionFromJson(std::move(j));
  } catch (const io::BadFile& e) {
    bad(path.string() + ": " + e.what());
  }
  if (s.runFile && s.runFile->is_relative()) s.runFile = path.parent_path() / *s.runFile;
  if (s.tailFile && s.tailFile->is_relative()) s.tailFile = path.parent_path() / *s.tailFile;
  if (s.runFile && !std::filesystem::is_regular_file(*s.runFile))
    bad(path.string() + ": its run file " + s.runFile->string() + " does not exist");
  return s;
}

}  // namespace archipelago
