#include "core/manifolds/MmpFlux.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/io/NumberText.hpp"
#include "core/manifolds/GeneratingFunction.hpp"
#include "core/manifolds/HyperbolicOrbit.hpp"
#include "core/manifolds/ManifoldParameterization.hpp"  // reverse(), Reversor
#include "core/manifolds/QuadText.hpp"
#include "core/limits/Limits.hpp"

namespace archipelago {

namespace {

using smooth::SymmetryLine;
using QPoint = smooth::Point<quad>;

std::string number(long double v) { return io::formatC("%.10Lg", v); }

/// 2⁻¹¹², the unit roundoff of __float128.
const quad kQuadEpsilon = quad(1) / (quad(1ULL << 56) * quad(1ULL << 56));

/// The index of the orbit's point nearest to `line` (the finder's root lies on it to rounding).
std::size_t pointOnLine(const PeriodicOrbit& orbit, SymmetryLine line) {
  std::size_t best = 0;
  long double bestOffset = -1;
  for (std::size_t k = 0; k < orbit.points.size(); ++k) {
    const smooth::Point<long double> z{orbit.points[k].x, orbit.points[k].y};
    const long double offset = std::fabs(smooth::offsetFromLine(line, orbit.K, z));
    if (bestOffset < 0 || offset < bestOffset) {
      bestOffset = offset;
      best = k;
    }
  }
  return best;
}

/// The orbit in __float128 (MmpFlux.hpp, method 2) and its action (method 3).
BirkhoffOrbit inQuad(const PeriodicOrbit& found) {
  BirkhoffOrbit out;
  out.line = found.symmetry == OrbitSymmetry::LineS1 ? SymmetryLine::S1 : SymmetryLine::S2;
  const std::size_t onLine = pointOnLine(found, out.line);
  out.orbit = found.rotatedToStart(onLine);
  const int q = found.period;
  const quad k = found.K;
  const quad s = polishSymmetricPoint(found.K, q, out.line, quad(out.orbit.points.front().x), quad(1e-9L));
  const Reversor reversor = out.line == SymmetryLine::S1 ? Reversor::I1 : Reversor::I2;
  const int half = (q + 1) / 2;
  std::vector<QPoint> forward(static_cast<std::size_t>(half) + 1);
  forward[0] = smooth::onLine(out.line, k, s);
  for (int i = 1; i <= half; ++i) forward[static_cast<std::size_t>(i)] = smooth::step(k, forward[static_cast<std::size_t>(i - 1)]);
  out.points.resize(static_cast<std::size_t>(q));
  for (int i = 0; i < q; ++i)
    out.points[static_cast<std::size_t>(i)] =
        2 * i <= q ? forward[static_cast<std::size_t>(i)] : reverse(reversor, k, forward[static_cast<std::size_t>(q - i)]);
  const QPoint reversed = reverse(reversor, k, forward[static_cast<std::size_t>(q - half)]);
  const QPoint direct = forward[static_cast<std::size_t>(half)];
  const quad dx = direct.x - reversed.x, dy = direct.y - reversed.y;
  out.mismatch = smooth::squareRoot(dx * dx + dy * dy);
  quad sum = 0, magnitude = 0;
  for (int i = 0; i < q; ++i) {
    const quad term = generatingFunction(k, out.points[static_cast<std::size_t>(i)].x,
                                         out.points[static_cast<std::size_t>((i + 1) % q)].x);
    sum += term;
    magnitude += smooth::absolute(term);
  }
  out.action = sum;
  out.actionError = 4 * kQuadEpsilon * magnitude;
  return out;
}

}  // namespace

std::optional<std::string> validationError(const MmpRequest& r) {
  if (auto e = manifoldKError(r.K)) return e;
  if (auto e = rangeError("stride", r.stride, 1, PeriodicOrbitSearch::kMaxPeriod / 2)) return e;
  if (auto e = rangeError("q", r.q, 2, PeriodicOrbitSearch::kMaxPeriod / r.stride,
                          "the period stride·q at most " + std::to_string(PeriodicOrbitSearch::kMaxPeriod)))
    return e;
  if (r.stride > 1 && (r.windows.empty() || !std::isfinite(r.about.x) || !std::isfinite(r.about.y)))
    return std::string("about an island (stride > 1) the windows of the lines and a finite island centre are needed");
  if (!r.members.empty() && r.members.size() != static_cast<std::size_t>(r.stride))
    return "the chain's members must be stride = " + std::to_string(r.stride) + " points, not " +
           std::to_string(r.members.size());
  if (auto e = rangeError("p", r.p, 1, static_cast<long long>(r.q) - 1, "q − 1 at most, q = " + std::to_string(r.q)))
    return e;
  if (std::gcd(r.p, static_cast<long>(r.q)) != 1)
    return "p/q = " + std::to_string(r.p) + "/" + std::to_string(r.q) + " must be in lowest terms";
  if (!std::isfinite(r.innerRadius) || !std::isfinite(r.outerRadius) || !(r.innerRadius > 0) ||
      !(r.innerRadius < r.outerRadius))
    return "the radii " + number(r.innerRadius) + " and " + number(r.outerRadius) + " must satisfy 0 < inner < outer";
  if (!(r.spacing > 0) || !std::isfinite(r.spacing)) return "spacing = " + number(r.spacing) + " must be a positive number";
  if (r.outerRadius > kMaxMmpRadius)
    return "outer radius = " + number(r.outerRadius) + " must be at most " + number(kMaxMmpRadius) +
           " (orbits beyond escape)";
  if ((r.outerRadius - r.innerRadius) / r.spacing > kMaxMmpSamples)
    return "the scan of " + number(r.outerRadius - r.innerRadius) + " at spacing " + number(r.spacing) +
           " would take more than " + number(kMaxMmpSamples) + " samples per window";
  for (const LineWindow& w : r.windows) {
    if (!std::isfinite(w.lo) || !std::isfinite(w.hi) || !(w.lo < w.hi) || (w.hi - w.lo) / r.spacing > kMaxMmpSamples)
      return "a window [" + number(w.lo) + ", " + number(w.hi) + "] must have finite ends, lo < hi, and at most " +
             number(kMaxMmpSamples) + " samples at spacing " + number(r.spacing);
  }
  return std::nullopt;
}

std::vector<PhysicalPoint> stridedAbout(std::span<const PhysicalPoint> points, int stride, PhysicalPoint about) {
  const std::size_t n = static_cast<std::size_t>(std::max(stride, 1));
  std::size_t start = 0;
  long double nearest = -1;
  for (std::size_t j = 0; j < std::min(n, points.size()); ++j) {
    const long double d = std::hypot(points[j].x - about.x, points[j].y - about.y);
    if (nearest < 0 || d < nearest) nearest = d, start = j;
  }
  std::vector<PhysicalPoint> out;
  for (std::size_t k = start; k < points.size(); k += n) out.push_back(points[k]);
  return out;
}

bool shadowsChain(std::span<const PhysicalPoint> points, std::span<const PhysicalPoint> members) {
  const std::size_t n = members.size();
  if (n <= 1) return true;
  if (points.empty() || points.size() % n != 0) return false;
  auto nearest = [&](const PhysicalPoint& z) {
    std::size_t best = 0;
    long double bestDistance = -1;
    for (std::size_t a = 0; a < n; ++a) {
      const long double d = std::hypot(z.x - members[a].x, z.y - members[a].y);
      if (bestDistance < 0 || d < bestDistance) bestDistance = d, best = a;
    }
    return best;
  };
  std::size_t previous = nearest(points.back());
  for (const PhysicalPoint& z : points) {
    const std::size_t a = nearest(z);
    if (a != (previous + 1) % n) return false;
    previous = a;
  }
  return true;
}

bool wellOrdered(std::span<const PhysicalPoint> points, PhysicalPoint centre) {
  const std::size_t q = points.size();
  if (q < 1) return false;
  std::vector<long double> angle(q);
  const long double start = std::atan2(points[0].y - centre.y, points[0].x - centre.x);
  constexpr long double kTwoPi = 6.283185307179586476925286766559L;
  for (std::size_t k = 0; k < q; ++k) {
    const long double dx = points[k].x - centre.x, dy = points[k].y - centre.y;
    if (dx == 0 && dy == 0) return false;
    long double a = -(std::atan2(dy, dx) - start);  // clockwise from z_0
    a = std::fmod(a, kTwoPi);
    if (a < 0) a += kTwoPi;
    angle[k] = a;
  }
  std::vector<std::size_t> order(q);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return angle[a] < angle[b]; });
  std::vector<std::size_t> position(q);
  for (std::size_t r = 0; r < q; ++r) {
    if (r > 0 && angle[order[r]] == angle[order[r - 1]]) return false;
    position[order[r]] = r;
  }
  const std::size_t shift = (position[1 % q] + q - position[0]) % q;
  for (std::size_t k = 0; k < q; ++k)
    if ((position[(k + 1) % q] + q - position[k]) % q != shift) return false;
  return true;
}

