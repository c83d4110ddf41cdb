#include "core/manifolds/HomoclinicPoints.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/manifolds/GeneratingFunction.hpp"
#include "core/parallel/ParallelFor.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"  // NotFound
#include "core/limits/Limits.hpp"

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
/// adjacent quads (from a long double bracket: ~50 halvings), then Newton along σ while it reduces |offset|.
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

/// A track of the scan, branch j and one line: its last sample.
struct Track {
  long double sigma0 = 0;  // carried parameter of the last sample
  long double offset = 0;
  bool started = false;
};

/// A crossing of a symmetry line found by the scan.
struct Candidate {
  int branch;
  SymmetryLine line;
  long double sigma0;  // carried to B_0
  long double a, b;    // bracket on B_j
  int target;
};

using CandidatePair = std::pair<Candidate, Candidate>;

/// The turnstile's orbit and request, checked before the scan.
void checkHeteroclinicRequest(const ManifoldParameterization& unstable, const ManifoldParameterization& stable,
                              int maxDomains) {
  if (unstable.kind() != ManifoldKind::Unstable || stable.kind() != ManifoldKind::Stable)
    throw std::invalid_argument("primaryHeteroclinicPoints() needs the unstable and the stable manifold");
  const HyperbolicOrbit& orbit = unstable.orbit();
  if (!(orbit.multiplier > 0))
    throw std::invalid_argument("the orbit is hyperbolic with reflection (multiplier < -1): its branches are exchanged "
                                "by Q^n and the turnstile is not between two consecutive intersections");
  if (!reversedIndex(orbit, Reversor::I1, 0) || !reversedIndex(orbit, Reversor::I2, 0))
    throw std::invalid_argument("the orbit is not symmetric (the involutions I1, I2 do not map it onto itself): its "
                                "heteroclinic points are not on the symmetry lines");
  if (auto e = rangeError("maxDomains", maxDomains, 0, 1000)) throw std::invalid_argument(*e);
}

/// The scan for the crossings of the symmetry lines by the unstable branches on one side.  It runs over the
/// fundamental domains of the parameter σ₀ carried to B_0 (σ_j = σ₀ · μ_0⋯μ_{j−1} on B_j), all branches and both
/// lines together, domain after domain, from kScanInsideDomains inside the series' radius at z_0: a crossing found on
/// B_j at σ_j is Qʲ of the point σ₀ of B_0, so after domain k every crossing with |σ₀| < s₀Λ^{k+1} is known, and the
/// scan stops as soon as the primary pair is certain.  Brackets are refined in long double; only the distinct orbits
/// found are refined in __float128.
struct CrossingScan {
  const ManifoldParameterization& unstable;
  const HyperbolicOrbit& orbit;
  int n;
  long double K;
  long double factor;     // Λ
  long double logFactor;
  long double sign;       // the side
  std::vector<long double> toBranch;  // μ_0⋯μ_{j−1}
  long double start;      // s₀

  CrossingScan(const ManifoldParameterization& u, BranchSide side)
      : unstable(u),
        orbit(u.orbit()),
        n(orbit.period),
        K(orbit.K),
        factor(static_cast<long double>(u.domainFactor())),
        logFactor(std::log(factor)),
        sign(static_cast<long double>(static_cast<int>(side))),
        toBranch(static_cast<std::size_t>(n)),
        start(static_cast<long double>(u.radius(0)) * std::pow(factor, -kScanInsideDomains)) {
    for (int j = 0; j < n; ++j)
      toBranch[static_cast<std::size_t>(j)] = static_cast<long double>(unstableStretchProduct(unstable, j));
  }

  /// σ₀ after `domains` fundamental domains of the scan.
  long double sigma0At(long double domains) const { return start * std::exp(logFactor * domains); }

  /// The offset from `line` of branch j at the carried parameter σ₀.
  long double offsetAt(int j, SymmetryLine line, long double sigma0) const {
    const long double scale = toBranch[static_cast<std::size_t>(j)];
    const long double branchSign = (sign > 0) == (scale > 0) ? 1.0L : -1.0L;
    return lineOffset(line, K, unstable.point(j, branchSign * std::fabs(sigma0 * scale)));
  }

