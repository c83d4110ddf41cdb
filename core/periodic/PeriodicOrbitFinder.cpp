#include "core/periodic/PeriodicOrbitFinder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/io/NumberText.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

using smooth::SymmetryLine;
template <class Real>
using Point = smooth::Point<Real>;

/// Orbits must close to this (physical units; the box is O(1)).  Quad polishing reaches ~1e-25 even at
/// period 138; 1e-12 leaves room for strongly hyperbolic orbits.
constexpr long double kClosureTolerance = 1e-12L;
/// A root whose point returns within this after a proper divisor of n steps has a smaller period.
constexpr long double kSubperiodTolerance = 1e-9L;
/// Iterates beyond this are escaping to infinity (the box is O(1)): stop following them.
constexpr long double kEscape = 1e3L;

std::string formatNumber(long double v) {
  const std::string buffer = io::formatC("%.10Lg", v);
  return buffer;
}

/// One shooting problem: start on `from` at abscissa s, take `steps` steps, land on `to`.
struct Shot {
  SymmetryLine from;
  SymmetryLine to;
  long steps;
};

/// The shot that starts on `from` for period n (see SmoothQuadraticMap.hpp for the four cases).
Shot shotFor(SymmetryLine from, int n) {
  if (n % 2 == 0) return {from, from, n / 2};
  return from == SymmetryLine::S2 ? Shot{from, SymmetryLine::S1, (n - 1) / 2}
                                  : Shot{from, SymmetryLine::S2, (n + 1) / 2};
}

template <class Real>
Real shootOffset(const Shot& shot, Real K, Real s) {
  Point<Real> z = smooth::onLine(shot.from, K, s);
  for (long i = 0; i < shot.steps; ++i) {
    z = smooth::step(K, z);
    if (!(smooth::absolute(z.x) < Real(kEscape) && smooth::absolute(z.y) < Real(kEscape)))
      return std::numeric_limits<Real>::quiet_NaN();
  }
  return smooth::offsetFromLine(shot.to, K, z);
}

/// Newton along the start line in quad: F(s) and F'(s) by propagating the line's tangent (1, slope).
quad polishOnLine(const Shot& shot, quad K, quad s, quad maxStep) {
  for (int iteration = 0; iteration < 8; ++iteration) {
    Point<quad> z = smooth::onLine(shot.from, K, s);
    quad vx = 1, vy = smooth::lineSlope(shot.from, s);
    for (long i = 0; i < shot.steps; ++i) {
      const smooth::Matrix2<quad> d = smooth::jacobian(z);
      const quad nx = d.xx * vx + d.xy * vy, ny = d.yx * vx + d.yy * vy;
      vx = nx;
      vy = ny;
      z = smooth::step(K, z);
    }
    const quad f = smooth::offsetFromLine(shot.to, K, z);
    const quad df = vy - smooth::lineSlope(shot.to, z.x) * vx;
    if (df == 0) break;
    const quad delta = f / df;
    if (!(smooth::absolute(delta) <= maxStep)) break;  // Newton left the bracket: keep the bisection result
    s -= delta;
    if (smooth::absolute(delta) <= quad(1e-32L) * (1 + smooth::absolute(s))) break;
  }
  return s;
}

/// The smallest d < n, d | n, with |Q^d(z) − z| small, or n when there is none.
int minimalPeriod(quad K, Point<quad> z0, int n) {
  Point<quad> z = z0;
  for (int d = 1; d < n; ++d) {
    z = smooth::step(K, z);
    if (n % d != 0) continue;
    const quad dx = z.x - z0.x, dy = z.y - z0.y;
    if (smooth::absolute(dx) + smooth::absolute(dy) <= quad(kSubperiodTolerance)) return d;
  }
  return n;
}

struct Window {
  long double lo, hi;
};