std::vector<LineWindow> annulusWindows(long double K, long double inner, long double outer) {
  if (auto e = manifoldKError(K)) throw std::invalid_argument(*e);
  if (!std::isfinite(inner) || !std::isfinite(outer) || !(inner > 0) || !(inner < outer))
    throw std::invalid_argument("the radii " + number(inner) + " and " + number(outer) + " must satisfy 0 < inner < outer");
  const long double c = -std::sqrt(K);
  // S₁: y = K − x² = (√K − x)(√K + x); with u = x + √K its distance from the centre is |u| √(1 + (2√K − u)²), which
  // grows with |u| on each side for the radii of the central island (checked: bisection needs a bracket).
  auto distanceS1 = [&](long double u) { return std::fabs(u) * std::sqrt(1 + (2 * std::sqrt(K) - u) * (2 * std::sqrt(K) - u)); };
  auto solveS1 = [&](long double r, long double sign) {
    long double lo = 0, hi = r;  // distance(u) ≥ |u|
    if (!(distanceS1(sign * hi) >= r))
      throw std::invalid_argument("radius " + number(r) + " is not reached on S1");
    for (int i = 0; i < 200; ++i) {
      const long double mid = (lo + hi) / 2;
      if (!(mid > lo && mid < hi)) break;
      (distanceS1(sign * mid) < r ? lo : hi) = mid;
    }
    return c + sign * hi;
  };
  std::vector<LineWindow> windows;
  windows.push_back({smooth::SymmetryLine::S2, c - outer, c - inner});
  windows.push_back({smooth::SymmetryLine::S2, c + inner, c + outer});
  windows.push_back({smooth::SymmetryLine::S1, solveS1(outer, -1), solveS1(inner, -1)});
  windows.push_back({smooth::SymmetryLine::S1, solveS1(inner, 1), solveS1(outer, 1)});
  return windows;
}

