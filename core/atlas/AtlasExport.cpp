#include "core/atlas/AtlasExport.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <numeric>
#include <nlohmann/json.hpp>
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

/// The cantori about the islands (issue 50): about which island, whether its boundary cantorus, what they lie between,
/// ΔW's terms, flux, zone and layer.
json cantoriJson(const std::vector<AtlasCantorus>& cantori) {
  json out = json::array();
  for (const AtlasCantorus& c : cantori) {
    json o;
    o["island"] = c.island;
    o["boundary"] = c.boundary;
    o["outer"] = toString(c.outer);
    o["inner"] = toString(c.inner);
    json terms = json::array();
    for (const Rational& r : c.convergents) terms.push_back(toString(r));
    o["convergents"] = terms;
    o["found"] = c.found;
    if (!c.failure.empty()) o["failure"] = c.failure;
    if (!c.note.empty()) o["note"] = c.note;
    if (c.flux > 0) {
      o["flux_per_step"] = num(c.flux);
      o["flux_uncertainty"] = num(c.fluxUncertainty);
      o["zone_area"] = num(c.zoneArea);
      o["zone_spread"] = num(c.zoneSpread);
      o["enclosed_islands_area"] = num(c.enclosedIslands);
      o["enclosed_islands"] = c.enclosedCount;
      o["layer_area"] = num(c.layerArea);
    }
    out.push_back(o);
  }
  return out;
}
}  // namespace

namespace {

/// A node's barrier: the outer separatrix's flux, zone, layer and residence (or why not), its partner, and the inner
/// separatrix (issue 50: its own flux and zone, and its layer once settled).
json fluxJson(const AtlasNode& n) {
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
      if (n.flux.inner.layerArea > 0) {  // settled: the band inside the chain (issue 50)
        in["enclosed_islands_area"] = num(n.flux.inner.enclosedIslands);
        in["enclosed_islands"] = n.flux.inner.enclosedCount;
        in["layer_area"] = num(n.flux.inner.layerArea);
      }
      in["flux_agreeing_digits"] = num(n.flux.inner.fluxDigits);
      in["zone_agreeing_digits"] = num(n.flux.inner.zoneDigits);
    }
    f["inner"] = in;
  }
  return f;
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
                  {"time_budget", a.request.timeBudget},
                  {"cantori", a.request.cantori}};
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
    o["flux"] = fluxJson(n);
    json internal = json::array();
    for (const Rational& r : n.internal) internal.push_back(toString(r));
    o["internal"] = internal;
    o["children"] = n.children;
    o["note"] = n.note;
    nodes.push_back(o);
  }
  j["nodes"] = nodes;
  if (!a.cantori.empty()) j["cantori"] = cantoriJson(a.cantori);
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
using io::JsonField;

[[noreturn]] void refuse(const std::string& what) { throw io::BadFile(what); }

PhysicalPoint point(const JsonField& v) {
  v.tuple(2, "[x, y]");
  return {v[0].real(), v[1].real()};
}

/// "p/q": integers, q ≥ 1 (toString(Rational)'s text).
Rational rational(const JsonField& v) {
  const std::string s = v.string();
  const auto slash = s.find('/');
  Rational r;
  const char* end = s.data() + s.size();
  const bool ok = slash != std::string::npos && slash > 0 &&
                  std::from_chars(s.data(), s.data() + slash, r.p).ptr == s.data() + slash &&
                  slash + 1 < s.size() && s[slash + 1] != '-' && s[slash + 1] != '+' &&
                  std::from_chars(s.data() + slash + 1, end, r.q).ptr == end && r.q >= 1;
  if (!ok) v.refuseValue("must be a fraction p/q with q ≥ 1");
  return r;
}

constexpr std::uint64_t kIntMax = std::numeric_limits<int>::max();

