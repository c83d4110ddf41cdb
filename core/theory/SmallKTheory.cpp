#include "core/theory/SmallKTheory.hpp"

// Notation (Karney 1983, §4):
//   X0      the trajectory's intercept with Y = 0, in scaled units (x = X0 √|K|)
//   T(X0)   its trapping time, eq. (tneg); T' = dT/dX0
//   r       √(X0² + 1)
//   m       the parameter (k²) of the complete elliptic integrals K(m), E(m); m = (1 − β)/2, β = (√3/2) X0/r
//   A       the K = 0 constant Γ(1/3)√π/Γ(5/6) (the paper's 4.207)
//   F(T)    segment density, eq. (fneg);  C(Θ) its second integral (the correlation function up to a constant)

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/io/NumberText.hpp"

namespace archipelago::smallk {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct CompleteElliptic {
  long double K;
  long double E;
};

// K(m) and E(m) by the arithmetic–geometric mean (Abramowitz & Stegun 17.6): K = π/(2 a_N),
// E = K (1 − Σ_{n≥0} 2^(n−1) c_n²).  Convergence is quadratic; here m ∈ (0.067, 0.933) always, so a_n > 0.25
// and five or six steps reach long double precision.
CompleteElliptic completeElliptic(long double m) {
  long double a = 1;
  long double b = std::sqrt(1 - m);
  long double c = std::sqrt(m);
  long double weight = 0.5L;
  long double sum = weight * c * c;
  for (int n = 0; n < 40 && c > std::numeric_limits<long double>::epsilon() * a; ++n) {
    c = (a - b) / 2;
    const long double mean = (a + b) / 2;
    b = std::sqrt(a * b);
    a = mean;
    weight *= 2;
    sum += weight * c * c;
  }
  const long double K = std::numbers::pi_v<long double> / (2 * a);
  return {K, K * (1 - sum)};
}

// 2·3^(1/4): T(X0) = kTimeScale K(m) / √r.
const long double kTimeScale = 2 * std::sqrt(std::sqrt(3.0L));
constexpr long double kSqrt3 = std::numbers::sqrt3_v<long double>;

// A root of a function that is monotonic on [lo, hi] (increasing when `increasing`), value(lo) and
// value(hi) of opposite signs (or zero): Newton steps, replaced by bisection when they leave the bracket.
template <class Value, class Slope>
double monotonicRoot(Value value, Slope slope, double lo, double hi, double guess, bool increasing) {
  double x = std::clamp(guess, lo, hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    const double f = value(x);
    if (f == 0) return x;
    if ((f < 0) == increasing) lo = x; else hi = x;
    const double d = slope(x);
    double next = d != 0 ? x - f / d : kNaN;
    if (!(next > lo && next < hi)) next = lo + (hi - lo) / 2;
    const double step = std::abs(next - x);
    x = next;
    if (step <= 2 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(x))) break;
    if (!(lo < x && x < hi)) break;  // the bracket has shrunk to adjacent doubles
  }
  return x;
}

// Gauss–Legendre nodes and weights on [−1, 1] (Newton on P_n from the Chebyshev guesses).
struct GaussLegendre {
  static constexpr int kOrder = 20;
  std::array<double, kOrder> node{};
  std::array<double, kOrder> weight{};
  GaussLegendre() {
    for (int i = 0; i < kOrder; ++i) {
      long double x = std::cos(std::numbers::pi_v<long double> * (i + 0.75L) / (kOrder + 0.5L));
      long double derivative = 0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        long double p0 = 1, p1 = x;
        for (int k = 2; k <= kOrder; ++k) {
          const long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        derivative = kOrder * (x * p1 - p0) / (x * x - 1);
        const long double dx = p1 / derivative;
        x -= dx;
        if (std::abs(dx) <= 4 * std::numeric_limits<long double>::epsilon()) break;
      }
      node[i] = static_cast<double>(x);
      weight[i] = static_cast<double>(2 / ((1 - x * x) * derivative * derivative));
    }
  }
};