std::vector<LineWindow> lineWindowsAbout(long double K, PhysicalPoint member, long double inner, long double outer) {
  if (!std::isfinite(inner) || !std::isfinite(outer) || !(inner >= 0) || !(inner < outer))
    throw std::invalid_argument("the radii " + number(inner) + " and " + number(outer) + " must satisfy 0 <= inner < outer");
  constexpr int kSamples = 4096;
  const long double step = 2 * outer / kSamples;
  std::vector<LineWindow> windows;
  for (SymmetryLine line : {SymmetryLine::S1, SymmetryLine::S2}) {
    std::optional<long double> runStart;
    for (int k = 0; k <= kSamples + 1; ++k) {
      const long double x = member.x - outer + step * (static_cast<long double>(k) - 0.5L);
      const smooth::Point<long double> z = smooth::onLine(line, K, x);
      const long double d = std::hypot(z.x - member.x, z.y - member.y);
      const bool inside = k <= kSamples && d >= inner && d <= outer;
      if (inside && !runStart) runStart = x;
      if (!inside && runStart) {
        windows.push_back({line, *runStart - step, x});
        runStart.reset();
      }
    }
  }
  return windows;
}

MmpActionDifference mmpActionDifference(const MmpRequest& request, std::stop_token stop) {
  if (auto e = validationError(request)) throw std::invalid_argument(*e);
  const std::vector<LineWindow> windows =
      request.windows.empty() ? annulusWindows(request.K, request.innerRadius, request.outerRadius) : request.windows;
  const int n = request.stride;
  const PhysicalPoint centre = n == 1 ? PhysicalPoint{-std::sqrt(request.K), 0.0L} : request.about;
  // The p turns about the centre (or about the island: every n-th point) in q steps of Qⁿ, either sense about an island.
  auto turnsP = [&](std::span<const PhysicalPoint> points) {
    const long turns = clockwiseTurns(points, centre.x, centre.y);
    return n == 1 ? turns == request.p : std::labs(turns) == request.p;
  };
  // Roots with another number of turns are dropped before the finder polishes them in quad (most of the roots in a
  // chaotic layer): n·q steps in long double, whose rounding (≈ 1e-19 |λ|) does not change the winding.
  // About an island the root may lie at another of the chain's islands: every n-th point from the one nearest it.
  auto rootTurnsP = [&](PhysicalPoint start) {
    std::vector<PhysicalPoint> points(static_cast<std::size_t>(n) * static_cast<std::size_t>(request.q));
    smooth::Point<long double> z{start.x, start.y};
    for (auto& point : points) {
      if (!(std::fabs(z.x) < 1e3L && std::fabs(z.y) < 1e3L)) return false;
      point = {z.x, z.y};
      z = smooth::step(request.K, z);
    }
    return turnsP(stridedAbout(points, n, centre));
  };
  const std::vector<PeriodicOrbit> found =
      findSymmetricPeriodicOrbitsIn(request.K, n * request.q, windows, request.spacing, stop, rootTurnsP);
  MmpActionDifference out;
  out.K = request.K;
  out.p = request.p;
  out.q = request.q;
  out.stride = n;
  std::vector<const PeriodicOrbit*> birkhoff;
  for (const PeriodicOrbit& orbit : found) {
    const std::vector<PhysicalPoint> about = stridedAbout(orbit.points, n, centre);
    if (n == 1 ? orbit.windingTurns != request.p : !turnsP(about)) continue;
    if (!shadowsChain(orbit.points, request.members)) continue;
    ++out.symmetricOrbits;
    if (wellOrdered(about, centre)) birkhoff.push_back(&orbit);
  }
  out.birkhoffOrbits = static_cast<int>(birkhoff.size());
  const auto negative = std::count_if(birkhoff.begin(), birkhoff.end(), [](const PeriodicOrbit* o) { return o->residue < 0; });
  const auto positive = std::count_if(birkhoff.begin(), birkhoff.end(), [](const PeriodicOrbit* o) { return o->residue > 0; });
  const std::string pq = std::to_string(request.p) + "/" + std::to_string(request.q);
  if (negative != 1 || positive != 1 || birkhoff.size() != 2) {
    std::string residues;
    for (const PeriodicOrbit* o : birkhoff) residues += (residues.empty() ? "" : ", ") + number(o->residue);
    throw NotFound("the Birkhoff orbits of type " + pq + (n == 1 ? "" : " about the island at " + number(centre.x) + ", " + number(centre.y) + " under Q^" + std::to_string(n)) +
                   " are not one with R < 0 and one with R > 0: the scan of " +
                   (request.windows.empty() ? "the symmetry lines from " + number(request.innerRadius) + " to " +
                                                  number(request.outerRadius) + " about the centre"
                                            : std::to_string(request.windows.size()) + " windows of the symmetry lines") +
                   " found " + std::to_string(found.size()) + " symmetric orbits of period " + std::to_string(request.q) +
                   (n == 1 ? "" : " (" + std::to_string(n * request.q) + " steps of Q)") + ", " +
                   std::to_string(out.symmetricOrbits) + " with " + std::to_string(request.p) + " turns" +
                   (request.members.size() > 1 ? " that follow the chain's islands" : "") + ", " +
                   std::to_string(birkhoff.size()) + " well ordered" + (residues.empty() ? "" : " (R = " + residues + ")") +
                   "; other radii or a finer spacing may separate them");
  }
  const PeriodicOrbit& minimizing = *(birkhoff[0]->residue < 0 ? birkhoff[0] : birkhoff[1]);
  const PeriodicOrbit& minimax = *(birkhoff[0]->residue < 0 ? birkhoff[1] : birkhoff[0]);
  if (stop.stop_requested()) throw OperationStopped();
  out.minimizing = inQuad(minimizing);
  out.minimax = inQuad(minimax);
  out.planeDifference = out.minimax.action - out.minimizing.action;
  out.flux = smooth::absolute(out.planeDifference);
  out.fluxError = out.minimizing.actionError + out.minimax.actionError;
  return out;
}