  /// Domain k of track (branch j, line): the crossings between its samples, each bisected in long double on the
  /// carried parameter, appended to `found`.
  void scanTrack(std::size_t track, int k, Track& t, std::vector<Candidate>& found) const {
    const int j = static_cast<int>(track / 2);
    const SymmetryLine line = track % 2 == 0 ? SymmetryLine::S1 : SymmetryLine::S2;
    if (!t.started) {
      t.sigma0 = sigma0At(k);
      t.offset = offsetAt(j, line, t.sigma0);
      t.started = true;
    }
    for (int i = 1; i <= kScanPerDomain; ++i) {
      const long double sigma0 = sigma0At(k + static_cast<long double>(i) / kScanPerDomain);
      const long double f = offsetAt(j, line, sigma0);
      if (std::isnan(f)) break;  // the branch escaped to infinity
      if ((f < 0) != (t.offset < 0) || f == 0) {
        long double a = t.sigma0, b = sigma0, fa = t.offset;
        for (int it = 0; it < 80 && b - a > 4 * std::numeric_limits<long double>::epsilon() * b; ++it) {
          const long double m = a + (b - a) / 2;
          const long double fm = offsetAt(j, line, m);
          if ((fm < 0) == (fa < 0)) {
            a = m;
            fa = fm;
          } else {
            b = m;
          }
        }
        const std::optional<int> image = reversedIndex(orbit, reversorOf(line), j);  // I(z_j) = z_b
        found.push_back({j, line, sign * (a + (b - a) / 2), a, b, modulo(*image - j, n)});
      }
      t.sigma0 = sigma0;
      t.offset = f;
    }
  }

  /// Domain k of every track, appended to `candidates`.  The 2n tracks (branch j, line) are independent: scanned in
  /// parallel, each into its own list, the lists then appended in the serial order (j, then S₁, S₂), so that the
  /// result does not depend on the threads.
  void scanDomain(int k, std::vector<Track>& tracks, std::vector<Candidate>& candidates, std::stop_token stop) const {
    std::vector<std::vector<Candidate>> perTrack(tracks.size());
    (void)parallelFor(tracks.size(), [&](std::size_t track, int) { scanTrack(track, k, tracks[track], perTrack[track]); },
                      stop);
    if (stop.stop_requested()) throw std::runtime_error("stopped");
    for (const std::vector<Candidate>& list : perTrack) candidates.insert(candidates.end(), list.begin(), list.end());
  }

  /// The candidates by |σ₀|, one per orbit (crossings of the same target whose σ₀ differ by a power of Λ are one).
  std::vector<Candidate> distinctOrbits(std::vector<Candidate> list) const {
    std::sort(list.begin(), list.end(), [](const Candidate& x, const Candidate& y) { return std::fabs(x.sigma0) < std::fabs(y.sigma0); });
    std::vector<Candidate> distinct;
    for (const Candidate& c : list) {
      const bool same = std::any_of(distinct.begin(), distinct.end(), [&](const Candidate& d) {
        if (d.target != c.target) return false;
        const long double ratio = std::log(std::fabs(c.sigma0 / d.sigma0)) / logFactor;
        return std::fabs(ratio - std::round(ratio)) < 1e-9L;
      });
      if (!same) distinct.push_back(c);
    }
    return distinct;
  }

  /// The primary pair: the nearest orbit and the next one to the same z_b within a factor Λ of it.
  std::optional<CandidatePair> primaryPair(const std::vector<Candidate>& distinct) const {
    if (distinct.empty()) return std::nullopt;
    const Candidate& first = distinct.front();
    for (std::size_t i = 1; i < distinct.size(); ++i) {
      const Candidate& c = distinct[i];
      if (c.target == first.target && std::fabs(c.sigma0) > std::fabs(first.sigma0) &&
          std::fabs(c.sigma0) < factor * std::fabs(first.sigma0))
        return CandidatePair{first, c};
    }
    return std::nullopt;
  }

