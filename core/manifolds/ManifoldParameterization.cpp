#include "core/manifolds/ManifoldParameterization.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/io/NumberText.hpp"  // shortText
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

using smooth::Matrix2;
using smooth::Point;

/// Truncation target of the local series, relative to its linear term (quad has 113 bits ≈ 1e−34).
constexpr long double kSeriesTolerance = 1e-32L;
/// The series radius is never taken larger than this (physical units; σ is arc length near the orbit).
constexpr long double kMaxRadius = 1e3L;
/// Iterates beyond this are escaping to infinity: point() returns NaN rather than overflow slowly.
constexpr long double kOverflow = 1e100L;

Point<quad> operator*(const Matrix2<quad>& m, Point<quad> v) { return {m.xx * v.x + m.xy * v.y, m.yx * v.x + m.yy * v.y}; }

quad norm(Point<quad> v) { return smooth::squareRoot(v.x * v.x + v.y * v.y); }

/// DQ⁻¹ at z (rows x, y of the preimage; columns x, y of z): Q⁻¹(x, y) = (x − y, y − g(x − y)).
Matrix2<quad> inverseJacobian(Point<quad> z) {
  const quad g1 = 4 * (z.x - z.y);
  return {1, -1, -g1, 1 + g1};
}

/// A unit eigenvector of m for the eigenvalue e (det m = 1, e real and simple).
Point<quad> eigenvector(const Matrix2<quad>& m, quad e) {
  const Point<quad> a{m.xy, e - m.xx}, b{e - m.yy, m.yx};
  const Point<quad> v = norm(a) >= norm(b) ? a : b;
  const quad n = norm(v);
  return {v.x / n, v.y / n};
}

/// The centre each point of the orbit winds around: for a chain around the central island, (−√K, 0) is not central
/// enough for distorted chains, and a sub-chain (the 138-chain of §6: 23 points around each of six islands) winds
/// around its island.  Among the divisors d of n leaving ≥ 3 points per class, the classes {z_{j+kd}} with the
/// smallest spread about their centroid are the clusters around one island; point j's centre is its class centroid.
/// The fixed point and orbits of period < 3: (−√K, 0).
std::vector<Point<quad>> chainCentres(const HyperbolicOrbit& orbit) {
  const int n = orbit.period;
  const Point<quad> central{-smooth::squareRoot(quad(orbit.K)), 0};
  if (n < 3) return std::vector<Point<quad>>(static_cast<std::size_t>(n), central);
  std::vector<Point<quad>> best;
  quad bestSpread = -1;
  for (int d = 1; n / d >= 3; ++d) {
    if (n % d != 0) continue;
    std::vector<Point<quad>> centres(static_cast<std::size_t>(n));
    quad spread = 0;
    for (int c = 0; c < d; ++c) {
      Point<quad> m{0, 0};
      for (int j = c; j < n; j += d) m = {m.x + orbit.points[static_cast<std::size_t>(j)].x, m.y + orbit.points[static_cast<std::size_t>(j)].y};
      m = {m.x / (n / d), m.y / (n / d)};
      for (int j = c; j < n; j += d) {
        centres[static_cast<std::size_t>(j)] = m;
        spread += norm({orbit.points[static_cast<std::size_t>(j)].x - m.x, orbit.points[static_cast<std::size_t>(j)].y - m.y});
      }
    }
    if (bestSpread < 0 || spread < bestSpread) {
      bestSpread = spread;
      best = centres;
    }
  }
  return best;
}

using Coefficients = std::vector<std::vector<Point<quad>>>;  ///< [j][k]

/// The point a step along the cycle leads to: j + 1 (unstable: Q) or j − 1 (stable: Q⁻¹).
int nextPoint(int j, int n, bool unstable) { return unstable ? (j + 1) % n : (j - 1 + n) % n; }

/// The linear maps of one step along the cycle: A_j = DQ(z_j) (unstable: point j → j+1) or DQ⁻¹(z_j) (stable:
/// point j → j−1).
std::vector<Matrix2<quad>> cycleSteps(const HyperbolicOrbit& orbit, bool unstable) {
  std::vector<Matrix2<quad>> step(static_cast<std::size_t>(orbit.period));
  for (int j = 0; j < orbit.period; ++j)
    step[static_cast<std::size_t>(j)] = unstable ? smooth::jacobian(orbit.points[static_cast<std::size_t>(j)])
                                                 : inverseJacobian(orbit.points[static_cast<std::size_t>(j)]);
  return step;
}