ConvergentLimit convergentLimit(std::span<const long double> a) {
  if (a.size() < 3) throw std::invalid_argument("a limit needs at least three terms, not " + std::to_string(a.size()));
  for (long double v : a)
    if (!std::isfinite(v)) throw std::invalid_argument("a term of the sequence is not finite");
  const std::size_t n = a.size() - 1;
  const long double last = a[n] - a[n - 1];
  ConvergentLimit out;
  out.terms = static_cast<int>(a.size());
  out.value = a[n];
  for (std::size_t k = std::max<std::size_t>(2, n - std::min<std::size_t>(n, 2)); k <= n; ++k) {
    const long double previous = a[k - 1] - a[k - 2];
    if (previous == 0) throw std::invalid_argument("the difference of the terms " + std::to_string(k - 2) + " and " +
                                                   std::to_string(k - 1) + " is zero");
    out.ratio = std::max(out.ratio, std::fabs((a[k] - a[k - 1]) / previous));
  }
  if (!(out.ratio < 1))
    throw std::invalid_argument("the sequence is not converging: its last differences grow (ratio " + number(out.ratio) + ")");
  out.uncertainty = std::fabs(last) * out.ratio / (1 - out.ratio);
  return out;
}

std::optional<std::string> validationError(const CantorusRequest& r) {
  if (r.convergents.empty()) return std::string("at least one convergent p/q is needed");
  for (const auto& [p, q] : r.convergents) {
    MmpRequest m;
    m.K = r.K;
    m.p = p;
    m.q = q;
    m.innerRadius = r.innerRadius;
    m.outerRadius = r.outerRadius;
    m.spacing = r.spacing;
    m.stride = r.stride;
    m.about = r.about;
    m.members = r.members;
    m.windows = r.windows;
    if (auto e = validationError(m)) return e;
  }
  // Convergents in order: each denominator larger than the one before (a repeated or reordered term would make a
  // "limit" of a sequence that is not the cantorus's).
  for (std::size_t i = 1; i < r.convergents.size(); ++i)
    if (r.convergents[i].second <= r.convergents[i - 1].second)
      return "the convergents must be in order of growing q: " + std::to_string(r.convergents[i].first) + "/" +
             std::to_string(r.convergents[i].second) + " follows " + std::to_string(r.convergents[i - 1].first) +
             "/" + std::to_string(r.convergents[i - 1].second);
  if (!(r.narrowHalfWidth > 0) || !std::isfinite(r.narrowHalfWidth))
    return "narrow half-width = " + number(r.narrowHalfWidth) + " must be a positive number";
  if (!(r.narrowSpacing > 0) || !std::isfinite(r.narrowSpacing))
    return "narrow spacing = " + number(r.narrowSpacing) + " must be a positive number";
  if (2 * r.narrowHalfWidth / r.narrowSpacing > kMaxMmpSamples)
    return "the narrow windows (half-width " + number(r.narrowHalfWidth) + ", spacing " + number(r.narrowSpacing) +
           ") would take more than " + number(kMaxMmpSamples) + " samples each";
  return std::nullopt;
}

