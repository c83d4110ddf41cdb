#include "core/manifolds/TurnstileFlux.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/manifolds/GeneratingFunction.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"  // NotFound
#include "core/manifolds/QuadText.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

using smooth::Point;

int modulo(int i, int n) { return ((i % n) + n) % n; }

void report(const ManifoldProgressCallback& progress, double fraction, const char* stage) {
  if (progress) progress({fraction, stage});
}

void checkStop(std::stop_token stop) {
  if (stop.stop_requested()) throw std::runtime_error("stopped");
}

long double digits(long double a, long double b) {
  const long double d = std::fabs(a - b);
  if (d == 0) return std::numeric_limits<long double>::infinity();
  return -std::log10(d / std::max(std::fabs(a), std::fabs(b)));
}

/// ΔW of the piece c of the zone boundary, Q^c(h): the orbit of h relabelled so that time 0 is at h_c, with the
/// references z_{c+t} (backward) and z_{b+c+t} (forward):  W_c = W_0 + Σ_{s=0}^{c−1} [L(z_{b+s}, z_{b+s+1}) −
/// L(z_s, z_{s+1})]  (GeneratingFunction.hpp).
quad pieceAction(const HyperbolicOrbit& orbit, quad action0, int b, int c) {
  const int n = orbit.period;
  const quad K = orbit.K;
  auto L = [&](int i) {
    return generatingFunction(K, orbit.points[static_cast<std::size_t>(modulo(i, n))].x,
                              orbit.points[static_cast<std::size_t>(modulo(i + 1, n))].x);
  };
  quad w = action0;
  for (int s = 0; s < c; ++s) w += L(b + s) - L(s);
  return w;
}

/// The signed normal offset of the W^s arc `s` from the midpoint of the W^u arc `u` (both of one lobe): positive when
/// the W^s arc lies to the left of W^u travelled away from its orbit point (increasing |σ|).  The W^s point is the one on
/// the normal through the W^u midpoint (Newton on μ in __float128, kept within the arc).
quad lobeSide(const ManifoldArc& u, const ManifoldArc& s) {
  const quad sigma = (u.from + u.to) / 2;
  Point<quad> t;
  const Point<quad> pu = u.manifold->point(u.point, sigma, &t);
  if (sigma < 0) t = {-t.x, -t.y};
  const quad lo = s.from < s.to ? s.from : s.to, hi = s.from < s.to ? s.to : s.from;
  quad mu = (s.from + s.to) / 2;
  for (int i = 0; i < 60; ++i) {
    Point<quad> ts;
    const Point<quad> ps = s.manifold->point(s.point, mu, &ts);
    const quad f = (ps.x - pu.x) * t.x + (ps.y - pu.y) * t.y;
    const quad df = ts.x * t.x + ts.y * t.y;
    if (df == 0) break;
    quad next = mu - f / df;
    next = next < lo ? lo : (next > hi ? hi : next);
    if (smooth::absolute(next - mu) <= quad(1e-32L) * smooth::absolute(mu)) break;
    mu = next;
  }
  const Point<quad> ps = s.manifold->point(s.point, mu);
  return (t.x * (ps.y - pu.y) - t.y * (ps.x - pu.x)) / smooth::squareRoot(t.x * t.x + t.y * t.y);
}

}  // namespace

std::optional<std::string> validationError(const TurnstileRequest& r) {
  if (auto e = manifoldKError(r.K)) return e;
  if (r.orbit && r.orbit->K != r.K)
    return "the orbit's K = " + shortestDecimal(static_cast<double>(r.orbit->K)) + " differs from K = " +
           shortestDecimal(static_cast<double>(r.K));
  if (auto e = rangeError("the domains scanned", r.maxDomains, 0, 1000, "0: automatic")) return e;
  if (auto e = lowerBoundError("the first level's vertices per arc", r.firstVertices, 4)) return e;
  if (auto e = rangeError("the finest level's vertices per arc", r.maxVertices, r.firstVertices, 1 << 20)) return e;
  if (auto e = rangeError("the boundary's vertices per arc", r.boundaryVertices, 8, 1 << 20)) return e;
  return std::nullopt;
}

std::vector<PhysicalPoint> arcPolygon(const ArcRing& arcs, int perArc) {
  std::vector<PhysicalPoint> v;
  v.reserve(arcs.size() * static_cast<std::size_t>(perArc));
  for (const ManifoldArc& a : arcs) {
    const long double from = static_cast<long double>(a.from), to = static_cast<long double>(a.to);
    for (int i = 0; i < perArc; ++i) {
      const long double s = from + (to - from) * static_cast<long double>(i) / perArc;
      const Point<long double> z = a.manifold->point(a.point, s);
      v.push_back({z.x, z.y});
    }
  }
  return v;
}

