#include "core/atlas/AtlasCantori.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/io/NumberText.hpp"
#include "core/manifolds/MmpFlux.hpp"
#include "core/manifolds/PolygonRegion.hpp"
#include "core/periodic/PeriodicOrbitFinder.hpp"
#include "core/periodic/SmoothQuadraticMap.hpp"

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

const AtlasNode& nodeAt(const Atlas& atlas, int i) { return atlas.nodes[static_cast<std::size_t>(i)]; }

/// The island's chains that are barriers, outermost (largest zone) first.
std::vector<int> barrierChains(const Atlas& atlas, int island) {
  std::vector<int> kids;
  for (int c : nodeAt(atlas, island).children) {
    const AtlasNode& n = nodeAt(atlas, c);
    if (n.flux.found && n.aboutParent && n.aboutParent->p > 0) kids.push_back(c);
  }
  std::stable_sort(kids.begin(), kids.end(), [&](int x, int y) {
    return nodeAt(atlas, x).flux.zoneArea > nodeAt(atlas, y).flux.zoneArea;
  });
  return kids;
}

/// The distances from `member` of the chains' points about it (every n-th point of each, from the nearest), with a
/// tenth to spare on each side; the inner end `innerShare` of the nearest (a boundary cantorus lies inside its chain).
std::pair<long double, long double> radiiAbout(std::span<const AtlasNode* const> chains, PhysicalPoint member, int n,
                                               long double innerShare) {
  long double lo = kMaxMmpRadius, hi = 0;
  for (const AtlasNode* c : chains)
    for (const PhysicalPoint& p : stridedAbout(c->orbit.points, n, member)) {
      const long double r = std::hypot(p.x - member.x, p.y - member.y);
      lo = std::min(lo, r);
      hi = std::max(hi, r);
    }
  return {innerShare * lo, std::min(1.1L * hi, kMaxMmpRadius)};
}

/// The windows of the lines where they pass each island of the chain between the radii of the chains' points about
/// its member (lineWindowsAbout).
std::vector<LineWindow> islandWindows(const Atlas& atlas, const AtlasNode& island,
                                      std::span<const AtlasNode* const> chains, long double innerShare) {
  const long double K = static_cast<long double>(atlas.request.map.K);
  std::vector<LineWindow> windows;
  for (const PhysicalPoint& m : island.orbit.points) {
    const auto [lo, hi] = radiiAbout(chains, m, static_cast<int>(island.period), innerShare);
    for (const LineWindow& w : lineWindowsAbout(K, m, lo, hi)) windows.push_back(w);
  }
  return windows;
}

/// The polygon of an orbit's points about the island's member c (every n-th point from the nearest) ordered by their
/// angle about it.
PolygonRegion byAngle(const BirkhoffOrbit& orbit, const AtlasNode& island) {
  std::vector<PhysicalPoint> all;
  for (const auto& z : orbit.points) all.push_back({static_cast<long double>(z.x), static_cast<long double>(z.y)});
  const PhysicalPoint c = island.centre;
  std::vector<PhysicalPoint> points = stridedAbout(all, static_cast<int>(island.period), c);
  std::sort(points.begin(), points.end(), [&](const PhysicalPoint& a, const PhysicalPoint& b) {
    return std::atan2(a.y - c.y, a.x - c.x) < std::atan2(b.y - c.y, b.x - c.x);
  });
  return PolygonRegion(points);
}

/// The request of ΔW over the cantorus's convergents about the island, scanning about `chains` first.
CantorusRequest requestAbout(const Atlas& atlas, const AtlasNode& island, const std::vector<Rational>& convergents,
                             std::span<const AtlasNode* const> chains, long double innerShare) {
  CantorusRequest r;
  r.K = static_cast<long double>(atlas.request.map.K);
  for (const Rational& q : convergents) r.convergents.push_back({static_cast<long>(q.p), static_cast<int>(q.q)});
  if (island.parent < 0) {
    std::tie(r.innerRadius, r.outerRadius) = radiiAbout(chains, island.centre, 1, innerShare);
    return r;
  }
  r.stride = static_cast<int>(island.period);
  r.about = island.centre;
  r.members = island.orbit.points;
  r.windows = islandWindows(atlas, island, chains, innerShare);
  return r;
}

