#include "core/manifolds/HomoclinicPoints.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/manifolds/GeneratingFunction.hpp"

namespace archipelago {

namespace {

using smooth::Point;
using smooth::SymmetryLine;

/// Grid points per fundamental domain of the bracketing scan.
constexpr int kScanPerDomain = 512;
/// The scan starts this many domains inside the local series' radius (where no line is crossed but at z_j).
constexpr int kScanInsideDomains = 3;

Reversor reversorOf(SymmetryLine line) { return line == SymmetryLine::S1 ? Reversor::I1 : Reversor::I2; }

template <class Real>
Real lineOffset(SymmetryLine line, Real K, const Point<Real>& z) {
  return smooth::offsetFromLine(line, K, z);
}

/// The crossing of `line` by Φ_j between σ = a and σ = b (offsets of opposite signs), in __float128: bisection to
/// adjacent quads, then Newton along σ while it reduces |offset|.
quad refineCrossing(const ManifoldParameterization& u, int j, SymmetryLine line, quad a, quad b) {
  const quad K = u.orbit().K;
  quad fa = lineOffset(line, K, u.point(j, a));
  for (int i = 0; i < 400; ++i) {
    const quad m = (a + b) / 2;
    if (!(m != a && m != b)) break;
    const quad fm = lineOffset(line, K, u.point(j, m));
    if (fm == 0) return m;
    if ((fm < 0) == (fa < 0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  quad s = (a + b) / 2;
  for (int i = 0; i < 4; ++i) {
    Point<quad> t;
    const Point<quad> z = u.point(j, s, &t);
    const quad f = lineOffset(line, K, z);
    const quad df = t.y - smooth::lineSlope(line, z.x) * t.x;
    if (df == 0 || f == 0) break;
    const quad next = s - f / df;
    if (!(smooth::absolute(lineOffset(line, K, u.point(j, next))) < smooth::absolute(f))) break;
    s = next;
  }
  return s;
}

/// Product of the unstable stretches μ_0 ⋯ μ_{j−1}: Qʲ multiplies σ on B_0 by it.
quad unstableStretchProduct(const ManifoldParameterization& u, int j) {
  quad p = 1;
  for (int i = 0; i < j; ++i) p *= u.stretch(i);
  return p;
}

int modulo(int i, int n) { return ((i % n) + n) % n; }

}  // namespace

void computeAction(const ManifoldParameterization& unstable, const ManifoldParameterization& stable,
                   HeteroclinicPoint& h) {
  const int n = unstable.period();
  const quad K = unstable.orbit().K;
  const auto& z = unstable.orbit().points;
  auto zx = [&](int i) { return z[static_cast<std::size_t>(modulo(i, n))].x; };
  auto reference = [&](int i) { return generatingFunction(K, zx(i), zx(i + 1)); };
  constexpr int kMaxTerms = 100000;
  constexpr int kQuiet = 4;  // consecutive negligible terms before stopping
  quad sum = 0;
  int terms = 0;
  // Backward on W^u: h_t = Φ_t(σ_t), σ_t = σ_{t+1}/μ_t.
  {
    quad s = h.sigma;
    quad xNext = unstable.point(0, s).x;
    int quiet = 0;
    for (int t = -1; t >= -kMaxTerms && quiet < kQuiet; --t) {
      s /= unstable.stretch(t);
      const quad x = unstable.point(t, s).x;
      const quad term = generatingFunction(K, x, xNext) - reference(t);
      sum += term;
      ++terms;
      quiet = smooth::absolute(term) <= quad(1e-40L) * (smooth::absolute(sum) + quad(1e-300L)) ? quiet + 1 : 0;
      xNext = x;
    }
  }
  // Forward on W^s: h_t = Ψ_{b+t}(μ_t), μ_{t+1} = μ_t/ν_{b+t+1}.
  {
    quad m = h.mu;
    quad x = stable.point(h.target, m).x;
    int quiet = 0;
    for (int t = 0; t < kMaxTerms && quiet < kQuiet; ++t) {
      m /= stable.stretch(h.target + t + 1);
      const quad xNext = stable.point(h.target + t + 1, m).x;
      const quad term = generatingFunction(K, x, xNext) - reference(h.target + t);
      sum += term;
      ++terms;
      quiet = smooth::absolute(term) <= quad(1e-40L) * (smooth::absolute(sum) + quad(1e-300L)) ? quiet + 1 : 0;
      x = xNext;
    }
  }
  h.action = sum;
  h.actionTerms = terms;
}

std::vector<Point<quad>> heteroclinicOrbit(const ManifoldParameterization& unstable,
                                          const ManifoldParameterization& stable, const HeteroclinicPoint& h,
                                          int past, int future) {
  if (past < 0 || future < 0) throw std::invalid_argument("heteroclinicOrbit: past and future must be >= 0");
  std::vector<Point<quad>> orbit(static_cast<std::size_t>(past) + static_cast<std::size_t>(future) + 1);
  quad s = h.sigma;
  orbit[static_cast<std::size_t>(past)] = unstable.point(0, s);
  for (int t = -1; t >= -past; --t) {
    s /= unstable.stretch(t);
    orbit[static_cast<std::size_t>(past + t)] = unstable.point(t, s);
  }
  quad m = h.mu;
  for (int t = 1; t <= future; ++t) {
    m /= stable.stretch(h.target + t);
    orbit[static_cast<std::size_t>(past + t)] = stable.point(h.target + t, m);
  }
  return orbit;
}

PrimaryIntersections primaryHeteroclinicPoints(const ManifoldParameterization& unstable,
                                               const ManifoldParameterization& stable, BranchSide side,
                                               int maxDomains, std::stop_token stop) {
  if (unstable.kind() != ManifoldKind::Unstable || stable.kind() != ManifoldKind::Stable)
    throw std::invalid_argument("primaryHeteroclinicPoints() needs the unstable and the stable manifold");
  const HyperbolicOrbit& orbit = unstable.orbit();
  const int n = orbit.period;
  if (!(orbit.multiplier > 0))
    throw std::invalid_argument("the orbit is hyperbolic with reflection (multiplier < -1): its branches are exchanged "
                                "by Q^n and the turnstile is not between two consecutive intersections");
  if (!reversedIndex(orbit, Reversor::I1, 0) || !reversedIndex(orbit, Reversor::I2, 0))
    throw std::invalid_argument("the orbit is not symmetric (the involutions I1, I2 do not map it onto itself): its "
                                "heteroclinic points are not on the symmetry lines");
  if (maxDomains < 1 || maxDomains > 1000) throw std::invalid_argument("maxDomains must be in [1, 1000]");
  const long double K = orbit.K;
  const long double factor = static_cast<long double>(unstable.domainFactor());
  const long double logFactor = std::log(factor);

  std::vector<HeteroclinicPoint> found;
  for (int j = 0; j < n; ++j) {
    if (stop.stop_requested()) break;
    const quad toBranch = unstableStretchProduct(unstable, j);  // σ on B_j = σ on B_0 · toBranch
    const long double sign = (static_cast<int>(side) > 0) == (toBranch > 0) ? 1.0L : -1.0L;
    const long double start = static_cast<long double>(unstable.radius(j)) * std::pow(factor, -kScanInsideDomains);
    const int samples = kScanPerDomain * (maxDomains + kScanInsideDomains);
    for (SymmetryLine line : {SymmetryLine::S1, SymmetryLine::S2}) {
      long double previousSigma = sign * start;
      long double previous = lineOffset(line, K, unstable.point(j, previousSigma));
      for (int i = 1; i <= samples; ++i) {
        const long double sigma = sign * start * std::exp(logFactor * static_cast<long double>(i) / kScanPerDomain);
        const Point<long double> zl = unstable.point(j, sigma);
        const long double f = lineOffset(line, K, zl);
        if (std::isnan(f)) break;  // the branch escaped to infinity
        if ((f < 0) != (previous < 0) || f == 0) {
          const quad root = refineCrossing(unstable, j, line, quad(previousSigma), quad(sigma));
          const Reversor r = reversorOf(line);
          const std::optional<int> b = reversedIndex(orbit, r, j);  // I(z_j) = z_b
          HeteroclinicPoint h;
          h.line = line;
          h.symmetricIndex = j;
          h.target = modulo(*b - j, n);
          h.sigma = root / toBranch;
          quad mu = reversalScale(unstable, stable, r, *b) * root;  // on Ψ_b
          for (int step = 0; step < j; ++step) mu *= stable.stretch(*b - step);  // Q⁻ʲ: Ψ_b → Ψ_{b−j}
          h.mu = mu;
          h.point = unstable.point(0, h.sigma);
          const Point<quad> other = stable.point(h.target, h.mu);
          h.mismatch = smooth::squareRoot((h.point.x - other.x) * (h.point.x - other.x) +
                                          (h.point.y - other.y) * (h.point.y - other.y));
          found.push_back(h);
          break;  // the first crossing of this line on this branch
        }
        previous = f;
        previousSigma = sigma;
      }
    }
  }
  if (stop.stop_requested()) throw std::runtime_error("stopped");

  // One entry per orbit: crossings whose σ differ by a power of Λ are the same orbit.
  std::sort(found.begin(), found.end(), [](const HeteroclinicPoint& a, const HeteroclinicPoint& b) {
    return smooth::absolute(a.sigma) < smooth::absolute(b.sigma);
  });
  std::vector<HeteroclinicPoint> distinct;
  for (const HeteroclinicPoint& h : found) {
    const bool same = std::any_of(distinct.begin(), distinct.end(), [&](const HeteroclinicPoint& d) {
      if (d.target != h.target) return false;
      const long double ratio = std::log(static_cast<long double>(smooth::absolute(h.sigma / d.sigma))) / logFactor;
      return std::fabs(ratio - std::round(ratio)) < 1e-9L;
    });
    if (!same) distinct.push_back(h);
  }
  PrimaryIntersections result;
  result.crossings = distinct;
  if (distinct.empty())
    throw std::runtime_error("no symmetric heteroclinic point found within " + std::to_string(maxDomains) +
                             " fundamental domains of the " + toString(side) + " branch");
  result.first = distinct.front();
  const quad lo = smooth::absolute(result.first.sigma);
  const auto second = std::find_if(distinct.begin() + 1, distinct.end(), [&](const HeteroclinicPoint& h) {
    const quad s = smooth::absolute(h.sigma);
    return h.target == result.first.target && s > lo && s < lo * unstable.domainFactor();
  });
  if (second == distinct.end())
    throw std::runtime_error("only one symmetric heteroclinic orbit found on the " + std::string(toString(side)) +
                             " branch (a turnstile needs two)");
  result.second = *second;
  computeAction(unstable, stable, result.first);
  computeAction(unstable, stable, result.second);
  return result;
}

}  // namespace archipelago
