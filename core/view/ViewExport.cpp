#include "core/view/ViewExport.hpp"

#include <nlohmann/json.hpp>

#include <sstream>

#include "core/map/FixedPointMap.hpp"
#include "core/runspec/RunSpecJson.hpp"
#include "core/view/ViewJson.hpp"

namespace archipelago {

namespace {
std::string longDouble(long double v) {
  std::ostringstream s;
  s.precision(19);
  s << v;
  return s.str();
}
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
  addView(provenance, view.physical(map));
}

void addView(Provenance& provenance, const PhysicalRect& b) {
  provenance.add("View x0", b.x0).add("View x1", b.x1).add("View y0", b.y0).add("View y1", b.y1);
}

}  // namespace archipelago