/// Sorted, merged windows of `line` near the iterates of the guess.
std::vector<Window> scanWindows(SymmetryLine line, long double K, const PeriodicOrbitSearch& search) {
  std::vector<Window> windows;
  Point<long double> w{search.near.x, search.near.y};
  const long double r = search.searchRadius;
  for (int k = 0; k < search.period; ++k) {
    if (!(std::fabs(w.x) < kEscape && std::fabs(w.y) < kEscape)) break;
    const long double slope = std::fabs(smooth::lineSlope(line, w.x));
    if (std::fabs(smooth::offsetFromLine(line, K, w)) <= r * (1 + slope))
      windows.push_back({w.x - r * (1 + slope), w.x + r * (1 + slope)});
    w = smooth::step(K, w);
  }
  std::sort(windows.begin(), windows.end(), [](const Window& a, const Window& b) { return a.lo < b.lo; });
  std::vector<Window> merged;
  for (const Window& win : windows) {
    if (!merged.empty() && win.lo <= merged.back().hi)
      merged.back().hi = std::max(merged.back().hi, win.hi);
    else
      merged.push_back(win);
  }
  return merged;
}

/// Bisection of a bracket [a, b] with fa·fb < 0 down to adjacent long doubles.
long double bisect(const Shot& shot, long double K, long double a, long double b, long double fa) {
  for (int i = 0; i < 200; ++i) {
    const long double mid = a + (b - a) / 2;
    if (!(mid > a && mid < b)) break;
    const long double fm = shootOffset(shot, K, mid);
    if (std::isnan(fm)) break;
    if (fm == 0) return mid;
    if ((fm < 0) == (fa < 0)) {
      a = mid;
      fa = fm;
    } else {
      b = mid;
    }
  }
  return a + (b - a) / 2;
}

bool sameOrbit(const PeriodicOrbit& a, const PeriodicOrbit& b) {
  return a.period == b.period && a.distanceTo(b.points.front()) <= 1e-9L;
}

}  // namespace

void validate(long double K, const PeriodicOrbitSearch& search) {
  if (!std::isfinite(K)) throw std::invalid_argument("K = " + formatNumber(K) + " must be a finite number");
  if (auto e = rangeError("period", search.period, 1, PeriodicOrbitSearch::kMaxPeriod)) throw std::invalid_argument(*e);
  if (!std::isfinite(search.near.x) || !std::isfinite(search.near.y))
    throw std::invalid_argument("the guess (" + formatNumber(search.near.x) + ", " + formatNumber(search.near.y) +
                                ") must be finite");
  if (!(search.searchRadius > 0) || !std::isfinite(search.searchRadius))
    throw std::invalid_argument("search radius = " + formatNumber(search.searchRadius) +
                                " must be a positive number");
  if (auto e = lowerBoundError("samples per window", search.samplesPerWindow, 8)) throw std::invalid_argument(*e);
}

