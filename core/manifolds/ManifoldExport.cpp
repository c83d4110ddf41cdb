#include "core/manifolds/ManifoldExport.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "core/io/AtomicFile.hpp"
#include "core/provenance/Provenance.hpp"

namespace archipelago {

namespace {

std::string number(long double v, int digits = 19) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*Lg", digits, v);
  return text;
}

std::string orbitText(const HyperbolicOrbit& orbit) {
  if (orbit.fixedPoint) return "the hyperbolic fixed point (sqrt K, 0)";
  return "a hyperbolic periodic orbit of period " + std::to_string(orbit.period);
}

nlohmann::ordered_json pointJson(const smooth::Point<quad>& p) {
  return nlohmann::ordered_json::array({static_cast<double>(p.x), static_cast<double>(p.y)});
}

nlohmann::ordered_json areaJson(quad action, const PolygonArea& polygon, long double digits) {
  nlohmann::ordered_json j;
  j["action"] = std::fabs(static_cast<double>(action));
  j["action_text"] = quadText(action < 0 ? -action : action);
  j["polygon"] = std::fabs(static_cast<double>(polygon.area));
  j["polygon_error"] = static_cast<double>(polygon.error);
  j["polygon_raw"] = std::fabs(static_cast<double>(polygon.raw));
  j["polygon_vertices_per_arc"] = polygon.verticesPerArc;
  j["romberg_levels"] = polygon.levels;
  j["agreeing_digits"] = std::isfinite(digits) ? nlohmann::ordered_json(static_cast<double>(digits)) : nlohmann::ordered_json("all");
  return j;
}

}  // namespace

void writeManifoldCsv(std::ostream& out, const ManifoldCurveRequest& r, const ManifoldCurve& c) {
  out << "# manifold: " << toString(r.kind) << " manifold, " << toString(r.side) << " branch, of "
      << (r.orbit ? "a hyperbolic periodic orbit of period " + std::to_string(r.orbit->period)
                  : std::string("the hyperbolic fixed point (sqrt K, 0)"))
      << " of Q (eq. qu): y' = y + 2(x^2 - K), x' = x + y'\n";
  out << "# program: " << programDescription() << "\n";
  out << "# K: " << number(r.K) << "\n";
  out << "# map: "
      << (r.box ? "Q* in the box [" + number(r.box->xmin, 17) + ", " + number(r.box->xmax, 17) + ") x [-L/2, L/2)"
                : std::string("Q in the plane"))
      << "\n";
  out << "# period: " << (r.orbit ? r.orbit->period : 1) << "\n";
  out << "# point: " << r.point << "\n";
  out << "# origin: " << number(c.origin.x) << "," << number(c.origin.y) << "\n";
  out << "# branch: " << toString(r.kind) << "\n";
  out << "# side: " << toString(r.side) << "\n";
  if (r.kind == ManifoldKind::Stable)
    out << "# stable_from: "
        << (r.stableFrom == StableConstruction::InverseMap ? "inverse map" : "reversing symmetry") << "\n";
  out << "# length_requested: " << number(r.length) << "\n";
  out << "# spacing: " << number(r.maxSpacing) << "\n";
  out << "# angle: " << number(r.maxAngle) << "\n";
  out << "# initial_points: " << r.initialPoints << "\n";
  out << "# domains_max: " << r.maxDomains << "\n";
  if (!r.box) out << "# escape_radius: " << number(r.escapeRadius) << "\n";
  if (r.view)
    out << "# view: " << number(r.view->x0) << "," << number(r.view->x1) << "," << number(r.view->y0) << ","
        << number(r.view->y1) << "\n";
  out << "# max_points: " << r.maxPoints << "\n";
  out << "# length: " << number(c.length) << "\n";
  out << "# domains: " << c.domains << "\n";
  out << "# points: " << c.points << "\n";
  out << "# pieces: " << c.pieces.size() << "\n";
  out << "# breaks: " << c.breaks << "\n";
  out << "# unresolved: " << c.unresolved << "\n";
  out << "# stopped_by: " << c.stoppedBy << "\n";
  out << "# precision: points in long double from a local series in __float128 (core/manifolds)\n";
  out << "s,x,y\n";
  char line[128];
  for (std::size_t k = 0; k < c.pieces.size(); ++k) {
    const ManifoldPiece& p = c.pieces[k];
    if (k > 0) out << "# piece " << k + 1 << "\n";
    for (std::size_t i = 0; i < p.points.size(); ++i) {
      std::snprintf(line, sizeof line, "%.19Lg,%.19Lg,%.19Lg\n", p.arcLength[i], p.points[i].x, p.points[i].y);
      out << line;
    }
  }
}