AtlasRequest requestFrom(const JsonField& root) {
  AtlasRequest r;
  const JsonField map = root["map"];
  map.keys({"K", "xmin", "xmax"});
  r.map.K = map["K"].real();
  r.map.xmin = map["xmin"].real();
  r.map.xmax = map["xmax"].real();
  const JsonField q = root["request"];
  q.keys({"depth", "max_period", "min_area", "iterations", "digits_threshold", "scan_points", "scan_steps", "bisections"},
         {"time_budget", "cantori"});  // absent in the first files
  r.depth = static_cast<int>(q["depth"].whole(kMaxAtlasDepth));
  r.maxPeriod = q["max_period"].whole(PeriodicOrbitSearch::kMaxPeriod, 1);
  r.minArea = q["min_area"].real();
  r.iterations = q["iterations"].whole();
  r.digitsThreshold = q["digits_threshold"].real();
  r.scanPoints = static_cast<int>(q["scan_points"].whole(kIntMax));
  r.scanSteps = q["scan_steps"].real();
  r.bisections = static_cast<int>(q["bisections"].whole(kIntMax));
  if (const auto t = q.find("time_budget")) r.timeBudget = t->nonNegative();
  if (const auto c = q.find("cantori")) r.cantori = c->boolean();
  if (auto e = validationError(r)) refuse("request: " + *e);
  return r;
}

/// A node's place in the tree: its index, parent and level, its period and its p/q about its parent.
void readPlace(const JsonField& o, std::size_t index, const Atlas& atlas, AtlasNode& n) {
  if (o["index"].whole(kMaxAtlasNodes) != index) o["index"].refuseValue("must be its position, " + std::to_string(index));
  const JsonField jp = o["parent"];
  n.parent = static_cast<int>(jp.integer(index == 0 ? -1 : 0, static_cast<std::int64_t>(index) - 1));
  if (index > 0 && n.parent < 0) jp.refuse("must name an island before it");
  const AtlasNode* parent = n.parent >= 0 ? &atlas.nodes[static_cast<std::size_t>(n.parent)] : nullptr;
  n.level = static_cast<int>(o["level"].whole(static_cast<std::uint64_t>(atlas.request.depth)));
  if (n.level != (parent ? parent->level + 1 : 0))
    o["level"].refuseValue("must be " + std::to_string(parent ? parent->level + 1 : 0) +
                           (parent ? " (its parent's plus one)" : " (the centre)"));
  (void)o["path"].string();  // written anew from the periods
  n.period = o["period"].whole(PeriodicOrbitSearch::kMaxPeriod, 1);
  const JsonField about = o["about_parent"];
  if (about.isNull()) {
    if (parent) about.refuse("must be p/q about its parent island");
  } else {
    if (!parent) about.refuse("must be null at the centre");
    const Rational r = rational(about);
    n.aboutParent = r;
    const std::string named = about.name() + " = " + toString(r);
    if (r.q > PeriodicOrbitSearch::kMaxPeriod) refuse(named + ": q above the largest period");
    if (r.q < 2 || r.p == 0 || std::llabs(r.p) >= r.q || std::gcd(std::llabs(r.p), static_cast<long long>(r.q)) != 1)
      refuse(named + " must be p/q in lowest terms with 0 < |p| < q");
    if (parent->boundaryFound && (r.p > 0) != (parent->boundaryRotation > 0))
      refuse(named + ": a chain turns about its parent in the sense of the parent's circles (its boundary rotation is " +
             shortestDecimal(parent->boundaryRotation) + ")");
  }
  const std::uint64_t expected = parent ? parent->period * static_cast<std::uint64_t>(n.aboutParent->q) : 1;
  if (n.period != expected)
    o["period"].refuseValue("must be " + std::to_string(expected) +
                            (parent ? " (its parent's period times q of its p/q)" : " (the centre)"));
}

/// The island's centre, its symmetry line, residue and sense, scan range and whether it was measured.
void readOrbit(const JsonField& o, const Atlas& atlas, AtlasNode& n) {
  n.centre = point(o["centre"]);
  const JsonField line = o["symmetry_line"];
  const std::string name = line.string();
  if (name != "S1" && name != "S2") line.refuseValue("must be \"S1\" or \"S2\"");
  n.onS1 = name == "S1";
  n.orbit.K = static_cast<long double>(atlas.request.map.K);
  n.orbit.period = static_cast<int>(n.period);
  n.orbit.points = {n.centre};
  n.orbit.residue = o["residue"].realOr(std::numeric_limits<double>::quiet_NaN());
  n.orbit.symmetry = n.onS1 ? OrbitSymmetry::LineS1 : OrbitSymmetry::LineS2;
  n.sense = static_cast<int>(o["sense"].integer(-1, 1));
  if (n.sense == 0) o["sense"].refuse("must be 1 or -1");
  n.scanRange = o["scan_range"].nonNegative();
  const auto measured = o.find("measured");
  n.measured = measured ? measured->boolean() : !atlas.cancelled;
  if (n.measured && n.parent >= 0 && !atlas.nodes[static_cast<std::size_t>(n.parent)].measured)
    refuse(o.name() + ".measured: its parent island is not");
}

