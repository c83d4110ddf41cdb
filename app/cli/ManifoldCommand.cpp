#include "ManifoldCommand.hpp"

#include <cstdio>
#include <iostream>
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
struct ManifoldOptions {
  MapParameters map;
  HyperbolicOrbitOptions orbit;
  ManifoldCurveRequest request;
  std::string branch = "unstable";
  std::string stableFrom = "inverse";
  std::string view;
  bool box = false;
  std::uint64_t maxPoints = ManifoldCurveRequest{}.maxPoints;
  std::string out;
};

int runManifold(ManifoldOptions o) {
  ManifoldCurveRequest& r = o.request;
  r.K = o.map.K;
  r.kind = parseManifoldKind(o.branch, "branch");  // core's names and message, as Python's manifold(branch=)
  r.stableFrom = parseStableConstruction(o.stableFrom, "stable_from");
  if (!o.view.empty()) {
    r.view = parseView(o.view);
  }
  if (o.box) {
    validate(o.map);
    r.box = o.map;
  }
  r.maxPoints = static_cast<std::size_t>(o.maxPoints);
  if (auto e = manifoldKError(r.K)) throw std::invalid_argument(*e);
  if (auto e = manifoldPeriodError(o.orbit.period)) throw std::invalid_argument(*e);
  if (auto e = orbitPointError(r.point, o.orbit.period)) throw std::invalid_argument(*e);
  {
    ManifoldCurveRequest check = r;  // every range before the orbit search and before the work
    check.point = 0;
    if (auto e = validationError(check)) throw std::invalid_argument(*e);
    checkManifoldMemory(check);
  }
  io::checkCommandFiles({{"--out", o.out, io::FileUse::Output}});
  r.orbit = chosenOrbit(r.K, o.orbit);
  r.side = chosenSide(o.orbit, !r.orbit);
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const ManifoldCurve curve = computeManifoldCurve(r);
  if (o.out.empty()) {
    writeManifoldCsv(std::cout, r, curve);
    std::cout.flush();
  } else {
    writeManifoldCsv(o.out, r, curve);
    std::printf("manifold: %zu points in %zu pieces, length %.6Lg, %d domains, stopped by %s; written to %s\n",
                curve.points, curve.pieces.size(), curve.length, curve.domains, curve.stoppedBy.c_str(), o.out.c_str());
  }
  return 0;
}
}  // namespace

void addManifoldCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<ManifoldOptions>();
  CLI::App* cmd = app.add_subcommand(
      "manifold", "a branch of the stable or unstable manifold of the fixed point (sqrt K, 0) or of a hyperbolic "
                  "periodic orbit, refined by spacing and turning angle; CSV s,x,y with a '#' metadata header");
  addMapOptions(*cmd, o->map);
  addHyperbolicOrbitOptions(*cmd, o->orbit);
  addNumberOption(*cmd, "--point", o->request.point, "which point z_j of the periodic orbit, [0, period)");
  cmd->add_option("--branch", o->branch, "stable or unstable")->default_str("unstable");
  cmd->add_option("--stable-from", o->stableFrom,
                  "stable branch from the inverse map (inverse) or by the reversing symmetry (symmetry)")
      ->default_str("inverse");
  addNumberOption(*cmd, "--length", o->request.length, "arc length to draw (physical units), (0, 1e6]");
  addNumberOption(*cmd, "--spacing", o->request.maxSpacing, "largest chord between neighbours, [1e-14, 1]");
  addNumberOption(*cmd, "--angle", o->request.maxAngle, "largest turning angle between neighbours (radians), (0, 1]");
  addNumberOption(*cmd, "--domains", o->request.maxDomains, "fundamental domains at most, [1, 10000]");
  addNumberOption(*cmd, "--initial-points", o->request.initialPoints, "points per domain before refinement");
  addNumberOption(*cmd, "--escape", o->request.escapeRadius, "plane map: drop points farther than this from the origin");
  addNumberOption(*cmd, "--max-points", o->maxPoints, "points at most, [16, 1e8] (and ~128 bytes each must be free)");
  cmd->add_option("--view", o->view, "x0,x1,y0,y1: refine finely only in this rectangle (a zoomed view)");
  cmd->add_flag("--box", o->box, "the manifold of the torus map Q* in the box --xmin, --xmax (default: Q in the plane)");
  cmd->add_option("--out", o->out, "write the CSV here (atomically) instead of stdout");
  cmd->callback([o, &status] { status = runManifold(*o); });
}

}  // namespace archipelago::cli
