#include "CliCommon.hpp"

namespace archipelago::cli {

void addMapOptions(CLI::App& command, MapParameters& params) {
  addNumberOption(command, "--K", params.K, "map parameter K of Q (eq. qu)");
  addNumberOption(command, "--xmin", params.xmin, "left edge of the box; must be < -sqrt(K)");
  addNumberOption(command, "--xmax", params.xmax, "right edge of the box; must be > xmin");
}

}  // namespace archipelago::cli