  /// The crossing c refined in __float128, carried to B_0 (σ) and to W^s (μ), with its mismatch.
  HeteroclinicPoint refine(const Candidate& c, const ManifoldParameterization& stable) const {
    const quad scale = unstableStretchProduct(unstable, c.branch);
    const long double branchSign = (sign > 0) == (scale > 0) ? 1.0L : -1.0L;
    const quad a = quad(branchSign) * smooth::absolute(quad(c.a) * scale), b = quad(branchSign) * smooth::absolute(quad(c.b) * scale);
    const quad root = refineCrossing(unstable, c.branch, c.line, a, b);
    const Reversor r = reversorOf(c.line);
    const int image = *reversedIndex(orbit, r, c.branch);
    HeteroclinicPoint h;
    h.line = c.line;
    h.symmetricIndex = c.branch;
    h.target = c.target;
    h.sigma = root / scale;
    quad mu = reversalScale(unstable, stable, r, image) * root;  // on Ψ_b
    for (int step = 0; step < c.branch; ++step) mu *= stable.stretch(image - step);  // Q⁻ʲ: Ψ_b → Ψ_{b−j}
    h.mu = mu;
    h.point = unstable.point(0, h.sigma);
    const Point<quad> other = stable.point(h.target, h.mu);
    h.mismatch = smooth::squareRoot((h.point.x - other.x) * (h.point.x - other.x) + (h.point.y - other.y) * (h.point.y - other.y));
    return h;
  }
};

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
  quad sum = 0, magnitude = 0;
  int terms = 0;
  // Backward on W^u: h_t = Φ_t(σ_t), σ_t = σ_{t+1}/μ_t.
  {
    quad s = h.sigma;
    quad xNext = unstable.point(0, s).x;
    int quiet = 0;
    for (int t = -1; t >= -kMaxTerms && quiet < kQuiet; --t) {
      s /= unstable.stretch(t);
      const quad x = unstable.point(t, s).x;
      const quad own = generatingFunction(K, x, xNext), ref = reference(t);
      const quad term = own - ref;
      magnitude += smooth::absolute(own) + smooth::absolute(ref);
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
      const quad own = generatingFunction(K, x, xNext), ref = reference(h.target + t);
      const quad term = own - ref;
      magnitude += smooth::absolute(own) + smooth::absolute(ref);
      sum += term;
      ++terms;
      quiet = smooth::absolute(term) <= quad(1e-40L) * (smooth::absolute(sum) + quad(1e-300L)) ? quiet + 1 : 0;
      x = xNext;
    }
  }
  h.action = sum;
  // Each L is a handful of operations on O(1) numbers and each summand one subtraction: a few ulps of |L| per term.
  h.actionError = 4 * quad(1.0L) / quad(5192296858534827628530496329220096.0L) * magnitude;  // ε_quad = 2^−112
  h.actionTerms = terms;
}

std::vector<Point<quad>> heteroclinicOrbit(const ManifoldParameterization& unstable,
                                          const ManifoldParameterization& stable, const HeteroclinicPoint& h,
                                          int past, int future) {
  for (const auto& [name, steps] : {std::pair{"past", past}, std::pair{"future", future}})
    if (auto e = lowerBoundError(name, steps, 0)) throw std::invalid_argument("heteroclinicOrbit: " + *e);
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
  checkHeteroclinicRequest(unstable, stable, maxDomains);
  const CrossingScan scan(unstable, side);
  if (maxDomains == 0) maxDomains = static_cast<int>(std::min(1000.0L, std::ceil(30 / scan.logFactor)));
  std::vector<Track> tracks(static_cast<std::size_t>(2 * scan.n));
  std::vector<Candidate> candidates;
  std::optional<CandidatePair> pair;
  const int domains = maxDomains + kScanInsideDomains;
  for (int k = 0; k < domains && !pair; ++k) {
    if (stop.stop_requested()) throw std::runtime_error("stopped");
    scan.scanDomain(k, tracks, candidates, stop);
    // Every crossing with |σ₀| < s₀Λ^{k+1} is known: the pair is certain once its second point is below that.
    std::vector<Candidate> distinct = scan.distinctOrbits(candidates);
    if (auto found = scan.primaryPair(distinct); found && std::fabs(found->second.sigma0) < scan.sigma0At(k + 1))
      pair = found;
  }
  const std::vector<Candidate> distinct = scan.distinctOrbits(candidates);
  if (distinct.empty())
    throw NotFound("no symmetric heteroclinic point found within " + std::to_string(maxDomains) +
                             " fundamental domains of the " + toString(side) + " branch");
  if (!pair)
    throw NotFound("only one symmetric heteroclinic orbit found on the " + std::string(toString(side)) +
                             " branch (a turnstile needs two)");

  // Refine in __float128 the distinct orbits up to the pair's second point.
  PrimaryIntersections result;
  for (const Candidate& c : distinct) {
    if (std::fabs(c.sigma0) > std::fabs(pair->second.sigma0)) break;
    result.crossings.push_back(scan.refine(c, stable));
  }
  result.first = scan.refine(pair->first, stable);
  result.second = scan.refine(pair->second, stable);
  computeAction(unstable, stable, result.first);
  computeAction(unstable, stable, result.second);
  return result;
}

}  // namespace archipelago
