#include "StochasticAreaCommand.hpp"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "CliCommon.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/stats/StochasticAreaQuantities.hpp"
#include "core/stochasticarea/StochasticArea.hpp"
#include "core/stochasticarea/StochasticAreaExport.hpp"

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
  io::checkCommandFiles({{"--json", o.json, io::FileUse::Output}});  // before the work, not after it
  // b₂ is an area (appendix A); the box counting measures the fraction of the box: both columns, by name.
  std::printf("iterations,boxes_visited,b2_area,b2_fraction\n");
  const MapParameters map = o.request.map;
  const StochasticAreaResult result = computeStochasticArea(o.request, [&map](const StochasticAreaPoint& p) {
    std::printf("%llu,%llu,%.6f,%.6f\n", static_cast<unsigned long long>(p.iterations),
                static_cast<unsigned long long>(p.boxesVisited), stochasticAreaOf(map, p.b2).area, p.b2);
    std::fflush(stdout);
  });
  if (!o.json.empty()) io::writeFileAtomically(o.json, stochasticAreaJson(o.request, result) + '\n');
  // The result for people on stderr (stdout stays CSV): the area, the §6 factor, the paper only at K = 0.1.
  const StochasticAreaValue b2 = stochasticAreaOf(map, result.fraction());
  std::fprintf(stderr, "%s\n", stochasticAreaText(map, b2).c_str());
  std::fprintf(stderr, "sec. 6: accelerator-mode factor (8/pi^2) b2 = %.4f; with the D of a run in this box, "
               "stats --b2 %.6f gives b2*D (eq. A3)\n", acceleratorModeFactor(b2.area), b2.area);
  if (const auto paper = paperStochasticAreaComparison(map, b2)) std::fprintf(stderr, "%s\n", paper->c_str());
  return 0;
}
}  // namespace

void addStochasticAreaCommand(CLI::App& app, int& status) {
  auto a = std::make_shared<AreaOptions>();
  CLI::App* area = app.add_subcommand("stochastic-area", "b2: area of the sea in the box (sec. 5, appendix A) from the 1024x1024 boxes it visits; CSV");
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
