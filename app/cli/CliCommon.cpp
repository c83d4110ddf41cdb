#include "CliCommon.hpp"

#include "core/kernels/KernelDispatch.hpp"
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago::cli {

void addMapOptions(CLI::App& command, MapParameters& params) {
  // Names, meanings and ranges from core's one table of parameters (trapping/TrappingParameters.hpp).
  const auto help = [](const char* key) {
    const ParameterRule* rule = findParameterRule(key);
    return std::string(rule->meaning) + "; " + std::string(rule->range);
  };
  addNumberOption(command, "--K", params.K, help("K"));
  addNumberOption(command, "--xmin", params.xmin, help("xmin"));
  addNumberOption(command, "--xmax", params.xmax, help("xmax"));
}

void addKernelOption(CLI::App& command, std::string& name) {
  command.add_option("--kernel", name,
                     "instruction-set path: auto, " + supportedKernelNames() + " (default: $ARCHIPELAGO_KERNEL or auto)");
}

}  // namespace archipelago::cli