namespace {

/// The scan of findSymmetricPeriodicOrbits() over given windows of one line: samples at spacing ≤ h, each sign change
/// bisected, polished in quad, kept when its minimal period is n, it closes and it is new.
void scanWindows(long double K, int n, SymmetryLine line, const std::vector<Window>& windows, long double h,
                 bool stableOnly, std::vector<PeriodicOrbit>& found, std::stop_token stop,
                 const std::function<bool(PhysicalPoint)>& accept = {}) {
  const Shot shot = shotFor(line, n);
  const OrbitSymmetry symmetry = line == SymmetryLine::S1 ? OrbitSymmetry::LineS1 : OrbitSymmetry::LineS2;
  for (const Window& window : windows) {
    const long samples = std::lround((window.hi - window.lo) / h) + 1;
    long double sPrevious = window.lo;
    long double fPrevious = shootOffset(shot, K, sPrevious);
    for (long i = 1; i <= samples; ++i) {
      if (stop.stop_requested()) throw OperationStopped();  // each sample costs n steps: checked every one
      const long double s = window.lo + (window.hi - window.lo) * static_cast<long double>(i) / samples;
      const long double f = shootOffset(shot, K, s);
      const bool bracket = !std::isnan(f) && !std::isnan(fPrevious) && ((f < 0) != (fPrevious < 0) || f == 0);
      if (bracket) {
        const long double root = f == 0 ? s : bisect(shot, K, sPrevious, s, fPrevious);
        const Point<long double> start = smooth::onLine(line, K, root);
        if (accept && !accept(PhysicalPoint{start.x, start.y})) {
          sPrevious = s;
          fPrevious = f;
          continue;
        }
        const quad polished = polishOnLine(shot, quad(K), quad(root), quad(s - sPrevious));
        const Point<quad> z0 = smooth::onLine(line, quad(K), polished);
        if (minimalPeriod(quad(K), z0, n) == n) {
          PeriodicOrbit orbit = analysePeriodicOrbit(K, n, z0.x, z0.y, symmetry);
          const bool duplicate = std::any_of(found.begin(), found.end(),
                                             [&](const PeriodicOrbit& o) { return sameOrbit(o, orbit); });
          if (orbit.closure <= kClosureTolerance && !duplicate && (!stableOnly || orbit.stable()))
            found.push_back(std::move(orbit));
        }
      }
      sPrevious = s;
      fPrevious = f;
    }
  }
}

}  // namespace

std::vector<PeriodicOrbit> findSymmetricPeriodicOrbits(long double K, const PeriodicOrbitSearch& search,
                                                       std::stop_token stop) {
  validate(K, search);
  const int n = search.period;
  std::vector<PeriodicOrbit> found;
  const long double h = 2 * search.searchRadius / search.samplesPerWindow;
  for (SymmetryLine line : {SymmetryLine::S1, SymmetryLine::S2})
    scanWindows(K, n, line, scanWindows(line, K, search), h, search.stableOnly, found, stop);
  for (PeriodicOrbit& orbit : found) orbit = orbit.rotatedToStart(orbit.nearestIndex(search.near));
  std::stable_sort(found.begin(), found.end(), [&](const PeriodicOrbit& a, const PeriodicOrbit& b) {
    return a.distanceTo(search.near) < b.distanceTo(search.near);
  });
  return found;
}

std::vector<PeriodicOrbit> findSymmetricPeriodicOrbitsIn(long double K, int period,
                                                         std::span<const LineWindow> windows, long double spacing,
                                                         std::stop_token stop,
                                                         const std::function<bool(PhysicalPoint)>& accept) {
  PeriodicOrbitSearch search;
  search.period = period;
  validate(K, search);
  if (!(spacing > 0) || !std::isfinite(spacing))
    throw std::invalid_argument("spacing = " + formatNumber(spacing) + " must be a positive number");
  std::vector<PeriodicOrbit> found;
  for (const LineWindow& w : windows) {
    if (!std::isfinite(w.lo) || !std::isfinite(w.hi) || !(w.lo < w.hi))
      throw std::invalid_argument("a window [" + formatNumber(w.lo) + ", " + formatNumber(w.hi) +
                                  "] of a symmetry line must have finite ends, lo < hi");
    scanWindows(K, period, w.line, {Window{w.lo, w.hi}}, spacing, false, found, stop, accept);
  }
  return found;
}

