#include "CliCommon.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "core/kernels/KernelDispatch.hpp"
#include "core/run/TrappingRun.hpp"  // orbitRangeError
#include "core/trapping/TrappingParameters.hpp"

namespace archipelago::cli {

std::string flagOf(std::string_view role) { return "--" + std::string(role); }

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

PhysicalRect parseView(const std::string& text) { return parsePhysicalRect(text, "--view"); }


PhysicalPoint parsePoint(const std::string& option, const std::string& text) {
  const auto v = parseNumbers<long double>(option, text, ',', 2, "two finite numbers x,y");
  return {v[0], v[1]};
}

void addKernelOption(CLI::App& command, std::string& name) {
  command.add_option("--kernel", name,
                     "instruction-set path: auto, " + supportedKernelNames() + " (default: $ARCHIPELAGO_KERNEL or auto)");
}

std::string seededPath(const std::string& path, std::uint64_t seed) {
  const std::filesystem::path p(path);
  std::filesystem::path out = p.parent_path() / p.stem();
  out += ".seed-" + std::to_string(seed);
  out += p.extension();
  return out.string();
}

std::pair<std::uint64_t, std::uint64_t> orbitRange(const std::string& text, std::uint64_t M) {
  if (text.empty()) return {0, M};
  const std::string rule = "BEGIN:END, whole numbers with BEGIN < END <= M = " + std::to_string(M);
  const std::vector<std::uint64_t> v = parseNumbers<std::uint64_t>("--orbits", text, ':', 2, rule);
  if (auto e = orbitRangeError(M, v[0], v[1])) throw std::invalid_argument(*e);  // core's rule and message
  return {v[0], v[1]};
}

int parseErrorStatus(const CLI::App& app, const CLI::ParseError& e) {
  if (dynamic_cast<const CLI::CallForHelp*>(&e) || dynamic_cast<const CLI::CallForAllHelp*>(&e) ||
      dynamic_cast<const CLI::CallForVersion*>(&e))
    return app.exit(e);
  std::fprintf(stderr, "ERROR: %s\n", io::shortText(e.what(), 400).c_str());
  return e.get_exit_code() != 0 ? e.get_exit_code() : 2;
}

}  // namespace archipelago::cli
