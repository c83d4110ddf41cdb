#include "CliCommon.hpp"

#include "kernels/KernelDispatch.hpp"

namespace archipelago::cli {

void addMapOptions(CLI::App& command, MapParameters& params) {
  addNumberOption(command, "--K", params.K, "map parameter K of Q (eq. qu)");
  addNumberOption(command, "--xmin", params.xmin, "left edge of the box; must be < -sqrt(K)");
  addNumberOption(command, "--xmax", params.xmax, "right edge of the box; must be > xmin");
}

void addKernelOption(CLI::App& command, std::string& name) {
  command.add_option("--kernel", name,
                     "instruction-set path: auto, " + supportedKernelNames() + " (default: $ARCHIPELAGO_KERNEL or auto)");
}

}  // namespace archipelago::cli
