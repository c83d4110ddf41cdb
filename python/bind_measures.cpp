// The orbit measures of core/measures as NumPy arrays: rotation numbers and island chains of single orbits,
// rotation profiles, indicator maps (dig, rotation, fli, megno, lyapunov) and measures of arbitrary starts.
// No maths here: every number comes from core (the same functions as archipelago-cli's `rotation` and
// `indicator`).  Long calls release the GIL and stop on Ctrl-C (python/Interruption.hpp) at core's next look at the
// stop token (every 2^14 steps of a group of orbits); the indicator map calls the progress callback between rounds.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "core/measures/ChainIdentification.hpp"
#include "core/measures/IndicatorMap.hpp"
#include "core/measures/MeasureExport.hpp"
#include "core/measures/RotationProfile.hpp"
#include "python/Conversions.hpp"
#include "python/Interruption.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

MeasureSettings settingsOf(const std::string& kind, double K, double xmin, double xmax, std::uint64_t iterations,
                           double threshold, const std::string& kernel) {
  MeasureSettings s;
  const auto k = parseIndicatorKind(kind);
  if (!k) throw std::invalid_argument("kind must be one of " + indicatorKindNames() + ", not " + kind);
  s.kind = *k;
  s.map = mapOf(K, xmin, xmax);
  s.iterations = iterations;
  s.digitsThreshold = threshold;
  s.kernel = &selectKernel(kernel);
  if (auto e = validationError(s)) throw std::invalid_argument(*e);
  return s;
}

py::array_t<std::uint8_t> verdictCodes(const std::vector<OrbitVerdict>& v, py::ssize_t rows, py::ssize_t cols) {
  py::array_t<std::uint8_t> a({rows, cols});
  std::transform(v.begin(), v.end(), a.mutable_data(), [](OrbitVerdict x) { return static_cast<std::uint8_t>(x); });
  return a;
}

py::dict verdictNames() {
  py::dict d;
  for (auto v : {OrbitVerdict::NotComputed, OrbitVerdict::Measured, OrbitVerdict::Regular, OrbitVerdict::Chaotic,
                 OrbitVerdict::Escaping})
    d[py::int_(static_cast<int>(v))] = std::string(toString(v));
  return d;
}

py::object rotation(double x, double y, double K, double xmin, double xmax, std::uint64_t iterations, double threshold,
                    std::uint64_t maxPeriod) {
  if (!std::isfinite(x) || !std::isfinite(y)) throw std::invalid_argument("x and y must be finite");
  ChainRequest r;
  r.map = mapOf(K, xmin, xmax);
  r.iterations = iterations;
  r.digitsThreshold = threshold;
  r.maxPeriod = maxPeriod;
  r = chainRequestAt(r, {x, y});  // core's recipe and messages, as the CLI's `rotation`
  // Stopped by Ctrl-C within a block of steps of its measurements (issue 36: it ran on for 42 s).
  const ChainIdentification chain = interruptible([&](std::stop_token stop) { return identifyChain(r, stop); });
  return py::module_::import("json").attr("loads")(rotationReportJson(r, chain));
}

py::dict rotationProfile(std::pair<double, double> start, std::pair<double, double> end, std::uint32_t points, double K,
                         double xmin, double xmax, std::uint64_t iterations, double threshold,
                         std::int64_t maxDenominator, const std::string& kernel) {
  RotationProfileRequest r;
  r.measure = settingsOf("rotation", K, xmin, xmax, iterations, threshold, kernel);
  r.from = {start.first, start.second};
  r.to = {end.first, end.second};
  r.points = points;
  r.maxDenominator = maxDenominator;
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const RotationProfile profile =
      interruptible([&](std::stop_token stop) { return computeRotationProfile(r, {}, stop); });
  const auto n = static_cast<py::ssize_t>(profile.points.size());
  py::array_t<double> x(n), y(n), rotation(n), digits(n);
  py::array_t<std::uint8_t> verdict(n);
  py::array_t<std::int64_t> p(n), q(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const RotationProfilePoint& pt = profile.points[static_cast<std::size_t>(i)];
    x.mutable_at(i) = static_cast<double>(pt.point.x);
    y.mutable_at(i) = static_cast<double>(pt.point.y);
    rotation.mutable_at(i) = pt.measure.value;
    digits.mutable_at(i) = pt.measure.digits;
    verdict.mutable_at(i) = static_cast<std::uint8_t>(pt.measure.verdict);
    p.mutable_at(i) = pt.rational ? pt.rational->p : 0;
    q.mutable_at(i) = pt.rational ? pt.rational->q : 0;
  }
  py::dict d;
  d["x"] = x; d["y"] = y; d["rotation"] = rotation; d["digits"] = digits; d["verdict"] = verdict;
  d["p"] = p; d["q"] = q;
  return d;
}