/// ΔW's limit, the zone of the last term's minimax orbit (n curves: n times the one about c) and its layer, for the
/// cantorus `c` about `island`; its layer checked to lie between `below` and `above`.
void measureCantorus(const Atlas& atlas, const AtlasNode& island, const CantorusRequest& r, long double below,
                     long double above, AtlasCantorus& c, std::stop_token stop) {
  try {
    if (r.windows.empty() && island.parent >= 0)
      throw NotFound("no symmetry line passes the island's chain between the chains' radii");
    const CantorusFlux f = cantorusFlux(r, stop);
    if (!f.limit) {
      c.failure = "ΔW over the convergents: " + f.limitProblem;
      return;
    }
    if (!(f.limit->value > f.limit->uncertainty)) {
      c.failure = "ΔW over the convergents falls to " + number(f.limit->value) + " ± " + number(f.limit->uncertainty) +
                  " (tail bound): no flux beyond zero, as through an invariant circle: not shown a cantorus";
      return;
    }
    const long double n = static_cast<long double>(island.period);
    c.flux = f.limit->value;
    c.fluxUncertainty = f.limit->uncertainty;
    const PolygonRegion minimax = byAngle(f.terms.back().minimax, island);
    c.zoneArea = n * minimax.area();
    c.zoneSpread = std::fabs(n * byAngle(f.terms.back().minimizing, island).area() - c.zoneArea);
    std::tie(c.enclosedIslands, c.enclosedCount) = atlasIslandsInside(atlas, minimax);
    c.enclosedIslands *= n;
    c.enclosedCount *= static_cast<int>(island.period);
    c.layerArea = c.zoneArea - c.enclosedIslands;
  } catch (const OperationStopped&) {
    throw;
  } catch (const std::exception& e) {
    c.failure = e.what();
    return;
  }
  if (!(c.layerArea > below && c.layerArea < above))
    c.failure = "its layer " + number(c.layerArea) + " does not lie between the layers of the barriers about it, " +
                number(below) + " and " + number(above);
  c.found = c.failure.empty();
}

/// The largest period of a term about `island`: q ≤ kMaxCantorusPeriod between chains about the centre, else
/// n·q ≤ kMaxIslandCantorusPeriod (n the island's chain's period; 1 at the centre).
int maxTermQ(const AtlasNode& island, bool boundary) {
  return island.parent < 0 && !boundary
             ? kMaxCantorusPeriod
             : static_cast<int>(kMaxIslandCantorusPeriod / static_cast<long long>(island.period));
}

std::string tooFew(const AtlasNode& island, bool boundary) {
  return island.parent < 0 && !boundary
             ? "fewer than three convergents of period ≤ " + std::to_string(kMaxCantorusPeriod)
             : "fewer than three convergents of period n·q ≤ " + std::to_string(kMaxIslandCantorusPeriod) + " (n = " +
                   std::to_string(island.period) + ")";
}

/// The layer just outside the cantori inside chain `outer`: its inner separatrix's, where found, else its outer one's.
long double layerInside(const AtlasNode& outer) {
  return outer.flux.inner.found && outer.flux.inner.layerArea > 0 ? outer.flux.inner.layerArea : outer.flux.layerArea;
}

/// The flux and zone of the cantorus between `outer` and `inner` (chains about `island`), its layer checked against theirs.
AtlasCantorus cantorusBetween(const Atlas& atlas, int island, const AtlasNode& outer, const AtlasNode& inner,
                              std::stop_token stop) {
  const AtlasNode& about = nodeAt(atlas, island);
  AtlasCantorus c;
  c.island = island;
  c.outer = *outer.aboutParent;
  c.inner = *inner.aboutParent;
  c.convergents = nobleConvergents(c.outer, c.inner, maxTermQ(about, false));
  if (c.convergents.size() < 3) {
    c.failure = c.convergents.empty() && std::llabs(c.outer.p * c.inner.q - c.inner.p * c.outer.q) != 1
                    ? "not Farey neighbours: a chain of lower period lies between them (not a barrier of the atlas)"
                    : tooFew(about, false);
    return c;
  }
  const AtlasNode* chains[] = {&outer, &inner};
  measureCantorus(atlas, about, requestAbout(atlas, about, c.convergents, chains, 0.9L), inner.flux.layerArea,
                  layerInside(outer), c, stop);
  return c;
}