TrappingTimeMaximum computeMaximum() {
  // T' > 0 at X0 = −2 and < 0 at X0 = 0 (T rises from 0 at −∞ and falls to 0 at +∞); bisect T' to the last
  // bit — T' is cheap and its sign is reliable well below the root's ulp scale.
  double lo = -2, hi = 0;
  while (true) {
    const double mid = lo + (hi - lo) / 2;
    if (!(mid > lo && mid < hi)) break;
    if (negativeKTrappingTimeDerivative(mid) > 0) lo = mid; else hi = mid;
  }
  const double x = lo + (hi - lo) / 2;
  // T'' by Richardson extrapolation of central differences of T' (truncation O(h⁴) ~ 1e-13, rounding ~ ε/h).
  const double h = 1.0 / 1024;
  auto central = [x](double step) {
    return (negativeKTrappingTimeDerivative(x + step) - negativeKTrappingTimeDerivative(x - step)) / (2 * step);
  };
  const double curvature = (4 * central(h) - central(2 * h)) / 3;
  return {x, negativeKTrappingTime(x), curvature};
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// K < 0

double negativeKTrappingTime(double X0) noexcept {
  if (!std::isfinite(X0)) return kNaN;
  const long double x = X0;
  const long double r = std::sqrt(x * x + 1);
  const long double m = (1 - kSqrt3 / 2 * (x / r)) / 2;
  return static_cast<double>(kTimeScale * completeElliptic(m).K / std::sqrt(r));
}

double negativeKTrappingTimeDerivative(double X0) noexcept {
  if (!std::isfinite(X0)) return kNaN;
  const long double x = X0;
  const long double r2 = x * x + 1;
  const long double r = std::sqrt(r2);
  const long double m = (1 - kSqrt3 / 2 * (x / r)) / 2;
  const auto [K, E] = completeElliptic(m);
  const long double dKdm = (E - (1 - m) * K) / (2 * m * (1 - m));
  const long double dmdx = -kSqrt3 / (4 * r2 * r);  // dβ/dX0 = (√3/2)/r³
  // T = c K(m) r^(−1/2):  T' = c r^(−1/2) (K'(m) m' − K X0 / (2 r²)).
  return static_cast<double>(kTimeScale / std::sqrt(r) * (dKdm * dmdx - K * x / (2 * r2)));
}

const TrappingTimeMaximum& negativeKMaximum() {
  static const TrappingTimeMaximum maximum = computeMaximum();
  return maximum;
}

TrappingTimeBranches negativeKInverse(double T) {
  const TrappingTimeMaximum& top = negativeKMaximum();
  if (!(T > 0 && T <= top.T)) return {kNaN, kNaN};
  if (T == top.T) return {top.X0, top.X0};
  auto value = [T](double x) { return negativeKTrappingTime(x) - T; };
  auto slope = [](double x) { return negativeKTrappingTimeDerivative(x); };
  // First guesses: the K = 0 laws far from the maximum, the parabola T ≈ Tmax + ½T''δ² near it.
  const double A = zeroKTimeConstant();
  const double parabola = std::sqrt(2 * (top.T - T) / -top.curvature);
  const bool nearTop = top.T - T < 0.1;
  const double leftGuess = nearTop ? top.X0 - parabola : -3 * (A / T) * (A / T);
  const double rightGuess = nearTop ? top.X0 + parabola : (A / T) * (A / T);

  double leftEnd = std::min(leftGuess, top.X0 - 1);
  while (negativeKTrappingTime(leftEnd) > T) leftEnd = top.X0 - 2 * (top.X0 - leftEnd);
  double rightEnd = std::max(rightGuess, top.X0 + 1);
  while (negativeKTrappingTime(rightEnd) > T) rightEnd = top.X0 + 2 * (rightEnd - top.X0);

  return {monotonicRoot(value, slope, leftEnd, top.X0, leftGuess, true),
          monotonicRoot(value, slope, top.X0, rightEnd, rightGuess, false)};
}

double negativeKSegmentDensity(double T) {
  if (!(T > 0)) return kNaN;
  const TrappingTimeMaximum& top = negativeKMaximum();
  if (T > top.T) return 0;
  if (T == top.T) return kInf;
  // Within 1e-9 of Tmax the inversion loses more (~ε Tmax/(Tmax − T)) than the cutoff law's O(Tmax − T)
  // relative error, so use the law.
  if (top.T - T < 1e-9) return negativeKCutoffCoefficient() / std::sqrt(top.T - T);
  const auto [left, right] = negativeKInverse(T);
  auto term = [](double x) { return 2 * (x * x + 1) / std::abs(negativeKTrappingTimeDerivative(x)); };
  return term(left) + term(right);
}

double negativeKSmallTCoefficient() {
  const double A = zeroKTimeConstant();
  return 112 * std::pow(A, 6);
}

double negativeKCutoffCoefficient() {
  const TrappingTimeMaximum& top = negativeKMaximum();
  return 2 * std::numbers::sqrt2 * (top.X0 * top.X0 + 1) / std::sqrt(-top.curvature);
}

double negativeKCorrelation(double Theta) {
  if (!(Theta > 0)) return kNaN;
  const TrappingTimeMaximum& top = negativeKMaximum();
  if (Theta >= top.T) return 0;
  static const GaussLegendre rule;
  const auto [left, right] = negativeKInverse(Theta);
  // X0 = sinh w keeps T's branch points X0 = ±i at a fixed distance (w = ±iπ/2) from the real axis however
  // far the range reaches, so panels of width ≤ 0.5 in w converge geometrically.  dX0 = cosh w dw and
  // X0² + 1 = cosh² w.
  const double wLeft = std::asinh(left), wRight = std::asinh(right);
  const int panels = std::max(1, static_cast<int>(std::ceil((wRight - wLeft) / 0.5)));
  const double width = (wRight - wLeft) / panels;
  long double sum = 0;
  for (int p = 0; p < panels; ++p) {
    const double centre = wLeft + (p + 0.5) * width;
    for (int i = 0; i < GaussLegendre::kOrder; ++i) {
      const double w = centre + 0.5 * width * rule.node[i];
      const double c = std::cosh(w);
      sum += rule.weight[i] * (negativeKTrappingTime(std::sinh(w)) - Theta) * 2 * c * c * c;
    }
  }
  return static_cast<double>(sum) * 0.5 * width;
}

double negativeKMaximumTime(double K) noexcept {
  if (!(K < 0)) return kNaN;
  return negativeKMaximum().T / std::sqrt(std::sqrt(-K));
}

double negativeKMaximumTimeInBox(double K, double xmin, double xmax) {
  if (!(K < 0) || !(xmin < 0 && xmax > 0) || !std::isfinite(xmin) || !std::isfinite(xmax)) return kNaN;
  const double eps = std::sqrt(std::sqrt(-K));
  const double Xb = xmax / (eps * eps), Yb = (xmax - xmin) / 2 / (eps * eps * eps), X0min = xmin / (eps * eps);
  // The time inside the box of the trajectory through (X0, 0).
  const auto inside = [&](double X0) {
    if (!(X0 < Xb)) return 0.0;
    // X_e: where the trajectory leaves, the first of X = Xb and |Y| = Yb (Y grows with X for X > X0).
    const auto Y = [X0](double X) { return 2 * std::sqrt(std::max(0.0, (X * X * X - X0 * X0 * X0) / 3 + X - X0)); };
    double Xe = Xb;
    if (Y(Xb) > Yb) {
      double lo = X0, hi = Xb;
      for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (Y(mid) > Yb ? hi : lo) = mid;
      }
      Xe = lo;
    }
    // ∫_0^U 2 du / √(⅓(X² + X X0 + X0²) + 1), X = X0 + u² (both branches: 2 × dX/Y): 8-point Gauss–Legendre on
    // 200 panels.
    static constexpr double node[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static constexpr double weight[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    const double U = std::sqrt(Xe - X0);
    constexpr int panels = 200;
    double sum = 0;
    for (int p = 0; p < panels; ++p) {
      const double a = U * p / panels, b = U * (p + 1) / panels, m = 0.5 * (a + b), r = 0.5 * (b - a);
      for (int k = 0; k < 4; ++k)
        for (const double sign : {-1.0, 1.0}) {
          const double u = m + sign * r * node[k], X = X0 + u * u;
          sum += weight[k] * r * 2 / std::sqrt((X * X + X * X0 + X0 * X0) / 3 + 1);
        }
    }
    return sum;
  };
  // The maximum lies near X0 = −0.5536 for a large box; a golden-section search over [max(xmin/ε², −5), 5].
  double lo = std::max(X0min, -5.0), hi = std::min(Xb, 5.0);
  const double g = (std::sqrt(5.0) - 1) / 2;
  double a = hi - g * (hi - lo), b = lo + g * (hi - lo), fa = inside(a), fb = inside(b);
  for (int i = 0; i < 100; ++i) {
    if (fa < fb) {
      lo = a, a = b, fa = fb, b = lo + g * (hi - lo), fb = inside(b);
    } else {
      hi = b, b = a, fb = fa, a = hi - g * (hi - lo), fa = inside(a);
    }
  }
  return std::max(fa, fb) / eps;
}

double negativeKMaximumPosition(double K) noexcept {
  if (!(K < 0)) return kNaN;
  return negativeKMaximum().X0 * std::sqrt(-K);
}

double negativeKSegmentShape(double t, double K) {
  if (!(K < 0 && t > 0)) return kNaN;
  return negativeKSegmentDensity(std::sqrt(std::sqrt(-K)) * t);
}

double negativeKCorrelationShape(double tau, double K) {
  if (!(K < 0 && tau > 0)) return kNaN;
  return negativeKCorrelation(std::sqrt(std::sqrt(-K)) * tau);
}

// ---------------------------------------------------------------------------------------------------------
// K = 0

double zeroKTimeConstant() noexcept {
  static const double A = static_cast<double>(std::tgamma(1.0L / 3) * std::sqrt(std::numbers::pi_v<long double>) /
                                              std::tgamma(5.0L / 6));
  return A;
}

double zeroKTrappingTime(double X0) noexcept {
  if (std::isnan(X0)) return kNaN;
  if (X0 == 0) return kInf;
  const double A = zeroKTimeConstant();
  return (X0 > 0 ? A : std::numbers::sqrt3 * A) / std::sqrt(std::abs(X0));
}

double zeroKSegmentShape(double t) noexcept {
  if (!(t > 0)) return kNaN;
  return std::pow(t, -7);
}

double zeroKCorrelationShape(double tau) noexcept {
  if (!(tau > 0)) return kNaN;
  return std::pow(tau, -5);
}

// ---------------------------------------------------------------------------------------------------------
// K > 0

double positiveKLyapunovNumber(double K) noexcept {
  if (!(K >= 0)) return kNaN;
  const double rootK = std::sqrt(K);
  return 1 + 2 * rootK + 2 * std::sqrt(rootK + K);
}

double positiveKDecayRate(double K) noexcept {
  if (!(K >= 0)) return kNaN;
  const double rootK = std::sqrt(K);
  return 0.5 * std::log1p(2 * rootK + 2 * std::sqrt(rootK + K));
}

double positiveKSegmentShape(double t, double K) noexcept {
  if (!(K > 0) || std::isnan(t)) return kNaN;
  return std::exp(-positiveKDecayRate(K) * t);
}

// ---------------------------------------------------------------------------------------------------------
// Any small K

double segmentShape(double t, double K) {
  if (K < 0) return negativeKSegmentShape(t, K);
  if (K == 0) return zeroKSegmentShape(t);
  return positiveKSegmentShape(t, K);
}

double correlationShape(double tau, double K) {
  if (K < 0) return negativeKCorrelationShape(tau, K);
  if (K == 0) return zeroKCorrelationShape(tau);
  return positiveKSegmentShape(tau, K);  // §4: "C_τ behaves in the same way"
}

AmplitudeFit fitAmplitude(std::span<const double> t, std::span<const double> f, double tLow, double tHigh,
                          const std::function<double(double)>& shape) {
  if (t.size() != f.size()) throw std::invalid_argument("fitAmplitude: t and f differ in size");
  std::vector<double> logRatio;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!(t[i] >= tLow && t[i] <= tHigh && f[i] > 0 && std::isfinite(f[i]))) continue;
    const double s = shape(t[i]);
    if (!(s > 0 && std::isfinite(s))) continue;
    logRatio.push_back(std::log(f[i] / s));
  }
  AmplitudeFit fit;
  if (logRatio.empty()) return fit;
  double mean = 0;
  for (double v : logRatio) mean += v;
  mean /= static_cast<double>(logRatio.size());
  double squares = 0;
  for (double v : logRatio) squares += (v - mean) * (v - mean);
  fit.amplitude = std::exp(mean);
  fit.points = logRatio.size();
  fit.rmsLogResidual = std::sqrt(squares / static_cast<double>(logRatio.size()));
  return fit;
}

std::optional<std::string> shapeArgumentError(double t, double K) {
  if (!(std::isfinite(t) && t >= 0)) return "t = " + io::shortestText(t) + " must be a finite time >= 0 (steps)";
  if (!std::isfinite(K)) return "K = " + io::shortestText(K) + " must be a finite number";
  return std::nullopt;
}

}  // namespace archipelago::smallk
