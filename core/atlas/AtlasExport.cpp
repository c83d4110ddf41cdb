#include "core/atlas/AtlasExport.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <numeric>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/io/AtomicFile.hpp"
#include "core/io/Json.hpp"
#include "core/io/NumberText.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/provenance/Provenance.hpp"

namespace archipelago {

namespace {
using json = nlohmann::ordered_json;

/// A finite long double as the nearest double; NaN and infinities as null.
json num(long double v) { return std::isfinite(v) ? json(static_cast<double>(v)) : json(nullptr); }

json pointJson(PhysicalPoint p) { return json::array({num(p.x), num(p.y)}); }

Provenance atlasProvenance(const Atlas& a) {
  Provenance p = mapProvenance(a.request.map);
  p.add("Output", std::string("atlas of the islands around islands"));
  p.add("Depth", std::to_string(a.request.depth));
  p.add("Max period", std::to_string(a.request.maxPeriod));
  p.add("Min area", a.request.minArea);
  p.add("Iterations", std::to_string(a.request.iterations));
  p.add("Digits threshold", a.request.digitsThreshold);
  p.add("Scan points", std::to_string(a.request.scanPoints));
  p.add("Scan steps", a.request.scanSteps);
  p.add("Bisections", std::to_string(a.request.bisections));
  if (a.request.timeBudget > 0) p.add("Time budget (s)", a.request.timeBudget);
  return p;
}

std::string rationalText(const std::optional<Rational>& r) { return r ? toString(*r) : ""; }

std::string text(long double v, int digits = 17) {
  if (!std::isfinite(v)) return "";
  return io::formatC("%.*Lg", digits, v);
}
}  // namespace

std::string atlasJson(const Atlas& a) {
  json j;
  j["format"] = "archipelago atlas";
  j["format_version"] = kAtlasFormatVersion;
  j["program"] = programDescription();
  json prov = json::object();
  for (const auto& [k, v] : atlasProvenance(a).fields) prov[k] = v;
  j["provenance"] = prov;
  j["map"] = {{"K", a.request.map.K}, {"xmin", a.request.map.xmin}, {"xmax", a.request.map.xmax}};
  j["request"] = {{"depth", a.request.depth},
                  {"max_period", a.request.maxPeriod},
                  {"min_area", a.request.minArea},
                  {"iterations", a.request.iterations},
                  {"digits_threshold", a.request.digitsThreshold},
                  {"scan_points", a.request.scanPoints},
                  {"scan_steps", a.request.scanSteps},
                  {"bisections", a.request.bisections},
                  {"time_budget", a.request.timeBudget}};
  j["cancelled"] = a.cancelled;
  j["stop_reason"] = a.stopReason;
  j["seconds"] = a.seconds;
  json nodes = json::array();
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const AtlasNode& n = a.nodes[i];
    json o;
    o["index"] = i;
    o["parent"] = n.parent;
    o["level"] = n.level;
    o["path"] = atlasPath(a, static_cast<int>(i));
    o["period"] = n.period;
    o["about_parent"] = n.aboutParent ? json(toString(*n.aboutParent)) : json(nullptr);
    o["centre"] = pointJson(n.centre);
    o["symmetry_line"] = n.onS1 ? "S1" : "S2";
    o["residue"] = num(n.orbit.residue);
    o["sense"] = n.sense;
    o["measured"] = n.measured;
    o["scan_range"] = num(n.scanRange);
    json b;
    b["found"] = n.boundaryFound;
    if (!n.boundaryFound) b["failure"] = n.boundaryFailure;
    else {
      b["point"] = pointJson(n.boundaryPoint);
      b["rotation"] = n.boundaryRotation;
      b["digits"] = n.boundaryDigits;
      b["bracket"] = num(n.gap);
    }
    o["boundary"] = b;
    o["area"] = num(n.area);
    o["area_error"] = num(n.areaError);
    o["area_lower"] = num(n.areaLower);
    o["area_upper"] = num(n.areaUpper);
    o["polygon_error"] = num(n.polygonError);
    o["area_points"] = n.areaPoints;
    o["islands_area"] = num(n.area * static_cast<long double>(n.period));
    json f;
    f["found"] = n.flux.found;
    if (!n.flux.found) f["failure"] = n.flux.failure;
    if (n.flux.partner) {
      f["partner"] = {{"point", pointJson(n.flux.partner->points.front())}, {"residue", num(n.flux.partner->residue)}};
    }
    if (n.flux.found) {
      f["flux_per_step"] = num(n.flux.flux);
      f["zone_area"] = num(n.flux.zoneArea);
      f["enclosed_islands_area"] = num(n.flux.enclosedIslands);
      f["enclosed_islands"] = n.flux.enclosedCount;
      f["layer_area"] = num(n.flux.layerArea);
      f["flux_agreeing_digits"] = num(n.flux.fluxDigits);
      f["zone_agreeing_digits"] = num(n.flux.zoneDigits);
      f["residence"] = n.flux.residence;
    }
    if (n.parent >= 0 && n.flux.partner) {  // both separatrices of a chain (issue 50)
      f["outer_by"] = n.flux.outerByZone ? "zone" : "label";
      json in;
      in["found"] = n.flux.inner.found;
      if (!n.flux.inner.found) in["failure"] = n.flux.inner.failure;
      else {
        in["flux_per_step"] = num(n.flux.inner.flux);
        in["zone_area"] = num(n.flux.inner.zoneArea);
        in["flux_agreeing_digits"] = num(n.flux.inner.fluxDigits);
        in["zone_agreeing_digits"] = num(n.flux.inner.zoneDigits);
      }
      f["inner"] = in;
    }
    o["flux"] = f;
    json internal = json::array();
    for (const Rational& r : n.internal) internal.push_back(toString(r));
    o["internal"] = internal;
    o["children"] = n.children;
    o["note"] = n.note;
    nodes.push_back(o);
  }
  j["nodes"] = nodes;
  // Signed as run and tail files are (issue 54): any edit of the file, consistent or not, is refused on load.
  j["checksum"] = io::jsonChecksum(nlohmann::json::parse(j.dump()));
  return j.dump(2) + "\n";
}