/// A unit eigenvector at z_0 for λ (of DQⁿ for W^u, of DQ⁻ⁿ for W^s), oriented "outward": at the point of the orbit
/// where the linear term is the most nearly radial (from that point's centre, chainCentres()), σ > 0 must point away
/// from the centre.  Q maps a branch onto a branch, so the orientation carried around the cycle (positive stretches)
/// is the same at every point: deciding where the geometry is clearest avoids the points of a distorted chain where
/// both branches are nearly tangential.
Point<quad> outwardTangent(const HyperbolicOrbit& orbit, const std::vector<Matrix2<quad>>& step, bool unstable) {
  const int n = orbit.period;
  const Matrix2<quad>& mono = orbit.monodromy;
  const Matrix2<quad> inverseMono{mono.yy, -mono.xy, -mono.yx, mono.xx};  // det = 1
  Point<quad> v0 = eigenvector(unstable ? mono : inverseMono, orbit.multiplier);
  const std::vector<Point<quad>> centres = chainCentres(orbit);
  Point<quad> v = v0;
  int j = 0;
  quad decisive = 0, sign = 1;
  for (int s = 0; s < n; ++s) {
    const auto uj = static_cast<std::size_t>(j);
    const Point<quad> r{orbit.points[uj].x - centres[uj].x, orbit.points[uj].y - centres[uj].y};
    const quad c = (v.x * r.x + v.y * r.y) / (norm(r) + quad(1e-300L));
    if (smooth::absolute(c) > decisive) {
      decisive = smooth::absolute(c);
      sign = c < 0 ? -1 : 1;
    }
    const Point<quad> w = step[uj] * v;
    const quad m = norm(w);
    v = {w.x / m, w.y / m};
    j = nextPoint(j, n, unstable);
  }
  if (sign < 0 || (decisive == 0 && v0.x < 0)) v0 = {-v0.x, -v0.y};
  return v0;
}

/// The linear terms a_{j,1}: v0 carried around the cycle, each step's stretch μ_j the length it multiplies it by
/// (negative at the last step when λ < 0: the cycle closes with a reflection).  Returns the stretches.
std::vector<quad> carryLinearTerms(Point<quad> v0, const std::vector<Matrix2<quad>>& step, bool unstable,
                                   Coefficients& coefficients) {
  const int n = static_cast<int>(step.size());
  std::vector<quad> stretch(step.size(), 0);
  Point<quad> v = v0;
  int j = 0;
  for (int s = 0; s < n; ++s) {
    coefficients[static_cast<std::size_t>(j)][1] = v;
    const Point<quad> w = step[static_cast<std::size_t>(j)] * v;
    quad mu = norm(w);
    Point<quad> vNext{w.x / mu, w.y / mu};
    if (s == n - 1 && vNext.x * v0.x + vNext.y * v0.y < 0) {  // λ < 0: the cycle closes with a reflection
      mu = -mu;
      vNext = {-vNext.x, -vNext.y};
    }
    stretch[static_cast<std::size_t>(j)] = mu;
    v = vNext;
    j = nextPoint(j, n, unstable);
  }
  return stretch;
}

