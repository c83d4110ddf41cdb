#pragma once
/// \file Atlas.hpp
/// \brief The atlas of the archipelago (issue 38): the hierarchy of islands around islands of Q — which chains
/// surround which island, each island's area, the flux into each chain's resonance zone and the mean residence time
/// there — found from the elliptic fixed point down to a depth, a largest period and a smallest area.
///
/// Karney (1983), §6 and fig. 8: the central island at K = 0.1 is surrounded by a chain of six islands (rotation
/// 1/6 about the centre), each of those by 23 (2/23 about it: the chain of order 138), and so on.  The tree is what
/// the models of the tail are built from (Meiss & Ott, Physica D 20 (1986) 387; Alus, Fishman & Meiss, PRE 90 (2014)
/// 054102).  The method (docs/atlas.md says why, and what it misses):
///
///  1. An island is a member c of an elliptic orbit of period n that lies on a symmetry line S (S₁: y = K − x², S₂:
///     y = 0; the centre (−√K, 0) lies on both; every member of a chain on a line is scanned).  Points p_i = (c.x ± R i/N, y_S) of S on
///     both sides of c (i = 1 … N; R = 2√K at the centre, else half the distance from c to the nearest other point of
///     its orbit) are classified by their rotation number about c under Qⁿ (RotationNumber.hpp, T iterations per
///     block, in the sense DQⁿ turns there): a **circle** is regular with no rational p/q (q ≤ maxPeriod/n) within
///     its measured accuracy; a **chain** point regular at such a p/q ≠ 0; anything else (chaotic, escaping, not
///     turning about c) is **outside**.  About a thin island's member — where the linear map's largest step of the
///     angle of z − c lies within 0.05 of half a turn (FloquetFrame::foldMargin) and steps a little way out fold — the
///     angle is taken in its normal-form (Floquet) coordinates (FloquetFrame.hpp, issue 50).
///  2. The boundary circle on one side is the outermost circle point (a circle about c lies in c's island: orbits
///     of the chains and circles outside it turn at a rational or not at all about c), bisected against its outer
///     neighbour (`bisections` halvings).  Its orbit under Qⁿ (8192 points), ordered by the angle k·ω mod 1 that
///     the conjugacy to the rotation ω gives each point, is a polygon whose shoelace area is the island's area
///     (Green's theorem).  The circle is *proven* (issue 50): its polygon winds about c and its area and perimeter
///     converge (4096 against 8192 points), and its rotation measured again with 4 T iterates agrees and names no
///     rational of denominator ≤ 10⁴ (an orbit of a long chain, or a sticky chaotic orbit, passed the scan's test: at
///     K = 0.12 one of the 25/143 chain did); a candidate that fails is dropped and the next circle inwards tried.  Of
///     all sides the largest area is kept (the outermost circle).  About a thin island circles are then sought the same
///     way on 8 of the 16 rays of its frame (below), each from the kept circle's crossing to the nearest escaping
///     point, and a larger one kept (issue 50: along the lines the bisection stops inside such an island's boundary).
///     The other side of the bracket: on every ray, the nearest point beyond the circle whose orbit is proven to leave
///     the island (farther from c than the next member of its orbit, or out of the box, within 2 T applications of
///     Qⁿ).  The area is an interval: from below the circle's polygon less its convergence, from above the circle
///     scaled about c by the widest ratio of those distances (AtlasNode::areaLower, areaUpper, areaError); for a thin
///     island over 16 straight rays from the kept circle's member equally spaced in angle in its normal-form frame.
///  3. The chains: the chain points beyond the boundary (turning about c in the sense of its circles), grouped by p/q,
///     the middle point of a group's first run (else of its longest: the first can be a sticky orbit) giving the
///     elliptic orbit of period n·q (ChainIdentification.hpp, ellipticOrbitAround); kept when it is stable, and
///     labelled by that orbit's own rotation about c (issue 50: the order of its Qⁿ-images about c, or the sum of
///     their angles' increments where none may be folded; not the scan's, whose increments fold about a long, thin
///     island), refused when that is not decided.  Chain
///     points inside the boundary, and the chains whose own rotation is not beyond the boundary's, are listed as
///     internal rationals and not followed.  About each island followed, every symmetric chain p/q (q ≤ 50; below the
///     centre of period n·q ≤ 300) whose rotation lies between the boundary's and the barrier's (0 turns per Qⁿ where
///     the rotation falls outwards, ½ where it rises: the rotation beside the barrier's hyperbolic fixed point of Qⁿ)
///     is sought by its rotation (the Farey rationals of that interval, for each q the symmetric orbits of period n·q
///     on the lines from the boundary to the cell's end, kept when elliptic and a well-ordered chain about the island):
///     the scan steps over chains whose islands are narrower than its step (the 4/25 chain about the centre at
///     K = 0.1) or misses them by chance (the 1/11 chain about the island of six).
///  4. For each chain: its hyperbolic partner (HyperbolicPartner.hpp) and the turnstile flux through its separatrix
///     and the area the separatrix encloses (TurnstileFlux.hpp's zone: around the parent island, or around each of the
///     parent chain's islands).  The layer is that area less the parent islands it encloses, and the mean residence
///     time inside the barrier is layer / flux (steps; Kac's lemma, as the Kac check of KacCheck.hpp measures it,
///     with the smaller islands inside the layer not subtracted).  At the centre the barrier is the fixed point
///     (√K, 0)'s loop around the central island.
///  5. Recursively, for one island of each chain (the member on a symmetry line nearest the scan; the others are its
///     images under Q and have the same area), to `depth` levels below the centre; an island of area below minArea
///     is listed and not followed.
///
/// Cost: level k scans 2N points of 2T·n steps each (scalar, in parallel) and a few Newton solves and flux
/// computations of period n; at K = 0.1 depth 2 takes seconds to a minute on two cores (docs/atlas.md).