void readBoundary(const JsonField& b, AtlasNode& n) {
  n.boundaryFound = b["found"].boolean();
  if (n.boundaryFound) {
    b.keys({"found", "point", "rotation", "digits", "bracket"});
    n.boundaryPoint = point(b["point"]);
    n.boundaryRotation = b["rotation"].real();
    n.boundaryDigits = b["digits"].real();
    n.gap = b["bracket"].nonNegative();
  } else {
    b.keys({"found", "failure"});
    n.boundaryFailure = b["failure"].string();
  }
}

/// The box's area: no island chain and no zone exceeds it.
long double boxArea(const Atlas& atlas) {
  return static_cast<long double>(atlas.request.map.width()) * atlas.request.map.width();
}

/// The area, its interval [area_lower, area_upper] and its errors (a file from before the interval: its area_error).
void readArea(const JsonField& o, const Atlas& atlas, AtlasNode& n) {
  n.area = o["area"].nonNegative();
  n.circleArea = n.area;
  const long double box = boxArea(atlas);
  if (n.area * static_cast<long double>(n.period) > box)
    refuse(o["area"].name() + " = " + shortestDecimal(n.area) + ": its chain's " + std::to_string(n.period) +
           " islands would exceed the box's area " + shortestDecimal(static_cast<double>(box)));
  const std::string key = o.name();
  if (o.contains("polygon_error")) {
    n.polygonError = o["polygon_error"].nonNegative();
    n.areaLower = o["area_lower"].nonNegative();
    if (o["area_upper"].isNull()) {  // unknown: an island read from a file from before the interval, resumed
      if (!o["area_error"].isNull()) o["area_error"].refuse("must be null when area_upper is (not known)");
      n.areaUpper = n.areaUpperRays = n.areaError = std::numeric_limits<long double>::quiet_NaN();
      if (!(n.areaLower <= n.area)) refuse(key + ": area " + shortestDecimal(n.area) + " must be at least area_lower");
    } else {
      n.areaUpper = n.areaUpperRays = o["area_upper"].nonNegative();
      n.areaError = o["area_error"].nonNegative();
    }
    if (!std::isnan(n.areaUpper) && !(n.areaLower <= n.area && n.area <= n.areaUpper))
      refuse(key + ": area " + shortestDecimal(n.area) + " must lie in [area_lower, area_upper] = [" +
             shortestDecimal(n.areaLower) + ", " + shortestDecimal(n.areaUpper) + "]");
    if (!std::isnan(n.areaUpper) && n.areaError < std::max(n.area - n.areaLower, n.areaUpper - n.area) * (1 - 1e-12L))
      refuse(key + ".area_error = " + shortestDecimal(n.areaError) + " does not cover [area_lower, area_upper]");
  } else {
    // A file from before the interval: its area_error measured the polygon's convergence only, and the boundary's
    // own uncertainty is not known — said as such (NaN: null in the JSON, blank in the CSV).
    n.polygonError = o["area_error"].nonNegative();
    n.areaLower = std::max<long double>(n.area - n.polygonError, 0);
    n.areaUpper = n.areaUpperRays = std::numeric_limits<long double>::quiet_NaN();
    n.areaError = std::numeric_limits<long double>::quiet_NaN();
  }
  n.areaPoints = static_cast<int>(o["area_points"].whole(kIntMax));
  (void)o["islands_area"].real();  // written anew: period × area
}

/// A separatrix's lobe: its flux per step (> 0), its zone (≥ 0) and their agreeing digits (null: every digit).
void readLobe(const JsonField& f, long double& flux, long double& zoneArea, long double& fluxDigits,
              long double& zoneDigits) {
  flux = f["flux_per_step"].real();
  if (!(flux > 0)) f["flux_per_step"].refuse("must be > 0");
  zoneArea = f["zone_area"].nonNegative();
  const double all = std::numeric_limits<double>::infinity();
  fluxDigits = f["flux_agreeing_digits"].realOr(all);
  zoneDigits = f["zone_agreeing_digits"].realOr(all);
}