void writeManifoldCsv(const std::filesystem::path& path, const ManifoldCurveRequest& request, const ManifoldCurve& curve) {
  io::AtomicOutputFile file(path);
  writeManifoldCsv(file.stream(), request, curve);
  file.commit();
}

std::string turnstileJson(const TurnstileRequest& request, const TurnstileFlux& f, const KacRequest* kac,
                          const KacResult* k, double seconds) {
  using json = nlohmann::ordered_json;
  json j;
  j["K"] = static_cast<double>(request.K);
  json orbit;
  orbit["description"] = orbitText(f.orbit);
  orbit["period"] = f.orbit.period;
  orbit["multiplier"] = static_cast<double>(f.orbit.multiplier);
  orbit["residue"] = static_cast<double>(f.orbit.residue());
  json points = json::array();
  for (const auto& p : f.orbit.points) points.push_back(pointJson(p));
  orbit["points"] = points;
  j["orbit"] = orbit;
  j["side"] = toString(f.side);
  j["target"] = f.target;
  json primary = json::array();
  for (const HeteroclinicPoint* h : {&f.intersections.first, &f.intersections.second}) {
    json p;
    p["point"] = pointJson(h->point);
    p["symmetry_line"] = h->line == smooth::SymmetryLine::S1 ? "S1: y = K - x^2" : "S2: y = 0";
    p["on_line_after_steps"] = h->symmetricIndex;
    p["sigma"] = static_cast<double>(h->sigma);
    p["mu"] = static_cast<double>(h->mu);
    p["action"] = static_cast<double>(h->action);
    p["action_text"] = quadText(h->action);
    p["action_terms"] = h->actionTerms;
    p["manifold_mismatch"] = static_cast<double>(h->mismatch);
    primary.push_back(p);
  }
  j[f.orbit.fixedPoint ? "homoclinic_points" : "heteroclinic_points"] = primary;
  j["lobe_area"] = areaJson(f.lobeAction, f.lobePolygon, f.lobeDigits());
  j["lobe_area"]["action_error"] = static_cast<double>(f.lobeActionError);
  j["flux_per_step"] = static_cast<double>(f.lobeArea);
  j["zone_area"] = areaJson(f.zoneAction, f.zonePolygon, f.zoneDigits());
  if (kac && k) {
    json c;
    c["max_steps"] = k->maxSteps;
    c["seed"] = kac->seed;
    c["entry_orbits"] = k->entryOrbits;
    c["mean_residence"] = k->meanResidence;
    c["mean_residence_error"] = k->meanResidenceError;
    c["still_inside"] = k->stillInside;
    c["longest_residence"] = k->longestResidence;
    c["zone_points"] = k->zonePoints;
    c["transit_fraction"] = k->transitFraction;
    c["transit_fraction_error"] = k->transitFractionError;
    c["transit_area"] = k->transitArea;
    c["transit_area_error"] = k->transitAreaError;
    c["transit_area_over_flux"] = k->predictedResidence;
    c["transit_area_over_flux_error"] = k->predictedResidenceError;
    c["island_area"] = k->islandArea;
    c["discrepancy_sigmas"] = k->discrepancy();
    c["inconsistent_orbits"] = k->inconsistent;
    c["steps"] = k->steps;
    c["seconds"] = k->seconds;
    j["kac"] = c;
  }
  if (seconds >= 0) j["seconds"] = seconds;
  return j.dump(2);
}

}  // namespace archipelago
