#include "PortraitCommand.hpp"

#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommon.hpp"
#include "PngWriter.hpp"
#include "kernels/KernelDispatch.hpp"
#include "portrait/ColourMap.hpp"
#include "portrait/PortraitExport.hpp"
#include "portrait/PortraitRenderer.hpp"
#include "portrait/StochasticArea.hpp"

namespace archipelago::cli {

namespace {
struct PortraitOptions {
  MapParameters map;
  std::string view;  // "x0,x1,y0,y1"; empty: the whole box
  std::string size = "800x800";
  std::string mode = "density";
  std::string colourMap = "inferno";
  std::string out;
  std::string npy;
  std::uint64_t points = 50'000'000;
  std::uint32_t orbits = 256;
  std::string seeds = "24x24";
  double Xr = 0.02;
  std::uint32_t q = 16;
  std::uint64_t seed = 1;
  std::string kernel;
  bool quiet = false;
};

long double parseNumber(const std::string& text, const char* what) {
  std::size_t used = 0;
  long double v = 0;
  try {
    v = std::stold(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw std::invalid_argument(std::string(what) + ": '" + text + "' is not a number");
  return v;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream s(text);
  for (std::string part; std::getline(s, part, separator);) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

PhysicalRect parseView(const std::string& text) {
  const auto parts = split(text, ',');
  if (parts.size() != 4)
    throw std::invalid_argument("--view '" + text + "' must be four numbers x0,x1,y0,y1 (physical coordinates)");
  return {parseNumber(parts[0], "--view x0"), parseNumber(parts[1], "--view x1"), parseNumber(parts[2], "--view y0"),
          parseNumber(parts[3], "--view y1")};
}

std::pair<int, int> parseSize(const std::string& text, const char* option, int limit) {
  const auto parts = split(text, 'x');
  if (parts.size() == 2) {
    const long double w = parseNumber(parts[0], option), h = parseNumber(parts[1], option);
    if (w >= 1 && h >= 1 && w <= limit && h <= limit && w == static_cast<int>(w) && h == static_cast<int>(h))
      return {static_cast<int>(w), static_cast<int>(h)};
  }
  throw std::invalid_argument(std::string(option) + " '" + text + "' must be WxH with whole numbers 1 ... " +
                              std::to_string(limit));
}

void runPortrait(const PortraitOptions& o) {
  validate(o.map);
  PortraitRequest req;
  req.map = o.map;
  req.view = o.view.empty() ? Viewport::wholeBox() : Viewport::fromPhysical(o.map, parseView(o.view));
  std::tie(req.width, req.height) = parseSize(o.size, "--size", 16384);
  const auto mode = parsePortraitMode(o.mode);
  if (!mode) throw std::invalid_argument("--mode '" + o.mode + "' must be density, orbits or stickiness");
  req.mode = *mode;
  const auto colours = parseColourMap(o.colourMap);
  if (!colours) throw std::invalid_argument("--colormap '" + o.colourMap + "' must be inferno, viridis or grey");
  const auto [columns, rows] = parseSize(o.seeds, "--seeds", 4096);
  req.seedColumns = static_cast<std::uint32_t>(columns);
  req.seedRows = static_cast<std::uint32_t>(rows);
  req.points = o.points;
  req.orbits = o.orbits;
  req.Xr = o.Xr;
  req.q = o.q;
  req.seed = o.seed;
  req.kernel = &selectKernel(o.kernel);
  if (auto e = validationError(req)) throw std::invalid_argument(*e);
  if (o.out.empty() && o.npy.empty()) throw std::invalid_argument("give --out FILE.png and/or --npy FILE.npy");

  const auto start = std::chrono::steady_clock::now();
  const PortraitResult result = renderPortrait(req, [&](const PortraitProgress& p) {
    if (!o.quiet && p.snapshot)
      std::fprintf(stderr, "pass %u/%u: %llu points\n", p.pass + 1, p.passes,
                   static_cast<unsigned long long>(p.pointsDone));
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const PortraitRaster& raster = result.raster;
  if (!o.out.empty()) {
    const RasterImage image = colourize(raster, *colours);
    writePng(o.out, image.width, image.height, image.rgb);
  }
  if (!o.npy.empty()) exportPortraitNpy(o.npy, req, raster);
  const PhysicalRect b = req.view.physical(req.map);
  std::printf("mode=%s view=[%.19Lg, %.19Lg] x [%.19Lg, %.19Lg] size=%dx%d points=%llu binned=%llu "
              "nonempty=%zu seconds=%.3f rate=%.4g points/s\n",
              std::string(toString(req.mode)).c_str(), b.x0, b.x1, b.y0, b.y1, req.width, req.height,
              static_cast<unsigned long long>(raster.pointsIterated),
              static_cast<unsigned long long>(raster.pointsBinned), raster.nonEmptyPixels(), seconds,
              static_cast<double>(raster.pointsIterated) / seconds);
}

struct AreaOptions {
  StochasticAreaRequest request;
  std::string json;
  std::string kernel;
};

void runArea(AreaOptions o) {
  o.request.kernel = &selectKernel(o.kernel);
  if (auto e = validationError(o.request)) throw std::invalid_argument(*e);
  std::printf("iterations,boxes_visited,b2\n");
  const StochasticAreaResult result = computeStochasticArea(o.request, [](const StochasticAreaPoint& p) {
    std::printf("%llu,%llu,%.6f\n", static_cast<unsigned long long>(p.iterations),
                static_cast<unsigned long long>(p.boxesVisited), p.b2);
    std::fflush(stdout);
  });
  if (!o.json.empty()) {
    std::ofstream out(o.json);
    out << stochasticAreaJson(o.request, result) << '\n';
    if (!out) throw std::runtime_error("cannot write '" + o.json + "'");
  }
}
}  // namespace

void addPortraitCommand(CLI::App& app) {
  auto o = std::make_shared<PortraitOptions>();
  CLI::App* cmd = app.add_subcommand("portrait", "render a phase portrait of Q* (exact map) to PNG and/or .npy");
  addMapOptions(*cmd, o->map);
  cmd->add_option("--view", o->view, "x0,x1,y0,y1 in physical coordinates (default: the whole box)");
  cmd->add_option("--size", o->size, "raster size WxH in pixels")->capture_default_str();
  cmd->add_option("--mode", o->mode, "density | orbits | stickiness")->capture_default_str();
  cmd->add_option("--out", o->out, "PNG file to write");
  cmd->add_option("--npy", o->npy, "NumPy .npy file to write (plus a .json sidecar)");
  cmd->add_option("--points", o->points, "map steps in all")->capture_default_str();
  cmd->add_option("--orbits", o->orbits, "orbits in parallel (density, stickiness)")->capture_default_str();
  cmd->add_option("--seeds", o->seeds, "seed grid CxR inside the view (orbits mode)")->capture_default_str();
  cmd->add_option("--colormap", o->colourMap, "inferno | viridis | grey")->capture_default_str();
  cmd->add_option("--Xr", o->Xr, "randomizing zone (stickiness)")->capture_default_str();
  cmd->add_option("--q", o->q, "steps of N^-1 per block (stickiness)")->capture_default_str();
  cmd->add_option("--seed", o->seed, "random seed")->capture_default_str();
  addKernelOption(*cmd, o->kernel);
  cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
  cmd->callback([o] { runPortrait(*o); });

  auto a = std::make_shared<AreaOptions>();
  CLI::App* area = app.add_subcommand("stochastic-area", "b2: fraction of 1024x1024 boxes visited by the sea (sec. 5); CSV");
  addMapOptions(*area, a->request.map);
  area->add_option("--iterations", a->request.iterations, "total steps of N^-1")->capture_default_str();
  area->add_option("--orbits", a->request.orbits, "orbits in parallel")->capture_default_str();
  area->add_option("--Xr", a->request.Xr, "randomizing zone")->capture_default_str();
  area->add_option("--q", a->request.q, "steps per block")->capture_default_str();
  area->add_option("--seed", a->request.seed, "random seed")->capture_default_str();
  area->add_option("--json", a->json, "also write the convergence curve as JSON");
  addKernelOption(*area, a->kernel);
  area->callback([a] { runArea(*a); });
}

}  // namespace archipelago::cli