std::string atlasCsv(const Atlas& a) {
  std::ostringstream out;
  for (const auto& [k, v] : atlasProvenance(a).fields) out << "# " << k << ": " << v << "\n";
  out << "# cancelled: " << (a.cancelled ? "yes" : "no") << "\n";
  out << "index,parent,level,path,period,about_parent,x,y,line,residue,boundary_rotation,boundary_digits,area,"
         "area_error,area_lower,area_upper,polygon_error,islands_area,flux,zone_area,layer_area,residence,note\n";
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const AtlasNode& n = a.nodes[i];
    out << i << "," << n.parent << "," << n.level << "," << atlasPath(a, static_cast<int>(i)) << "," << n.period << ","
        << rationalText(n.aboutParent) << "," << text(n.centre.x, 19) << "," << text(n.centre.y, 19) << ","
        << (n.onS1 ? "S1" : "S2") << "," << text(n.orbit.residue) << ","
        << (n.boundaryFound ? text(n.boundaryRotation) : "") << "," << (n.boundaryFound ? text(n.boundaryDigits, 4) : "")
        << "," << (n.boundaryFound ? text(n.area) : "") << "," << (n.boundaryFound ? text(n.areaError, 3) : "") << ","
        << (n.boundaryFound ? text(n.areaLower) : "") << "," << (n.boundaryFound ? text(n.areaUpper) : "") << ","
        << (n.boundaryFound ? text(n.polygonError, 3) : "") << ","
        << (n.boundaryFound ? text(n.area * static_cast<long double>(n.period)) : "") << ","
        << (n.flux.found ? text(n.flux.flux) : "") << "," << (n.flux.found ? text(n.flux.zoneArea) : "") << ","
        << (n.flux.found ? text(n.flux.layerArea) : "") << ","
        << (n.flux.found ? text(n.flux.residence, 6) : "") << ",\"" << n.note << "\"\n";
  }
  return out.str();
}