PolygonArea extrapolatedArea(const std::vector<ArcRing>& rings, int firstVertices, int maxVertices,
                             std::stop_token stop) {
  PolygonArea out;
  std::vector<std::vector<long double>> table;
  for (int n = firstVertices, level = 0; n <= maxVertices; n *= 2, ++level) {
    checkStop(stop);
    long double raw = 0;    // −(counter-clockwise area) = ∮ y dx, ring by ring
    long double floor = 0;  // the shoelace sum's rounding, worst case: one rounding of each cross product, ε Σ|cross|
    for (const ArcRing& ring : rings) {
      const std::vector<PhysicalPoint> v = arcPolygon(ring, n);
      raw -= signedShoelaceArea(v);
      long double cross = 0;
      for (std::size_t i = 0; i < v.size(); ++i) {
        const PhysicalPoint& a = v[i];
        const PhysicalPoint& b = v[(i + 1) % v.size()];
        cross += std::fabs((a.x - v[0].x) * (b.y - v[0].y)) + std::fabs((b.x - v[0].x) * (a.y - v[0].y));
      }
      floor += std::numeric_limits<long double>::epsilon() * cross;
    }
    std::vector<long double> row{raw};
    for (int j = 1; j <= level; ++j) {
      const long double p = std::ldexp(1.0L, 2 * j);  // 4^j
      row.push_back((p * row[static_cast<std::size_t>(j - 1)] - table.back()[static_cast<std::size_t>(j - 1)]) / (p - 1));
    }
    table.push_back(row);
    out.raw = raw;
    out.verticesPerArc = n;
    out.levels = level + 1;
    out.area = row.back();
    if (level >= 1) {
      const long double previous = out.error;
      out.error = std::max(std::fabs(row.back() - table[static_cast<std::size_t>(level - 1)].back()), floor);
      // Converged to the rounding of long double (relative to the area, or, for a lobe much smaller than its
      // coordinates, the error stopped falling at the extrapolation's order): more levels only add noise.
      const long double eps = std::numeric_limits<long double>::epsilon();
      if (level >= 3 && out.error <= 64 * eps * std::fabs(out.area)) break;
      if (level >= 4 && out.error > previous / 4 && out.error <= 1e-12L * std::fabs(out.area)) break;
    } else {
      out.error = std::fabs(raw);
    }
    if (n > maxVertices / 2) break;
  }
  return out;
}

long double TurnstileFlux::lobeDigits() const noexcept { return digits(static_cast<long double>(lobeAction), lobePolygon.area); }

long double TurnstileFlux::zoneDigits() const noexcept { return digits(static_cast<long double>(zoneAction), zonePolygon.area); }

