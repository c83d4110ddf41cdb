#include "OrbitCommand.hpp"

#include <cstdio>
#include <string>
#include <memory>
#include <stdexcept>

#include "CliCommon.hpp"
#include "core/map/FixedPointMap.hpp"
#include "core/map/OrbitIterator.hpp"

namespace archipelago::cli {

namespace {
struct OrbitOptions {
  MapParameters map;
  long double x = 0;
  long double y = 0;
  std::uint64_t steps = 100;
  bool backward = false;
};

int runOrbit(const OrbitOptions& o) {
  // core's one orbit loop and its rules (the map's, the length limit): checked before the header is printed.
  const OrbitRequest r = orbitRequestAt(o.map, o.x, o.y, o.steps, o.backward);
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const FixedPointMap map(o.map);
  std::printf("step,x,y,X,Y,wrapped\n");
  iterateOrbit(r, [&](std::uint64_t step, const UnitState& z, bool wrapped) {
    const PhysicalPoint p = map.toPhysical(z);
    std::printf("%llu,%.21Lg,%.21Lg,%llu,%llu,%d\n", static_cast<unsigned long long>(step), p.x, p.y,
                static_cast<unsigned long long>(z.X), static_cast<unsigned long long>(z.Y), wrapped ? 1 : 0);
  });
  return 0;
}
}  // namespace

void addOrbitCommand(CLI::App& app, int& status) {
  auto options = std::make_shared<OrbitOptions>();
  CLI::App* cmd = app.add_subcommand("orbit", "iterate the exact map N (or N^-1) from a point; CSV on stdout");
  addMapOptions(*cmd, options->map);
  addNumberOption(*cmd, "--x", options->x, "initial x (physical)")->required();
  addNumberOption(*cmd, "--y", options->y, "initial y (physical)")->required();
  addNumberOption(*cmd, "--steps", options->steps, "number of steps (at most " + std::to_string(limits::kOrbitLength) + ")");
  cmd->add_flag("--backward", options->backward, "iterate N^-1 instead of N");
  cmd->callback([options, &status] { status = runOrbit(*options); });
}

}  // namespace archipelago::cli
