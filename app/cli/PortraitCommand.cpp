#include "PortraitCommand.hpp"

#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "CliCommon.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/io/Png.hpp"
#include "core/limits/Limits.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/portrait/PortraitColours.hpp"
#include "core/portrait/PortraitExport.hpp"
#include "core/portrait/PortraitRenderer.hpp"

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

int runPortrait(const PortraitOptions& o) {
  validate(o.map);
  PortraitRequest req;
  req.map = o.map;
  req.view = o.view.empty() ? Viewport::wholeBox() : Viewport::fromPhysical(o.map, parseView(o.view));
  std::tie(req.width, req.height) = parseSize(o.size, "--size", limits::kRasterSide);
  const auto mode = parsePortraitMode(o.mode);
  if (!mode) throw std::invalid_argument("--mode '" + o.mode + "' must be density, orbits or stickiness");
  req.mode = *mode;
  const std::optional<ColourMapName> colours = colourMapNamed(o.colourMap, "--colormap");  // core's names
  const auto [columns, rows] = parseSize(o.seeds, "--seeds", static_cast<int>(limits::kSeedGridSide));
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
  // Every output path before the work, not after it (issue #12, finding 7).
  io::checkCommandFiles({{"--out", o.out, io::FileUse::Output},
                         {"--npy", o.npy, io::FileUse::Output},
                         {"the sidecar of --npy", o.npy.empty() ? "" : sidecarPath(o.npy), io::FileUse::Output}});

  const auto start = std::chrono::steady_clock::now();
  const PortraitResult result = renderPortrait(req, [&](const PortraitProgress& p) {
    if (!o.quiet && p.snapshot)
      std::fprintf(stderr, "pass %u/%u: %llu points\n", p.pass + 1, p.passes,
                   static_cast<unsigned long long>(p.pointsDone));
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const PortraitRaster& raster = result.raster;
  io::OutputBatch outputs;  // all or nothing (issue 36, class 5)
  if (!o.out.empty()) {
    const RasterImage image = colourize(raster, *colours);
    io::writePng(o.out, image.width, image.height, image.rgb, portraitProvenance(req).fields);
  }
  if (!o.npy.empty()) exportPortraitNpy(o.npy, req, raster);
  outputs.commit();
  const PhysicalRect b = req.view.physical(req.map);
  std::printf("mode=%s view=[%.19Lg, %.19Lg] x [%.19Lg, %.19Lg] size=%dx%d points=%llu binned=%llu "
              "nonempty=%zu seconds=%.3f rate=%.4g points/s\n",
              std::string(toString(req.mode)).c_str(), b.x0, b.x1, b.y0, b.y1, req.width, req.height,
              static_cast<unsigned long long>(raster.pointsIterated),
              static_cast<unsigned long long>(raster.pointsBinned), raster.nonEmptyPixels(), seconds,
              static_cast<double>(raster.pointsIterated) / seconds);
  return 0;
}

}  // namespace

void addPortraitCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<PortraitOptions>();
  CLI::App* cmd = app.add_subcommand("portrait", "render a phase portrait of Q* (exact map) to PNG and/or .npy");
  addMapOptions(*cmd, o->map);
  cmd->add_option("--view", o->view, "x0,x1,y0,y1 in physical coordinates (default: the whole box)");
  cmd->add_option("--size", o->size, "raster size WxH in pixels")->capture_default_str();
  cmd->add_option("--mode", o->mode, "density | orbits | stickiness")->capture_default_str();
  cmd->add_option("--out", o->out, "PNG file to write");
  cmd->add_option("--npy", o->npy, "NumPy .npy file to write (plus a .json sidecar)");
  addNumberOption(*cmd, "--points", o->points, "map steps in all");
  addNumberOption(*cmd, "--orbits", o->orbits, "orbits in parallel (density, stickiness)");
  cmd->add_option("--seeds", o->seeds, "seed grid CxR inside the view (orbits mode)")->capture_default_str();
  cmd->add_option("--colormap", o->colourMap, "inferno | viridis | grey")->capture_default_str();
  addNumberOption(*cmd, "--Xr", o->Xr, "randomizing zone (stickiness)");
  addNumberOption(*cmd, "--q", o->q, "steps of N^-1 per block (stickiness)");
  addNumberOption(*cmd, "--seed", o->seed, "random seed");
  addKernelOption(*cmd, o->kernel);
  cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
  cmd->callback([o, &status] { status = runPortrait(*o); });
}

}  // namespace archipelago::cli
