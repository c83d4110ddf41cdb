#include "core/stats/LogFits.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace archipelago {

namespace {
using Real = long double;
using LogPoint = LogSeries::Point;

bool usable(const Series& s, std::size_t i) { return s.x[i] > 0 && s.value[i] > 0 && std::isfinite(s.value[i]); }

/// (log x, log y, σ of log y) of the series' usable points with index in [begin, end), in increasing x.
std::vector<LogPoint> logPoints(const Series& s, std::size_t begin, std::size_t end) {
  std::vector<LogPoint> out;
  for (std::size_t i = begin; i < end; ++i) {
    if (!usable(s, i)) continue;
    const Real e = i < s.error.size() && std::isfinite(s.error[i]) ? s.error[i] : 0;
    out.push_back({std::log(static_cast<Real>(s.x[i])), std::log(static_cast<Real>(s.value[i])),
                   e / static_cast<Real>(s.value[i])});
  }
  return out;
}

/// The points a fit over [from, to] reads: those in the window (widened by 10⁻⁶, more than the grid's rounding) and,
/// on each side, the two nearest usable points outside it (the interpolation's brackets and the clamps at the
/// series' ends), when x increases; else every point.  The same fit as over the whole series, without a logarithm
/// of each of its points for every window (the tail's bootstrap fits thousands of windows of long series: a third
/// of the report's time went to those logarithms).
std::vector<LogPoint> windowPoints(const Series& s, double from, double to) {
  std::size_t begin = 0, end = s.x.size();
  if (std::is_sorted(s.x.begin(), s.x.end())) {
    begin = static_cast<std::size_t>(std::lower_bound(s.x.begin(), s.x.end(), from * (1 - 1e-6)) - s.x.begin());
    end = static_cast<std::size_t>(std::upper_bound(s.x.begin(), s.x.end(), to * (1 + 1e-6)) - s.x.begin());
    for (int k = 0; k < 2 && begin > 0;) k += usable(s, --begin) ? 1 : 0;
    for (int k = 0; k < 2 && end < s.x.size();) k += usable(s, end++) ? 1 : 0;
  }
  return logPoints(s, begin, end);
}

SlopeFit fitPoints(const std::vector<LogPoint>& p, double from, double to, int perDecade) {
  SlopeFit fit;
  if (p.size() < 2 || !(from > 0) || !(to > from) || perDecade < 1) return fit;
  const Real ln10 = std::log(Real(10));
  const Real first = std::max(std::log(static_cast<Real>(from)), p.front().u);
  const Real last = std::min(std::log(static_cast<Real>(to)), p.back().u);
  const long k0 = static_cast<long>(std::ceil(first / ln10 * perDecade - 1e-9));
  const long k1 = static_cast<long>(std::floor(last / ln10 * perDecade + 1e-9));
  std::vector<LogPoint> grid;
  std::size_t j = 0;
  for (long k = k0; k <= k1; ++k) {
    const Real u = std::min(std::max(ln10 * k / perDecade, p.front().u), p.back().u);
    while (j + 2 < p.size() && p[j + 1].u < u) ++j;
    const LogPoint& a = p[j];
    const LogPoint& b = p[j + 1];
    const Real w = b.u > a.u ? std::min(std::max((u - a.u) / (b.u - a.u), Real(0)), Real(1)) : 0;
    grid.push_back({u, a.v + w * (b.v - a.v), a.sigma + w * (b.sigma - a.sigma)});
  }
  fit.points = grid.size();
  if (grid.size() < 3) return fit;
  Real su = 0, sv = 0;
  for (const LogPoint& g : grid) su += g.u, sv += g.v;
  const Real n = static_cast<Real>(grid.size()), ub = su / n, vb = sv / n;
  Real suu = 0, suv = 0;
  for (const LogPoint& g : grid) suu += (g.u - ub) * (g.u - ub), suv += (g.u - ub) * (g.v - vb);
  if (!(suu > 0)) return fit;
  const Real slope = suv / suu;
  Real variance = 0;
  for (const LogPoint& g : grid) variance += (g.u - ub) * (g.u - ub) / (suu * suu) * g.sigma * g.sigma;
  fit.slope = static_cast<double>(slope);
  fit.error = static_cast<double>(std::sqrt(variance));
  fit.from = static_cast<double>(std::exp(grid.front().u));
  fit.to = static_cast<double>(std::exp(grid.back().u));
  return fit;
}
}  // namespace