namespace {

/// The points of a term's two orbits that lie on a symmetry line, with their lines.
std::vector<LineWindow> linePoints(const MmpActionDifference& term, long double K) {
  std::vector<LineWindow> points;
  for (const BirkhoffOrbit* o : {&term.minimizing, &term.minimax})
    for (const PhysicalPoint& z : o->orbit.points)
      for (SymmetryLine line : {SymmetryLine::S1, SymmetryLine::S2})
        if (std::fabs(smooth::offsetFromLine(line, K, smooth::Point<long double>{z.x, z.y})) < 1e-12L * (1 + std::fabs(z.x)))
          points.push_back({line, z.x, z.x});
  return points;
}

}  // namespace

CantorusFlux cantorusFlux(const CantorusRequest& request, std::stop_token stop) {
  if (auto e = validationError(request)) throw std::invalid_argument(*e);
  CantorusFlux out;
  for (const auto& [p, q] : request.convergents) {
    MmpRequest wide;
    wide.K = request.K;
    wide.p = p;
    wide.q = q;
    wide.innerRadius = request.innerRadius;
    wide.outerRadius = request.outerRadius;
    wide.spacing = request.spacing;
    wide.stride = request.stride;
    wide.about = request.about;
    wide.members = request.members;
    wide.windows = request.windows;
    MmpRequest narrow = wide;
    narrow.windows.clear();
    narrow.spacing = request.narrowSpacing;
    std::vector<LineWindow> previous;
    if (!out.terms.empty()) {
      previous = linePoints(out.terms.back(), request.K);
      for (const LineWindow& z : previous)
        narrow.windows.push_back({z.line, z.lo - request.narrowHalfWidth, z.lo + request.narrowHalfWidth});
    }
    // Narrow first when there is a previous term: it costs 4 × 2·halfWidth/spacing samples (a few ms where it finds
    // nothing: early terms, whose points still move by 10⁻² from one convergent to the next), while the annulus costs
    // 150 s at q = 729 and misses the pair there.
    std::vector<std::pair<const MmpRequest*, bool>> attempts;
    if (!previous.empty()) attempts = {{&narrow, true}, {&wide, false}};
    else attempts = {{&wide, false}};
    std::string failures;
    bool done = false;
    for (const auto& [attempt, isNarrow] : attempts) {
      try {
        out.terms.push_back(mmpActionDifference(*attempt, stop));
        out.narrowed.push_back(isNarrow);
        done = true;
        break;
      } catch (const NotFound& e) {
        failures += (failures.empty() ? "" : "; ") + std::string(isNarrow ? "about the previous convergent's points: " : "") + e.what();
      }
    }
    if (!done) throw NotFound(failures);
  }
  std::vector<long double> fluxes;
  for (const MmpActionDifference& t : out.terms) fluxes.push_back(static_cast<long double>(t.flux));
  try {
    out.limit = convergentLimit(fluxes);
  } catch (const std::invalid_argument& e) {
    out.limitProblem = e.what();
  }
  return out;
}