/// Orders k ≥ 2: a_{next(j),k} = stretch_j^{−k} (A_j a_{j,k} + b_{j,k}); shoot around the cycle from point 0 with
/// a_{j,k} = T_j a_{0,k} + r_j, then solve (I − T_n) a_{0,k} = r_n.
void solveHigherOrders(const std::vector<Matrix2<quad>>& step, const std::vector<quad>& stretch, bool unstable,
                       int order, Coefficients& coefficients) {
  const int n = static_cast<int>(step.size());
  const std::size_t un = step.size();
  std::vector<quad> power(un, 1);  // stretch_j^{−k}
  std::vector<Point<quad>> b(un);
  for (int k = 2; k <= order; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    for (std::size_t j = 0; j < un; ++j) {
      power[j] = (k == 2 ? 1 / (stretch[j] * stretch[j]) : power[j] / stretch[j]);
      quad c = 0;
      const std::vector<Point<quad>>& a = coefficients[j];
      for (int i = 1; i < k; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        if (unstable) c += a[ui].x * a[uk - ui].x;
        else c += (a[ui].x - a[ui].y) * (a[uk - ui].x - a[uk - ui].y);
      }
      b[j] = unstable ? Point<quad>{2 * c, 2 * c} : Point<quad>{0, -2 * c};
    }
    Matrix2<quad> T;  // identity
    Point<quad> r{0, 0};
    int j = 0;
    for (int s = 0; s < n; ++s) {
      const auto uj = static_cast<std::size_t>(j);
      const Matrix2<quad> scaled{power[uj] * step[uj].xx, power[uj] * step[uj].xy, power[uj] * step[uj].yx,
                                 power[uj] * step[uj].yy};
      T = scaled * T;
      const Point<quad> ar = scaled * r;
      r = {ar.x + power[uj] * b[uj].x, ar.y + power[uj] * b[uj].y};
      j = nextPoint(j, n, unstable);
    }
    const quad a11 = 1 - T.xx, a12 = -T.xy, a21 = -T.yx, a22 = 1 - T.yy;
    const quad det = a11 * a22 - a12 * a21;
    Point<quad> a{(a22 * r.x - a12 * r.y) / det, (-a21 * r.x + a11 * r.y) / det};
    j = 0;
    for (int s = 0; s < n; ++s) {
      const auto uj = static_cast<std::size_t>(j);
      coefficients[uj][uk] = a;
      const Point<quad> image = step[uj] * a;
      a = {power[uj] * (image.x + b[uj].x), power[uj] * (image.y + b[uj].y)};
      j = nextPoint(j, n, unstable);
    }
  }
}

/// The radius of one point's series a_0 … a_order: the last three terms below kSeriesTolerance of the linear one
/// (|a_1| = 1) and no term above it.
long double seriesRadius(const std::vector<Point<quad>>& coefficients, int order) {
  long double rho = kMaxRadius;
  for (int k = 2; k <= order; ++k) {
    const Point<quad>& a = coefficients[static_cast<std::size_t>(k)];
    const long double size = static_cast<long double>(std::max(smooth::absolute(a.x), smooth::absolute(a.y)));
    if (!(size > 0)) continue;
    const long double e = 1.0L / (k - 1);
    rho = std::min(rho, std::pow(1 / size, e));
    if (k > order - 3) rho = std::min(rho, std::pow(kSeriesTolerance / (3 * size), e));
  }
  return rho;
}

template <class Real>
bool escaped(const Point<Real>& z) {
  return !(smooth::absolute(z.x) < Real(kOverflow) && smooth::absolute(z.y) < Real(kOverflow));
}

}  // namespace

const char* toString(ManifoldKind kind) noexcept { return kind == ManifoldKind::Unstable ? "unstable" : "stable"; }

ManifoldKind parseManifoldKind(const std::string& text, const std::string& option) {
  for (const ManifoldKind kind : {ManifoldKind::Stable, ManifoldKind::Unstable})
    if (text == toString(kind)) return kind;
  throw std::invalid_argument(option + " '" + io::shortText(text) + "' must be stable or unstable");
}

const char* toString(BranchSide side) noexcept { return side == BranchSide::Outward ? "outward" : "inward"; }

BranchSide parseBranchSide(const std::string& text, bool fixedPoint, const std::string& option) {
  if (text == "inward") return BranchSide::Inward;
  if (text == "outward") return BranchSide::Outward;
  if (text == "auto") return defaultSide(fixedPoint);
  throw std::invalid_argument(option + " '" + text + "' must be inward, outward or auto");
}

ManifoldParameterization::ManifoldParameterization(HyperbolicOrbit orbit, ManifoldKind kind, int order)
    : orbit_(std::move(orbit)), kind_(kind), order_(order) {
  if (auto e = rangeError("the order of the manifold's series", order, 2, 200)) throw std::invalid_argument(*e);
  const int n = orbit_.period;
  if (n < 1 || orbit_.points.size() != static_cast<std::size_t>(n))
    throw std::invalid_argument("the hyperbolic orbit has no points");
  const bool unstable = kind == ManifoldKind::Unstable;
  const auto un = static_cast<std::size_t>(n);

  const std::vector<Matrix2<quad>> step = cycleSteps(orbit_, unstable);
  coefficients_.assign(un, std::vector<Point<quad>>(static_cast<std::size_t>(order) + 1));
  for (int j = 0; j < n; ++j) coefficients_[static_cast<std::size_t>(j)][0] = orbit_.points[static_cast<std::size_t>(j)];
  stretch_ = carryLinearTerms(outwardTangent(orbit_, step, unstable), step, unstable, coefficients_);
  solveHigherOrders(step, stretch_, unstable, order, coefficients_);

  radius_.assign(un, 0);
  coefficientsLd_.assign(un, {});
  for (std::size_t j = 0; j < un; ++j) {
    const long double rho = seriesRadius(coefficients_[j], order);
    radius_[j] = rho;
    radiusLd_.push_back(rho);
    stretchLd_.push_back(static_cast<long double>(stretch_[j]));
    for (const Point<quad>& a : coefficients_[j])
      coefficientsLd_[j].push_back({static_cast<long double>(a.x), static_cast<long double>(a.y)});
  }
}

