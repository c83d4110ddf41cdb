#include "IndicatorCommand.hpp"

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "CliCommon.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/io/Png.hpp"
#include "core/limits/Limits.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/measures/IndicatorMap.hpp"
#include "core/measures/MeasureExport.hpp"
#include "core/view/ViewExport.hpp"  // sidecarPath

namespace archipelago::cli {

namespace {
struct IndicatorOptions {
  MapParameters map;
  std::string kind = "dig";
  std::string view;  // "x0,x1,y0,y1"; empty: the whole box
  std::string size = "256x256";
  std::uint64_t iterations = kDefaultIterations;
  double threshold = kDefaultDigitsThreshold;
  std::uint32_t passes = IndicatorRequest{}.passes;
  std::string out;
  std::string npy;
  std::string verdicts;
  std::string colourMap = "viridis";
  std::string kernel;
  bool quiet = false;
};

int runIndicator(const IndicatorOptions& o) {
  validate(o.map);
  IndicatorRequest req;
  const auto kind = parseIndicatorKind(o.kind);
  if (!kind) throw std::invalid_argument("--kind '" + o.kind + "' must be one of " + indicatorKindNames());
  req.measure.map = o.map;
  req.measure.kind = *kind;
  req.measure.iterations = o.iterations;
  req.measure.digitsThreshold = o.threshold;
  req.measure.kernel = &selectKernel(o.kernel);
  req.view = o.view.empty() ? Viewport::wholeBox() : Viewport::fromPhysical(o.map, parseView(o.view));
  std::tie(req.width, req.height) = parseSize(o.size, "--size", limits::kRasterSide);
  req.passes = o.passes;
  const std::optional<ColourMapName> colours = colourMapNamed(o.colourMap, "--colormap");  // core's names
  if (auto e = validationError(req)) throw std::invalid_argument(*e);
  if (o.out.empty() && o.npy.empty()) throw std::invalid_argument("give --out FILE.png and/or --npy FILE.npy");
  if (!o.verdicts.empty() && o.npy.empty()) throw std::invalid_argument("--verdicts needs --npy (the sidecar names it)");
  // Every output path before the work, not after it.
  io::checkCommandFiles({{"--out", o.out, io::FileUse::Output},
                         {"--npy", o.npy, io::FileUse::Output},
                         {"the sidecar of --npy", o.npy.empty() ? "" : sidecarPath(o.npy), io::FileUse::Output},
                         {"--verdicts", o.verdicts, io::FileUse::Output}});

  const IndicatorResult result = computeIndicatorMap(req, [&](const IndicatorProgress& p) {
    if (!o.quiet && p.snapshot)
      std::fprintf(stderr, "pass %u/%u (every %u-th pixel): %llu of %llu pixels\n", p.pass + 1, p.passes, p.stride,
                   static_cast<unsigned long long>(p.pixelsDone), static_cast<unsigned long long>(p.pixelsTotal));
  });
  const IndicatorRaster& raster = result.raster;
  io::OutputBatch outputs;  // all or nothing: a full disk at the .npy leaves no PNG either (issue 36, class 5)
  if (!o.out.empty()) {
    const RasterImage image = colourizeIndicator(raster, *colours);
    io::writePng(o.out, image.width, image.height, image.rgb, indicatorProvenance(req).fields);
  }
  if (!o.npy.empty()) exportIndicatorNpy(o.npy, req, result, o.verdicts);
  outputs.commit();
  const PhysicalRect b = req.view.physical(req.measure.map);
  const double steps = static_cast<double>(stepsPerOrbit(req.measure)) * static_cast<double>(raster.pixelsDone);
  std::printf("kind=%s view=[%.19Lg, %.19Lg] x [%.19Lg, %.19Lg] size=%dx%d iterations=%llu pixels=%llu regular=%zu "
              "chaotic=%zu escaping=%zu measured=%zu kernel=%s seconds=%.3f rate=%.4g steps/s\n",
              o.kind.c_str(), b.x0, b.x1, b.y0, b.y1, req.width, req.height,
              static_cast<unsigned long long>(o.iterations), static_cast<unsigned long long>(raster.pixelsDone),
              raster.count(OrbitVerdict::Regular), raster.count(OrbitVerdict::Chaotic),
              raster.count(OrbitVerdict::Escaping), raster.count(OrbitVerdict::Measured),
              std::string(kernelOrBest(req.measure.kernel).name).c_str(), result.seconds,
              result.seconds > 0 ? steps / result.seconds : 0.0);
  return 0;
}
}  // namespace

void addIndicatorCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<IndicatorOptions>();
  CLI::App* cmd = app.add_subcommand("indicator", "chaos-indicator map of a view (one exact orbit per pixel): dig, "
                                                  "rotation, fli, megno or lyapunov, to .npy (+ JSON) and/or PNG");
  addMapOptions(*cmd, o->map);
  cmd->add_option("--kind", o->kind, "dig | rotation | fli | megno | lyapunov")->capture_default_str();
  cmd->add_option("--view", o->view, "x0,x1,y0,y1 in physical coordinates (default: the whole box)");
  cmd->add_option("--size", o->size, "raster size WxH in pixels (at most 2^24 pixels)")->capture_default_str();
  addNumberOption(*cmd, "--iterations", o->iterations,
                  "T: iterates per block (dig, rotation: two blocks) or in all (fli, megno, lyapunov)");
  addNumberOption(*cmd, "--threshold", o->threshold, "dig, rotation: digits below which an orbit is chaotic, 0 ... 16");
  addNumberOption(*cmd, "--passes", o->passes, "progressive passes, 1 ... 12 (the first every 2^(passes-1)-th pixel)");
  cmd->add_option("--out", o->out, "PNG file to write");
  cmd->add_option("--npy", o->npy, "NumPy .npy file of the values (float64, NaN: no number) plus a .json sidecar");
  cmd->add_option("--verdicts", o->verdicts, "NumPy .npy file of the verdict codes (uint32, see the sidecar)");
  cmd->add_option("--colormap", o->colourMap, "inferno | viridis | grey")->capture_default_str();
  addKernelOption(*cmd, o->kernel);
  cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
  cmd->callback([o, &status] { status = runIndicator(*o); });
}

}  // namespace archipelago::cli
