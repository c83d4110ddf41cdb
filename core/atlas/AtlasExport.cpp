#include "core/atlas/AtlasExport.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/io/AtomicFile.hpp"
#include "core/io/NumberText.hpp"
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
                  {"bisections", a.request.bisections}};
  j["cancelled"] = a.cancelled;
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
      f["layer_area"] = num(n.flux.layerArea);
      f["flux_agreeing_digits"] = num(n.flux.fluxDigits);
      f["zone_agreeing_digits"] = num(n.flux.zoneDigits);
      f["residence"] = n.flux.residence;
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
  return j.dump(2) + "\n";
}

std::string atlasCsv(const Atlas& a) {
  std::ostringstream out;
  for (const auto& [k, v] : atlasProvenance(a).fields) out << "# " << k << ": " << v << "\n";
  out << "# cancelled: " << (a.cancelled ? "yes" : "no") << "\n";
  out << "index,parent,level,path,period,about_parent,x,y,line,residue,boundary_rotation,boundary_digits,area,"
         "area_error,islands_area,flux,zone_area,layer_area,residence,note\n";
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const AtlasNode& n = a.nodes[i];
    out << i << "," << n.parent << "," << n.level << "," << atlasPath(a, static_cast<int>(i)) << "," << n.period << ","
        << rationalText(n.aboutParent) << "," << text(n.centre.x, 19) << "," << text(n.centre.y, 19) << ","
        << (n.onS1 ? "S1" : "S2") << "," << text(n.orbit.residue) << ","
        << (n.boundaryFound ? text(n.boundaryRotation) : "") << "," << (n.boundaryFound ? text(n.boundaryDigits, 4) : "")
        << "," << (n.boundaryFound ? text(n.area) : "") << "," << (n.boundaryFound ? text(n.areaError, 3) : "") << ","
        << (n.boundaryFound ? text(n.area * static_cast<long double>(n.period)) : "") << ","
        << (n.flux.found ? text(n.flux.flux) : "") << "," << (n.flux.found ? text(n.flux.zoneArea) : "") << ","
        << (n.flux.found ? text(n.flux.layerArea) : "") << ","
        << (n.flux.found ? text(n.flux.residence, 6) : "") << ",\"" << n.note << "\"\n";
  }
  return out.str();
}

void writeAtlasJson(const std::filesystem::path& path, const Atlas& atlas) { io::writeFileAtomically(path, atlasJson(atlas)); }
void writeAtlasCsv(const std::filesystem::path& path, const Atlas& atlas) { io::writeFileAtomically(path, atlasCsv(atlas)); }

}  // namespace archipelago