Point<quad> ManifoldParameterization::coefficient(int j, int k) const {
  if (k < 0 || k > order_) throw std::out_of_range("coefficient order " + std::to_string(k));
  return coefficients_[static_cast<std::size_t>(index(j))][static_cast<std::size_t>(k)];
}

quad ManifoldParameterization::domainFactor() const noexcept {
  return orbit_.multiplier > 0 ? orbit_.multiplier : orbit_.multiplier * orbit_.multiplier;
}

int ManifoldParameterization::stepsPerDomain() const noexcept {
  return orbit_.multiplier > 0 ? orbit_.period : 2 * orbit_.period;
}

long ManifoldParameterization::stepsTo(int j, long double sigma) const {
  const int n = orbit_.period;
  const bool unstable = kind_ == ManifoldKind::Unstable;
  int i = index(j);
  long double s = std::fabs(sigma);
  long m = 0;
  while (s > radiusLd_[static_cast<std::size_t>(i)] && m <= kMaxSteps) {
    i = unstable ? (i - 1 + n) % n : (i + 1) % n;
    s /= std::fabs(stretchLd_[static_cast<std::size_t>(i)]);
    ++m;
  }
  return m;
}

template <class Real>
Point<Real> ManifoldParameterization::point(int j, Real sigma, Point<Real>* tangent) const {
  const int n = orbit_.period;
  const bool unstable = kind_ == ManifoldKind::Unstable;
  int i = index(j);
  Real s = sigma;
  Real scale = 1;  // dσ_local/dσ
  long m = 0;
  while (smooth::absolute(s) > radiusAs<Real>(static_cast<std::size_t>(i))) {
    i = unstable ? (i - 1 + n) % n : (i + 1) % n;
    const Real mu = stretchAs<Real>(static_cast<std::size_t>(i));
    s /= mu;
    scale /= mu;
    if (++m > kMaxSteps) {
      const Real nan = std::numeric_limits<Real>::quiet_NaN();
      if (tangent) *tangent = {nan, nan};
      return {nan, nan};
    }
  }
  Point<Real> z{0, 0}, dz{0, 0};
  const auto ui = static_cast<std::size_t>(i);
  for (int k = order_; k >= 0; --k) {
    Real ax, ay;
    if constexpr (std::is_same_v<Real, quad>) {
      ax = coefficients_[ui][static_cast<std::size_t>(k)].x;
      ay = coefficients_[ui][static_cast<std::size_t>(k)].y;
    } else {
      ax = static_cast<Real>(coefficientsLd_[ui][static_cast<std::size_t>(k)].x);
      ay = static_cast<Real>(coefficientsLd_[ui][static_cast<std::size_t>(k)].y);
    }
    if (tangent && k >= 1) {
      dz.x = dz.x * s + Real(k) * ax;
      dz.y = dz.y * s + Real(k) * ay;
    }
    z.x = z.x * s + ax;
    z.y = z.y * s + ay;
  }
  if (tangent) dz = {dz.x * scale, dz.y * scale};  // Σ k a_k s^{k−1} · ds/dσ
  const Real K = static_cast<Real>(orbit_.K);
  for (long step = 0; step < m; ++step) {
    if (tangent) {
      const Real g1 = unstable ? 4 * z.x : 4 * (z.x - z.y);
      if (unstable) dz = {(1 + g1) * dz.x + dz.y, g1 * dz.x + dz.y};
      else dz = {dz.x - dz.y, -g1 * dz.x + (1 + g1) * dz.y};
    }
    z = unstable ? smooth::step(K, z) : smooth::inverseStep(K, z);
    if (escaped(z)) {
      const Real nan = std::numeric_limits<Real>::quiet_NaN();
      if (tangent) *tangent = {nan, nan};
      return {nan, nan};
    }
  }
  if (tangent) *tangent = dz;
  return z;
}