#include <cstdint>
#include <functional>
#include <optional>
#include <stop_token>
#include <string>
#include <vector>

#include "core/map/MapParameters.hpp"
#include "core/measures/ChainIdentification.hpp"
#include "core/periodic/PeriodicOrbit.hpp"

namespace archipelago {

/// What to map.  Plain values; validationError() checks them.
struct AtlasRequest {
  MapParameters map;                                 ///< K in (0, 1) and the box Q* must stay in (orbits leaving it are outside)
  int depth = 2;                                     ///< levels of chains below the centre, 0 … kMaxAtlasDepth
  std::uint64_t maxPeriod = 1000;                    ///< largest period of a chain (the product of the q's), 1 … 100000
  double minArea = 1e-7;                             ///< islands of smaller area are listed, not followed; ≥ 0
  std::uint64_t iterations = 4000;                   ///< T of each rotation measurement (kMinIterations … kMaxIterations)
  double digitsThreshold = kDefaultDigitsThreshold;  ///< regular when digits ≥ this
  int scanPoints = 1000;                             ///< N: points of a symmetry line on each side of an island, 16 … 10000
  double scanSteps = 2e9;                            ///< more points (up to 10000) where this many steps of the map allow:
                                                     ///< islands of short period are scanned finely, 0 … 1e13
  int bisections = 20;                               ///< halvings of the boundary's bracket, 0 … 60
  int threads = 0;                                   ///< 0: one per core
  double timeBudget = 0;                             ///< seconds, 0 … 1e7 (0: none): reached, the atlas stops as on a
                                                     ///< stop request, keeping what is finished (Atlas::stopReason);
                                                     ///< checked between islands, after the first of the computation
  bool cantori = false;                              ///< once every island is measured, the cantori between the
                                                     ///< centre's chains (AtlasCantori.hpp; Atlas::cantori): ~3 s
                                                     ///< each at K = 0.1 on two quiet cores, four there
};

inline constexpr int kMaxAtlasDepth = 6;
/// The largest atlas file read back (--resume, sessions hold theirs): a depth-3 tree is a few megabytes.
inline constexpr std::uintmax_t kMaxAtlasFileBytes = std::uintmax_t{1} << 28;

/// The first violated rule, naming the field, or nothing.
[[nodiscard]] std::optional<std::string> validationError(const AtlasRequest& r);

/// What computeAtlas refuses, for a front end to say before it starts: validationError, then a box that does not
/// hold the central island and its loop (atlasBoxError, BoxIslandCheck.hpp: tens of milliseconds, it measures the
/// island's circle).
[[nodiscard]] std::optional<std::string> atlasRequestError(const AtlasRequest& r);

/// One separatrix's turnstile: the lobe area crossing it per step and the zone it encloses.
struct SeparatrixFlux {
  bool found = false;
  std::string failure;            ///< why not, when not found
  long double flux = 0;           ///< lobe area per step
  long double zoneArea = 0;       ///< the area the separatrix encloses (all its closed curves)
  long double fluxDigits = 0;     ///< digits on which the action and the polygon agree for the lobe
  long double zoneDigits = 0;     ///< the same for the zone
  /// The inner separatrix's layer (issue 50), settled as the outer's (settleLayers; 0 in a file from before): its
  /// zone less the atlas's islands inside it — the region between it and the next barrier inwards (the island's
  /// boundary circle, or the next chain's outer separatrix), where an orbit that crossed it inwards moves.
  long double enclosedIslands = 0;
  int enclosedCount = 0;
  long double layerArea = 0;
};

/// The flux through a chain's separatrix (the fixed point (√K, 0)'s loop at the centre).
struct AtlasFlux {
  bool found = false;
  std::string failure;            ///< why not, when not found
  std::optional<PeriodicOrbit> partner;  ///< the hyperbolic partner (none at the centre: the fixed point (√K, 0))
  long double flux = 0;           ///< lobe area: area crossing into the zone per step
  long double zoneArea = 0;       ///< the area the barrier encloses (TurnstileFlux.hpp's zone: all its curves)
  long double fluxDigits = 0;     ///< digits on which the action and the polygon agree for the lobe
  long double zoneDigits = 0;     ///< the same for the zone
  long double enclosedIslands = 0; ///< the atlas's islands inside the zone: Σ over its nodes of (members of the node's
                                   ///< orbit inside the zone's curves) × the node's area — the parent's islands, the
                                   ///< chain's own, its descendants' and those of the chains between (settled when
                                   ///< the atlas is complete; islands below the cut-offs are not known, not subtracted)
  int enclosedCount = 0;          ///< how many islands that is
  long double layerArea = 0;      ///< zoneArea − enclosedIslands: the layer an orbit that crossed the barrier moves in
                                  ///< (Kac's transit area, KacCheck.hpp), an upper bound by the islands not found
  double residence = 0;           ///< layerArea / flux: the mean residence time inside the barrier, in steps (Kac)
  /// The fields above are the **outer** separatrix's: of the partner's two, the one enclosing the larger zone (issue
  /// 50: decided by the zones, not by the label "outward").  `inner` is the other (not computed at the centre).
  SeparatrixFlux inner;
  bool outerByZone = false;       ///< both sides found and the outer chosen by its zone (else the label "outward")
};

/// No silent wrong answer: a barrier whose zone is no larger than the atlas's islands inside it has no layer (the
/// separatrix's curves do not enclose the region an orbit crossing it moves in: at K = 0.15 the 1/5 chain about the
/// island of 21 gave a zone of 4.5e−4 round islands of 8.7e−4, a layer of −4.2e−4 and a residence of −1.5e9 steps).
/// Such a flux is refused (found = false, `failure` says why); the computation's layers and a file read back obey it.
void refuseEmptyLayer(AtlasFlux& f);
/// The same rule for an inner separatrix whose layer is settled (> 0 enclosed or a layer given): a layer ≤ 0 is refused.
void refuseEmptyLayer(SeparatrixFlux& f);

/// One island of the tree (with its chain: all the islands that are its images).
struct AtlasNode {
  int parent = -1;                       ///< index of the parent island, −1 at the centre
  int level = 0;                         ///< 0: the central island
  std::uint64_t period = 1;              ///< n: the chain's period (its number of islands)
  std::optional<Rational> aboutParent;   ///< p/q about the parent island (q islands of this chain around each)
  PeriodicOrbit orbit;                   ///< the elliptic orbit of the chain (the fixed point at the centre)
  PhysicalPoint centre;                  ///< the member whose island was measured
  bool onS1 = false;                     ///< its symmetry line: S₁ (else S₂)
  int sense = 1;                         ///< +1: DQⁿ turns clockwise about it

