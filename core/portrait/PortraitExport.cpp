#include "core/portrait/PortraitExport.hpp"

#include <nlohmann/json.hpp>

#include <sstream>
#include <stdexcept>

#include "core/io/AtomicFile.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/portrait/PortraitJson.hpp"
#include "core/runspec/RunSpecJson.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"

namespace archipelago {

namespace {
std::string longDouble(long double v) {
  std::ostringstream s;
  s.precision(19);
  s << v;
  return s.str();
}

void writeText(const std::string& path, const std::string& text) { io::writeFileAtomically(path, text + '\n'); }
}  // namespace

nlohmann::json mapWithCoefficientsJson(const MapParameters& map) {
  const MapCoefficients k = computeCoefficients(map);
  nlohmann::json j = spec::mapJson(map);
  j["coefficients"] = {{"A", k.A}, {"B", k.B}, {"C", k.C}, {"m", k.m}};
  return j;
}

nlohmann::json viewportJson(const MapParameters& map, const Viewport& view) {
  const PhysicalRect b = view.physical(map);
  return {{"centre_unit", {{"X", view.centre().X}, {"Y", view.centre().Y}}},
          {"width_units", longDouble(view.widthUnits())},
          {"height_units", longDouble(view.heightUnits())},
          {"physical", {{"x0", longDouble(b.x0)}, {"x1", longDouble(b.x1)}, {"y0", longDouble(b.y0)}, {"y1", longDouble(b.y1)}}},
          {"unit", "physical x = xmin + L*X/2^52, y = -L/2 + L*Y/2^52, L = xmax - xmin"}};
}

std::string sidecarPath(const std::string& npyPath) {
  const std::string ext = ".npy";
  if (npyPath.size() > ext.size() && npyPath.compare(npyPath.size() - ext.size(), ext.size(), ext) == 0)
    return npyPath.substr(0, npyPath.size() - ext.size()) + ".json";
  return npyPath + ".json";
}

void addView(Provenance& provenance, const MapParameters& map, const Viewport& view) {
  const PhysicalRect b = view.physical(map);
  provenance.add("View x0", b.x0).add("View x1", b.x1).add("View y0", b.y0).add("View y1", b.y1);
}

Provenance portraitProvenance(const PortraitRequest& r) {
  Provenance p = mapProvenance(r.map);
  addView(p, r.map, r.view);
  p.add("Image", "phase portrait, " + std::string(toString(r.mode)));
  p.add("Size", std::to_string(r.width) + "x" + std::to_string(r.height));
  p.add("Points", std::to_string(r.points));
  if (r.mode == PortraitMode::Orbits)
    p.add("Seed grid", std::to_string(r.seedColumns) + "x" + std::to_string(r.seedRows));
  else
    p.add("Orbits", std::to_string(r.orbits));
  if (r.mode == PortraitMode::Stickiness) p.add("Xr", r.Xr).add("q", std::to_string(r.q));
  p.add("Seed", std::to_string(r.seed));
  return p;
}

std::string portraitMetadataJson(const PortraitRequest& r, const PortraitRaster& raster, const std::string& arrayName) {
  using nlohmann::json;
  std::uint64_t maxCount = 0;
  for (std::uint64_t c : raster.counts) maxCount = std::max(maxCount, c);
  json j;
  j["format"] = "archipelago portrait raster";
  j["version"] = ARCHIPELAGO_VERSION;
  j["program"] = programDescription();
  j["array"] = arrayName;
  j["rows"] = "row 0 is the top of the view (largest y); column 0 its left edge (smallest x)";
  j["shape"] = {raster.height, raster.width};
  j["mode"] = std::string(toString(r.mode));
  j["map"] = mapWithCoefficientsJson(r.map);
  j["viewport"] = viewportJson(r.map, r.view);
  j["request"] = {{"points", r.points},     {"orbits", r.orbitCount()}, {"steps_per_orbit", r.stepsPerOrbit()},
                  {"seed", r.seed},         {"passes", r.passes},       {"seed_grid", {r.seedColumns, r.seedRows}},
                  {"Xr", r.Xr},             {"q", r.q}};
  j["counts"] = {{"points_iterated", raster.pointsIterated},
                 {"points_binned", raster.pointsBinned},
                 {"non_empty_pixels", raster.nonEmptyPixels()},
                 {"max_count", maxCount}};
  return j.dump(2);
}

void exportPortraitNpy(const std::string& npyPath, const PortraitRequest& request, const PortraitRaster& raster) {
  const auto rows = static_cast<std::size_t>(raster.height), cols = static_cast<std::size_t>(raster.width);
  std::string name;
  switch (raster.mode) {
    case PortraitMode::Density:
      writeNpy(npyPath, raster.counts, rows, cols);
      name = "counts";
      break;
    case PortraitMode::Orbits:
      writeNpy(npyPath, raster.labels, rows, cols);
      name = "labels (1 + smallest seed index reaching the pixel; 0 = none)";
      break;
    case PortraitMode::Stickiness:
      writeNpy(npyPath, raster.meanSegmentLengths(), rows, cols);
      name = "mean trapped-segment length in steps of N^-1 (0 = no visit)";
      break;
  }
  writeText(sidecarPath(npyPath), portraitMetadataJson(request, raster, name));
}

std::string stochasticAreaJson(const StochasticAreaRequest& r, const StochasticAreaResult& result) {
  using nlohmann::json;
  json curve = json::array();
  // b₂ is an area (appendix A), the box counting measures the fraction of the box: both, by their names.
  for (const auto& p : result.convergence)
    curve.push_back({{"iterations", p.iterations}, {"boxes_visited", p.boxesVisited},
                     {"b2_area", stochasticAreaOf(r.map, p.b2).area}, {"b2_fraction", p.b2}});
  json j;
  j["quantity"] = "b2: area of the chaotic sea of Q* in the box (Karney 1983, sec. 5 and appendix A: b0 = L^2), "
                  "b2_fraction: the fraction of the boxes of the grid it visits";
  j["map"] = spec::mapJson(r.map);
  j["Xr"] = r.Xr;
  j["q"] = r.q;
  j["orbits"] = r.orbits;
  j["seed"] = r.seed;
  j["grid"] = std::uint64_t{1} << r.gridBits;
  const StochasticAreaValue b2 = stochasticAreaOf(r.map, result.b2());
  j["box_area"] = b2.boxArea;
  j["b2_area"] = b2.area;
  j["b2_fraction"] = b2.fraction;
  j["cancelled"] = result.cancelled;
  j["convergence"] = curve;
  return j.dump(2);
}

}  // namespace archipelago