LogSeries::LogSeries(const Series& s) : points_(logPoints(s, 0, s.x.size())) {}
LogSeries::LogSeries(const Series& s, double from, double to) : points_(windowPoints(s, from, to)) {}

SlopeFit logLogSlope(const Series& s, double from, double to, int perDecade) {
  return fitPoints(windowPoints(s, from, to), from, to, perDecade);
}

SlopeFit logLogSlope(const LogSeries& s, double from, double to, int perDecade) {
  return fitPoints(s.points(), from, to, perDecade);
}

namespace {
template <class S>
double decayExponent(const S& s, double from, double to, std::size_t* points) {
  const SlopeFit fit = logLogSlope(s, from, to);
  if (points) *points = fit.points;
  return fit.valid() ? -fit.slope : kTailUndefined;
}
}  // namespace

double fitLogSlope(const Series& s, double from, double to, std::size_t* points) {
  return decayExponent(s, from, to, points);
}
double fitLogSlope(const LogSeries& s, double from, double to, std::size_t* points) {
  return decayExponent(s, from, to, points);
}

SlopeFit logLinearSlope(const Series& s, double from, double to) {
  SlopeFit fit;
  struct Point {
    Real x, v, w;
  };
  std::vector<Point> p;
  bool anyError = false;
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!(s.x[i] >= from && s.x[i] <= to && s.value[i] > 0) || !std::isfinite(s.value[i])) continue;
    const Real e = i < s.error.size() && std::isfinite(s.error[i]) ? s.error[i] : 0;
    anyError = anyError || e > 0;
    p.push_back({static_cast<Real>(s.x[i]), std::log(static_cast<Real>(s.value[i])),
                 e > 0 ? (static_cast<Real>(s.value[i]) / e) * (static_cast<Real>(s.value[i]) / e) : 0});
  }
  if (!anyError)
    for (Point& q : p) q.w = 1;
  std::erase_if(p, [](const Point& q) { return !(q.w > 0); });
  fit.points = p.size();
  if (p.size() < 3) return fit;
  Real sw = 0, sx = 0, sv = 0;
  for (const Point& q : p) sw += q.w, sx += q.w * q.x, sv += q.w * q.v;
  const Real xb = sx / sw, vb = sv / sw;
  Real sxx = 0, sxv = 0;
  for (const Point& q : p) sxx += q.w * (q.x - xb) * (q.x - xb), sxv += q.w * (q.x - xb) * (q.v - vb);
  if (!(sxx > 0)) return fit;
  fit.slope = static_cast<double>(sxv / sxx);
  // Weights from the data's errors: the slope's variance is 1/Σw(x − x̄)²; with equal weights (no errors), the
  // residual scatter estimates the points' variance.
  if (anyError) {
    fit.error = static_cast<double>(std::sqrt(1 / sxx));
  } else {
    Real r = 0;
    for (const Point& q : p) {
      const Real d = q.v - (vb + static_cast<Real>(fit.slope) * (q.x - xb));
      r += d * d;
    }
    fit.error = static_cast<double>(std::sqrt(r / static_cast<Real>(p.size() - 2) / sxx));
  }
  fit.from = static_cast<double>(p.front().x);
  fit.to = static_cast<double>(p.back().x);
  return fit;
}

std::vector<LogWindow> runningExponentWindows(double tEnd, double lowest) {
  std::vector<LogWindow> windows;
  if (!(std::isfinite(tEnd) && std::isfinite(lowest) && lowest > 0 && tEnd >= 3 * lowest)) return windows;
  for (int k = 0; k < 16; ++k) {
    LogWindow w;
    w.to = tEnd * std::pow(10.0, -k / 2.0);
    w.from = w.to / 10;
    if (w.from < lowest) {
      if (k > 0) break;
      w.from = lowest;  // the tail fit alone may be shorter than a decade
    }
    windows.push_back(w);
  }
  return windows;
}

}  // namespace archipelago