std::string cantorusFluxJson(const CantorusRequest& request, const CantorusFlux& result, double seconds) {
  using json = nlohmann::ordered_json;
  json j;
  j["K"] = static_cast<double>(request.K);
  j["method"] = "MacKay-Meiss-Percival: flux = |W(minimax) - W(minimizing)| of the Birkhoff p/q orbits about (-sqrt K, 0)";
  if (request.stride > 1) {
    j["method"] = "MacKay-Meiss-Percival: flux = |W(minimax) - W(minimizing)| of the Birkhoff p/q orbits about an island, "
                  "Q-orbits of period stride*q";
    j["stride"] = request.stride;
    j["about"] = json::array({static_cast<double>(request.about.x), static_cast<double>(request.about.y)});
  }
  j["inner_radius"] = static_cast<double>(request.innerRadius);
  j["outer_radius"] = static_cast<double>(request.outerRadius);
  j["spacing"] = static_cast<double>(request.spacing);
  j["narrow_half_width"] = static_cast<double>(request.narrowHalfWidth);
  j["narrow_spacing"] = static_cast<double>(request.narrowSpacing);
  auto orbitJson = [](const BirkhoffOrbit& o) {
    json b;
    b["residue"] = static_cast<double>(o.orbit.residue);
    b["symmetry_line"] = o.line == SymmetryLine::S1 ? "S1: y = K - x^2" : "S2: y = 0";
    b["point"] = json::array({static_cast<double>(o.points.front().x), static_cast<double>(o.points.front().y)});
    b["action_text"] = quadText(o.action, 30);
    b["halves_mismatch"] = static_cast<double>(o.mismatch);
    return b;
  };
  json terms = json::array();
  for (std::size_t i = 0; i < result.terms.size(); ++i) {
    const MmpActionDifference& t = result.terms[i];
    json e;
    e["p"] = t.p;
    e["q"] = t.q;
    e["flux"] = static_cast<double>(t.flux);
    e["flux_text"] = quadText(t.flux, 30);
    e["flux_error"] = static_cast<double>(t.fluxError);
    e["plane_difference_text"] = quadText(t.planeDifference, 30);
    e["minimizing"] = orbitJson(t.minimizing);
    e["minimax"] = orbitJson(t.minimax);
    e["symmetric_orbits"] = t.symmetricOrbits;
    e["birkhoff_orbits"] = t.birkhoffOrbits;
    e["narrow_windows"] = static_cast<bool>(result.narrowed[i]);
    terms.push_back(e);
  }
  j["terms"] = terms;
  if (result.limit) {
    json l;
    l["value"] = static_cast<double>(result.limit->value);
    l["uncertainty"] = static_cast<double>(result.limit->uncertainty);
    l["ratio"] = static_cast<double>(result.limit->ratio);
    l["terms"] = result.limit->terms;
    j["limit"] = l;
  } else {
    j["limit"] = nullptr;
    j["limit_problem"] = result.limitProblem;
  }
  if (seconds >= 0) j["seconds"] = seconds;
  return j.dump(2);
}

}  // namespace archipelago