py::dict indicator(const std::string& kind, double K, double xmin, double xmax,
                   std::optional<std::tuple<double, double, double, double>> view, int width, int height,
                   std::uint64_t iterations, double threshold, std::uint32_t passes, const std::string& kernel,
                   int threads, const py::object& progress) {
  IndicatorRequest r;
  r.measure = settingsOf(kind, K, xmin, xmax, iterations, threshold, kernel);
  if (view) {
    const auto [x0, x1, y0, y1] = *view;
    r.view = Viewport::fromPhysical(r.measure.map, {x0, x1, y0, y1});
  }
  r.width = width;
  r.height = height;
  r.passes = passes;
  r.threads = threads;
  r.roundPixels = 4096;  // Ctrl-C and progress between rounds
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  Interruption interruption;  // Ctrl-C every 50 ms, not only between rounds of pixels (issue 36)
  const IndicatorResult result = interruption.withoutGilPolled([&](std::stop_token stop) {
    return computeIndicatorMap(r, [&](const IndicatorProgress& p) {
      interruption.check(progress, [&p] {
        py::dict d;
        d["pixels_done"] = p.pixelsDone;
        d["pixels_total"] = p.pixelsTotal;
        d["pass"] = p.pass;
        d["passes"] = p.passes;
        d["stride"] = p.stride;
        return d;
      });
    }, stop);
  });
  interruption.raisePending();
  const IndicatorRaster& ras = result.raster;
  const py::ssize_t rows = ras.height, cols = ras.width;
  py::dict d;
  d["kind"] = kind;
  d["values"] = toArray(ras.values, rows, cols);
  d["digits"] = toArray(ras.digits, rows, cols);
  d["verdicts"] = verdictCodes(ras.verdicts, rows, cols);
  d["seconds"] = result.seconds;
  d["metadata"] = py::module_::import("json").attr("loads")(indicatorMetadataJson(r, result));
  return d;
}

py::dict orbitMeasures(const std::string& kind, py::array_t<double> x, py::array_t<double> y, double K, double xmin,
                       double xmax, std::uint64_t iterations, double threshold, const std::string& kernel,
                       int threads) {
  if (x.ndim() != 1 || y.ndim() != 1 || x.size() != y.size())
    throw std::invalid_argument("x and y must be one-dimensional arrays of the same size");
  const MeasureSettings s = settingsOf(kind, K, xmin, xmax, iterations, threshold, kernel);
  const FixedPointMap map(s.map);
  std::vector<UnitState> starts(static_cast<std::size_t>(x.size()));
  for (py::ssize_t i = 0; i < x.size(); ++i) {
    if (auto e = boxPointError("point " + std::to_string(i), s.map, {x.at(i), y.at(i)}))
      throw std::invalid_argument(*e);
    starts[static_cast<std::size_t>(i)] = map.toUnit(x.at(i), y.at(i));
  }
  const OrbitMeasurer measurer(s);
  std::vector<OrbitMeasure> out(starts.size());
  interruptible([&](std::stop_token stop) { return measurer.measure(starts, out, stop, threads); });
  const auto n = static_cast<py::ssize_t>(out.size());
  py::array_t<double> value(n), digits(n);
  py::array_t<std::uint8_t> verdict(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    value.mutable_at(i) = out[static_cast<std::size_t>(i)].value;
    digits.mutable_at(i) = out[static_cast<std::size_t>(i)].digits;
    verdict.mutable_at(i) = static_cast<std::uint8_t>(out[static_cast<std::size_t>(i)].verdict);
  }
  py::dict d;
  d["value"] = value; d["digits"] = digits; d["verdict"] = verdict;
  return d;
}

}  // namespace

