#include "core/manifolds/ManifoldCurve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/io/Memory.hpp"
#include "core/io/NumberText.hpp"  // shortText
#include "core/random/CounterRng.hpp"  // mix64, for the wrap signatures
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

using smooth::Point;

/// Intervals whose three points are all invalid (escaped) are looked into this many levels before being dropped.
constexpr int kInvalidLookahead = 3;
/// Coarse bounds away from the view.
constexpr long double kCoarseAngle = 0.5L;

struct Sample {
  long double t = 0;
  PhysicalPoint z;
  bool valid = false;
  std::uint64_t signature = 0;  ///< hash of the torus wraps taken (0 in the plane)
};

/// Wraps v into [lo, lo + L); returns the number of periods removed.
long wrap(long double& v, long double lo, long double L) {
  const long double k = std::floor((v - lo) / L);
  v -= k * L;
  return static_cast<long>(k);
}

class Evaluator {
 public:
  Evaluator(const ManifoldCurveRequest& r, const ManifoldParameterization& unstable,
            const ManifoldParameterization& stable)
      : request_(r), K_(r.K) {
    reversal_ = r.kind == ManifoldKind::Stable && r.stableFrom == StableConstruction::ReversingSymmetry;
    const ManifoldParameterization& own = r.kind == ManifoldKind::Unstable ? unstable : stable;
    source_ = reversal_ ? &unstable : &own;
    sourcePoint_ = r.point;
    if (reversal_) {
      for (Reversor candidate : {Reversor::I2, Reversor::I1})
        if (const std::optional<int> i = reversedIndex(unstable.orbit(), candidate, r.point)) {
          reversor_ = candidate;
          sourcePoint_ = *i;
          break;
        }
      if (sourcePoint_ < 0 || !reversedIndex(unstable.orbit(), reversor_, r.point))
        throw std::invalid_argument("the reversing symmetries do not map this orbit onto itself: draw its stable "
                                    "manifold from the inverse map");
      scale_ = static_cast<long double>(reversalScale(unstable, stable, reversor_, r.point));
    }
    sign_ = static_cast<long double>(static_cast<int>(r.side));
    factor_ = static_cast<long double>(own.domainFactor());
    logFactor_ = std::log(factor_);
    sigma0_ = static_cast<long double>(own.radius(r.point)) / factor_;
    if (reversal_) sigma0_ = std::min(sigma0_, std::fabs(scale_) * static_cast<long double>(unstable.radius(sourcePoint_)) / factor_);
  }

  [[nodiscard]] long double sigma(long double t) const {
    return sign_ * sigma0_ * (t <= 0 ? 1 + t : std::exp(t * logFactor_));
  }

  [[nodiscard]] Sample operator()(long double t) const {
    Sample s;
    s.t = t;
    long double parameter = sigma(t);
    if (reversal_) parameter /= scale_;  // Ψ_j(cσ) = I(Φ_i(σ))
    Point<long double> z;
    if (request_.box) {
      long steps = 0;
      z = source_->localPoint(sourcePoint_, parameter, &steps);
      if (steps < 0) return s;
      const bool forward = source_->kind() == ManifoldKind::Unstable;
      std::uint64_t h = 0;
      for (long i = 0; i < steps; ++i) {
        z = forward ? smooth::step(K_, z) : smooth::inverseStep(K_, z);
        if (!std::isfinite(z.x) || !std::isfinite(z.y)) return s;
        const long kx = wrap(z.x, xmin_(), L_()), ky = wrap(z.y, -L_() / 2, L_());
        if (kx != 0 || ky != 0)
          h = mix64(h ^ (static_cast<std::uint64_t>(i) << 20) ^ (static_cast<std::uint64_t>(kx + 512) << 10) ^
                    static_cast<std::uint64_t>(ky + 512));
      }
      if (reversal_) {
        z = reverse(reversor_, K_, z);
        const long kx = wrap(z.x, xmin_(), L_()), ky = wrap(z.y, -L_() / 2, L_());
        h = mix64(h ^ 0xABCDULL ^ (static_cast<std::uint64_t>(kx + 512) << 10) ^ static_cast<std::uint64_t>(ky + 512));
      }
      s.signature = h;
    } else {
      z = source_->point(sourcePoint_, parameter);
      if (reversal_) z = reverse(reversor_, K_, z);
      if (!std::isfinite(z.x) || !std::isfinite(z.y) || std::hypot(z.x, z.y) > request_.escapeRadius) return s;
    }
    s.z = {z.x, z.y};
    s.valid = true;
    return s;
  }

