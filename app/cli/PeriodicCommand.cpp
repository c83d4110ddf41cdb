#include "PeriodicCommand.hpp"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "CliCommon.hpp"
#include "core/io/NumberText.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago::cli {

namespace {
struct PeriodicOptions {
  MapParameters map;
  int period = 0;
  std::string near;
  long double radius = PeriodicOrbitSearch{}.searchRadius;
  bool stableOnly = false;
};

int runPeriodic(const PeriodicOptions& o) {
  validate(o.map);  // the box of Q*: Q* = Q inside it (appendix B rules)
  PeriodicOrbitSearch search;
  search.period = o.period;
  search.near = parsePoint("--near", o.near);
  search.searchRadius = o.radius;
  search.stableOnly = o.stableOnly;
  const long double K = o.map.K;
  const PeriodicOrbit orbit = findPeriodicOrbit(K, search);  // throws with a one-line reason

  const OrbitClassification kind = orbit.classification();
  std::printf("# periodic orbit of Q (eq. qu), K = %s\n", io::shortestText(o.map.K).c_str());
  std::printf("# period: %d\n", orbit.period);
  std::printf("# residue: %.18Lg\n", orbit.residue);
  std::printf("# trace: %.18Lg\n", orbit.trace);
  std::printf("# class: %s\n", toString(kind.stability));
  std::printf("# stable: %s (%s)\n", kind.stable() ? "yes" : "no", kind.description());
  std::printf("# rotation_number: %s\n", rotationNumberText(orbit, 18).c_str());
  std::printf("# symmetry: %s\n", toString(orbit.symmetry));
  std::printf("# closure: %.3Lg\n", orbit.closure);
  std::printf("# inside_box: %s\n", orbit.insideBox(o.map) ? "yes (also an orbit of Q*)" : "no (Q* differs from Q there)");
  std::printf("k,x,y\n");
  for (std::size_t k = 0; k < orbit.points.size(); ++k)
    std::printf("%zu,%.21Lg,%.21Lg\n", k, orbit.points[k].x, orbit.points[k].y);
  return 0;
}
}  // namespace

void addPeriodicCommand(CLI::App& app, int& status) {
  auto options = std::make_shared<PeriodicOptions>();
  CLI::App* cmd = app.add_subcommand(
      "periodic", "find a periodic orbit of Q near a point (Newton in quad precision); residue, stability, rotation "
                  "number and points (CSV after '#' header lines) on stdout");
  addMapOptions(*cmd, options->map);
  addNumberOption(*cmd, "--period", options->period, "the period n >= 1")->required();
  cmd->add_option("--near", options->near, "x,y: a guess for one point of the orbit (use --near=-0.3,0 for x < 0)")
      ->required();
  addNumberOption(*cmd, "--radius", options->radius, "how far (physical units) from the guess's iterates to search");
  cmd->add_flag("--stable", options->stableOnly, "only elliptic orbits (0 < R < 1)");
  cmd->callback([options, &status] { status = runPeriodic(*options); });
}

}  // namespace archipelago::cli