namespace {

/// Damped Newton on Qⁿ(z) − z in __float128 with the exact Jacobian DQⁿ − I (refinePeriodicOrbit's method):
/// the converged point, or nothing when Newton escaped, stalled above the quad rounding floor or the Jacobian
/// was singular.
std::optional<Point<quad>> newtonPeriodicPoint(quad k, int period, Point<quad> z, int maxIterations) {
  auto residual = [&](Point<quad> w, smooth::Matrix2<quad>* jacobian) {
    const Point<quad> image = smooth::iterate(k, w, period, jacobian);
    return Point<quad>{image.x - w.x, image.y - w.y};
  };
  auto size = [](Point<quad> v) { return smooth::absolute(v.x) + smooth::absolute(v.y); };
  bool converged = false;
  for (int iteration = 0; iteration < maxIterations && !converged; ++iteration) {
    smooth::Matrix2<quad> m;
    const Point<quad> f = residual(z, &m);
    const quad norm = size(f);
    if (!(norm < quad(kEscape))) return std::nullopt;
    if (norm <= quad(1e-30L)) {
      converged = true;
      break;
    }
    // (DQⁿ − I) δ = −F
    const quad a = m.xx - 1, b = m.xy, c = m.yx, d = m.yy - 1;
    const quad det = a * d - b * c;
    if (det == 0) return std::nullopt;
    const Point<quad> delta{-(d * f.x - b * f.y) / det, -(-c * f.x + a * f.y) / det};
    quad lambda = 1;
    Point<quad> trial;
    quad trialNorm = 0;
    for (;;) {
      trial = {z.x + lambda * delta.x, z.y + lambda * delta.y};
      trialNorm = size(residual(trial, nullptr));
      if (trialNorm < norm || lambda < quad(1e-6L)) break;
      lambda /= 2;
    }
    if (!(trialNorm < norm)) {
      converged = norm <= quad(1e-24L);  // stalled at the rounding floor of quad
      break;
    }
    z = trial;
  }
  if (!converged) {
    const quad norm = size(residual(z, nullptr));
    converged = norm <= quad(1e-24L);
  }
  if (!converged) return std::nullopt;
  return z;
}

}  // namespace

std::optional<PeriodicOrbit> refinePeriodicOrbit(long double K, int period, PhysicalPoint guess, int maxIterations) {
  if (period < 1 || !std::isfinite(K) || !std::isfinite(guess.x) || !std::isfinite(guess.y)) return std::nullopt;
  const quad k = K;
  const std::optional<Point<quad>> z = newtonPeriodicPoint(k, period, Point<quad>{guess.x, guess.y}, maxIterations);
  if (!z || minimalPeriod(k, *z, period) != period) return std::nullopt;
  PeriodicOrbit orbit = analysePeriodicOrbit(K, period, z->x, z->y, OrbitSymmetry::None);
  if (!(orbit.closure <= kClosureTolerance)) return std::nullopt;
  return orbit;
}

std::optional<smooth::Point<quad>> polishPeriodicPoint(long double K, int period, smooth::Point<quad> guess,
                                                       int maxIterations) {
  if (period < 1 || !std::isfinite(K) || !std::isfinite(static_cast<long double>(guess.x)) ||
      !std::isfinite(static_cast<long double>(guess.y)))
    return std::nullopt;
  return newtonPeriodicPoint(quad(K), period, guess, maxIterations);
}

quad polishSymmetricPoint(long double K, int period, SymmetryLine line, quad s, quad maxStep) {
  if (auto e = lowerBoundError("period", period, 1)) throw std::invalid_argument(*e);
  return polishOnLine(shotFor(line, period), quad(K), s, maxStep);
}

PeriodicOrbit findPeriodicOrbit(long double K, const PeriodicOrbitSearch& search, std::stop_token stop) {
  std::vector<PeriodicOrbit> symmetric = findSymmetricPeriodicOrbits(K, search, stop);
  if (stop.stop_requested()) throw OperationStopped();
  if (!symmetric.empty()) return std::move(symmetric.front());
  if (std::optional<PeriodicOrbit> general = refinePeriodicOrbit(K, search.period, search.near)) {
    if (!search.stableOnly || general->stable()) return general->rotatedToStart(general->nearestIndex(search.near));
  }
  throw NotFound("no " + std::string(search.stableOnly ? "stable " : "") + "periodic orbit of period " +
                           std::to_string(search.period) + " found near (" + formatNumber(search.near.x) + ", " +
                           formatNumber(search.near.y) + ") within search radius " +
                           formatNumber(search.searchRadius) + " (Newton did not converge)");
}

}  // namespace archipelago
