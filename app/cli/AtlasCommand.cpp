#include "AtlasCommand.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <thread>

#include "CliCommon.hpp"
#include "RunSession.hpp"
#include "core/atlas/AtlasCantori.hpp"
#include "core/atlas/AtlasExport.hpp"
#include "core/atlas/AtlasJob.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"

namespace archipelago::cli {

namespace {
struct AtlasOptions {
  MapParameters map;
  AtlasRequest request;
  std::string json;
  std::string csv;
  std::string resume;
  bool quiet = false;
};

void printTable(const Atlas& a) {
  std::printf("# atlas of the islands around islands, K = %s (Karney 1983, section 6)\n", shortestDecimal(a.request.map.K).c_str());
  std::printf("# %-14s %6s %7s %12s %10s %12s %12s %12s\n", "island", "period", "p/q", "area", "area_err", "flux/step",
              "layer_area", "residence");
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const AtlasNode& n = a.nodes[i];
    const std::string path = std::string(static_cast<std::size_t>(2 * n.level), ' ') + atlasPath(a, static_cast<int>(i));
    std::printf("  %-14s %6llu %7s", path.c_str(), static_cast<unsigned long long>(n.period),
                n.aboutParent ? toString(*n.aboutParent).c_str() : "-");
    if (n.boundaryFound) std::printf(" %12.6Le %10.2Le", n.area, n.areaError);
    else std::printf(" %12s %10s", "-", "-");
    if (n.flux.found) std::printf(" %12.6Le %12.6Le %12.6g", n.flux.flux, n.flux.layerArea, n.flux.residence);
    else std::printf(" %12s %12s %12s", "-", "-", "-");
    const std::string note = n.measured ? n.note : "not measured yet";
    std::printf("%s%s\n", note.empty() ? "" : "  # ", note.c_str());
  }
  for (const AtlasCantorus& c : a.cantori) {
    if (c.found)
      std::printf("# %s: flux %.10Le +- %.1Le per step (MMP to %s, +- its tail bound), layer %.6Le (zone %.6Le; "
                  "its two orbits' polygons differ by %.1Le)\n",
                  atlasCantorusName(a, c).c_str(), c.flux, c.fluxUncertainty, toString(c.convergents.back()).c_str(),
                  c.layerArea, c.zoneArea, c.zoneSpread);
    else
      std::printf("# %s: not a barrier: %s\n", atlasCantorusName(a, c).c_str(), c.failure.c_str());
  }
  std::printf("# %zu islands in %.1f s%s\n", a.nodes.size(), a.seconds, a.cancelled ? (" (" + a.stopReason + ": the rest not computed)").c_str() : "");
}

int runAtlas(AtlasOptions o) {
  o.request.map = o.map;
  if (auto e = atlasRequestError(o.request)) throw std::invalid_argument(*e);
  io::checkCommandFiles({{"--resume", o.resume, io::FileUse::ResumedState},
                         {"--json", o.json, io::FileUse::SavedState},
                         {"--csv", o.csv, io::FileUse::Output}});
  std::optional<Atlas> previous;
  if (!o.resume.empty())
    previous = atlasToResume(o.request, io::readRegularFile(o.resume, kMaxAtlasFileBytes), "--resume " + o.resume);
  const auto started = std::chrono::steady_clock::now();
  AtlasProgress progress;
  if (!o.quiet)
    progress = [&](const Atlas& sofar, int done, const std::string& stage) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      const int known = static_cast<int>(sofar.nodes.size());
      // The islands known so far at the mean time per island finished: a lower bound (deeper levels add islands).
      const std::string eta =
          done > 0 && known > done ? ", at least " + clockText(s / done * (known - done)) + " left" : "";
      std::fprintf(stderr, "atlas: %d of %d islands known done, %s elapsed%s: %s\n", done, known,
                   clockText(s).c_str(), eta.c_str(), stage.c_str());
    };
  // Ctrl-C stops the computation (the program's one stop, interruptToken()) and keeps what is finished.
  const Atlas atlas = computeAtlas(o.request, progress, interruptToken(), previous ? &*previous : nullptr);
  io::OutputBatch outputs;  // the JSON and the CSV: all or nothing (issue 54, item 4)
  if (!o.json.empty()) writeAtlasJson(o.json, atlas);
  if (!o.csv.empty()) writeAtlasCsv(o.csv, atlas);
  outputs.commit();
  if (!o.quiet) printTable(atlas);
  if (atlas.cancelled && !o.quiet)
    std::fprintf(stderr, "atlas: %s: %s; --resume with the JSON file continues it\n", atlas.stopReason.c_str(),
                 o.json.empty() ? "nothing saved (no --json)" : ("the finished islands are in " + o.json).c_str());
  // Ctrl-C: 130 as every command; a time budget reached is the request's own end: 0.
  return atlas.cancelled && atlas.stopReason == "stopped" ? 130 : 0;
}
}  // namespace

void addAtlasCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<AtlasOptions>();
  CLI::App* cmd = app.add_subcommand(
      "atlas", "the hierarchy of islands around islands from the centre (-sqrt K, 0): each chain's period, p/q about its "
               "parent, island area, turnstile flux, zone area and mean residence time (docs/atlas.md)");
  addMapOptions(*cmd, o->map);
  addNumberOption(*cmd, "--depth", o->request.depth, "levels of chains below the central island");
  addNumberOption(*cmd, "--max-period", o->request.maxPeriod, "largest period of a chain (the product of its q's)");
  addNumberOption(*cmd, "--min-area", o->request.minArea, "islands of smaller area are listed but not followed");
  addNumberOption(*cmd, "--iterations", o->request.iterations, "T of each rotation measurement (2T n steps)");
  addNumberOption(*cmd, "--threshold", o->request.digitsThreshold, "regular when the rotation has this many digits");
  addNumberOption(*cmd, "--scan-points", o->request.scanPoints, "points of the symmetry line on each side of an island");
  addNumberOption(*cmd, "--scan-steps", o->request.scanSteps,
                  "more scan points where this many steps of the map allow (islands of short period scanned finely)");
  addNumberOption(*cmd, "--bisections", o->request.bisections, "halvings of the boundary circle's bracket");
  addNumberOption(*cmd, "--threads", o->request.threads, "threads (0: one per core)");
  addNumberOption(*cmd, "--time-budget", o->request.timeBudget,
                  "seconds: then stop as Ctrl-C does, keeping the finished islands (0: none)");
  cmd->add_flag("--cantori", o->request.cantori,
                "once the islands are measured, the cantori about each island (between its successive chains, and its "
                "boundary cantorus inside its innermost chain): their MacKay-Meiss-Percival flux and layer, barriers of "
                "markov-tree (seconds each; with --resume, added to a finished atlas)");
  cmd->add_option("--resume", o->resume,
                  "continue the atlas in this JSON file (one stopped early), with the same options; its finished "
                  "islands are kept");
  cmd->add_option("--json", o->json, "write the tree as JSON here (atomically)");
  cmd->add_option("--csv", o->csv, "write one row per island here (atomically)");
  cmd->add_flag("--quiet", o->quiet, "no progress and no table");
  cmd->callback([o, &status] { status = runAtlas(*o); });
}

}  // namespace archipelago::cli