TurnstileFlux computeTurnstileFlux(const TurnstileRequest& request, const ManifoldProgressCallback& progress,
                                   std::stop_token stop) {
  if (auto e = validationError(request)) throw std::invalid_argument(*e);
  report(progress, 0, "manifolds");
  TurnstileFlux out;
  out.side = request.side;
  out.orbit = request.orbit ? hyperbolicOrbitOf(*request.orbit) : hyperbolicFixedPoint(request.K);
  const ManifoldParameterization unstable(out.orbit, ManifoldKind::Unstable);
  const ManifoldParameterization stable(out.orbit, ManifoldKind::Stable);
  const int n = out.orbit.period;
  checkStop(stop);

  report(progress, 0.05, "primary intersections");
  out.intersections = primaryHeteroclinicPoints(unstable, stable, request.side, request.maxDomains, stop);
  const HeteroclinicPoint& h = out.intersections.first;
  const HeteroclinicPoint& h2 = out.intersections.second;
  const int b = out.target = h.target;
  out.lobeAction = h.action - h2.action;
  out.lobeActionError = h.actionError + h2.actionError;
  out.lobeArea = std::fabs(static_cast<long double>(out.lobeAction));
  if (!(out.lobeActionError <= quad(1e-9L) * smooth::absolute(out.lobeAction)))
    throw NotFound("the lobe's area (" + quadText(smooth::absolute(out.lobeAction), 3) +
                             ") is not resolved by __float128: the rounding of the two actions is ~" +
                             quadText(out.lobeActionError, 2) + " (K too small: the lobe is exponentially small, "
                             "A ~ 3.9e5 exp(-2 pi^2 / ln lambda))");
  checkStop(stop);

  // The zone: pieces c, c + b, c + 2b, … (mod n) join into closed curves (piece c ends at z_{c+b}, where piece c + b
  // starts): gcd(b, n) of them (one when b = 0, n = 1).
  // σ_c on Φ_c and μ_c on Ψ_{b+c} for h_c = Q^c(h) (and h'_c): σ_{c+1} = μ_c σ_c, μ_{c+1} = μ_c / ν_{b+c+1}.
  auto carried = [&](const HeteroclinicPoint& p) {
    std::vector<std::pair<quad, quad>> v(static_cast<std::size_t>(n));
    v[0] = {p.sigma, p.mu};
    for (int c = 1; c < n; ++c)
      v[static_cast<std::size_t>(c)] = {v[static_cast<std::size_t>(c - 1)].first * unstable.stretch(c - 1),
                                        v[static_cast<std::size_t>(c - 1)].second / stable.stretch(b + c)};
    return v;
  };
  const auto hc = carried(h), h2c = carried(h2);
  std::vector<ArcRing> zoneRings;
  {
    quad action = 0;
    std::vector<bool> used(static_cast<std::size_t>(n), false);
    for (int start = 0; start < n; ++start) {
      if (used[static_cast<std::size_t>(start)]) continue;
      ArcRing ring;
      int c = start;
      do {
        const auto uc = static_cast<std::size_t>(c);
        used[uc] = true;
        ring.push_back({&unstable, c, 0, hc[uc].first});
        ring.push_back({&stable, b + c, hc[uc].second, 0});
        action += pieceAction(out.orbit, h.action, b, c);
        c = modulo(c + b, n);
      } while (c != start);
      zoneRings.push_back(std::move(ring));
    }
    out.zoneAction = action;
    out.zoneArea = std::fabs(static_cast<long double>(action));
  }
  // The lobe between h' and h (the loop of ΔW(h) − ΔW(h')): W^u from σ_h' to σ_h, W^s from μ_h to μ_h'.
  const ArcRing lobeArcs{{&unstable, 0, h2.sigma, h.sigma}, {&stable, b, h.mu, h2.mu}};
  // The turnstile, on the last piece p = n − 1, between Q⁻ⁿ(h_p) (σ_p/λ, λμ_p) and h_p: the lobe up to Q⁻ⁿ(h'_p)
  // and the lobe from there to h_p.
  const quad lambda = out.orbit.multiplier;
  const int p = n - 1;
  const auto [sp, mp] = hc[static_cast<std::size_t>(p)];
  const auto [sq, mq] = h2c[static_cast<std::size_t>(p)];
  const ArcRing firstTurnstileArcs{{&unstable, p, sp / lambda, sq / lambda}, {&stable, b + p, mq * lambda, mp * lambda}};
  const ArcRing secondTurnstileArcs{{&unstable, p, sq / lambda, sp}, {&stable, b + p, mp, mq * lambda}};

  report(progress, 0.2, "lobe polygon");
  out.lobePolygon = extrapolatedArea({lobeArcs}, request.firstVertices, request.maxVertices, stop);
  report(progress, 0.5, "zone polygon");
  out.zonePolygon = extrapolatedArea(zoneRings, request.firstVertices, request.maxVertices, stop);

  report(progress, 0.85, "boundaries");
  for (const ArcRing& ring : zoneRings) out.zoneBoundary.push_back(arcPolygon(ring, request.boundaryVertices));
  out.lobeBoundary = arcPolygon(lobeArcs, request.boundaryVertices);
  {
    // Which turnstile lobe is inside the zone.  Both have their W^u arc on the zone's boundary, traversed away from
    // z_p; a lobe is inside when its W^s arc lies on the interior side of that arc, i.e. to the left of it for a
    // counter-clockwise boundary (ΔW = ∮ y dx < 0).  The side is the signed normal offset of the W^s arc from the
    // midpoint of the W^u arc, in __float128, so that lobes far thinner than the polygons' chords are classified.
    const bool counterClockwise = out.zoneAction < 0;
    const quad first = lobeSide(firstTurnstileArcs[0], firstTurnstileArcs[1]);
    const quad second = lobeSide(secondTurnstileArcs[0], secondTurnstileArcs[1]);
    if ((first > 0) == (second > 0) || first == 0 || second == 0)
      throw std::runtime_error("the turnstile's lobes lie on the same side of the zone's boundary: the separatrix arcs "
                               "do not bound a simple resonance zone here");
    const bool firstInside = (first > 0) == counterClockwise;
    out.exitLobe = arcPolygon(firstInside ? firstTurnstileArcs : secondTurnstileArcs, request.boundaryVertices);
    out.entryLobe = arcPolygon(firstInside ? secondTurnstileArcs : firstTurnstileArcs, request.boundaryVertices);
  }
  report(progress, 1, "done");
  return out;
}

}  // namespace archipelago