template <class Real>
Point<Real> ManifoldParameterization::localPoint(int j, Real sigma, long* steps) const {
  const int n = orbit_.period;
  const bool unstable = kind_ == ManifoldKind::Unstable;
  int i = index(j);
  Real s = sigma;
  long m = 0;
  while (smooth::absolute(s) > radiusAs<Real>(static_cast<std::size_t>(i))) {
    i = unstable ? (i - 1 + n) % n : (i + 1) % n;
    s /= stretchAs<Real>(static_cast<std::size_t>(i));
    if (++m > kMaxSteps) {
      *steps = -1;
      const Real nan = std::numeric_limits<Real>::quiet_NaN();
      return {nan, nan};
    }
  }
  Point<Real> z{0, 0};
  const auto ui = static_cast<std::size_t>(i);
  for (int k = order_; k >= 0; --k) {
    z.x = z.x * s + static_cast<Real>(coefficientsLd_[ui][static_cast<std::size_t>(k)].x);
    z.y = z.y * s + static_cast<Real>(coefficientsLd_[ui][static_cast<std::size_t>(k)].y);
  }
  *steps = m;
  return z;
}

template Point<long double> ManifoldParameterization::localPoint(int, long double, long*) const;
template Point<double> ManifoldParameterization::localPoint(int, double, long*) const;

template Point<double> ManifoldParameterization::point(int, double, Point<double>*) const;
template Point<long double> ManifoldParameterization::point(int, long double, Point<long double>*) const;
template Point<quad> ManifoldParameterization::point(int, quad, Point<quad>*) const;

std::optional<int> reversedIndex(const HyperbolicOrbit& orbit, Reversor r, int j) {
  const int n = orbit.period;
  const Point<quad>& target = orbit.points[static_cast<std::size_t>(((j % n) + n) % n)];
  for (int i = 0; i < n; ++i) {
    const Point<quad> image = reverse(r, quad(orbit.K), orbit.points[static_cast<std::size_t>(i)]);
    if (smooth::absolute(image.x - target.x) + smooth::absolute(image.y - target.y) <= quad(1e-20L)) return i;
  }
  return std::nullopt;
}

template <class Real>
Point<Real> reversedUnstable(const ManifoldParameterization& unstable, Reversor r, int j, Real sigma) {
  if (unstable.kind() != ManifoldKind::Unstable)
    throw std::invalid_argument("reversedUnstable() needs the unstable manifold");
  const std::optional<int> i = reversedIndex(unstable.orbit(), r, j);
  if (!i) throw std::invalid_argument("the reversor does not map the orbit onto itself");
  return reverse(r, static_cast<Real>(unstable.orbit().K), unstable.point(*i, sigma));
}

template Point<double> reversedUnstable(const ManifoldParameterization&, Reversor, int, double);
template Point<long double> reversedUnstable(const ManifoldParameterization&, Reversor, int, long double);
template Point<quad> reversedUnstable(const ManifoldParameterization&, Reversor, int, quad);

quad reversalScale(const ManifoldParameterization& unstable, const ManifoldParameterization& stable, Reversor r, int j) {
  if (unstable.kind() != ManifoldKind::Unstable || stable.kind() != ManifoldKind::Stable)
    throw std::invalid_argument("reversalScale() needs the unstable and the stable manifold");
  const std::optional<int> i = reversedIndex(unstable.orbit(), r, j);
  if (!i) throw std::invalid_argument("the reversor does not map the orbit onto itself");
  const Point<quad> z = unstable.coefficient(*i, 0), v = unstable.coefficient(*i, 1);
  // D I at z: I₁ = (x, −y − g(x)) → [[1, 0], [−4x, −1]]; I₂ = (x − y, −y) → [[1, −1], [0, −1]].
  const Point<quad> w = r == Reversor::I1 ? Point<quad>{v.x, -4 * z.x * v.x - v.y} : Point<quad>{v.x - v.y, -v.y};
  const Point<quad> s = stable.coefficient(j, 1);
  return w.x * s.x + w.y * s.y;
}

}  // namespace archipelago