  long double scanRange = 0;             ///< R: how far along the line it was scanned (0 until scanned; set for the
                                         ///< last level from the run of the parent's scan that found it)
  bool boundaryFound = false;
  std::string boundaryFailure;           ///< why not, when not found
  PhysicalPoint boundaryPoint;           ///< a point of the boundary circle about `centre`: on a symmetry line, or
                                         ///< on a ray of a thin island's normal-form frame (docs/atlas.md, step 3)
  double boundaryRotation = 0;           ///< its rotation number about `centre` (turns per Qⁿ)
  double boundaryDigits = 0;
  long double gap = 0;                   ///< the bisection's last step: the circle point's distance to the next point
                                         ///< not proven a circle (a resolution of the bisection, not of the boundary)
  long double area = 0;                  ///< one island's area: the outermost proven circle's (its polygon's)
  long double areaError = 0;             ///< area ± areaError holds the island's true area: the larger distance from
                                         ///< `area` to the ends of [areaLower, areaUpper]
  long double areaLower = 0;             ///< the true area is at least this: the circle's area less polygonError
  long double areaUpper = 0;             ///< and at most this: the circle scaled to the nearest escaping points
                                         ///< (areaUpperRays), or the chain's eye where smaller (the band between its
                                         ///< two separatrices over its n islands: each island lies in an eye)
  long double areaUpperRays = 0;         ///< the rays' upper end alone (not in the files: read back, area_upper)
  long double circleArea = 0;            ///< the proven circle's polygon area (= area)
  long double polygonError = 0;          ///< |polygon area − with every other point|: the curve's convergence only
  int areaPoints = 0;                    ///< points of the polygon

