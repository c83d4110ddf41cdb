#include "core/measures/MeasureExport.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include "core/io/AtomicFile.hpp"
#include "core/io/Npy.hpp"
#include "core/view/ViewExport.hpp"  // sidecarPath
#include "core/view/ViewJson.hpp"

namespace archipelago {

namespace {
constexpr OrbitVerdict kVerdicts[] = {OrbitVerdict::NotComputed, OrbitVerdict::Measured, OrbitVerdict::Regular,
                                      OrbitVerdict::Chaotic, OrbitVerdict::Escaping};

/// A double for JSON: null when not finite.
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

/// The p-th quantile (0 ≤ p ≤ 1) of the sorted values, by the nearest rank.
double quantile(const std::vector<double>& sorted, double p) {
  const auto i = static_cast<std::size_t>(std::lround(p * static_cast<double>(sorted.size() - 1)));
  return sorted[i];
}
}  // namespace

std::string indicatorQuantity(IndicatorKind kind) {
  switch (kind) {
    case IndicatorKind::Dig:
      return "digits: -log10 |difference of the weighted Birkhoff averages of x over two consecutive blocks of T "
             "points| (16 = equal)";
    case IndicatorKind::Rotation:
      return "rotation number about (-sqrt K, 0), turns per step, positive in the sense Q turns (clockwise); "
             "NaN: chaotic or escaping (see the verdicts)";
    case IndicatorKind::Fli: return "fast Lyapunov indicator: max over n <= T of ln |v_n|, v_0 = (1, 0)";
    case IndicatorKind::Megno: return "MEGNO <Y>_T: 2 on invariant curves, 0 at stable periodic orbits, ~ lambda T / 2 if chaotic";
    case IndicatorKind::Lyapunov: return "finite-time maximal Lyapunov exponent ln |v_T| / T, per step";
  }
  return "";
}

Provenance indicatorProvenance(const IndicatorRequest& r) {
  Provenance p = mapProvenance(r.measure.map);
  addView(p, r.measure.map, r.view);
  p.add("Image", "indicator map, " + std::string(toString(r.measure.kind)));
  p.add("Size", std::to_string(r.width) + "x" + std::to_string(r.height));
  p.add("Iterations", std::to_string(r.measure.iterations));
  p.add("Digits threshold", r.measure.digitsThreshold);
  return p;
}

std::string indicatorMetadataJson(const IndicatorRequest& r, const IndicatorResult& result, const std::string& verdictsFile) {
  using nlohmann::json;
  const IndicatorRaster& raster = result.raster;
  json j;
  j["format"] = "archipelago indicator raster";
  j["version"] = ARCHIPELAGO_VERSION;
  j["program"] = programDescription();
  j["kind"] = std::string(toString(r.measure.kind));
  j["array"] = indicatorQuantity(r.measure.kind);
  j["rows"] = "row 0 is the top of the view (largest y); column 0 its left edge (smallest x)";
  j["shape"] = {raster.height, raster.width};
  j["pixel_start"] = "the centre of the pixel's cell, rounded to the 52-bit grid (as the portrait's orbit mode seeds)";
  j["map"] = mapWithCoefficientsJson(r.measure.map);
  j["viewport"] = viewportJson(r.measure.map, r.view);
  j["request"] = {{"iterations", r.measure.iterations},
                  {"steps_per_orbit", stepsPerOrbit(r.measure)},
                  {"digits_threshold", r.measure.digitsThreshold},
                  {"passes", r.passes},
                  {"kernel", std::string(kernelOrBest(r.measure.kernel).name)}};
  json codes = json::object(), counts = json::object();
  for (OrbitVerdict v : kVerdicts) {
    codes[std::to_string(static_cast<int>(v))] = std::string(toString(v));
    counts[std::string(toString(v))] = raster.count(v);
  }
  j["verdicts"] = {{"codes", codes}, {"counts", counts}};
  if (!verdictsFile.empty()) j["verdicts"]["file"] = verdictsFile;
  j["cancelled"] = result.cancelled;
  j["seconds"] = result.seconds;
  return j.dump(2);
}

void exportIndicatorNpy(const std::string& npyPath, const IndicatorRequest& request, const IndicatorResult& result,
                        const std::string& verdictsPath) {
  const IndicatorRaster& raster = result.raster;
  const auto rows = static_cast<std::size_t>(raster.height), cols = static_cast<std::size_t>(raster.width);
  writeNpy(npyPath, raster.values, rows, cols);
  if (!verdictsPath.empty()) {
    std::vector<std::uint32_t> codes(raster.verdicts.size());
    std::transform(raster.verdicts.begin(), raster.verdicts.end(), codes.begin(),
                   [](OrbitVerdict v) { return static_cast<std::uint32_t>(v); });
    writeNpy(verdictsPath, codes, rows, cols);
  }
  const std::string name = verdictsPath.empty() ? "" : std::filesystem::path(verdictsPath).filename().string();
  io::writeFileAtomically(sidecarPath(npyPath), indicatorMetadataJson(request, result, name) + '\n');
}

RasterImage colourizeIndicator(const IndicatorRaster& raster, ColourMapName mapName) {
  const ColourMap colours(mapName);
  const std::vector<double> values = raster.filled();
  const std::vector<OrbitVerdict> verdicts = raster.filledVerdicts();
  RasterImage image;
  image.width = raster.width;
  image.height = raster.height;
  image.rgb.assign(3 * raster.pixelCount(), 0);
  double lo = 0, hi = kMaxDigits;
  if (raster.kind != IndicatorKind::Dig) {
    std::vector<double> finite;
    for (double v : values)
      if (std::isfinite(v)) finite.push_back(v);
    std::sort(finite.begin(), finite.end());
    lo = finite.empty() ? 0 : quantile(finite, 0.01);
    hi = finite.empty() ? 1 : quantile(finite, 0.99);
    if (!(hi > lo)) hi = lo + 1;
  }
  image.scaleMin = lo;
  image.scaleMax = hi;
  image.quantity = raster.kind == IndicatorKind::Dig ? "digits" : std::string(toString(raster.kind));
  for (std::size_t i = 0; i < values.size(); ++i) {
    Rgb c{0, 0, 0};
    if (std::isfinite(values[i])) {
      const double t = std::clamp((values[i] - lo) / (hi - lo), 0.0, 1.0);
      c = colours.at(kLowest + (1 - kLowest) * t);
    } else if (verdicts[i] == OrbitVerdict::Chaotic) {
      c = kChaoticColour;
    } else if (verdicts[i] == OrbitVerdict::Escaping) {
      c = kEscapingColour;
    }
    image.rgb[3 * i] = c.r;
    image.rgb[3 * i + 1] = c.g;
    image.rgb[3 * i + 2] = c.b;
  }
  return image;
}

std::string rotationReportJson(const ChainRequest& r, const ChainIdentification& chain) {
  using nlohmann::json;
  const FixedPointMap map(r.map);
  const PhysicalPoint p = map.toPhysical(r.start);
  json j;
  j["format"] = "archipelago rotation report";
  j["version"] = ARCHIPELAGO_VERSION;
  j["program"] = programDescription();
  j["map"] = mapWithCoefficientsJson(r.map);
  j["start"] = {{"x", static_cast<double>(p.x)}, {"y", static_cast<double>(p.y)}, {"X", r.start.X}, {"Y", r.start.Y}};
  j["iterations"] = r.iterations;
  j["digits_threshold"] = r.digitsThreshold;
  j["convention"] = "turns per application of Q^n, positive in the sense Q^n turns about the point it is measured "
                    "about (clockwise about (-sqrt K, 0)); weighted Birkhoff average over two blocks of T";
  const RotationMeasurement& m0 = chain.levels.front().rotation;
  j["rotation"] = number(m0.rotation);
  j["digits"] = number(m0.digits);
  j["verdict"] = std::string(toString(m0.verdict));
  json levels = json::array();
  for (const ChainLevel& level : chain.levels) {
    json l;
    l["power"] = level.power;
    l["centre"] = {{"x", static_cast<double>(level.centre.x)}, {"y", static_cast<double>(level.centre.y)}};
    l["sense"] = level.sense > 0 ? "clockwise" : "counter-clockwise";
    l["rotation"] = number(level.rotation.rotation);
    l["digits"] = number(level.rotation.digits);
    l["verdict"] = std::string(toString(level.rotation.verdict));
    l["rational"] = level.rational ? json(toString(*level.rational)) : json(nullptr);
    if (level.orbit) {
      const double R = static_cast<double>(level.orbit->residue);
      l["orbit"] = {{"period", level.orbit->period},
                    {"residue", R},
                    {"linear_rotation", std::acos(1 - 2 * R) / (2 * std::numbers::pi)},
                    {"closure", static_cast<double>(level.orbit->closure)}};
    }
    levels.push_back(l);
  }
  j["chain"] = {{"period", chain.period},
                {"factors", chain.factors},
                {"summary", chain.summary},
                {"ending", chain.ending},
                {"cancelled", chain.cancelled},
                {"levels", levels}};
  return j.dump(2);
}

}  // namespace archipelago