/// The outer separatrix's flux, its zone, layer and residence, consistent with one another and the box.
void readOuterFlux(const JsonField& f, const Atlas& atlas, AtlasFlux& flux) {
  f.keys({"found", "flux_per_step", "zone_area", "enclosed_islands_area", "layer_area", "flux_agreeing_digits",
          "zone_agreeing_digits", "residence"},
         {"partner", "enclosed_islands", "inner", "outer_by"});
  if (const auto c = f.find("enclosed_islands")) flux.enclosedCount = static_cast<int>(c->whole(kIntMax));
  readLobe(f, flux.flux, flux.zoneArea, flux.fluxDigits, flux.zoneDigits);
  flux.enclosedIslands = f["enclosed_islands_area"].nonNegative();
  flux.layerArea = f["layer_area"].real();
  flux.residence = f["residence"].real();
  const long double box = boxArea(atlas);
  if (!(flux.zoneArea <= box))
    refuse(f["zone_area"].name() + " = " + shortestDecimal(flux.zoneArea) + " exceeds the box's area " +
           shortestDecimal(static_cast<double>(box)));
  const long double layer = flux.zoneArea - flux.enclosedIslands;
  if (std::fabs(flux.layerArea - layer) > 1e-9L * flux.zoneArea)
    refuse(f["layer_area"].name() + " = " + shortestDecimal(flux.layerArea) +
           " must be zone_area − enclosed_islands_area = " + shortestDecimal(layer));
  if (flux.layerArea > 0 &&
      std::fabs(flux.residence - static_cast<double>(flux.layerArea / flux.flux)) > 1e-9 * std::fabs(flux.residence))
    refuse(f["residence"].name() + " = " + shortestDecimal(flux.residence) + " must be layer_area / flux_per_step");
  refuseEmptyLayer(flux);  // a file written before the rule, or edited, obeys it as the computation does
}

/// The inner separatrix's layer when the file has it (written since its layers were settled): all three fields, the
/// layer the zone less the islands, positive.
void readInnerLayer(const JsonField& in, SeparatrixFlux& inner) {
  const auto layer = in.find("layer_area");
  if (!layer) return;
  inner.enclosedIslands = in["enclosed_islands_area"].nonNegative();
  inner.enclosedCount = static_cast<int>(in["enclosed_islands"].whole(kIntMax));
  inner.layerArea = layer->real();
  const long double expected = inner.zoneArea - inner.enclosedIslands;
  if (!(inner.layerArea > 0) || std::fabs(inner.layerArea - expected) > 1e-9L * inner.zoneArea)
    layer->refuse("must be zone_area − enclosed_islands_area = " + shortestDecimal(expected) + " and > 0");
}

/// The inner separatrix (issue 50), no larger a zone than the outer when the zones chose the outer.
void readInnerFlux(const JsonField& in, AtlasFlux& flux) {
  SeparatrixFlux& inner = flux.inner;
  inner.found = in["found"].boolean();
  if (!inner.found) {
    in.keys({"found", "failure"});
    inner.failure = in["failure"].string();
    return;
  }
  in.keys({"found", "flux_per_step", "zone_area", "flux_agreeing_digits", "zone_agreeing_digits"},
          {"enclosed_islands_area", "enclosed_islands", "layer_area"});
  readLobe(in, inner.flux, inner.zoneArea, inner.fluxDigits, inner.zoneDigits);
  readInnerLayer(in, inner);
  if (flux.found && flux.outerByZone && !(inner.zoneArea <= flux.zoneArea))
    refuse(in["zone_area"].name() + " = " + shortestDecimal(static_cast<double>(inner.zoneArea)) +
           " exceeds the outer separatrix's " + shortestDecimal(static_cast<double>(flux.zoneArea)) +
           ": the outer is the larger zone");
}

