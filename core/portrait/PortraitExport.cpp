#include "core/portrait/PortraitExport.hpp"

#include <nlohmann/json.hpp>

#include <sstream>
#include <stdexcept>

#include "core/io/AtomicFile.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/view/ViewJson.hpp"  // the map and the viewport, as every raster of a view writes them

namespace archipelago {

namespace {
void writeText(const std::string& path, const std::string& text) { io::writeFileAtomically(path, text + '\n'); }
}  // namespace

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

}  // namespace archipelago