 private:
  [[nodiscard]] long double xmin_() const { return static_cast<long double>(request_.box->xmin); }
  [[nodiscard]] long double L_() const { return static_cast<long double>(request_.box->width()); }

  const ManifoldCurveRequest& request_;
  long double K_;
  const ManifoldParameterization* source_ = nullptr;
  int sourcePoint_ = -1;
  bool reversal_ = false;
  Reversor reversor_ = Reversor::I2;
  long double scale_ = 1;
  long double sign_ = 1;
  long double factor_ = 2;
  long double logFactor_ = 1;
  long double sigma0_ = 1;
};

struct Full {};  // thrown inside the refinement when maxPoints is reached

class Builder {
 public:
  Builder(const ManifoldCurveRequest& r, const Evaluator& evaluate, std::stop_token stop)
      : request_(r), evaluate_(evaluate), stop_(stop) {}

  void emit(const Sample& s) {
    if (!s.valid) return;
    if (!open_.points.empty()) length_ += std::hypot(s.z.x - open_.points.back().x, s.z.y - open_.points.back().y);
    open_.points.push_back(s.z);
    open_.arcLength.push_back(length_);
    open_.parameter.push_back(s.t);
    ++curve.points;
    broken_ = false;
    checkBudget();
  }

  void cut() {
    if (open_.points.size() >= 2) curve.pieces.push_back(std::move(open_));
    else if (!open_.points.empty()) curve.points -= open_.points.size();
    if (!broken_) ++curve.breaks;
    open_ = {};
    broken_ = true;
  }

  void close() {
    if (open_.points.size() >= 2) curve.pieces.push_back(std::move(open_));
    else curve.points -= open_.points.size();
    open_ = {};
  }

  /// Emits the points after a up to and including b (a was emitted, or cut).
  void refine(const Sample& a, const Sample& b, int invalidDepth) {
    if (stop_.stop_requested()) throw std::runtime_error("stopped");
    const long double resolution =
        64 * std::numeric_limits<long double>::epsilon() * std::max({1.0L, std::fabs(a.t), std::fabs(b.t)});
    const bool continuous = a.valid && b.valid && a.signature == b.signature;
    if (b.t - a.t <= resolution) {
      // Still too coarse at the resolution of t (the branch runs off to infinity here, or rounding dominates), or
      // discontinuous: cut rather than draw a chord that is not the curve.
      if (continuous) {
        ++curve.unresolved;
        checkBudget();  // a region unresolved all through emits nothing: without this it split for hours (issue 36)
      }
      cut();
      emit(b);
      return;
    }
    const Sample m = evaluate_((a.t + b.t) / 2);
    if (continuous && m.valid && m.signature == a.signature) {
      if (acceptable(a, m, b)) {
        emit(m);
        emit(b);
      } else {
        refine(a, m, 0);
        refine(m, b, 0);
      }
      return;
    }
    if (!a.valid && !b.valid && !m.valid) {
      if (invalidDepth >= kInvalidLookahead) return;  // escaped all through, as far as we look
      refine(a, m, invalidDepth + 1);
      refine(m, b, invalidDepth + 1);
      return;
    }
    refine(a, m, 0);
    refine(m, b, 0);
  }