void bindMeasures(py::module_& m) {
  m.attr("VERDICTS") = verdictNames();
  m.attr("DEFAULT_ITERATIONS") = kDefaultIterations;
  m.attr("DEFAULT_DIGITS_THRESHOLD") = kDefaultDigitsThreshold;

  m.def("rotation", &rotation,
        py::arg("x"), py::arg("y"), py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin, py::arg("xmax") = kDefaultMap.xmax, py::kw_only(),
        py::arg("iterations") = kDefaultIterations, py::arg("threshold") = kDefaultDigitsThreshold,
        py::arg("max_period") = ChainRequest{}.maxPeriod,
        "The rotation number about (-sqrt K, 0) of the exact orbit from (x, y) (turns per step, positive in the sense\n"
        "Q turns: clockwise; weighted Birkhoff average over two blocks of `iterations`), its digits and verdict, and\n"
        "its island chain (core/measures/ChainIdentification.hpp): e.g. chain['summary'] = '6 x 23 = 138, rotation\n"
        "1/6 about the centre, 2/23 about its island; ...'.  The same dict as `archipelago-cli rotation --json`;\n"
        "rotation is None for a chaotic or escaping orbit.");

  m.def("rotation_profile", &rotationProfile,
        py::arg("start"), py::arg("end"), py::arg("points") = 1000, py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin,
        py::arg("xmax") = kDefaultMap.xmax, py::kw_only(), py::arg("iterations") = kDefaultIterations,
        py::arg("threshold") = kDefaultDigitsThreshold, py::arg("max_denominator") = RotationProfileRequest{}.maxDenominator,
        py::arg("kernel") = "auto",
        "The rotation number about (-sqrt K, 0) along the segment start -> end ((x, y) tuples, physical), `points`\n"
        "starts (core/measures/RotationProfile.hpp): arrays x, y, rotation (NaN unless regular), digits, verdict\n"
        "(codes in VERDICTS), and p, q: the fraction of smallest denominator within the measured accuracy (q = 0:\n"
        "none), the chain's p/q on a plateau.  Same numbers as `archipelago-cli rotation --line ... --csv`.");

  m.def("indicator", &indicator,
        py::arg("kind"), py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin, py::arg("xmax") = kDefaultMap.xmax, py::kw_only(),
        py::arg("view") = py::none(), py::arg("width") = IndicatorRequest{}.width, py::arg("height") = IndicatorRequest{}.height,
        py::arg("iterations") = kDefaultIterations, py::arg("threshold") = kDefaultDigitsThreshold,
        py::arg("passes") = 1, py::arg("kernel") = "auto", py::arg("threads") = 0, py::arg("progress") = py::none(),
        "A chaos-indicator map (core/measures/IndicatorMap.hpp): kind dig, rotation, fli, megno or lyapunov; one\n"
        "exact orbit per pixel from the pixel's centre; view = (x0, x1, y0, y1) physical (default: the whole box).\n"
        "Returns values, digits (float64) and verdicts (uint8, codes in VERDICTS) of shape (height, width), row 0 at\n"
        "the top, and the sidecar's metadata.  The same numbers as `archipelago-cli indicator` (its .npy).");

  m.def("orbit_measures", &orbitMeasures,
        py::arg("kind"), py::arg("x"), py::arg("y"), py::arg("K") = kDefaultMap.K, py::arg("xmin") = kDefaultMap.xmin, py::arg("xmax") = kDefaultMap.xmax,
        py::kw_only(), py::arg("iterations") = kDefaultIterations, py::arg("threshold") = kDefaultDigitsThreshold,
        py::arg("kernel") = "auto", py::arg("threads") = 0,
        "The measure `kind` of the exact orbits from the physical points (x[i], y[i]) (inside the box): arrays value,\n"
        "digits and verdict, as an indicator map's pixels (core/measures/OrbitMeasures.hpp).");
}