// ------------------------------------------------------------------------------------------------------ reading

namespace {

using rjson = nlohmann::json;

[[noreturn]] void refuse(const std::string& what) { throw std::runtime_error(what); }

/// The object's keys: every one of `required` present, none outside `required` and `optional`.
void keys(const rjson& j, const std::string& where, std::initializer_list<const char*> required,
          std::initializer_list<const char*> optional = {}) {
  if (!j.is_object()) refuse(where + " must be a JSON object, not " + io::describeJson(j));
  std::set<std::string> known(required.begin(), required.end());
  known.insert(optional.begin(), optional.end());
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!known.count(it.key())) refuse("unknown key '" + io::shortText(it.key()) + "' in " + where);
  for (const char* k : required)
    if (!j.contains(k)) refuse(where + " has no '" + k + "'");
}


double finite(const rjson& v, const std::string& key) {
  if (!v.is_number()) refuse(key + " must be a number, not " + io::describeJson(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) refuse(key + " must be finite");
  return d;
}

double nonNegative(const rjson& v, const std::string& key) {
  const double d = finite(v, key);
  if (!(d >= 0)) refuse(key + " = " + io::describeJson(v) + " must be ≥ 0");
  return d;
}

/// A number, or null for the non-finite value the writer writes as null.
double finiteOr(const rjson& v, const std::string& key, double null) { return v.is_null() ? null : finite(v, key); }

std::uint64_t whole(const rjson& v, const std::string& key, std::uint64_t min, std::uint64_t max) {
  const std::optional<std::uint64_t> n = io::wholeJson(v, max);
  if (!n || *n < min)
    refuse(key + " = " + io::describeJson(v) + " must be a whole number in [" + std::to_string(min) + ", " +
           std::to_string(max) + "]");
  return *n;
}

bool boolean(const rjson& v, const std::string& key) {
  if (!v.is_boolean()) refuse(key + " must be true or false, not " + io::describeJson(v));
  return v.get<bool>();
}

std::string string(const rjson& v, const std::string& key) {
  if (!v.is_string()) refuse(key + " must be a string, not " + io::describeJson(v));
  return v.get<std::string>();
}

PhysicalPoint point(const rjson& v, const std::string& key) {
  if (!v.is_array() || v.size() != 2) refuse(key + " must be [x, y], not " + io::describeJson(v));
  return {finite(v[0], key + "[0]"), finite(v[1], key + "[1]")};
}

/// "p/q": integers, q ≥ 1 (toString(Rational)'s text).
Rational rational(const rjson& v, const std::string& key) {
  const std::string s = string(v, key);
  const auto slash = s.find('/');
  Rational r;
  const char* end = s.data() + s.size();
  const bool ok = slash != std::string::npos && slash > 0 &&
                  std::from_chars(s.data(), s.data() + slash, r.p).ptr == s.data() + slash &&
                  slash + 1 < s.size() && s[slash + 1] != '-' && s[slash + 1] != '+' &&
                  std::from_chars(s.data() + slash + 1, end, r.q).ptr == end && r.q >= 1;
  if (!ok) refuse(key + " = " + io::describeJson(v) + " must be a fraction p/q with q ≥ 1");
  return r;
}

/// An int in [min, max] (parents, senses): a JSON integer, signed or not.
long long integer(const rjson& v, const std::string& key, long long min, long long max) {
  if (!v.is_number_integer() || (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(max)) ||
      v.get<long long>() < min || v.get<long long>() > max)
    refuse(key + " = " + io::describeJson(v) + " must be an integer in [" + std::to_string(min) + ", " +
           std::to_string(max) + "]");
  return v.get<long long>();
}

AtlasRequest requestFrom(const rjson& j) {
  AtlasRequest r;
  const rjson& map = j.at("map");
  keys(map, "map", {"K", "xmin", "xmax"});
  r.map.K = finite(map.at("K"), "map.K");
  r.map.xmin = finite(map.at("xmin"), "map.xmin");
  r.map.xmax = finite(map.at("xmax"), "map.xmax");
  const rjson& q = j.at("request");
  keys(q, "request", {"depth", "max_period", "min_area", "iterations", "digits_threshold", "scan_points", "scan_steps",
                      "bisections"},
       {"time_budget"});  // absent in the first files
  r.depth = static_cast<int>(whole(q.at("depth"), "request.depth", 0, kMaxAtlasDepth));
  r.maxPeriod = whole(q.at("max_period"), "request.max_period", 1, PeriodicOrbitSearch::kMaxPeriod);
  r.minArea = finite(q.at("min_area"), "request.min_area");
  r.iterations = whole(q.at("iterations"), "request.iterations", 0, std::numeric_limits<std::uint64_t>::max());
  r.digitsThreshold = finite(q.at("digits_threshold"), "request.digits_threshold");
  r.scanPoints = static_cast<int>(whole(q.at("scan_points"), "request.scan_points", 0, std::numeric_limits<int>::max()));
  r.scanSteps = finite(q.at("scan_steps"), "request.scan_steps");
  r.bisections = static_cast<int>(whole(q.at("bisections"), "request.bisections", 0, std::numeric_limits<int>::max()));
  if (const auto t = q.find("time_budget"); t != q.end()) r.timeBudget = nonNegative(*t, "request.time_budget");
  if (auto e = validationError(r)) refuse("request: " + *e);
  return r;
}

AtlasNode nodeFrom(const rjson& o, const std::string& key, std::size_t index, const Atlas& atlas) {
  keys(o, key, {"index", "parent", "level", "path", "period", "about_parent", "centre", "symmetry_line", "residue",
                "sense", "scan_range", "boundary", "area", "area_error", "area_points", "islands_area", "flux",
                "internal", "children", "note"},
       {"measured",  // absent in the first files: every island of a finished atlas was measured
        "area_lower", "area_upper", "polygon_error"});  // absent before issue 50: area_error was the polygon's
  const long double K = static_cast<long double>(atlas.request.map.K);
  AtlasNode n;
  if (whole(o.at("index"), key + ".index", 0, kMaxAtlasNodes) != index)
    refuse(key + ".index = " + io::describeJson(o.at("index")) + " must be its position, " + std::to_string(index));
  const long long maxParent = static_cast<long long>(index) - 1;
  n.parent = static_cast<int>(integer(o.at("parent"), key + ".parent", index == 0 ? -1 : 0, maxParent));
  if (index > 0 && n.parent < 0) refuse(key + ".parent must name an island before it");
  const AtlasNode* parent = n.parent >= 0 ? &atlas.nodes[static_cast<std::size_t>(n.parent)] : nullptr;
  n.level = static_cast<int>(whole(o.at("level"), key + ".level", 0, static_cast<std::uint64_t>(atlas.request.depth)));
  if (n.level != (parent ? parent->level + 1 : 0))
    refuse(key + ".level = " + std::to_string(n.level) + " must be " + std::to_string(parent ? parent->level + 1 : 0) +
           (parent ? " (its parent's plus one)" : " (the centre)"));
  (void)string(o.at("path"), key + ".path");  // written anew from the periods
  n.period = whole(o.at("period"), key + ".period", 1, PeriodicOrbitSearch::kMaxPeriod);
  if (o.at("about_parent").is_null()) {
    if (parent) refuse(key + ".about_parent must be p/q about its parent island");
  } else {
    if (!parent) refuse(key + ".about_parent must be null at the centre");
    n.aboutParent = rational(o.at("about_parent"), key + ".about_parent");
    if (n.aboutParent->q > PeriodicOrbitSearch::kMaxPeriod)
      refuse(key + ".about_parent = " + toString(*n.aboutParent) + ": q above the largest period");
    const Rational& r = *n.aboutParent;
    if (r.q < 2 || r.p == 0 || std::llabs(r.p) >= r.q || std::gcd(std::llabs(r.p), static_cast<long long>(r.q)) != 1)
      refuse(key + ".about_parent = " + toString(r) + " must be p/q in lowest terms with 0 < |p| < q");
    if (parent->boundaryFound && (r.p > 0) != (parent->boundaryRotation > 0))
      refuse(key + ".about_parent = " + toString(r) + ": a chain turns about its parent in the sense of the parent's "
             "circles (its boundary rotation is " + shortestDecimal(parent->boundaryRotation) + ")");
  }
  const std::uint64_t expected = parent ? parent->period * static_cast<std::uint64_t>(n.aboutParent->q) : 1;
  if (n.period != expected)
    refuse(key + ".period = " + std::to_string(n.period) + " must be " + std::to_string(expected) +
           (parent ? " (its parent's period times q of its p/q)" : " (the centre)"));
  n.centre = point(o.at("centre"), key + ".centre");
  const std::string line = string(o.at("symmetry_line"), key + ".symmetry_line");
  if (line != "S1" && line != "S2") refuse(key + ".symmetry_line = " + io::describeJson(o.at("symmetry_line")) + " must be \"S1\" or \"S2\"");
  n.onS1 = line == "S1";
  n.orbit.K = K;
  n.orbit.period = static_cast<int>(n.period);
  n.orbit.points = {n.centre};
  n.orbit.residue = finiteOr(o.at("residue"), key + ".residue", std::numeric_limits<double>::quiet_NaN());
  n.orbit.symmetry = n.onS1 ? OrbitSymmetry::LineS1 : OrbitSymmetry::LineS2;
  n.sense = static_cast<int>(integer(o.at("sense"), key + ".sense", -1, 1));
  if (n.sense == 0) refuse(key + ".sense must be 1 or -1");
  n.scanRange = nonNegative(o.at("scan_range"), key + ".scan_range");
  const auto measured = o.find("measured");
  n.measured = measured != o.end() ? boolean(*measured, key + ".measured") : !atlas.cancelled;
  if (n.measured && parent && !parent->measured) refuse(key + ".measured: its parent island is not");

  const std::string bkey = key + ".boundary";
  const rjson& b = o.at("boundary");
  if (!b.is_object() || !b.contains("found")) refuse(bkey + " must be an object with 'found'");
  n.boundaryFound = boolean(b.at("found"), bkey + ".found");
  if (n.boundaryFound) {
    keys(b, bkey, {"found", "point", "rotation", "digits", "bracket"});
    n.boundaryPoint = point(b.at("point"), bkey + ".point");
    n.boundaryRotation = finite(b.at("rotation"), bkey + ".rotation");
    n.boundaryDigits = finite(b.at("digits"), bkey + ".digits");
    n.gap = nonNegative(b.at("bracket"), bkey + ".bracket");
  } else {
    keys(b, bkey, {"found", "failure"});
    n.boundaryFailure = string(b.at("failure"), bkey + ".failure");
  }
  n.area = nonNegative(o.at("area"), key + ".area");
  n.circleArea = n.area;
  const long double box = static_cast<long double>(atlas.request.map.width()) * atlas.request.map.width();
  if (n.area * static_cast<long double>(n.period) > box)
    refuse(key + ".area = " + shortestDecimal(n.area) + ": its chain's " + std::to_string(n.period) +
           " islands would exceed the box's area " + shortestDecimal(static_cast<double>(box)));
  if (o.contains("polygon_error")) {
    n.polygonError = nonNegative(o.at("polygon_error"), key + ".polygon_error");
    n.areaLower = nonNegative(o.at("area_lower"), key + ".area_lower");
    if (o.at("area_upper").is_null()) {  // unknown: an island read from a file from before the interval, resumed
      if (!o.at("area_error").is_null()) refuse(key + ".area_error must be null when area_upper is (not known)");
      n.areaUpper = n.areaError = std::numeric_limits<long double>::quiet_NaN();
      if (!(n.areaLower <= n.area)) refuse(key + ": area " + shortestDecimal(n.area) + " must be at least area_lower");
    } else {
      n.areaUpper = nonNegative(o.at("area_upper"), key + ".area_upper");
      n.areaError = nonNegative(o.at("area_error"), key + ".area_error");
    }
    if (!std::isnan(n.areaUpper) && !(n.areaLower <= n.area && n.area <= n.areaUpper))
      refuse(key + ": area " + shortestDecimal(n.area) + " must lie in [area_lower, area_upper] = [" +
             shortestDecimal(n.areaLower) + ", " + shortestDecimal(n.areaUpper) + "]");
    if (!std::isnan(n.areaUpper) && n.areaError < std::max(n.area - n.areaLower, n.areaUpper - n.area) * (1 - 1e-12L))
      refuse(key + ".area_error = " + shortestDecimal(n.areaError) + " does not cover [area_lower, area_upper]");
  } else {
    // A file from before the interval: its area_error measured the polygon's convergence only, and the boundary's
    // own uncertainty is not known — said as such (NaN: null in the JSON, blank in the CSV).
    n.polygonError = nonNegative(o.at("area_error"), key + ".area_error");
    n.areaLower = std::max<long double>(n.area - n.polygonError, 0);
    n.areaUpper = std::numeric_limits<long double>::quiet_NaN();
    n.areaError = std::numeric_limits<long double>::quiet_NaN();
  }
  n.areaPoints = static_cast<int>(whole(o.at("area_points"), key + ".area_points", 0, std::numeric_limits<int>::max()));
  (void)finite(o.at("islands_area"), key + ".islands_area");  // written anew: period × area

  const std::string fkey = key + ".flux";
  const rjson& f = o.at("flux");
  if (!f.is_object() || !f.contains("found")) refuse(fkey + " must be an object with 'found'");
  n.flux.found = boolean(f.at("found"), fkey + ".found");
  if (n.flux.found) {
    keys(f, fkey, {"found", "flux_per_step", "zone_area", "enclosed_islands_area", "layer_area", "flux_agreeing_digits",
                   "zone_agreeing_digits", "residence"},
         {"partner", "enclosed_islands", "inner", "outer_by"});
    if (const auto c = f.find("enclosed_islands"); c != f.end())
      n.flux.enclosedCount = static_cast<int>(whole(*c, fkey + ".enclosed_islands", 0, std::numeric_limits<int>::max()));
    n.flux.flux = finite(f.at("flux_per_step"), fkey + ".flux_per_step");
    if (!(n.flux.flux > 0)) refuse(fkey + ".flux_per_step must be > 0");
    n.flux.zoneArea = nonNegative(f.at("zone_area"), fkey + ".zone_area");
    n.flux.enclosedIslands = nonNegative(f.at("enclosed_islands_area"), fkey + ".enclosed_islands_area");
    n.flux.layerArea = finite(f.at("layer_area"), fkey + ".layer_area");
    const double all = std::numeric_limits<double>::infinity();  // null: every digit agrees
    n.flux.fluxDigits = finiteOr(f.at("flux_agreeing_digits"), fkey + ".flux_agreeing_digits", all);
    n.flux.zoneDigits = finiteOr(f.at("zone_agreeing_digits"), fkey + ".zone_agreeing_digits", all);
    n.flux.residence = finite(f.at("residence"), fkey + ".residence");
    if (!(n.flux.zoneArea <= box))
      refuse(fkey + ".zone_area = " + shortestDecimal(n.flux.zoneArea) + " exceeds the box's area " +
             shortestDecimal(static_cast<double>(box)));
    const long double layer = n.flux.zoneArea - n.flux.enclosedIslands;
    if (std::fabs(n.flux.layerArea - layer) > 1e-9L * n.flux.zoneArea)
      refuse(fkey + ".layer_area = " + shortestDecimal(n.flux.layerArea) + " must be zone_area − enclosed_islands_area = " +
             shortestDecimal(layer));
    if (n.flux.layerArea > 0 &&
        std::fabs(n.flux.residence - static_cast<double>(n.flux.layerArea / n.flux.flux)) > 1e-9 * std::fabs(n.flux.residence))
      refuse(fkey + ".residence = " + shortestDecimal(n.flux.residence) + " must be layer_area / flux_per_step");
    refuseEmptyLayer(n.flux);  // a file written before the rule, or edited, obeys it as the computation does
  } else {
    keys(f, fkey, {"found", "failure"}, {"partner", "inner", "outer_by"});
    n.flux.failure = string(f.at("failure"), fkey + ".failure");
  }
  if (const auto by = f.find("outer_by"); by != f.end()) {  // absent before issue 50: the label's side, no inner
    const std::string text = string(*by, fkey + ".outer_by");
    if (text != "zone" && text != "label") refuse(fkey + ".outer_by = " + io::describeJson(*by) + " must be \"zone\" or \"label\"");
    n.flux.outerByZone = text == "zone";
  }
  if (const auto in = f.find("inner"); in != f.end()) {
    if (!parent) refuse(fkey + ".inner: the centre's barrier is the fixed point's loop, it has no inner side");
    const std::string ikey = fkey + ".inner";
    if (!in->is_object() || !in->contains("found")) refuse(ikey + " must be an object with 'found'");
    SeparatrixFlux& inner = n.flux.inner;
    inner.found = boolean(in->at("found"), ikey + ".found");
    if (inner.found) {
      keys(*in, ikey, {"found", "flux_per_step", "zone_area", "flux_agreeing_digits", "zone_agreeing_digits"});
      inner.flux = finite(in->at("flux_per_step"), ikey + ".flux_per_step");
      if (!(inner.flux > 0)) refuse(ikey + ".flux_per_step must be > 0");
      inner.zoneArea = nonNegative(in->at("zone_area"), ikey + ".zone_area");
      const double all = std::numeric_limits<double>::infinity();
      inner.fluxDigits = finiteOr(in->at("flux_agreeing_digits"), ikey + ".flux_agreeing_digits", all);
      inner.zoneDigits = finiteOr(in->at("zone_agreeing_digits"), ikey + ".zone_agreeing_digits", all);
      if (n.flux.found && n.flux.outerByZone && !(inner.zoneArea <= n.flux.zoneArea))
        refuse(ikey + ".zone_area = " + shortestDecimal(static_cast<double>(inner.zoneArea)) +
               " exceeds the outer separatrix's " + shortestDecimal(static_cast<double>(n.flux.zoneArea)) +
               ": the outer is the larger zone");
    } else {
      keys(*in, ikey, {"found", "failure"});
      inner.failure = string(in->at("failure"), ikey + ".failure");
    }
  }
  if (const auto p = f.find("partner"); p != f.end()) {
    if (!parent) refuse(fkey + ".partner: the centre's barrier is the fixed point's loop, it has none");
    keys(*p, fkey + ".partner", {"point", "residue"});
    PeriodicOrbit partner;
    partner.K = K;
    partner.period = static_cast<int>(n.period);
    partner.points = {point(p->at("point"), fkey + ".partner.point")};
    partner.residue = finiteOr(p->at("residue"), fkey + ".partner.residue", std::numeric_limits<double>::quiet_NaN());
    n.flux.partner = std::move(partner);
  }

  const rjson& internal = o.at("internal");
  if (!internal.is_array()) refuse(key + ".internal must be an array of p/q");
  for (std::size_t k = 0; k < internal.size(); ++k)
    n.internal.push_back(rational(internal[k], key + ".internal[" + std::to_string(k) + "]"));
  const rjson& children = o.at("children");
  if (!children.is_array()) refuse(key + ".children must be an array of indices");
  for (std::size_t k = 0; k < children.size(); ++k) {
    const std::uint64_t c = whole(children[k], key + ".children[" + std::to_string(k) + "]", index + 1, kMaxAtlasNodes);
    if (!n.children.empty() && c <= static_cast<std::uint64_t>(n.children.back()))
      refuse(key + ".children must be increasing indices");
    n.children.push_back(static_cast<int>(c));
  }
  n.note = string(o.at("note"), key + ".note");
  if (!n.measured && !n.children.empty()) refuse(key + ".children: an island not measured has none yet");
  return n;
}

Atlas atlasFrom(rjson j) {
  keys(j, "the atlas", {"format", "program", "provenance", "map", "request", "cancelled", "seconds", "nodes"},
       {"stop_reason", "format_version", "checksum"});
  if (!j.at("format").is_string() || j.at("format").get<std::string>() != "archipelago atlas")
    refuse("format = " + io::describeJson(j.at("format")) + ": not an atlas (\"archipelago atlas\")");
  // Version 2 (issue 54) is signed; a file without a version is one from before (read as it was, unsigned).
  if (j.contains("format_version")) {
    if (whole(j.at("format_version"), "format_version", 2, 2) != kAtlasFormatVersion)
      refuse("format_version must be " + std::to_string(kAtlasFormatVersion));
    if (!j.contains("checksum") || !j.at("checksum").is_string()) refuse("checksum: a signed atlas (version 2) must have one");
    const std::string sum = j.at("checksum").get<std::string>();
    j.erase("checksum");
    if (io::jsonChecksum(j) != sum)
      refuse("the atlas was modified after it was written (its checksum does not match its content)");
  } else if (j.contains("checksum")) {
    refuse("checksum without format_version");
  }
  (void)string(j.at("program"), "program");  // written anew
  if (!j.at("provenance").is_object()) refuse("provenance must be a JSON object");
  Atlas a;
  a.request = requestFrom(j);
  a.cancelled = boolean(j.at("cancelled"), "cancelled");
  if (const auto r = j.find("stop_reason"); r != j.end()) a.stopReason = string(*r, "stop_reason");
  a.seconds = nonNegative(j.at("seconds"), "seconds");
  const rjson& nodes = j.at("nodes");
  if (!nodes.is_array()) refuse("nodes must be an array");
  if (nodes.empty()) refuse("nodes must hold the central island at least");
  if (nodes.size() > kMaxAtlasNodes)
    refuse("nodes has " + std::to_string(nodes.size()) + " entries; at most " + std::to_string(kMaxAtlasNodes));
  a.nodes.reserve(nodes.size());
  std::size_t links = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    a.nodes.push_back(nodeFrom(nodes[i], "nodes[" + std::to_string(i) + "]", i, a));
    links += a.nodes.back().children.size();
  }
  // Each child names its parent, and every island but the centre is a child once.
  for (std::size_t i = 0; i < a.nodes.size(); ++i)
    for (const int c : a.nodes[i].children)
      if (static_cast<std::size_t>(c) >= a.nodes.size() || a.nodes[static_cast<std::size_t>(c)].parent != static_cast<int>(i))
        refuse("nodes[" + std::to_string(i) + "].children names " + std::to_string(c) + ", which is not its child");
  if (links != a.nodes.size() - 1) refuse("nodes: some island is missing from its parent's children");
  if (!a.cancelled)
    for (std::size_t i = 0; i < a.nodes.size(); ++i)
      if (!a.nodes[i].measured) refuse("nodes[" + std::to_string(i) + "] is not measured in an atlas not cancelled");
  return a;
}

}  // namespace

Atlas atlasFromJson(const std::string& text) {
  try {
    return atlasFrom(io::parseJson(text));  // a copy: its checksum is taken out to verify the rest
  } catch (const std::runtime_error&) {
    throw;
  } catch (const std::exception& e) {  // parseJson's std::invalid_argument; nlohmann's own, should one escape
    throw std::runtime_error(e.what());
  }
}

void writeAtlasJson(const std::filesystem::path& path, const Atlas& atlas) { io::writeFileAtomically(path, atlasJson(atlas)); }
void writeAtlasCsv(const std::filesystem::path& path, const Atlas& atlas) { io::writeFileAtomically(path, atlasCsv(atlas)); }

}  // namespace archipelago