  [[nodiscard]] long double length() const noexcept { return length_; }

  ManifoldCurve curve;

 private:
  void checkBudget() const {
    if (curve.points + curve.unresolved >= request_.maxPoints) throw Full{};
  }

  [[nodiscard]] bool acceptable(const Sample& a, const Sample& m, const Sample& b) const {
    long double spacing = request_.maxSpacing, angle = request_.maxAngle;
    if (request_.view) {
      const PhysicalRect& v = *request_.view;
      const long double margin = request_.maxSpacing;
      const long double x0 = std::min({a.z.x, m.z.x, b.z.x}) - margin, x1 = std::max({a.z.x, m.z.x, b.z.x}) + margin;
      const long double y0 = std::min({a.z.y, m.z.y, b.z.y}) - margin, y1 = std::max({a.z.y, m.z.y, b.z.y}) + margin;
      if (x1 < v.x0 || x0 > v.x1 || y1 < v.y0 || y0 > v.y1) {
        spacing = std::max(v.x1 - v.x0, v.y1 - v.y0);
        angle = kCoarseAngle;
      }
    }
    if (std::hypot(b.z.x - a.z.x, b.z.y - a.z.y) > spacing) return false;
    const long double ux = m.z.x - a.z.x, uy = m.z.y - a.z.y, vx = b.z.x - m.z.x, vy = b.z.y - m.z.y;
    const long double turn = std::fabs(std::atan2(ux * vy - uy * vx, ux * vx + uy * vy));
    return !(turn > angle);
  }

  const ManifoldCurveRequest& request_;
  const Evaluator& evaluate_;
  std::stop_token stop_;
  ManifoldPiece open_;
  long double length_ = 0;
  bool broken_ = false;
};

}  // namespace

std::optional<std::string> validationError(const ManifoldCurveRequest& r) {
  if (auto e = manifoldKError(r.K)) return e;
  if (r.orbit && r.orbit->K != r.K)
    return "the orbit's K = " + shortestDecimal(static_cast<double>(r.orbit->K)) + " differs from K = " +
           shortestDecimal(static_cast<double>(r.K));
  const int period = r.orbit ? r.orbit->period : 1;
  if (auto e = orbitPointError(r.point, period)) return e;
  if (auto e = realIntervalError("length", static_cast<double>(r.length), 0, true, 1e6, "physical units")) return e;
  if (auto e = rangeError("domains", r.maxDomains, 1, 10000)) return e;
  if (auto e = realRangeError("spacing", static_cast<double>(r.maxSpacing), static_cast<double>(kMinManifoldSpacing), 1))
    return e;
  if (auto e = realIntervalError("angle", static_cast<double>(r.maxAngle), 0, true, 1, "radians")) return e;
  if (auto e = rangeError("initial points per domain", r.initialPoints, 2, 1000000)) return e;
  if (auto e = realRangeError("escape radius", static_cast<double>(r.escapeRadius), 0.1, 1e6)) return e;
  if (auto e = rangeError("maximum points", r.maxPoints, 16, 100'000'000)) return e;
  if (r.view) {
    const PhysicalRect& v = *r.view;
    if (!std::isfinite(v.x0) || !std::isfinite(v.x1) || !std::isfinite(v.y0) || !std::isfinite(v.y1) || !(v.x0 < v.x1) ||
        !(v.y0 < v.y1))
      return "the view must have finite bounds x0 < x1, y0 < y1";
  }
  if (r.box) {
    if (auto e = validationError(*r.box)) return e;
  }
  return std::nullopt;
}

void checkManifoldMemory(const ManifoldCurveRequest& r) {
  io::checkMemory(r.maxPoints * kManifoldBytesPerPoint,
                  "a manifold branch of up to " + std::to_string(r.maxPoints) + " points (maximum points)");
}

