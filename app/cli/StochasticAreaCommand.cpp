#include "StochasticAreaCommand.hpp"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "CliCommon.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/portrait/PortraitExport.hpp"  // stochasticAreaJson
#include "core/portrait/StochasticArea.hpp"

namespace archipelago::cli {

namespace {
struct AreaOptions {
  StochasticAreaRequest request;
  std::string json;
  std::string kernel;  // empty: $ARCHIPELAGO_KERNEL, else the fastest the CPU supports
};

int runArea(AreaOptions o) {
  o.request.kernel = &selectKernel(o.kernel);
  if (auto e = validationError(o.request)) throw std::invalid_argument(*e);
  if (!o.json.empty()) io::checkWritableTarget(o.json);  // before the work, not after it
  std::printf("iterations,boxes_visited,b2\n");
  const StochasticAreaResult result = computeStochasticArea(o.request, [](const StochasticAreaPoint& p) {
    std::printf("%llu,%llu,%.6f\n", static_cast<unsigned long long>(p.iterations),
                static_cast<unsigned long long>(p.boxesVisited), p.b2);
    std::fflush(stdout);
  });
  if (!o.json.empty()) io::writeFileAtomically(o.json, stochasticAreaJson(o.request, result) + '\n');
  return 0;
}
}  // namespace

void addStochasticAreaCommand(CLI::App& app, int& status) {
  auto a = std::make_shared<AreaOptions>();
  CLI::App* area = app.add_subcommand("stochastic-area", "b2: fraction of 1024x1024 boxes visited by the sea (sec. 5); CSV");
  addMapOptions(*area, a->request.map);
  addNumberOption(*area, "--iterations", a->request.iterations, "total steps of N^-1");
  addNumberOption(*area, "--orbits", a->request.orbits, "orbits in parallel");
  addNumberOption(*area, "--Xr", a->request.Xr, "randomizing zone");
  addNumberOption(*area, "--q", a->request.q, "steps per block");
  addNumberOption(*area, "--seed", a->request.seed, "random seed");
  area->add_option("--json", a->json, "also write the convergence curve as JSON");
  addKernelOption(*area, a->kernel);
  area->callback([a, &status] { status = runArea(*a); });
}

}  // namespace archipelago::cli
