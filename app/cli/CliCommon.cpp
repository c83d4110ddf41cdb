#include "CliCommon.hpp"

#include "kernels/KernelDispatch.hpp"

namespace archipelago::cli {

void addMapOptions(CLI::App& command, MapParameters& params) {
  command.add_option("--K", params.K, "map parameter K of Q (eq. qu)")->capture_default_str();
  command.add_option("--xmin", params.xmin, "left edge of the box; must be < -sqrt(K)")->capture_default_str();
  command.add_option("--xmax", params.xmax, "right edge of the box; must be > xmin")->capture_default_str();
}

void addKernelOption(CLI::App& command, std::string& name) {
  command.add_option("--kernel", name,
                     "instruction-set path: auto, " + supportedKernelNames() + " (default: $ARCHIPELAGO_KERNEL or auto)");
}

}  // namespace archipelago::cli