ManifoldCurve computeManifoldCurve(const ManifoldCurveRequest& request, const ManifoldProgressCallback& progress,
                                   std::stop_token stop) {
  if (auto e = validationError(request)) throw std::invalid_argument(*e);
  checkManifoldMemory(request);
  const HyperbolicOrbit orbit = request.orbit ? hyperbolicOrbitOf(*request.orbit) : hyperbolicFixedPoint(request.K);
  const ManifoldParameterization unstable(orbit, ManifoldKind::Unstable);
  const ManifoldParameterization stable(orbit, ManifoldKind::Stable);
  const Point<quad>& z0 = orbit.points[static_cast<std::size_t>(request.point)];
  const PhysicalPoint origin{static_cast<long double>(z0.x), static_cast<long double>(z0.y)};
  if (request.box) {
    const MapParameters& b = *request.box;
    const long double L = b.width();
    if (!(origin.x >= b.xmin && origin.x < b.xmax && origin.y >= -L / 2 && origin.y < L / 2))
      throw std::invalid_argument("the orbit point (" + shortestDecimal(static_cast<double>(origin.x)) + ", " +
                                  shortestDecimal(static_cast<double>(origin.y)) +
                                  ") lies outside the box, where Q* differs from Q");
  }
  const Evaluator evaluate(request, unstable, stable);
  Builder builder(request, evaluate, stop);
  builder.curve.origin = origin;
  const int n = request.initialPoints;
  try {
    Sample previous = evaluate(-1);  // σ = 0: the orbit point itself
    builder.emit(previous);
    for (int d = -1; d < request.maxDomains; ++d) {  // d = −1: the local arc; d ≥ 0: the fundamental domains
      bool anyValid = false;
      for (int k = 1; k <= n; ++k) {
        const Sample next = evaluate(d + static_cast<long double>(k) / n);
        anyValid = anyValid || next.valid;
        builder.refine(previous, next, 0);
        previous = next;
      }
      builder.curve.domains = d + 1;
      if (progress) progress({static_cast<double>(d + 2) / (request.maxDomains + 1), "domain " + std::to_string(d + 1)});
      if (builder.length() >= request.length) {
        builder.curve.stoppedBy = "length";
        break;
      }
      if (!anyValid && d >= 0) {
        builder.curve.stoppedBy = "escaped";
        break;
      }
    }
    if (builder.curve.stoppedBy.empty()) builder.curve.stoppedBy = "domains";
  } catch (const Full&) {
    builder.curve.stoppedBy = "points";
  }
  builder.close();
  ManifoldCurve curve = std::move(builder.curve);
  // Truncate at the requested length.
  for (std::size_t i = 0; i < curve.pieces.size(); ++i) {
    ManifoldPiece& p = curve.pieces[i];
    const auto beyond = std::find_if(p.arcLength.begin(), p.arcLength.end(), [&](long double s) { return s >= request.length; });
    if (beyond == p.arcLength.end()) continue;
    const auto keep = static_cast<std::size_t>(beyond - p.arcLength.begin()) + 1;
    p.points.resize(keep);
    p.arcLength.resize(keep);
    p.parameter.resize(keep);
    curve.pieces.resize(i + 1);
    break;
  }
  curve.points = 0;
  curve.length = 0;
  for (const ManifoldPiece& p : curve.pieces) {
    curve.points += p.points.size();
    curve.length = std::max(curve.length, p.arcLength.back());
  }
  return curve;
}

const char* toString(StableConstruction c) noexcept {
  return c == StableConstruction::ReversingSymmetry ? "symmetry" : "inverse";
}

StableConstruction parseStableConstruction(const std::string& text, const std::string& option) {
  for (const StableConstruction c : {StableConstruction::InverseMap, StableConstruction::ReversingSymmetry})
    if (text == toString(c)) return c;
  throw std::invalid_argument(option + " '" + io::shortText(text) + "' must be inverse or symmetry");
}

}  // namespace archipelago
