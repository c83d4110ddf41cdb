#include "core/atlas/AtlasCantori.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/manifolds/MmpFlux.hpp"
#include "core/manifolds/PolygonRegion.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"

namespace archipelago {

std::vector<Rational> nobleConvergents(const Rational& outer, const Rational& inner, int maxPeriod) {
  if (std::llabs(outer.p * inner.q - inner.p * outer.q) != 1) return {};
  Rational previous = outer.q < inner.q ? outer : inner;
  Rational current = outer.q < inner.q ? inner : outer;
  std::vector<Rational> terms;
  while (current.q <= maxPeriod) {
    terms.push_back(current);
    const Rational next{current.p + previous.p, current.q + previous.q};
    previous = current;
    current = next;
  }
  return terms;
}

namespace {

std::string number(long double v) { return shortestDecimal(static_cast<double>(v)); }

/// The centre's chains that are barriers, outermost (largest zone) first.
std::vector<int> centreBarriers(const Atlas& atlas) {
  std::vector<int> kids;
  for (int c : atlas.nodes.front().children) {
    const AtlasNode& n = atlas.nodes[static_cast<std::size_t>(c)];
    if (n.flux.found && n.aboutParent && n.aboutParent->p > 0) kids.push_back(c);
  }
  std::stable_sort(kids.begin(), kids.end(), [&](int x, int y) {
    return atlas.nodes[static_cast<std::size_t>(x)].flux.zoneArea > atlas.nodes[static_cast<std::size_t>(y)].flux.zoneArea;
  });
  return kids;
}

/// The annulus about the centre that holds both chains' orbits, with a tenth to spare on each side.
std::pair<long double, long double> annulusOf(const AtlasNode& a, const AtlasNode& b, PhysicalPoint centre) {
  long double lo = kMaxMmpRadius, hi = 0;
  for (const AtlasNode* n : {&a, &b})
    for (const PhysicalPoint& p : n->orbit.points) {
      const long double r = std::hypot(p.x - centre.x, p.y - centre.y);
      lo = std::min(lo, r);
      hi = std::max(hi, r);
    }
  return {0.9L * lo, std::min(1.1L * hi, kMaxMmpRadius)};
}

/// The polygon of an orbit's points ordered by their angle about the centre.
PolygonRegion byAngle(const BirkhoffOrbit& orbit, PhysicalPoint centre) {
  std::vector<PhysicalPoint> points;
  for (const auto& z : orbit.points) points.push_back({static_cast<long double>(z.x), static_cast<long double>(z.y)});
  std::sort(points.begin(), points.end(), [&](const PhysicalPoint& a, const PhysicalPoint& b) {
    return std::atan2(a.y - centre.y, a.x - centre.x) < std::atan2(b.y - centre.y, b.x - centre.x);
  });
  return PolygonRegion(points);
}

/// The flux and zone of the cantorus between `outer` and `inner` (atlas nodes), its layer checked against theirs.
AtlasCantorus cantorusBetween(const Atlas& atlas, const AtlasNode& outer, const AtlasNode& inner, std::stop_token stop) {
  AtlasCantorus c;
  c.outer = *outer.aboutParent;
  c.inner = *inner.aboutParent;
  c.convergents = nobleConvergents(c.outer, c.inner, kMaxCantorusPeriod);
  if (c.convergents.size() < 3) {
    c.failure = c.convergents.empty()
                    ? "not Farey neighbours: a chain of lower period lies between them (not a barrier of the atlas)"
                    : "fewer than three convergents of period ≤ " + std::to_string(kMaxCantorusPeriod);
    return c;
  }
  const PhysicalPoint centre = atlas.nodes.front().centre;
  CantorusRequest r;
  r.K = static_cast<long double>(atlas.request.map.K);
  for (const Rational& q : c.convergents) r.convergents.push_back({static_cast<long>(q.p), static_cast<int>(q.q)});
  std::tie(r.innerRadius, r.outerRadius) = annulusOf(outer, inner, centre);
  try {
    const CantorusFlux f = cantorusFlux(r, stop);
    if (!f.limit) {
      c.failure = "ΔW over the convergents: " + f.limitProblem;
      return c;
    }
    c.flux = f.limit->value;
    c.fluxUncertainty = f.limit->uncertainty;
    const PolygonRegion minimax = byAngle(f.terms.back().minimax, centre);
    c.zoneArea = minimax.area();
    c.zoneSpread = std::fabs(byAngle(f.terms.back().minimizing, centre).area() - c.zoneArea);
    std::tie(c.enclosedIslands, c.enclosedCount) = atlasIslandsInside(atlas, minimax);
    c.layerArea = c.zoneArea - c.enclosedIslands;
  } catch (const OperationStopped&) {
    throw;
  } catch (const std::exception& e) {
    c.failure = e.what();
    return c;
  }
  const long double below = inner.flux.layerArea;
  const long double above = outer.flux.inner.layerArea > 0 ? outer.flux.inner.layerArea : outer.flux.layerArea;
  if (!(c.layerArea > below && c.layerArea < above))
    c.failure = "its layer " + number(c.layerArea) + " does not lie between the layers of the barriers about it, " +
                number(below) + " and " + number(above);
  c.found = c.failure.empty();
  return c;
}

}  // namespace

std::vector<AtlasCantorus> centreCantori(const Atlas& atlas, std::stop_token stop) {
  std::vector<AtlasCantorus> out;
  const std::vector<int> chains = centreBarriers(atlas);
  for (std::size_t k = 1; k < chains.size() && !stop.stop_requested(); ++k)
    out.push_back(cantorusBetween(atlas, atlas.nodes[static_cast<std::size_t>(chains[k - 1])],
                                  atlas.nodes[static_cast<std::size_t>(chains[k])], stop));
  return out;
}

}  // namespace archipelago