/// The flux through the chain's barrier: the outer separatrix, which side is outer, the inner one, the partner.
void readFlux(const JsonField& f, const Atlas& atlas, AtlasNode& n) {
  n.flux.found = f["found"].boolean();
  if (n.flux.found) {
    readOuterFlux(f, atlas, n.flux);
  } else {
    f.keys({"found", "failure"}, {"partner", "inner", "outer_by"});
    n.flux.failure = f["failure"].string();
  }
  if (const auto by = f.find("outer_by")) {  // absent before issue 50: the label's side, no inner
    const std::string text = by->string();
    if (text != "zone" && text != "label") by->refuseValue("must be \"zone\" or \"label\"");
    n.flux.outerByZone = text == "zone";
  }
  const bool centre = n.parent < 0;
  if (const auto in = f.find("inner")) {
    if (centre) in->refuseDocument(in->name() + ": the centre's barrier is the fixed point's loop, it has no inner side");
    readInnerFlux(*in, n.flux);
  }
  if (const auto p = f.find("partner")) {
    if (centre) p->refuseDocument(p->name() + ": the centre's barrier is the fixed point's loop, it has none");
    p->keys({"point", "residue"});
    PeriodicOrbit partner;
    partner.K = static_cast<long double>(atlas.request.map.K);
    partner.period = static_cast<int>(n.period);
    partner.points = {point((*p)["point"])};
    partner.residue = (*p)["residue"].realOr(std::numeric_limits<double>::quiet_NaN());
    n.flux.partner = std::move(partner);
  }
}

/// The rotation numbers inside the island and its children's indices (after it, increasing).
void readLinks(const JsonField& o, std::size_t index, AtlasNode& n) {
  const JsonField internal = o["internal"];
  for (std::size_t k = 0, size = internal.array(); k < size; ++k) n.internal.push_back(rational(internal[k]));
  const JsonField children = o["children"];
  for (std::size_t k = 0, size = children.array(); k < size; ++k) {
    const std::uint64_t c = children[k].whole(kMaxAtlasNodes, index + 1);
    if (!n.children.empty() && c <= static_cast<std::uint64_t>(n.children.back()))
      children.refuse("must be increasing indices");
    n.children.push_back(static_cast<int>(c));
  }
  if (!n.measured && !n.children.empty()) children.refuseDocument(children.name() + ": an island not measured has none yet");
}

AtlasNode nodeFrom(const JsonField& o, std::size_t index, const Atlas& atlas) {
  o.keys({"index", "parent", "level", "path", "period", "about_parent", "centre", "symmetry_line", "residue", "sense",
          "scan_range", "boundary", "area", "area_error", "area_points", "islands_area", "flux", "internal", "children",
          "note"},
         {"measured",  // absent in the first files: every island of a finished atlas was measured
          "area_lower", "area_upper", "polygon_error"});  // absent before issue 50: area_error was the polygon's
  AtlasNode n;
  readPlace(o, index, atlas, n);
  readOrbit(o, atlas, n);
  readBoundary(o["boundary"], n);
  readArea(o, atlas, n);
  readFlux(o["flux"], atlas, n);
  readLinks(o, index, n);
  n.note = o["note"].string();
  return n;
}

/// The format, its version and, from version 2, the checksum over the rest (taken out of `j`).
void checkSignature(rjson& j, const JsonField& root) {
  const JsonField format = root["format"];
  if (!format.value().is_string() || format.value().get<std::string>() != "archipelago atlas")
    refuse("format = " + io::describeJson(format.value()) + ": not an atlas (\"archipelago atlas\")");
  // Version 2 (issue 54) is signed; a file without a version is one from before (read as it was, unsigned).
  io::checkSignature(j, root, kAtlasFormatVersion, "atlas", "the atlas", [](const std::string& why) { refuse(why); });
}

/// Each child names its parent, every island but the centre is a child once, and a finished atlas measured them all.
void checkTree(const Atlas& a) {
  std::size_t links = 0;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    links += a.nodes[i].children.size();
    for (const int c : a.nodes[i].children)
      if (static_cast<std::size_t>(c) >= a.nodes.size() || a.nodes[static_cast<std::size_t>(c)].parent != static_cast<int>(i))
        refuse("nodes[" + std::to_string(i) + "].children names " + std::to_string(c) + ", which is not its child");
  }
  if (links != a.nodes.size() - 1) refuse("nodes: some island is missing from its parent's children");
  if (!a.cancelled)
    for (std::size_t i = 0; i < a.nodes.size(); ++i)
      if (!a.nodes[i].measured) refuse("nodes[" + std::to_string(i) + "] is not measured in an atlas not cancelled");
}

