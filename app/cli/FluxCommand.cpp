#include "FluxCommand.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "CliCommon.hpp"
#include "HyperbolicOrbitOptions.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/manifolds/ManifoldExport.hpp"

namespace archipelago::cli {

namespace {
struct FluxOptions {
  MapParameters map;
  HyperbolicOrbitOptions orbit;
  TurnstileRequest request;
  bool json = false;
  std::string out;
  bool kac = false;
  KacRequest kacRequest;
};

std::string digitsText(long double d) {
  if (!std::isfinite(d)) return "all";
  char t[32];
  std::snprintf(t, sizeof t, "%.1Lf", d);
  return t;
}

void printText(const TurnstileFlux& f, const KacResult* k, double seconds) {
  const HeteroclinicPoint& h = f.intersections.first;
  const HeteroclinicPoint& h2 = f.intersections.second;
  std::printf("# flux through the separatrix of %s, K = %.17Lg (MacKay, Meiss & Percival 1984)\n",
              f.orbit.fixedPoint ? "the fixed point (sqrt K, 0)" : ("a periodic orbit of period " + std::to_string(f.orbit.period)).c_str(),
              f.orbit.K);
  std::printf("# side: %s\n", toString(f.side));
  std::printf("# multiplier: %.19Lg\n", static_cast<long double>(f.orbit.multiplier));
  for (const HeteroclinicPoint* p : {&h, &h2})
    std::printf("# %s_point: %.19Lg,%.19Lg (on %s after %d steps; action %s)\n",
                f.orbit.fixedPoint ? "homoclinic" : "heteroclinic", static_cast<long double>(p->point.x),
                static_cast<long double>(p->point.y), p->line == smooth::SymmetryLine::S1 ? "S1" : "S2", p->symmetricIndex,
                quadText(p->action, 25).c_str());
  std::printf("# lobe_area_action: %s\n", quadText(f.lobeAction < 0 ? -f.lobeAction : f.lobeAction, 25).c_str());
  std::printf("# lobe_action_error: %s\n", quadText(f.lobeActionError, 2).c_str());
  std::printf("# lobe_area_polygon: %.19Lg\n", std::fabs(f.lobePolygon.area));
  std::printf("# lobe_polygon_error: %.3Lg (Romberg, %d vertices per arc)\n", f.lobePolygon.error, f.lobePolygon.verticesPerArc);
  std::printf("# lobe_agreeing_digits: %s\n", digitsText(f.lobeDigits()).c_str());
  std::printf("# flux_per_step: %.19Lg\n", f.lobeArea);
  std::printf("# zone_area_action: %s\n", quadText(f.zoneAction < 0 ? -f.zoneAction : f.zoneAction, 25).c_str());
  std::printf("# zone_area_polygon: %.19Lg\n", std::fabs(f.zonePolygon.area));
  std::printf("# zone_agreeing_digits: %s\n", digitsText(f.zoneDigits()).c_str());
  if (k) {
    std::printf("# kac_max_steps: %llu\n", static_cast<unsigned long long>(k->maxSteps));
    std::printf("# kac_mean_residence: %.6g +- %.2g (%llu orbits from the entry lobe, %llu still inside)\n",
                k->meanResidence, k->meanResidenceError, static_cast<unsigned long long>(k->entryOrbits),
                static_cast<unsigned long long>(k->stillInside));
    std::printf("# kac_transit_area: %.6g +- %.2g (fraction %.5f of the zone leaves within the steps)\n", k->transitArea,
                k->transitAreaError, k->transitFraction);
    std::printf("# kac_transit_area_over_flux: %.6g +- %.2g\n", k->predictedResidence, k->predictedResidenceError);
    std::printf("# kac_discrepancy_sigmas: %.2f\n", k->discrepancy());
    std::printf("# kac_inconsistent_orbits: %llu\n", static_cast<unsigned long long>(k->inconsistent));
  }
  std::printf("# seconds: %.3f\n", seconds);
}

int runFlux(FluxOptions o) {
  TurnstileRequest& r = o.request;
  r.K = o.map.K;
  if (auto e = manifoldKError(r.K)) throw std::invalid_argument(*e);
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  o.kacRequest.K = r.K;  // the Kac options are checked even without --kac: a bad value is never ignored silently
  if (auto e = validationError(o.kacRequest)) throw std::invalid_argument(*e);
  io::checkCommandFiles({{"--out", o.out, io::FileUse::Output}});
  const auto started = std::chrono::steady_clock::now();
  r.orbit = chosenOrbit(r.K, o.orbit);
  r.side = chosenSide(o.orbit, !r.orbit);
  const TurnstileFlux flux = computeTurnstileFlux(r);
  std::optional<KacResult> kac;
  if (o.kac) {
    o.kacRequest.orbit = r.orbit;
    o.kacRequest.side = r.side;
    kac = runKacCheck(o.kacRequest);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string json = turnstileJson(r, flux, o.kac ? &o.kacRequest : nullptr, kac ? &*kac : nullptr, seconds) + "\n";
  if (!o.out.empty()) io::writeFileAtomically(o.out, json);
  if (o.json) std::fputs(json.c_str(), stdout);
  else printText(flux, kac ? &*kac : nullptr, seconds);
  return 0;
}
}  // namespace

void addFluxCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<FluxOptions>();
  CLI::App* cmd = app.add_subcommand(
      "flux", "turnstile flux through the separatrix of the fixed point (sqrt K, 0) or of a symmetric hyperbolic "
              "periodic orbit: the lobe area by the action difference and by the polygon area, the zone's area, and "
              "(--kac) the mean residence time against transit area / flux");
  // Only K: the flux is of the plane map Q (no box), so --xmin/--xmax would be ignored silently.
  addNumberOption(*cmd, "--K", o->map.K, "map parameter K of Q: y′ = y + 2(x² − K), x′ = x + y′ (§2); in (0, 1]");
  addHyperbolicOrbitOptions(*cmd, o->orbit);
  cmd->add_flag("--json", o->json, "print JSON instead of '# key: value' lines");
  cmd->add_option("--out", o->out, "also write the JSON here (atomically)");
  addNumberOption(*cmd, "--vertices", o->request.maxVertices, "polygon vertices per arc at the finest Romberg level");
  addNumberOption(*cmd, "--domains", o->request.maxDomains, "fundamental domains scanned for the primary points (0: automatic)");
  cmd->add_flag("--kac", o->kac, "also run the Kac check: mean residence of orbits entering the zone against transit area / flux");
  addNumberOption(*cmd, "--kac-samples", o->kacRequest.entrySamples, "orbits started in the entry lobe");
  addNumberOption(*cmd, "--kac-zone-samples", o->kacRequest.zoneSamples, "points of the zone for the transit area");
  addNumberOption(*cmd, "--kac-steps", o->kacRequest.maxSteps, "T: residence times are capped at T steps");
  addNumberOption(*cmd, "--seed", o->kacRequest.seed, "seed of the Kac check's random points");
  addNumberOption(*cmd, "--threads", o->kacRequest.threads, "threads of the Kac check (0: one per core)");
  cmd->callback([o, &status] { status = runFlux(*o); });
}

}  // namespace archipelago::cli