/// The island's boundary cantorus: between its innermost barrier chain `chain` (p₁/q₁) and its boundary circle, the
/// first of the nobles between p₁/q₁ and its Farey neighbours r₀ = boundaryNeighbour, r_{j+1} = r_j ⊕ p₁/q₁ (each nearer
/// the chain) whose ΔW does not fall to zero within its tail bound and whose layer lies outside the island and inside
/// the chain's; the nobles nearer the boundary that were tried are named in `note`.
AtlasCantorus boundaryCantorus(const Atlas& atlas, int island, const AtlasNode& chain, std::stop_token stop) {
  const AtlasNode& about = nodeAt(atlas, island);
  const int maxQ = maxTermQ(about, true);
  AtlasCantorus c;
  c.island = island;
  c.boundary = true;
  c.outer = *chain.aboutParent;
  c.inner = c.outer;
  std::optional<Rational> neighbour = boundaryNeighbour(c.outer, about.boundaryRotation, maxQ);
  if (!neighbour) {
    c.failure = "no Farey neighbour of " + toString(c.outer) + " between it and the boundary rotation " +
                number(about.boundaryRotation) + " has q ≤ " + std::to_string(maxQ) + " (" + tooFew(about, true) + ")";
    return c;
  }
  const AtlasNode* chains[] = {&chain};
  std::string tried;
  const AtlasCantorus none = c;
  for (int j = 0; j < kMaxBoundaryCandidates && neighbour; ++j) {
    AtlasCantorus candidate = none;
    candidate.inner = *neighbour;
    candidate.convergents = nobleConvergents(candidate.outer, candidate.inner, maxQ);
    if (candidate.convergents.size() < 3) {
      candidate.failure = tooFew(about, true);
      c = candidate;
      break;
    }
    measureCantorus(atlas, about, requestAbout(atlas, about, candidate.convergents, chains, 0.7L), 0,
                    layerInside(chain), candidate, stop);
    c = candidate;
    if (c.found) break;
    tried += (tried.empty() ? "" : "; ") + toString(candidate.outer) + "-" + toString(candidate.inner) + ": " +
             candidate.failure;
    neighbour = Rational{neighbour->p + none.outer.p, neighbour->q + none.outer.q};
  }
  if (c.found) c.note = tried.empty() ? "" : "nearer the boundary: " + tried;
  else if (!tried.empty()) c.failure = "none of the nobles tried: " + tried;
  return c;
}

}  // namespace

std::optional<Rational> boundaryNeighbour(const Rational& chain, double boundaryRotation, int maxQ) {
  const long double a = static_cast<long double>(chain.p) / static_cast<long double>(chain.q);
  const long double w = boundaryRotation;
  if (!std::isfinite(w) || w == a) return std::nullopt;
  const std::int64_t sign = w > a ? 1 : -1;  // p·chain.q − chain.p·q = sign: the neighbour on the boundary's side
  for (std::int64_t q = 1; q <= maxQ; ++q) {
    const std::int64_t top = sign + chain.p * q;
    if (top % chain.q != 0) continue;
    const Rational r{top / chain.q, q};
    const long double v = static_cast<long double>(r.p) / static_cast<long double>(r.q);
    if (sign > 0 ? v < w : v > w) return r;
  }
  return std::nullopt;
}

std::string atlasCantorusName(const Atlas& atlas, const AtlasCantorus& c) {
  std::string name = (c.boundary ? "boundary cantorus " : "cantorus ") + toString(c.outer) + "-" + toString(c.inner);
  if (c.island != 0) name += (c.boundary ? " of " : " about ") + atlasPath(atlas, c.island);
  return name;
}

std::vector<AtlasCantorus> atlasCantori(const Atlas& atlas, std::stop_token stop) {
  std::vector<AtlasCantorus> out;
  for (std::size_t i = 0; i < atlas.nodes.size() && !stop.stop_requested(); ++i) {
    if (!atlas.nodes[i].measured || !atlas.nodes[i].boundaryFound) continue;
    const int island = static_cast<int>(i);
    const std::vector<int> chains = barrierChains(atlas, island);
    for (std::size_t k = 1; k < chains.size() && !stop.stop_requested(); ++k)
      out.push_back(cantorusBetween(atlas, island, nodeAt(atlas, chains[k - 1]), nodeAt(atlas, chains[k]), stop));
    if (!chains.empty() && !stop.stop_requested())
      out.push_back(boundaryCantorus(atlas, island, nodeAt(atlas, chains.back()), stop));
  }
  return out;
}

}  // namespace archipelago