  AtlasFlux flux;                        ///< through the chain's separatrix (the central island's loop at level 0)
  std::vector<Rational> internal;        ///< rationals about `centre` found inside the boundary circle
  bool measured = false;                 ///< its island scanned and its barrier computed (false: known, not yet
                                         ///< measured — an atlas stopped early; computeAtlas resumes there)
  std::vector<int> children;             ///< chains just outside, by index
  std::string note;                      ///< why the recursion stopped here, when it did
};

/// One eye of a chain of n islands (issue 50): the band between its outer and inner separatrices' zones (each with the
/// two methods' disagreement, zoneArea·10^−zoneDigits, added) over n.  Each island lies in an eye of its own (the
/// separatrices are invariant and cross none of its circles), and Q permutes the n eyes and keeps areas, so no island
/// is larger.  Nothing unless both separatrices were found (and for n = 0).
[[nodiscard]] std::optional<long double> atlasEyeArea(const AtlasFlux& flux, std::uint64_t n);

/// A measured island's upper end: its rays' (areaUpperRays), or its chain's eye (atlasEyeArea) where that is smaller
/// (at K = 0.1, depth 2, the island of 6 > 204's rays reached 0.168 for a circle of 1.6·10⁻⁶: orbits near its
/// resonance stay within 2T applications of Qⁿ).  An eye below the proven circle's lower end is a zone computed
/// wrong, not a bound: it is not used.  areaError follows.  Nothing for an island without a boundary or without the
/// rays' end (a file from before the interval).
void capAreaByEye(AtlasNode& node);

/// A cantorus between two successive chains about the central island (issue 50; AtlasCantori.hpp): a barrier with
/// the MacKay–Meiss–Percival flux, splitting the band between the two chains' separatrices.
struct AtlasCantorus {
  int island = 0;                        ///< the node about whose island it lies (0: the centre)
  bool boundary = false;                 ///< the island's boundary cantorus: between its innermost barrier chain
                                         ///< (`outer`) and its boundary circle; `inner` is then the Farey neighbour of
                                         ///< `outer` of least q between the two, a rational of no chain of the atlas
  Rational outer, inner;                 ///< the chains about the island it lies between (p/q about it)
  std::vector<Rational> convergents;     ///< the terms of ΔW, in order (the last gives the zone)
  bool found = false;
  std::string failure;                   ///< why not, when not found
  std::string note;                      ///< a boundary cantorus: the nobles nearer the boundary tried first, and why
                                         ///< they were not taken
  long double flux = 0;                  ///< the last term's ΔW: the area crossing it per step
  long double fluxUncertainty = 0;       ///< the tail bound of the convergents' limit (convergentLimit)
  long double zoneArea = 0;              ///< the polygon of the last term's minimax orbit, by angle about the centre
  long double zoneSpread = 0;            ///< |the minimizing orbit's polygon − zoneArea|: the polygons' disagreement
  long double enclosedIslands = 0;       ///< the atlas's islands inside the zone (as AtlasFlux::enclosedIslands)
  int enclosedCount = 0;
  long double layerArea = 0;             ///< zoneArea − enclosedIslands
};

struct Atlas {
  AtlasRequest request;
  std::vector<AtlasNode> nodes;          ///< nodes[0] is the central island; parents precede children
  std::vector<AtlasCantorus> cantori;    ///< about each island, parents first: between its successive chains,
                                         ///< outermost first, then its boundary cantorus (issue 50)
  bool cancelled = false;                ///< stopped before the end: the nodes not `measured` are to do
  std::string stopReason;                ///< why: "stopped" (a stop request) or "time budget of … s reached"
  double seconds = 0;                    ///< of the computation, every part of a resumed one (a 44-min atlas
                                         ///< resumed for 101 s said "in 1:41")
};

/// Progress on the calling thread, before each island and at the end: the atlas so far (its finished islands and
/// those known but not yet measured: `known` = sofar.nodes.size()), how many are finished, and what is being done.
/// A front end may copy `sofar` to show the tree as it grows (the first levels first).
using AtlasProgress = std::function<void(const Atlas& sofar, int done, const std::string& stage)>;

/// Computes the atlas, the first levels first.  Throws std::invalid_argument when validationError(request) is set; a
/// stop request or the time budget returns what is finished (cancelled set).  With `resume` (an atlas stopped early,
/// e.g. read back by atlasFromJson), its measured islands are kept and the others measured: the result is the
/// atlas an uninterrupted computation gives (the barriers' zones, which the files do not hold, are computed again
/// for the layers: seconds each); a finished atlas resumed with `cantori` gains them.  Throws std::invalid_argument when `resume` was computed with another request
/// (its threads and time budget aside) or is not a tree this request could have made.
[[nodiscard]] Atlas computeAtlas(const AtlasRequest& request, const AtlasProgress& progress = {},
                                 std::stop_token stop = {}, const Atlas* resume = nullptr);

/// Why `resume` cannot continue `request` (the first field that differs, threads, time budget and cantori aside), or
/// nothing.
[[nodiscard]] std::optional<std::string> resumeError(const AtlasRequest& request, const Atlas& resume);

/// The central island's boundary circle as the atlas finds it on one ray — steps 1 and 2 of the header alone, the
/// scan's classifier (the rational test, rationalOfRotation), the bisection and the proof (the polygon's convergence,
/// the rotation measured again) — for a look at the island without the tree, at the resolution the caller chooses
/// (BoxIslandCheck.hpp: 64 points over √K).  The ray is S₂ from the centre (−√K, 0) towards smaller x, over `range`
/// (0 < range ≤ 2√K), in request.map's box, with request.scanPoints points, request.iterations, digitsThreshold,
/// maxPeriod, bisections and threads.  Nothing when the ray shows no proven circle.  Throws std::invalid_argument
/// when validationError(request) is set or the range is outside its own.
struct BoundaryCircle {
  PhysicalPoint point;               ///< the circle's point on the ray: the bisection's inner end
  double rotation = 0;               ///< its rotation number about the centre (turns per step)
  std::vector<PhysicalPoint> curve;  ///< its orbit ordered by k·ω mod 1 (8192 points): the polygon of its area
};
[[nodiscard]] std::optional<BoundaryCircle> centralBoundaryCircle(const AtlasRequest& request, long double range,
                                                                  std::stop_token stop = {});

/// "centre", "6", "6 > 138": the periods from the centre down to node i.
[[nodiscard]] std::string atlasPath(const Atlas& atlas, int node);

}  // namespace archipelago