/// The cantori (absent in a file from before issue 50's): each between two chains about the centre, its flux and
/// layer positive and finite, the layer its zone less its islands, within the box.
void readCantori(const JsonField& list, Atlas& a) {
  const long double box = boxArea(a);
  for (std::size_t k = 0, size = list.array(kMaxAtlasNodes); k < size; ++k) {
    const JsonField o = list[k];
    o.keys({"outer", "inner", "convergents", "found"},
           {"island", "boundary", "failure", "note", "flux_per_step", "flux_uncertainty", "zone_area", "zone_spread", "enclosed_islands_area",
            "enclosed_islands", "layer_area"});
    AtlasCantorus c;
    if (const auto i = o.find("island")) {  // absent in a file from before the islands' cantori: the centre's
      c.island = static_cast<int>(i->whole(a.nodes.empty() ? 0 : static_cast<long long>(a.nodes.size()) - 1));
      if (!a.nodes[static_cast<std::size_t>(c.island)].boundaryFound) i->refuse("is an island without a boundary circle");
    }
    if (const auto b = o.find("boundary")) c.boundary = b->boolean();
    c.outer = rational(o["outer"]);
    c.inner = rational(o["inner"]);
    const JsonField terms = o["convergents"];
    for (std::size_t t = 0, n = terms.array(); t < n; ++t) c.convergents.push_back(rational(terms[t]));
    c.found = o["found"].boolean();
    if (const auto f = o.find("failure")) c.failure = f->string();
    if (const auto f = o.find("note")) c.note = f->string();
    if (c.found != c.failure.empty()) o["found"].refuse("must be true exactly when there is no failure");
    if (o.find("flux_per_step")) {
      c.flux = o["flux_per_step"].real();
      if (!(c.flux > 0)) o["flux_per_step"].refuse("must be > 0");
      c.fluxUncertainty = o["flux_uncertainty"].nonNegative();
      c.zoneArea = o["zone_area"].nonNegative();
      if (!(c.zoneArea <= box)) o["zone_area"].refuse("exceeds the box's area " + shortestDecimal(static_cast<double>(box)));
      c.zoneSpread = o["zone_spread"].nonNegative();
      c.enclosedIslands = o["enclosed_islands_area"].nonNegative();
      c.enclosedCount = static_cast<int>(o["enclosed_islands"].whole(kIntMax));
      c.layerArea = o["layer_area"].real();
      if (std::fabs(c.layerArea - (c.zoneArea - c.enclosedIslands)) > 1e-9L * c.zoneArea)
        o["layer_area"].refuse("must be zone_area − enclosed_islands_area");
    } else if (c.found) {
      o.refuseDocument(o.name() + ": a cantorus found has a flux");
    }
    a.cantori.push_back(std::move(c));
  }
}

Atlas atlasFrom(rjson j) {
  const JsonField root(j, "the atlas");
  root.keys({"format", "program", "provenance", "map", "request", "cancelled", "seconds", "nodes"},
            {"stop_reason", "format_version", "checksum", "cantori"});
  checkSignature(j, root);
  (void)root["program"].string();  // written anew
  (void)root["provenance"].object();
  Atlas a;
  a.request = requestFrom(root);
  a.cancelled = root["cancelled"].boolean();
  if (const auto r = root.find("stop_reason")) a.stopReason = r->string();
  a.seconds = root["seconds"].nonNegative();
  const JsonField nodes = root["nodes"];
  const std::size_t n = nodes.array(kMaxAtlasNodes);
  if (n == 0) nodes.refuse("must hold the central island at least");
  a.nodes.reserve(n);
  for (std::size_t i = 0; i < n; ++i) a.nodes.push_back(nodeFrom(nodes[i], i, a));
  checkTree(a);
  if (const auto c = root.find("cantori")) readCantori(*c, a);
  return a;
}

}  // namespace

Atlas atlasFromJson(const std::string& text) {
  try {
    return atlasFrom(io::parseJson(text));  // a copy: its checksum is taken out to verify the rest
  } catch (const io::BadFile&) {
    throw;
  } catch (const std::exception& e) {  // nlohmann's own, should one escape
    throw io::BadFile(e.what());
  }
}

void writeAtlasJson(const std::filesystem::path& path, const Atlas& atlas) { io::writeFileAtomically(path, atlasJson(atlas)); }
void writeAtlasCsv(const std::filesystem::path& path, const Atlas& atlas) { io::writeFileAtomically(path, atlasCsv(atlas)); }

}  // namespace archipelago
