#include "OrbitCommand.hpp"

#include <cstdio>
#include <memory>

#include "CliCommon.hpp"
#include "core/map/FixedPointMap.hpp"

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
  const FixedPointMap map(o.map);  // throws std::invalid_argument with the rule that failed
  UnitState z = map.toUnit(o.x, o.y);
  std::printf("step,x,y,X,Y,wrapped\n");
  auto print = [&](std::uint64_t step, bool wrapped) {
    const PhysicalPoint p = map.toPhysical(z);
    std::printf("%llu,%.21Lg,%.21Lg,%llu,%llu,%d\n", static_cast<unsigned long long>(step), p.x, p.y,
                static_cast<unsigned long long>(z.X), static_cast<unsigned long long>(z.Y), wrapped ? 1 : 0);
  };
  print(0, false);
  for (std::uint64_t i = 1; i <= o.steps; ++i) {
    const bool wrapped = o.backward ? map.backward(z) : map.forward(z);
    print(i, wrapped);
  }
  return 0;
}
}  // namespace

void addOrbitCommand(CLI::App& app, int& status) {
  auto options = std::make_shared<OrbitOptions>();
  CLI::App* cmd = app.add_subcommand("orbit", "iterate the exact map N (or N^-1) from a point; CSV on stdout");
  addMapOptions(*cmd, options->map);
  addNumberOption(*cmd, "--x", options->x, "initial x (physical)")->required();
  addNumberOption(*cmd, "--y", options->y, "initial y (physical)")->required();
  addNumberOption(*cmd, "--steps", options->steps, "number of steps");
  cmd->add_flag("--backward", options->backward, "iterate N^-1 instead of N");
  cmd->callback([options, &status] { status = runOrbit(*options); });
}

}  // namespace archipelago::cli
