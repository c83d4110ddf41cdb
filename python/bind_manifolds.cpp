// Python bindings of core/manifolds (issue 28): branches of stable and unstable manifolds, the turnstile flux by two
// methods, the Kac check.  Arrays out (NumPy); the numbers are core's (the flux dict is parsed from the same JSON the
// CLI prints, so `archipelago-cli flux --json` and flux() agree to the last digit).  Long calls release the GIL and
// stop on Ctrl-C at core's next check of the stop token (python/Interruption.hpp): KeyboardInterrupt.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <stop_token>
#include <string>
#include <vector>

#include "core/manifolds/KacCheck.hpp"
#include "core/manifolds/ManifoldCurve.hpp"
#include "core/manifolds/ManifoldExport.hpp"
#include "core/manifolds/MmpFlux.hpp"
#include "core/manifolds/TurnstileFlux.hpp"
#include "python/Conversions.hpp"
#include "python/Interruption.hpp"

namespace py = pybind11;
using namespace archipelago;
using namespace archipelago::bindings;

namespace {

std::optional<PhysicalPoint> guess(const py::object& near) {
  if (near.is_none()) return std::nullopt;
  const auto xy = near.cast<std::vector<double>>();
  if (xy.size() != 2 || !std::isfinite(xy[0]) || !std::isfinite(xy[1]))
    throw std::invalid_argument("near must be two finite numbers (x, y)");
  return PhysicalPoint{xy[0], xy[1]};
}

void checkK(double K) {
  if (auto e = manifoldKError(K)) throw std::invalid_argument(*e);
}

py::dict manifold(double K, const std::string& branch, const std::string& side, double length, int period,
                  const py::object& near, double radius, int point, const py::object& box, const py::object& view,
                  double spacing, double angle, int domains, int initialPoints, const std::string& stableFrom,
                  double escape, std::size_t maxPoints) {
  checkK(K);
  ManifoldCurveRequest r;
  r.K = K;
  r.kind = parseManifoldKind(branch, "branch");  // core's names and message, as the CLI's --branch
  r.stableFrom = parseStableConstruction(stableFrom, "stable_from");
  r.length = length;
  r.point = point;
  r.maxSpacing = spacing;
  r.maxAngle = angle;
  r.maxDomains = domains;
  r.initialPoints = initialPoints;
  r.escapeRadius = escape;
  r.maxPoints = maxPoints;
  if (!box.is_none()) {
    const auto b = box.cast<std::vector<double>>();
    if (b.size() != 2) throw std::invalid_argument("box must be (xmin, xmax)");
    r.box = MapParameters{K, b[0], b[1]};
  }
  if (!view.is_none()) {
    const auto v = view.cast<std::vector<double>>();
    if (v.size() != 4) throw std::invalid_argument("view must be (x0, x1, y0, y1)");
    r.view = PhysicalRect{v[0], v[1], v[2], v[3]};
  }
  {
    ManifoldCurveRequest check = r;  // every range before the orbit search
    check.point = 0;
    if (auto e = validationError(check)) throw std::invalid_argument(*e);
    checkManifoldMemory(check);
  }
  const std::optional<PhysicalPoint> at = guess(near);
  const ManifoldCurve c = interruptible([&](std::stop_token stop) {
    r.orbit = hyperbolicOrbitNear(r.K, period, at, radius);
    r.side = parseBranchSide(side, !r.orbit);
    return computeManifoldCurve(r, {}, stop);
  });
  std::vector<double> s, x, y, t;
  std::vector<std::int32_t> piece;
  for (std::size_t k = 0; k < c.pieces.size(); ++k) {
    const ManifoldPiece& p = c.pieces[k];
    for (std::size_t i = 0; i < p.points.size(); ++i) {
      s.push_back(static_cast<double>(p.arcLength[i]));
      x.push_back(static_cast<double>(p.points[i].x));
      y.push_back(static_cast<double>(p.points[i].y));
      t.push_back(static_cast<double>(p.parameter[i]));
      piece.push_back(static_cast<std::int32_t>(k));
    }
  }
  py::dict d;
  d["s"] = toArray(s);
  d["x"] = toArray(x);
  d["y"] = toArray(y);
  d["piece"] = toArray(piece);
  d["parameter"] = toArray(t);
  d["origin"] = py::make_tuple(static_cast<double>(c.origin.x), static_cast<double>(c.origin.y));
  d["length"] = static_cast<double>(c.length);
  d["domains"] = c.domains;
  d["points"] = c.points;
  d["pieces"] = c.pieces.size();
  d["breaks"] = c.breaks;
  d["unresolved"] = c.unresolved;
  d["stopped_by"] = c.stoppedBy;
  d["side"] = std::string(toString(r.side));
  d["period"] = r.orbit ? r.orbit->period : 1;
  return d;
}

py::dict boundary(const std::vector<PhysicalPoint>& v) {
  std::vector<double> x, y;
  for (const PhysicalPoint& p : v) {
    x.push_back(static_cast<double>(p.x));
    y.push_back(static_cast<double>(p.y));
  }
  py::dict d;
  d["x"] = toArray(x);
  d["y"] = toArray(y);
  return d;
}

py::dict flux(double K, int period, const py::object& near, double radius, const std::string& side, int vertices,
              int domains, bool kac, std::uint64_t kacSamples, std::uint64_t kacZoneSamples, std::uint64_t kacSteps,
              std::uint64_t seed, int threads) {
  checkK(K);
  TurnstileRequest r;
  r.K = K;
  r.maxVertices = vertices;
  r.maxDomains = domains;
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  KacRequest k;
  k.K = K;
  k.entrySamples = kacSamples;
  k.zoneSamples = kacZoneSamples;
  k.maxSteps = kacSteps;
  k.seed = seed;
  k.threads = threads;
  if (auto e = validationError(k)) throw std::invalid_argument(*e);  // checked even without kac=True
  const std::optional<PhysicalPoint> at = guess(near);
  TurnstileFlux f;
  std::optional<KacResult> result;
  std::string json = interruptible([&](std::stop_token stop) {
    r.orbit = hyperbolicOrbitNear(r.K, period, at, radius);
    r.side = parseBranchSide(side, !r.orbit);
    f = computeTurnstileFlux(r, {}, stop);
    k.orbit = r.orbit;
    k.side = r.side;
    if (kac) result = runKacCheck(k, {}, stop);
    return turnstileJson(r, f, kac ? &k : nullptr, result ? &*result : nullptr);
  });
  py::dict d = py::module_::import("json").attr("loads")(json);
  py::list rings;
  for (const std::vector<PhysicalPoint>& ring : f.zoneBoundary) rings.append(boundary(ring));
  d["zone_boundary"] = rings;
  d["lobe_boundary"] = boundary(f.lobeBoundary);
  d["entry_lobe"] = boundary(f.entryLobe);
  d["exit_lobe"] = boundary(f.exitLobe);
  return d;
}

py::dict cantorus(double K, const std::vector<std::pair<long, int>>& convergents, double inner, double outer,
                  double spacing, double narrowWidth, double narrowSpacing) {
  CantorusRequest r;
  r.K = K;
  r.convergents = convergents;
  r.innerRadius = inner;
  r.outerRadius = outer;
  r.spacing = spacing;
  r.narrowHalfWidth = narrowWidth;
  r.narrowSpacing = narrowSpacing;
  if (auto e = validationError(r)) throw std::invalid_argument(*e);
  const std::string json =
      interruptible([&](std::stop_token stop) { return cantorusFluxJson(r, cantorusFlux(r, stop)); });
  return py::module_::import("json").attr("loads")(json);
}

}  // namespace

