#include "RotationCommand.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "CliCommon.hpp"
#include "core/io/AtomicFile.hpp"
#include "core/io/CommandFiles.hpp"
#include "core/kernels/KernelDispatch.hpp"
#include "core/measures/ChainIdentification.hpp"
#include "core/measures/MeasureExport.hpp"
#include "core/measures/RotationProfile.hpp"

namespace archipelago::cli {

namespace {
struct RotationOptions {
  MapParameters map;
  long double x = 0;
  long double y = 0;
  CLI::Option* xOption = nullptr;
  CLI::Option* yOption = nullptr;
  std::uint64_t iterations = kDefaultIterations;
  double threshold = kDefaultDigitsThreshold;
  std::uint64_t maxPeriod = ChainRequest{}.maxPeriod;
  bool json = false;
  std::string line;  // "X0,Y0:X1,Y1"
  std::uint32_t points = 1000;
  std::int64_t maxDenominator = RotationProfileRequest{}.maxDenominator;
  std::string csv;
  std::string about;  // "X,Y": a point of an elliptic orbit of period `period` (issue 37, finding 17)
  std::uint64_t period = 1;
  std::string kernel;
  bool quiet = false;
};

/// "x0,y0:x1,y1" → the two ends.
std::pair<PhysicalPoint, PhysicalPoint> parseLine(const std::string& text) {
  const std::string rule = "two points X0,Y0:X1,Y1 (physical coordinates, four finite numbers)";
  const std::size_t colon = text.find(':');
  if (colon == std::string::npos || text.find(':', colon + 1) != std::string::npos)
    throw std::invalid_argument("--line '" + text + "' must be " + rule);
  try {
    return {parsePoint("--line", text.substr(0, colon)), parsePoint("--line", text.substr(colon + 1))};
  } catch (const std::invalid_argument&) {
    throw std::invalid_argument("--line '" + text + "' must be " + rule);
  }
}

std::string number(double v, const char* format = "%.17g") {
  if (!std::isfinite(v)) return "";
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

int runProfile(const RotationOptions& o) {
  if (o.csv.empty()) throw std::invalid_argument("--line needs --csv FILE (the profile's table)");
  RotationProfileRequest r;
  r.measure.map = o.map;
  r.measure.kind = IndicatorKind::Rotation;
  r.measure.iterations = o.iterations;
  r.measure.digitsThreshold = o.threshold;
  r.measure.kernel = &selectKernel(o.kernel);
  std::tie(r.from, r.to) = parseLine(o.line);
  r.points = o.points;
  r.maxDenominator = o.maxDenominator;
  if (!o.about.empty()) {
    r.about = parsePoint("--about", o.about);
    r.power = o.period;
  }
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  io::checkCommandFiles({{"--csv", o.csv, io::FileUse::Output}});  // before the work
  const RotationProfile profile = computeRotationProfile(r, [&](std::uint64_t done, std::uint64_t total) {
    if (!o.quiet) std::fprintf(stderr, "%llu/%llu points\n", static_cast<unsigned long long>(done),
                               static_cast<unsigned long long>(total));
  });
  writeRotationProfileCsv(o.csv, r, profile);
  std::size_t regular = 0, chaotic = 0, escaping = 0;
  for (const RotationProfilePoint& p : profile.points) {
    regular += p.measure.verdict == OrbitVerdict::Regular;
    chaotic += p.measure.verdict == OrbitVerdict::Chaotic;
    escaping += p.measure.verdict == OrbitVerdict::Escaping;
  }
  std::printf("points=%u regular=%zu chaotic=%zu escaping=%zu csv=%s\n", r.points, regular, chaotic, escaping,
              o.csv.c_str());
  return 0;
}

int runOrbit(const RotationOptions& o) {
  validate(o.map);
  // One orbit runs on the scalar path, whatever the kernel; a name that is not one (or one the CPU lacks) is still
  // an error, as for every command that takes --kernel (issue 36).
  (void)selectKernel(o.kernel);
  ChainRequest r;
  r.map = o.map;
  r.iterations = o.iterations;
  r.digitsThreshold = o.threshold;
  r.maxPeriod = o.maxPeriod;
  r = chainRequestAt(r, {o.x, o.y});  // core's recipe and messages, as Python's rotation() and the GUI's orbits
  const ChainIdentification chain = identifyChain(r);
  if (o.json) {
    std::printf("%s\n", rotationReportJson(r, chain).c_str());
    return 0;
  }
  const PhysicalPoint p = FixedPointMap(o.map).toPhysical(r.start);
  const ChainLevel& centre = chain.levels.front();
  std::printf("# rotation number about (-sqrt K, 0) of Q, K = %s: turns per step, positive clockwise (the sense Q "
              "turns)\n", shortestDecimal(o.map.K).c_str());
  std::printf("# start: %.19Lg,%.19Lg\n", p.x, p.y);
  std::printf("# start_unit: %llu,%llu\n", static_cast<unsigned long long>(r.start.X),
              static_cast<unsigned long long>(r.start.Y));
  std::printf("# iterations: %llu per block, two blocks\n", static_cast<unsigned long long>(o.iterations));
  std::printf("# rotation: %s\n", centre.rotation.verdict == OrbitVerdict::Regular
                                      ? number(centre.rotation.rotation).c_str()
                                      : ("none (" + std::string(toString(centre.rotation.verdict)) + ")").c_str());
  std::printf("# digits: %s\n", number(centre.rotation.digits, "%.3f").c_str());
  std::printf("# verdict: %s (threshold %s digits)\n", std::string(toString(centre.rotation.verdict)).c_str(),
              shortestDecimal(o.threshold).c_str());
  std::printf("# chain: %s\n", chain.summary.c_str());
  std::printf("# period: %llu\n", static_cast<unsigned long long>(chain.period));
  std::printf("level,power,centre_x,centre_y,sense,rotation,digits,verdict,rational,residue\n");
  for (std::size_t i = 0; i < chain.levels.size(); ++i) {
    const ChainLevel& l = chain.levels[i];
    std::printf("%zu,%llu,%.19Lg,%.19Lg,%s,%s,%s,%s,%s,%s\n", i, static_cast<unsigned long long>(l.power), l.centre.x,
                l.centre.y, l.sense > 0 ? "clockwise" : "counter-clockwise", number(l.rotation.rotation).c_str(),
                number(l.rotation.digits, "%.3f").c_str(), std::string(toString(l.rotation.verdict)).c_str(),
                l.rational ? toString(*l.rational).c_str() : "",
                l.orbit ? number(static_cast<double>(l.orbit->residue)).c_str() : "");
  }
  return 0;
}

int runRotation(const RotationOptions& o) {
  const bool point = o.xOption->count() > 0 || o.yOption->count() > 0;
  if (!o.line.empty()) {
    if (point) throw std::invalid_argument("give --x and --y (one orbit) or --line (a profile), not both");
    if (o.json) throw std::invalid_argument("--json is for one orbit; a profile (--line) is written by --csv");
    return runProfile(o);
  }
  if (o.xOption->count() == 0 || o.yOption->count() == 0)
    throw std::invalid_argument("give --x and --y (one orbit) or --line X0,Y0:X1,Y1 with --csv (a profile)");
  if (!o.csv.empty()) throw std::invalid_argument("--csv is for a profile (--line); one orbit prints to stdout");
  if (!o.about.empty()) throw std::invalid_argument("--about is for a profile (--line); one orbit names its chain itself");
  return runOrbit(o);
}
}  // namespace

void addRotationCommand(CLI::App& app, int& status) {
  auto o = std::make_shared<RotationOptions>();
  CLI::App* cmd = app.add_subcommand(
      "rotation", "rotation number about (-sqrt K, 0) and island chain of an orbit (e.g. 6 x 23 = 138), or the "
                  "rotation profile along a segment (--line ... --csv)");
  addMapOptions(*cmd, o->map);
  o->xOption = addNumberOption(*cmd, "--x", o->x, "start x (physical; use --x=-0.3 for x < 0)");
  o->yOption = addNumberOption(*cmd, "--y", o->y, "start y (physical)");
  addNumberOption(*cmd, "--iterations", o->iterations, "T: iterates per block of the weighted Birkhoff average");
  addNumberOption(*cmd, "--threshold", o->threshold, "digits below which an orbit is chaotic, 0 ... 16");
  addNumberOption(*cmd, "--max-period", o->maxPeriod, "the longest chain period tried, 1 ... 100000");
  cmd->add_flag("--json", o->json, "one orbit: JSON on stdout instead of text");
  cmd->add_option("--line", o->line, "X0,Y0:X1,Y1: a profile of --points starts along this segment (physical)");
  addNumberOption(*cmd, "--points", o->points, "profile: points along the segment, 1 ... 1000000");
  addNumberOption(*cmd, "--max-denominator", o->maxDenominator, "profile: largest q of the p/q shown, 1 ... 1000000");
  cmd->add_option("--csv", o->csv, "profile: CSV file to write");
  cmd->add_option("--about", o->about,
                  "profile: X,Y, a point of an elliptic periodic orbit of period --period (archipelago-cli periodic "
                  "finds one): the rotation of Q^period about it instead of about (-sqrt K, 0) (use --about=-0.3,0)");
  addNumberOption(*cmd, "--period", o->period, "profile with --about: the orbit's period n, 1 ... 100000");
  addKernelOption(*cmd, o->kernel);
  cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
  cmd->callback([o, &status] { status = runRotation(*o); });
}

}  // namespace archipelago::cli
