#include "OrbitCommand.hpp"

#include <cstdio>
#include <iostream>
#include <string>
#include <memory>
#include <stdexcept>

#include "CliCommon.hpp"
#include "core/limits/Limits.hpp"
#include "core/portrait/MapOverlays.hpp"

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
  writeOrbitCsv(std::cout, o.map, o.x, o.y, o.steps, o.backward);  // throws std::invalid_argument (the failed rule)
  std::cout.flush();
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