// The defaults of manifold() and flux() are the requests' own (issue 35: a front end restates no default).
const ManifoldCurveRequest kManifold{};
const TurnstileRequest kTurnstile{};
const KacRequest kKac{};
const CantorusRequest kCantorus{};

void bindManifolds(py::module_& m) {
  m.def("manifold", &manifold, py::arg("K") = kDefaultMap.K, py::kw_only(), py::arg("branch") = "unstable",
        py::arg("side") = "auto", py::arg("length") = static_cast<double>(kManifold.length), py::arg("period") = 1,
        py::arg("near") = py::none(), py::arg("radius") = 0.01, py::arg("point") = kManifold.point,
        py::arg("box") = py::none(), py::arg("view") = py::none(),
        py::arg("spacing") = static_cast<double>(kManifold.maxSpacing),
        py::arg("angle") = static_cast<double>(kManifold.maxAngle), py::arg("domains") = kManifold.maxDomains,
        py::arg("initial_points") = kManifold.initialPoints, py::arg("stable_from") = toString(kManifold.stableFrom),
        py::arg("escape") = static_cast<double>(kManifold.escapeRadius), py::arg("max_points") = kManifold.maxPoints,
        "A branch of the stable or unstable manifold of the fixed point (sqrt K, 0) (period=1, near=None) or of the\n"
        "hyperbolic periodic orbit of that period near `near` (x, y), by fundamental-domain iteration with adaptive\n"
        "refinement (core/manifolds/ManifoldCurve.hpp).  side: 'inward', 'outward' or 'auto' (inward for the fixed\n"
        "point, outward for an orbit).  box=(xmin, xmax): the torus map Q* in that box; view=(x0, x1, y0, y1): refine\n"
        "finely only there.  Returns arrays s (arc length), x, y, piece (the polyline is cut where the branch escapes\n"
        "or wraps), parameter, and the counts.  ValueError for bad input.");
  m.def("flux", &flux, py::arg("K") = kDefaultMap.K, py::kw_only(), py::arg("period") = 1, py::arg("near") = py::none(),
        py::arg("radius") = 0.01, py::arg("side") = "auto", py::arg("vertices") = kTurnstile.maxVertices,
        py::arg("domains") = kTurnstile.maxDomains, py::arg("kac") = false, py::arg("kac_samples") = kKac.entrySamples,
        py::arg("kac_zone_samples") = kKac.zoneSamples, py::arg("kac_steps") = kKac.maxSteps,
        py::arg("seed") = kKac.seed, py::arg("threads") = kKac.threads,
        "The turnstile flux through the separatrix of the fixed point (sqrt K, 0) or of a symmetric hyperbolic\n"
        "periodic orbit (MacKay, Meiss & Percival 1984; core/manifolds/TurnstileFlux.hpp): the lobe area by the\n"
        "action difference of the two primary homoclinic (heteroclinic) orbits and by the Romberg-extrapolated\n"
        "polygon area, the zone's area both ways, the points, and with kac=True the Kac check (mean residence of\n"
        "orbits entering the zone against transit area / flux).  The same fields as `archipelago-cli flux --json`,\n"
        "plus the boundaries as x, y arrays: zone_boundary (a list of closed curves: one, or one around each island a\n"
        "sub-chain surrounds), lobe_boundary, entry_lobe and exit_lobe.");
  m.def("cantorus", &cantorus, py::arg("K") = kDefaultMap.K, py::kw_only(), py::arg("convergents"),
        py::arg("inner") = static_cast<double>(kCantorus.innerRadius),
        py::arg("outer") = static_cast<double>(kCantorus.outerRadius),
        py::arg("spacing") = static_cast<double>(kCantorus.spacing),
        py::arg("narrow_width") = static_cast<double>(kCantorus.narrowHalfWidth),
        py::arg("narrow_spacing") = static_cast<double>(kCantorus.narrowSpacing),
        "The MacKay-Meiss-Percival flux through a cantorus about the central island (core/manifolds/MmpFlux.hpp):\n"
        "|W(minimax) - W(minimizing)| of the two Birkhoff p/q orbits for each convergent (p, q) in `convergents`,\n"
        "found on the symmetry lines between the distances `inner` and `outer` from (-sqrt K, 0), and the limit (the\n"
        "last term with a bound on the tail).  The dict of `archipelago-cli cantorus --json`.  ValueError for bad\n"
        "input or orbits not found.");
}
